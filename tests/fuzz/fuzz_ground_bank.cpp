// The ground bank reader (io::read_ground_bank), structure-aware like fuzz_pan_bank: a valid bank
// mutated item by item, rebuilt as a well-formed HDF5 file. It must end in InputError (bad
// content) or std::runtime_error (HDF5 could not read what it holds), and a bank it returns must be
// one synth/ground_source.cpp can interpolate without checks.
#include <cmath>

#include "core/errors.hpp"
#include "io/ground_bank.hpp"
#include "tests/fuzz/fuzz_input.hpp"
#include "tests/fuzz/h5_mutator.hpp"

namespace {

using namespace clatter;

model::GroundBank template_bank() {
  model::GroundBank bank;
  model::GroundMaterial m;
  m.name = "concrete";
  m.youngs_pa = 3e10;
  m.poisson = 0.2;
  m.rho_kg_m3 = 2400;
  m.source = "fuzz template";
  m.elevation_rad = {0.1, 1.5707963267948966};
  m.eta = {0.05, 0.1};
  for (int i = 0; i < 4; ++i) m.series.push_back({5.0 + i, 0.01 * (i + 1), {0.0, -0.1 * i, 0.2, 0.3}, std::vector<double>(model::kGroundTailTerms, 0.01 * i)});
  bank.materials.push_back(m);
  return bank;
}

const std::vector<fuzz::H5Item>& template_items() {
  static const std::vector<fuzz::H5Item> items = [] {
    const std::string path = fuzz::scratch_path("template-ground-bank.h5");
    io::write_ground_bank(path, template_bank(), "fuzz", "");
    return fuzz::take_apart(path);
  }();
  return items;
}

void check(const model::GroundBank& bank) {
  for (const auto& m : bank.materials) {
    if (m.elevation_rad.empty() || m.eta.empty() || m.series.size() != m.elevation_rad.size() * m.eta.size())
      fuzz::broken("series per grid point");
    for (std::size_t i = 0; i < m.elevation_rad.size(); ++i)
      if (!(m.elevation_rad[i] > 0) || (i > 0 && !(m.elevation_rad[i] > m.elevation_rad[i - 1]))) fuzz::broken("elevations");
    for (std::size_t i = 0; i < m.eta.size(); ++i)
      if (!(m.eta[i] > 0) || (i > 0 && !(m.eta[i] > m.eta[i - 1]))) fuzz::broken("eta grid");
    for (const auto& s : m.series) {
      if (!(s.dt_hat > 0) || !std::isfinite(s.t_hat_start)) fuzz::broken("series time grid");
      for (double v : s.pi)
        if (!std::isfinite(v)) fuzz::broken("non-finite Pi");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider input(data, size);
  std::vector<fuzz::H5Item> items = template_items();
  fuzz::mutate(items, input);
  const std::string path = fuzz::scratch_path("ground-bank.h5");
  fuzz::build(items, path);
  try {
    check(io::read_ground_bank(path));
  } catch (const std::runtime_error&) {  // InputError, or an HDF5 read failure
  }
  return 0;
}
