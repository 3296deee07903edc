#include "banks/ground/ground_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/errors.hpp"
#include "io/materials.hpp"
#include "io/text_file.hpp"
#include "kernels/ground/lamb.hpp"

namespace clatter::jobs {
namespace {

// The volume series' step as a fraction of the smallest eta. pressure_antiderivative takes phi
// linear between samples, an error second order in ds / eta and largest where the leaky waves make
// phi least smooth: at 30 degrees over concrete, eta 0.02, the rendered pressure was 1.84 % off at
// eta / 8 and 0.27 % at eta / 16 (docs/ground.md "The rendered sound against an independent route").
constexpr double kStepsPerEtaMin = 16;
// How far the stored window reaches beyond the volume series at either end, in eta (ground_spec.hpp).
constexpr double kLeadEtas = 20;
// Time after the last front (the direct sound or the Rayleigh wave) the volume series covers.
constexpr double kSettleTime = 1.5;
// A series longer than this is a config mistake (eta_min far below any contact), not a bank.
constexpr double kMaxSamplesPerSeries = 1e7;

// The eight grounds of Qu & James's poster (seed 004), all in configs/materials.toml.
io::StringList default_materials() { return {"steel", "ceramic", "granite", "concrete", "wood", "plastic", "soil", "wax"}; }

// A name that is safe as an HDF5 group and a task file name.
bool plain_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

std::string list_text(const io::RealList& xs) {
  std::string out;
  for (double x : xs) out += fmt::format("{}{}", out.empty() ? "" : ", ", x);
  return "[" + out + "]";
}

// eta_min * r^k, k = 0 .. n - 1, ending exactly at eta_max, with at least `per_octave` points per
// octave.
std::vector<double> eta_grid(double eta_min, double eta_max, double per_octave) {
  const double octaves = std::log2(eta_max / eta_min);
  const auto steps = static_cast<std::size_t>(std::ceil(octaves * per_octave - 1e-9));
  if (steps == 0) return {eta_min};
  std::vector<double> eta(steps + 1);
  for (std::size_t k = 0; k <= steps; ++k)
    eta[k] = eta_min * std::exp2(octaves * static_cast<double>(k) / static_cast<double>(steps));
  eta.back() = eta_max;
  return eta;
}

std::vector<model::GroundMaterial> read_materials(const io::Config& config, GroundSpec& spec) {
  const auto all = io::read_materials(config.string("ground.table"), spec.material_table);
  const auto& names = config.strings("ground.materials");
  if (names.empty()) throw InputError("ground.materials = []: a ground bank needs at least one material");
  std::vector<model::GroundMaterial> out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string head = fmt::format("ground.materials[{}] = \"{}\": ", i, names[i]);
    if (std::count(names.begin(), names.end(), names[i]) > 1) throw InputError(head + "named more than once");
    try {
      // The bank keeps the moduli, density and source; no damping or fracture data.
      model::GroundMaterial g;
      static_cast<model::Material&>(g) = io::find_material(all, names[i], spec.material_table);
      g.damping.reset(), g.fracture_energy_j_m2.reset(), g.tensile_strength_pa.reset();
      out.push_back(std::move(g));
    } catch (const InputError& e) {
      throw InputError(head + e.what());
    }
    if (!plain_name(names[i])) throw InputError(head + "a bank's material name may hold only letters, digits, '_' and '-'");
    const auto& m = out.back();
    try {
      kernels::ground::check_lamb_ground(m);  // Lamb's closed form needs 0 < nu
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("{}: [{}]: {}", spec.material_table, m.name, e.what()));
    }
  }
  return out;
}

void read_grid(const io::Config& config, GroundSpec& spec) {
  const auto& deg = config.reals("ground.elevations_deg");
  if (deg.empty()) throw InputError("ground.elevations_deg = []: a ground bank needs at least one elevation");
  for (std::size_t i = 1; i < deg.size(); ++i)
    if (!(deg[i] > deg[i - 1]))
      throw InputError(fmt::format("ground.elevations_deg = {}: [{}] = {} after {}: the elevations must ascend",
                                   list_text(deg), i, deg[i], deg[i - 1]));
  for (double d : deg) spec.elevation_rad.push_back(d == 90 ? std::numbers::pi / 2 : d * std::numbers::pi / 180);
  const double eta_min = config.real("ground.eta_min"), eta_max = config.real("ground.eta_max");
  if (!(eta_max >= eta_min))
    throw InputError(fmt::format("ground.eta_max = {}: must be >= ground.eta_min = {}", eta_max, eta_min));
  spec.eta = eta_grid(eta_min, eta_max, config.real("ground.etas_per_octave"));
  spec.samples_per_eta = config.real("ground.samples_per_eta");
  spec.ds = eta_min / kStepsPerEtaMin;
}

}  // namespace

const io::Schema& ground_schema() {
  static const io::Schema schema{
      "clatter-bank ground: the ground bank (Lamb's problem, regularized, radiated by the Rayleigh integral)",
      {
          {"ground.materials", default_materials(), "ground materials of the bank: tables of ground.table (each needs 0 < poisson)"},
          {"ground.table", std::string(""), "another materials file in the format of configs/materials.toml "
                                            "(docs/materials.md); empty: the built-in configs/materials.toml"},
          {"ground.elevations_deg", io::RealList{1, 2, 5, 10, 15, 20, 30, 45, 60, 75, 90},
           "listener elevations above the ground, ascending [deg]", {0.0, 90.0, true}},
          {"ground.eta_min", 1e-2,
           "smallest regularization width eta = epsilon / distance (4 epsilon = c_s t_c); phi is sampled at "
           "eta_min / 16, so the grid's cost grows as 1/eta_min (0.01: 45 core-minutes measured at eta_min / 8; the "
           "demo grid takes 1.3 times as long at eta_min / 16); clatter-synth clamps a "
           "smaller eta, inaudibly while the pulse t_c / 4 is no longer than a sample (docs/ground.md)",
           {0.0, 1.0, true}},
          {"ground.eta_max", 0.5, "largest eta of the grid", {0.0, 1.0, true}},
          {"ground.etas_per_octave", 2.0, "eta grid points per octave (log-spaced, at least this many)", {0.0, 64.0, true}},
          {"ground.samples_per_eta", 8.0, "samples of Pi per eta: dt_hat = eta / samples_per_eta", {1.0, 1000.0}},
          {"air.c0_m_s", 343.2, "speed of sound of the air the ground radiates into [m/s]", {0.0, 1e5, true}},
          {"air.rho0_kg_m3", 1.2041, "density of the air [kg/m^3]", {0.0, 1e5, true}},
      }};
  return schema;
}

GroundSpec make_ground_spec(const io::Config& config) {
  GroundSpec spec;
  spec.materials = read_materials(config, spec);
  read_grid(config, spec);
  spec.c0_m_s = config.real("air.c0_m_s");
  spec.rho0_kg_m3 = config.real("air.rho0_kg_m3");
  for (auto& m : spec.materials) {
    m.elevation_rad = spec.elevation_rad;
    m.eta = spec.eta;
    const GroundWindow w = ground_window(spec, static_cast<std::size_t>(&m - spec.materials.data()), 0);
    const double samples = (w.t_hat_end(spec.eta.front()) - w.t_hat_start(spec.eta.front())) * spec.samples_per_eta /
                           spec.eta.front();
    if (samples > kMaxSamplesPerSeries)
      throw InputError(fmt::format("ground.eta_min = {}: {:.3g} samples per series for {} (at most {:.0g}); raise "
                                   "ground.eta_min or lower ground.samples_per_eta", spec.eta.front(), samples, m.name,
                                   kMaxSamplesPerSeries));
  }
  return spec;
}

GroundWindow ground_window(const GroundSpec& spec, std::size_t material, std::size_t elevation) {
  const auto& m = spec.materials.at(material);
  const kernels::ground::LambSurface surface(m.poisson);
  GroundWindow w;
  w.mach = m.shear_speed_m_s() / spec.c0_m_s;
  w.s_end = std::max(w.mach, surface.rayleigh_tau()) + kSettleTime;
  w.first_arrival = kernels::ground::first_arrival(surface, w.mach, spec.elevation_rad.at(elevation));
  w.lead_etas = kLeadEtas;
  return w;
}

std::string ground_sweep_toml(const io::Config& config, const GroundSpec& spec) {
  std::string text = config.to_toml() + fmt::format("\n# ground materials as read from {}:\n", spec.material_table);
  for (const auto& m : spec.materials)
    text += fmt::format("# {}: youngs_pa = {:.17g}, poisson = {:.17g}, rho_kg_m3 = {:.17g}\n", m.name, m.youngs_pa,
                        m.poisson, m.rho_kg_m3);
  return text;
}

std::vector<GroundTask> ground_tasks(const GroundSpec& spec) {
  std::vector<GroundTask> tasks;
  for (std::size_t m = 0; m < spec.materials.size(); ++m)
    for (std::size_t e = 0; e < spec.elevation_rad.size(); ++e)
      tasks.push_back({m, e, fmt::format("{}-el{:02d}", spec.materials[m].name, e)});
  return tasks;
}

}  // namespace clatter::jobs
