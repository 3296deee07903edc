#pragma once
// The input contract of `clatter-bank modal`, without MPI: its config schema, the validated
// ModalSpec (material, patch samples, mesh, modes, solver) and the task list it implies. In
// clatter_specs, so a fuzzer or a serial tool checks a modal config exactly as clatter-bank does.
#include <array>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "kernels/fem/ellipsoid_mesh.hpp"
#include "model/modal_bank.hpp"

namespace clatter::jobs {

const io::Schema& modal_schema();

struct ModalSpec {
  model::ModalBankHeader header;            // material and the settings every entry shares (the solve's,
                                            // the pre-solve's mesh, the transfer's)
  std::string material_table;               // where the material came from ("built-in" or a path)
  std::vector<std::array<double, 3>> samples_m;  // patch points, a <= b <= c, a^2 + b^2 + c^2 = 1
  kernels::fem::EllipsoidMeshBounds bounds;  // a mesh outside them fails its task
};

// What the modal and object kinds' configs share (the same keys): the solve's settings from
// modes.cluster_gap and solver.* (InputError unless residual_limit > tolerance; f_max_multiple left
// at its default), the medium.* and transfer.* keys both schemas have, and the mesh's bounds.
model::ModalSolveSettings solve_settings(const io::Config& config);
void read_transfer_keys(const io::Config& config, model::TransferSettings& transfer);
kernels::fem::EllipsoidMeshBounds mesh_bounds(const io::Config& config);

// Reads the material table (material.table, or the built-in configs/materials.toml) and checks
// every key and combination; InputError naming the key and value.
ModalSpec make_modal_spec(const io::Config& config);

// The sweep text of a modal config: its TOML plus the material as resolved from the table (as
// comments), so a changed table entry makes another sweep (io::sweep_id).
std::string modal_sweep_toml(const io::Config& config, const ModalSpec& spec);

// The band rule in words (model::ModalBand), for the sweep's summary, `plan` and `info`.
std::string band_text(const model::ModalBankHeader& header);

// One task per patch sample, named "eNNN".
struct ModalTask {
  std::size_t entry = 0;
  std::string name;
};
std::vector<ModalTask> modal_tasks(const ModalSpec& spec);

}  // namespace clatter::jobs
