// The materials table (io/materials.hpp, configs/materials.toml, docs/materials.md): the built-in
// table, every kind of bad input, the optional keys, the derived quantities against closed forms
// and hand-computed values, and the
// error of sharing one bank among the materials of a Poisson-ratio class, measured on Lamb's free
// sphere (tests/reference/lamb_sphere.hpp).
#include <gtest/gtest.h>

#include "tests/unit/input_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.hpp"
#include "io/materials.hpp"
#include "tests/reference/lamb_sphere.hpp"

using clatter::InputError;
using clatter::io::builtin_materials;
using clatter::io::builtin_materials_toml;
using clatter::io::find_material;
using clatter::io::parse_materials;
using clatter::model::Material;

namespace {

void expect_contains(const std::string& text, const std::vector<std::string>& parts) {
  for (const auto& p : parts) EXPECT_NE(text.find(p), std::string::npos) << "'" << p << "' not in: " << text;
}

// A valid one-material table; the bad-input cases each replace one of its lines.
const std::vector<std::string> kGoodLines = {
    "# a test table",            // line 1
    "[glass]",                   // 2
    "rho_kg_m3 = 2600.0",        // 3
    "youngs_pa = 6.2e10",        // 4
    "poisson = 0.2",             // 5
    "rayleigh_alpha_1_s = 1.0",  // 6
    "rayleigh_beta_s = 1e-7",    // 7
    "source = \"test values\"",  // 8
};

// The good table with line `line` (1-based) replaced by `text`.
std::string with_line(std::size_t line, const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < kGoodLines.size(); ++i) out += (i + 1 == line ? text : kGoodLines[i]) + "\n";
  return out;
}

std::string error_for(const std::string& toml) {
  return error_of([&] { parse_materials(toml, "test.toml"); });
}

}  // namespace

TEST(Materials, BuiltinTableHasTheTwelveMaterials) {
  const auto& materials = builtin_materials();
  std::vector<std::string> names;
  for (const auto& m : materials) names.push_back(m.name);
  EXPECT_EQ(names, (std::vector<std::string>{"glass", "ceramic", "steel", "aluminium", "brass", "wood", "plastic",
                                             "concrete", "granite", "stone", "soil", "wax"}));
  for (const auto& m : materials) {
    EXPECT_FALSE(m.source.empty()) << m.name;
    EXPECT_EQ(clatter::model::check_material(m), "") << m.name;
    // The grounds below the knee have no damping (no modal bank); every other material has it.
    EXPECT_EQ(m.damping.has_value(), m.name != "soil" && m.name != "wax") << m.name;
  }
}

TEST(Materials, DemoBanksMaterialsKeepTheirValues) {
  // make demo's modal banks (glass, ceramic) and ground bank (concrete, soil, steel): each value
  // as its cited source gives it (docs/materials.md), so their banks do not change.
  const std::map<std::string, std::tuple<double, double, double>> want = {
      {"glass", {2600, 6.2e10, 0.20}},  {"ceramic", {2700, 7.2e10, 0.19}}, {"steel", {7850, 2.0e11, 0.29}},
      {"concrete", {2400, 3.0e10, 0.20}}, {"soil", {1800, 1.0e8, 0.30}}};
  for (const auto& [name, v] : want) {
    const Material& m = find_material(builtin_materials(), name, "test");
    EXPECT_EQ(std::make_tuple(m.rho_kg_m3, m.youngs_pa, m.poisson), v) << name;
  }
}

TEST(Materials, ResolvedGraniteWoodPlastic) {
  // The values the two former tables disagreed on, as docs/materials.md resolves them: granite and
  // plastic at the E that Qu & James's poster implies within the cited ranges, wood KleinPAT's.
  const std::map<std::string, std::tuple<double, double, double>> want = {
      {"granite", {2650, 5.4e10, 0.25}}, {"wood", {750, 1.1e10, 0.25}}, {"plastic", {1050, 3.5e9, 0.35}}};
  for (const auto& [name, v] : want) {
    const Material& m = find_material(builtin_materials(), name, "test");
    EXPECT_EQ(std::make_tuple(m.rho_kg_m3, m.youngs_pa, m.poisson), v) << name;
  }
}

TEST(Materials, GlassAndCeramicAreTable1OfZhengJames2010) {
  const auto& materials = builtin_materials();
  const Material& glass = find_material(materials, "glass", "test");
  EXPECT_EQ(glass.rho_kg_m3, 2600.0);
  EXPECT_EQ(glass.youngs_pa, 6.2e10);  // the table's "6.2 x 10^10 GPa" is Pa
  EXPECT_EQ(glass.poisson, 0.2);
  const Material& ceramic = find_material(materials, "ceramic", "test");
  EXPECT_EQ(ceramic.rho_kg_m3, 2700.0);
  EXPECT_EQ(ceramic.youngs_pa, 7.2e10);
  EXPECT_EQ(ceramic.poisson, 0.19);
}

TEST(Materials, BuiltinTextIsTheShippedFile) {
  std::ifstream in(std::string(CLATTER_SOURCE_DIR) + "/configs/materials.toml", std::ios::binary);
  if (!in) GTEST_SKIP() << "source tree not at " << CLATTER_SOURCE_DIR;
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(builtin_materials_toml(), text.str());  // a stale build would differ
}

TEST(Materials, GoodTableParses) {
  const auto materials = parse_materials(with_line(0, ""), "test.toml");
  ASSERT_EQ(materials.size(), 1u);
  EXPECT_EQ(materials[0].name, "glass");
  ASSERT_TRUE(materials[0].damping);
  EXPECT_EQ(materials[0].damping->alpha_1_s, 1.0);
  EXPECT_EQ(materials[0].damping->beta_s, 1e-7);
  EXPECT_FALSE(materials[0].fracture_energy_j_m2);
  EXPECT_FALSE(materials[0].tensile_strength_pa);
  EXPECT_EQ(materials[0].source, "test values");
  // An integer is a fine value for a real-valued key.
  EXPECT_EQ(parse_materials(with_line(3, "rho_kg_m3 = 2600"), "test.toml")[0].rho_kg_m3, 2600.0);
}

TEST(Materials, OutOfRangeValuesNameFileKeyAndValue) {
  const std::vector<std::tuple<std::size_t, std::string, std::vector<std::string>>> cases = {
      {5, "poisson = 0.7", {"test.toml:5: glass.poisson = 0.7: must be in (-1, 0.5)"}},
      {5, "poisson = 0.5", {"test.toml:5: glass.poisson = 0.5: must be in (-1, 0.5)"}},
      {5, "poisson = -1.0", {"test.toml:5: glass.poisson = -1.0: must be in (-1, 0.5)"}},
      {3, "rho_kg_m3 = 0.0", {"test.toml:3: glass.rho_kg_m3 = 0.0: must be > 0"}},
      {3, "rho_kg_m3 = -2600", {"test.toml:3: glass.rho_kg_m3 = -2600: must be > 0"}},
      {4, "youngs_pa = -6.2e10", {"test.toml:4: glass.youngs_pa = -6.2e10: must be > 0"}},
      {4, "youngs_pa = nan", {"test.toml:4: glass.youngs_pa = nan: must be > 0"}},
      {4, "youngs_pa = inf", {"test.toml:4: glass.youngs_pa = inf: must be > 0"}},
      {6, "rayleigh_alpha_1_s = -1.0", {"test.toml:6: glass.rayleigh_alpha_1_s = -1.0: must be >= 0"}},
      {7, "rayleigh_beta_s = -1e-7", {"test.toml:7: glass.rayleigh_beta_s = -1e-7: must be >= 0"}},
  };
  for (const auto& [line, text, parts] : cases) expect_contains(error_for(with_line(line, text)), parts);
  // Zero damping is allowed (an undamped reference bank).
  EXPECT_EQ(parse_materials(with_line(6, "rayleigh_alpha_1_s = 0.0"), "t")[0].damping->alpha_1_s, 0.0);
  // The optional fracture keys are checked like the others.
  expect_contains(error_for(with_line(0, "") + "fracture_energy_j_m2 = 0\n"),
                  {"test.toml:9: glass.fracture_energy_j_m2 = 0: must be > 0"});
  expect_contains(error_for(with_line(0, "") + "tensile_strength_pa = -1e7\n"),
                  {"test.toml:9: glass.tensile_strength_pa = -1e7: must be > 0"});
}

TEST(Materials, OptionalKeys) {
  // No damping at all: a ground's material (soil, wax); the modal bank refuses it, not the reader.
  std::string undamped = with_line(6, "");
  undamped = undamped.replace(undamped.find("rayleigh_beta_s = 1e-7"), 22, "");
  const auto plain = parse_materials(undamped, "test.toml");
  EXPECT_FALSE(plain[0].damping);
  EXPECT_EQ(plain[0].damping_ratio(1000.0), 0.0);
  // One of the Rayleigh pair alone is an error naming the missing one.
  expect_contains(error_for(with_line(6, "")), {"test.toml:2: [glass]: missing key 'rayleigh_alpha_1_s'"});
  expect_contains(error_for(with_line(7, "")), {"test.toml:2: [glass]: missing key 'rayleigh_beta_s'"});
  // The fracture data, in J/m^2 and Pa, when given.
  const auto m = parse_materials(with_line(0, "") + "fracture_energy_j_m2 = 40.0\ntensile_strength_pa = 1e7\n", "t")[0];
  ASSERT_TRUE(m.fracture_energy_j_m2 && m.tensile_strength_pa);
  EXPECT_EQ(*m.fracture_energy_j_m2, 40.0);
  EXPECT_EQ(*m.tensile_strength_pa, 1e7);
}

TEST(Materials, WrongTypesNameFileKeyAndValue) {
  expect_contains(error_for(with_line(5, "poisson = \"0.2\"")), {"test.toml:5: glass.poisson = \"0.2\": expected a number"});
  expect_contains(error_for(with_line(3, "rho_kg_m3 = [2600]")),
                  {"test.toml:3: glass.rho_kg_m3 = an array: expected a number"});
  expect_contains(error_for(with_line(8, "source = 3")), {"test.toml:8: glass.source = 3: expected a string"});
  expect_contains(error_for(with_line(8, "source = \"\"")), {"test.toml:8: glass.source = \"\": must name"});
}

TEST(Materials, MissingAndUnknownKeys) {
  expect_contains(error_for(with_line(5, "")), {"test.toml:2: [glass]: missing key 'poisson'"});
  expect_contains(error_for(with_line(8, "")), {"test.toml:2: [glass]: missing key 'source'"});
  // An unknown key is reported where it is, before the key it may have been meant for is missed.
  expect_contains(error_for(with_line(5, "poison = 0.2")),
                  {"test.toml:5: glass.poison = 0.2: unknown key 'poison' (did you mean 'poisson'?)",
                   "a material has rho_kg_m3"});
  expect_contains(error_for(with_line(1, "poisson = 0.2")),
                  {"test.toml:1: poisson = 0.2: expected a [material] table"});
}

TEST(Materials, MalformedOrEmptyDocuments) {
  expect_contains(error_for(with_line(5, "poisson = = 0.2")), {"test.toml:5", "malformed TOML"});
  expect_contains(error_for(with_line(2, "[glass")), {"test.toml:2", "malformed TOML"});
  expect_contains(error_for(with_line(8, "source = \"caf\xe9\"")), {"test.toml:8: malformed TOML: not UTF-8 text"});
  expect_contains(error_for("# nothing here\n"), {"test.toml: no materials"});
  // A second [glass] is a TOML error, not a silent override.
  expect_contains(error_for(with_line(0, "") + "[glass]\nrho_kg_m3 = 1.0\n"), {"test.toml", "malformed TOML"});
}

TEST(Materials, FindMaterialListsTheKnownNames) {
  const auto& materials = builtin_materials();
  EXPECT_EQ(find_material(materials, "steel", "scene.json").name, "steel");
  expect_contains(error_of([&] { find_material(materials, "glas", "scene.json"); }),
                  {"scene.json: unknown material 'glas'", "known: glass, ceramic, steel,", "granite, stone, soil, wax)"});
}

TEST(Materials, WaveSpeedsAgainstTheClosedForms) {
  // c_p = sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))), c_s = sqrt(E / (2 rho (1 + nu))), written
  // here from the definitions, for every material of the table.
  for (const auto& m : builtin_materials()) {
    const double e = m.youngs_pa, nu = m.poisson, rho = m.rho_kg_m3;
    const double c_p = std::sqrt(e * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu))), c_s = std::sqrt(e / (2 * rho * (1 + nu)));
    EXPECT_NEAR(m.pressure_speed_m_s(), c_p, 1e-12 * c_p) << m.name;
    EXPECT_NEAR(m.shear_speed_m_s(), c_s, 1e-12 * c_s) << m.name;
    // Viktorov's approximation of the Rayleigh speed, c_R / c_s = (0.862 + 1.14 nu) / (1 + nu),
    // is good to 0.5 % for 0 <= nu < 0.5.
    EXPECT_NEAR(m.rayleigh_speed_m_s() / c_s, (0.862 + 1.14 * nu) / (1 + nu), 5e-3) << m.name;
  }
  // Exactly, at nu = 1/4 (Pekeris): c_R / c_s = sqrt(2 - 2 / sqrt(3)).
  const Material& granite = find_material(builtin_materials(), "granite", "t");
  EXPECT_NEAR(granite.rayleigh_speed_m_s() / granite.shear_speed_m_s(), std::sqrt(2 - 2 / std::sqrt(3.0)), 1e-12);
}

TEST(Materials, ShearSpeedAgainstHandValues) {
  // sqrt(E / (2 (1 + nu) rho)), evaluated separately: glass 6.2e10 / 6240, steel 2e11 / 20253.
  const auto& materials = builtin_materials();
  EXPECT_NEAR(find_material(materials, "glass", "t").shear_speed_m_s(), 3152.125859780576, 1e-9);
  EXPECT_NEAR(find_material(materials, "steel", "t").shear_speed_m_s(), 3142.464038780223, 1e-9);
  EXPECT_NEAR(find_material(materials, "ceramic", "t").shear_speed_m_s(), 3347.309635022892, 1e-9);
}

TEST(Materials, DampingRatioAgainstHandValues) {
  const Material& glass = find_material(builtin_materials(), "glass", "t");  // alpha 1/s, beta 1e-7 s
  const double omega_1khz = 2 * std::numbers::pi * 1000;
  EXPECT_NEAR(glass.damping_ratio(omega_1khz), 3.9373673690492694e-4, 1e-15);  // (1/w + 1e-7 w) / 2
  // Rayleigh damping is least at omega = sqrt(alpha / beta), where xi = sqrt(alpha beta).
  const Material& wood = find_material(builtin_materials(), "wood", "t");  // alpha 60, beta 2e-6
  EXPECT_NEAR(wood.damping_ratio(5477.2255750516615), 0.010954451150103323, 1e-15);
  EXPECT_GT(wood.damping_ratio(5000), wood.damping_ratio(5477.2255750516615));
  EXPECT_GT(wood.damping_ratio(6000), wood.damping_ratio(5477.2255750516615));
}

namespace {

using clatter::reference::LambFamily;
using clatter::reference::LambMode;
using ModeKey = std::tuple<LambFamily, int, int>;  // family, degree n, overtone: one distinct frequency

// The free sphere's modes with omega a / c_s <= 9 (the first 10 distinct ones end near 5.8), by
// Poisson ratio, computed once each: the root scan is what makes this test take time.
const std::vector<LambMode>& sphere_modes(double poisson) {
  static std::map<double, std::vector<LambMode>> cache;
  auto it = cache.find(poisson);
  if (it == cache.end()) it = cache.emplace(poisson, clatter::reference::lamb_sphere_modes(poisson, 9.0)).first;
  return it->second;
}

// "S2" for the gravest spheroidal mode of degree 2, "S2.1" for its first overtone.
std::string mode_name(const LambMode& m) {
  std::string name = m.family == LambFamily::torsional ? "T" : "S";
  name += std::to_string(m.degree_n);
  if (m.overtone > 0) name.append(".").append(std::to_string(m.overtone));
  return name;
}

struct ModeError {
  LambMode mode;  // the material's
  double relative_error;
};

// The relative frequency errors, for the first `count` distinct modes of a free sphere of Poisson
// ratio nu_mat, of a bank computed at nu_bank: the proxy is scaled so that its lowest frequency is
// the material's (equi-frequency scaling, Zheng & James 2010 section 5.4), then each mode is
// compared with the same mode (family, degree, overtone) of the bank.
std::vector<ModeError> sharing_errors(double nu_bank, double nu_mat, std::size_t count) {
  const auto& material = sphere_modes(nu_mat);
  std::map<ModeKey, double> bank;
  for (const LambMode& m : sphere_modes(nu_bank)) bank[{m.family, m.degree_n, m.overtone}] = m.omega_a_over_cs;
  const double scale = material.at(0).omega_a_over_cs / sphere_modes(nu_bank).at(0).omega_a_over_cs;
  std::vector<ModeError> errors;
  for (std::size_t i = 0; i < count && i < material.size(); ++i) {
    const LambMode& m = material[i];
    errors.push_back({m, scale * bank.at({m.family, m.degree_n, m.overtone}) / m.omega_a_over_cs - 1});
  }
  return errors;
}

ModeError worst(const std::vector<ModeError>& errors) {
  return *std::max_element(errors.begin(), errors.end(), [](const ModeError& a, const ModeError& b) {
    return std::abs(a.relative_error) < std::abs(b.relative_error);
  });
}

void print_modes(const char* what, const std::vector<ModeError>& errors) {
  std::printf("%s:", what);
  for (const auto& e : errors) std::printf(" %s %+.3f", mode_name(e.mode).c_str(), 100 * e.relative_error);
  std::printf("\n");
}

}  // namespace

// Prints the tables of docs/materials.md (run with --gtest_filter='*Material*' to see them).
TEST(MaterialClasses, SharingErrorOnTheLambSphere) {
  const auto& materials = builtin_materials();
  constexpr std::size_t kModes = 10;
  std::printf("Sharing error on the free sphere, first %zu distinct modes, base frequency matched:\n", kModes);
  std::printf("max |f_bank / f_true - 1| in %% (the mode where it is)\n%-10s", "bank");
  for (const auto& m : materials) std::printf(" %12s", (m.name + " " + std::to_string(m.poisson).substr(0, 4)).c_str());
  std::printf("\n");
  for (const std::string bank : {"glass", "wood", "steel", "brass"}) {
    const double nu_bank = find_material(materials, bank, "test").poisson;
    std::printf("%-5s %.2f", bank.c_str(), nu_bank);
    for (const auto& m : materials) {
      const ModeError w = worst(sharing_errors(nu_bank, m.poisson, kModes));
      std::printf(" %6.2f (%-4s)", 100 * std::abs(w.relative_error), mode_name(w.mode).c_str());
    }
    std::printf("\n");
  }
  const auto ceramic = sharing_errors(0.20, 0.19, kModes);
  print_modes("glass bank for ceramic, mode by mode (%)", ceramic);
  print_modes("brass bank for aluminium (%)", sharing_errors(0.34, 0.33, kModes));
  print_modes("brass bank for plastic (%)", sharing_errors(0.34, 0.35, kModes));

  ASSERT_EQ(ceramic.size(), kModes);
  // The base (T2) is matched, and torsional modes do not depend on nu at all.
  for (const auto& e : ceramic) {
    if (e.mode.family == LambFamily::torsional) {
      EXPECT_EQ(e.relative_error, 0.0) << mode_name(e.mode);
    }
  }
  // 003 section 5.3 shares one glass bank with ceramic. The expectation that this costs under
  // 0.5 % does not hold for every mode: the breathing mode S0, set by the compressional speed,
  // is 1.9 % off; every other mode of the ten is within 0.75 %.
  EXPECT_EQ(mode_name(worst(ceramic).mode), "S0");
  EXPECT_LT(std::abs(worst(ceramic).relative_error), 0.02);
  for (const auto& e : ceramic) {
    if (mode_name(e.mode) != "S0") {
      EXPECT_LT(std::abs(e.relative_error), 0.0075) << mode_name(e.mode);
    }
  }
  // The widest class of docs/materials.md, nu 0.33-0.35 on the nu = 0.34 bank: under 3.5 %.
  EXPECT_LT(std::abs(worst(sharing_errors(0.34, 0.33, kModes)).relative_error), 0.035);
  EXPECT_LT(std::abs(worst(sharing_errors(0.34, 0.35, kModes)).relative_error), 0.035);
}
