#pragma once
// The input contract of `clatter-bank ground`, without MPI: its config schema, the validated
// GroundSpec (ground materials from their table, the (elevation, eta) grid, the air, the time
// windows) and the task list it implies. In clatter_specs, so a fuzzer or a serial tool checks a
// ground config exactly as clatter-bank does.
#include <string>
#include <vector>

#include "io/config.hpp"
#include "kernels/ground/ground_response.hpp"
#include "model/ground_bank.hpp"

namespace clatter::jobs {

const io::Schema& ground_schema();

// configs/ground-demo.toml as built in (cmake/EmbedText.cmake): the config a run without
// -c/--config uses, small enough for `make demo` (the schema's defaults are the full grid,
// configs/ground.toml).
const std::string& builtin_ground_demo_toml();
inline constexpr const char* kBuiltinGroundDemoSource = "configs/ground-demo.toml (built in)";

struct GroundSpec {
  std::string material_table;                  // where the materials came from ("built-in ..." or a path)
  std::vector<model::GroundMaterial> materials;  // moduli and source; grids filled, series empty
  std::vector<double> elevation_rad;           // ascending, in (0, pi/2]
  std::vector<double> eta;                     // ascending, log-spaced over [eta_min, eta_max]
  double c0_m_s = 0, rho0_kg_m3 = 0;
  double samples_per_eta = 8;                  // dt_hat = eta / samples_per_eta
  double ds = 0;                               // the volume series' step: eta_min / 16 (docs/ground.md)
  kernels::ground::VolumeSettings volume;      // the Rayleigh integral's quadrature (the kernel's defaults)
};

// Reads the materials table (ground.table, or the built-in configs/materials.toml) and
// checks every key and combination; InputError naming the key and value.
GroundSpec make_ground_spec(const io::Config& config);

// The sweep text of a ground config: its TOML plus the materials as resolved from the table (as
// comments), so a changed table entry makes another sweep (io::sweep_id).
std::string ground_sweep_toml(const io::Config& config, const GroundSpec& spec);

// One task per (material, elevation), named "MATERIAL-elNN" (NN: the elevation's index).
struct GroundTask {
  std::size_t material = 0, elevation = 0;
  std::string name;
};
std::vector<GroundTask> ground_tasks(const GroundSpec& spec);

// The time windows of one (material, elevation) (Lamb's problem has no length scale: they depend
// on the distance only through t_hat): the volume series runs from first_arrival to s_end =
// max(M, x_R) + 1.5, M = c_s / c0, x_R the Rayleigh front: the last front (the direct sound or
// the Rayleigh wave) and 1.5 units of t_hat past it; phi continues by its tail after it
// (kernels/ground/ground_response.hpp). Pi is stored on [first_arrival - 20 eta, s_end + 20 eta]:
// the smoothed delta spreads every front over a few eta and its tails fall as (eta / t)^4 (its
// 1/t^2 terms cancel), so 20 eta before the first arrival Pi is 0 to about 2e-5 of its swing, and
// 20 eta past s_end it is the tail's closed form, which the series' tail coefficients continue. (The window must grow with eta: ending at s_end - 20 eta, as first planned,
// would cut the whole pulse off for eta above about 0.07.)
struct GroundWindow {
  double mach = 0;           // M = c_s / c0
  double s_end = 0;          // end of the volume series
  double first_arrival = 0;  // start of the volume series (kernels::ground::first_arrival)
  double lead_etas = 20;    // the window reaches this many eta beyond both ends
  double t_hat_start(double eta) const { return first_arrival - lead_etas * eta; }
  double t_hat_end(double eta) const { return s_end + lead_etas * eta; }
};
GroundWindow ground_window(const GroundSpec& spec, std::size_t material, std::size_t elevation);

}  // namespace clatter::jobs
