#include "banks/pan/solve_job.hpp"

#include <spdlog/spdlog.h>

#include <array>
#include <chrono>
#include <memory>
#include <optional>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/progress.hpp"
#include "core/stage_log.hpp"
#include "io/h5.hpp"
#include "io/provenance.hpp"
#include "cli/command.hpp"
#include "cli/run_options.hpp"
#include "kernels/fdtd/engine.hpp"
#include "kernels/fdtd/float_mode.hpp"
#include "kernels/fdtd/operator.hpp"
#include "kernels/fdtd/recorder.hpp"
#include "mpi/cart.hpp"
#include "mpi/collectives.hpp"
#include "mpi/comm.hpp"
#include "mpi/halo.hpp"

namespace clatter::jobs {

namespace fdtd = kernels::fdtd;

namespace {

class Progress {
 public:
  Progress(double interval_s, long long total_steps, long long cells) : timer_(interval_s), total_(total_steps), cells_(cells) {}
  void step(long long done, int field, int n_fields) {
    if (!timer_.due()) return;
    const double d = static_cast<double>(done), total = static_cast<double>(total_);
    spdlog::info("solve: field {}/{}, step {}/{} ({:.1f} %), {:.3g} cell-updates/s, ETA {:.1f} s", field, n_fields,
                 done, total_, 100.0 * d / total, static_cast<double>(cells_) * d / timer_.elapsed_s(), timer_.eta_s(d / total));
  }

 private:
  ProgressTimer timer_;
  long long total_, cells_;
};

// Every rank of the solve agrees every kHealthCheckSteps steps (one small allreduce, far below a
// step's cost) on whether to go on: a SIGTERM/SIGINT stops the solve (Interrupted), and a
// non-finite pressure at any listener or on the Kirchhoff surface means the scheme blew up
// (TaskFailure), so nobody runs on to the end of a worthless solve.
constexpr int kHealthCheckSteps = 64;

void check_health(MPI_Comm comm, bool finite, int n, int field) {
  // Both flags in one reduction: this runs inside the time loop.
  const std::array<int, 2> any = mpi::all_reduce_max(comm, std::array<int, 2>{interrupt_requested() ? 1 : 0, finite ? 0 : 1});
  if (any[1])
    throw TaskFailure(fmt::format("field {}: the pressure at a listener or on the Kirchhoff surface is not finite at step {} (unstable: "
                                  "check time.dt_s against the CFL limit and the geometry)", field, n));
  if (any[0]) throw Interrupted(fmt::format("field {}: interrupted at step {}", field, n));
}

// The operator of this rank's block, built once for every field; logs and sums its storage.
std::unique_ptr<fdtd::Operator> build_operator(MPI_Comm comm, const SolveSpec& spec, const fdtd::Box& owned,
                                               SolveResult& result) {
  Stage stage("setup");
  fdtd::Problem problem = spec.problem;
  problem.field = spec.fields.front();
  auto op = std::make_unique<fdtd::Operator>(problem, owned);
  const auto& k = op->counts();
  spdlog::debug("solve: rank owns {} cells: {} bulk, {} cut, {} solid, {} PML; {:.1f} MiB", k.owned, k.bulk, k.cut,
                k.solid, k.pml, static_cast<double>(k.bytes) / 1048576.0);
  const double total = mpi::all_reduce_sum(comm, static_cast<double>(k.bytes));
  result.bytes = total;
  const fdtd::Box in = spec.problem.grid.interior();
  spdlog::info("solve: memory {:.1f} MiB: {:.1f} bytes per cell, {:.1f} per cell outside the PML", total / 1048576.0,
               total / static_cast<double>(result.cells), total / static_cast<double>(in.cells()));
  return op;
}

// What one field's solve gives rank 0.
struct FieldRecord {
  std::vector<float> series;                       // [listener][sample]
  std::vector<fdtd::KirchhoffSeries> far, near;  // per far direction, per surface listener
  double surface_s = 0;                           // rank 0's time hearing through the surface
};

// One field: start, step with the health check and progress, gather the corners (and the
// Kirchhoff surface) to rank 0. Returns the record on rank 0, nothing elsewhere.
FieldRecord solve_field(MPI_Comm comm, const SolveSpec& spec, std::size_t fi, fdtd::Engine& engine,
                        Progress& progress, const SurfaceHook& hook) {
  fdtd::Problem problem = spec.problem;
  problem.field = spec.fields[fi];
  const int steps = spec.n_samples - 1;
  std::optional<fdtd::Recorder> recorder;
  std::optional<fdtd::SurfaceRecorder> surface;
  {
    Stage stage("start");
    engine.start(problem.field);
    recorder.emplace(problem, spec.listeners_m, engine.layout(), spec.n_samples);
    if (spec.kirchhoff.radius_m > 0) surface.emplace(problem, spec.kirchhoff, engine.layout(), spec.n_samples);
  }
  {
    Stage loop("time loop");
    for (int n = 0;; ++n) {
      recorder->record(n, engine.pressure());
      if (surface) surface->record(n, engine.pressure());
      if (n % kHealthCheckSteps == 0 || n == steps)
        check_health(comm, recorder->finite_at(n) && (!surface || surface->finite_at(n)), n, problem.field);
      if (n == steps) break;
      engine.step((n - spec.i_time_zero) * problem.dt_s);
      progress.step(static_cast<long long>(fi) * steps + n + 1, static_cast<int>(fi) + 1,
                    static_cast<int>(spec.fields.size()));
    }
  }
  FieldRecord out;
  {
    Stage stage("gather");
    const auto all = mpi::gather(comm, recorder->pack());
    if (mpi::rank(comm) == 0) out.series = fdtd::interpolate_listeners(recorder->stencils(), spec.n_samples, all);
  }
  if (!surface) return out;
  std::vector<std::string> packs;
  {
    Stage stage("gather");
    packs = mpi::gather(comm, surface->pack());
    surface.reset();
  }
  // Rank 0 hears through the surface (most of a PAN task's time) while the group's other ranks wait
  // here. A SIGTERM meanwhile, which the hook polls (Interrupted), stops every rank together.
  int interrupted = 0;
  if (mpi::rank(comm) == 0) {
    Stage stage("Kirchhoff surface");
    const auto t_surface = std::chrono::steady_clock::now();
    const fdtd::SurfaceField surface_field =
        fdtd::assemble_surface(problem, spec.kirchhoff, spec.n_samples, -spec.i_time_zero * problem.dt_s, packs);
    packs.clear();
    std::vector<fdtd::FarListener> far;
    for (const auto& d : spec.far_directions) far.push_back({d, 0.0});
    out.far = fdtd::far_field(surface_field, far);  // each in one pass per few listeners
    out.near = fdtd::pressure_at(surface_field, spec.surface_listeners_m);
    try {
      if (hook) hook(fi, surface_field);
    } catch (const Interrupted&) {
      interrupted = 1;
    }
    out.surface_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_surface).count();
  }
  if (mpi::all_reduce_max(comm, interrupted))
    throw Interrupted(fmt::format("field {}: interrupted while hearing through the Kirchhoff surface", problem.field));
  return out;
}

}  // namespace

SolveResult run_solve(MPI_Comm comm, const SolveSpec& spec, double progress_interval_s, const SurfaceHook& hook) {
  const fdtd::Grid& grid = spec.problem.grid;
  std::optional<mpi::CartTopology> topo;
  mpi::agree(comm, [&] { topo.emplace(comm, grid.n); });
  const auto start = topo->local_start(), count = topo->local_count();
  const fdtd::Box owned{start, {start[0] + count[0], start[1] + count[1], start[2] + count[2]}};
  mpi::HaloExchange halo(*topo, fdtd::Layout(owned));
  const long long cells = 1LL * grid.n[0] * grid.n[1] * grid.n[2];
  const int steps = spec.n_samples - 1;
  spdlog::info("solve: {} grid of {}x{}x{} cells ({:.3g} M) of {} mm, {} ranks as {}x{}x{}, {} steps of {:.4g} us, "
               "Courant {:.3f}, {} field(s)",
               grid.octant ? "octant" : "full", grid.n[0], grid.n[1], grid.n[2], static_cast<double>(cells) / 1e6, grid.dx_m * 1e3,
               mpi::size(comm), topo->dims()[0], topo->dims()[1], topo->dims()[2], steps, spec.problem.dt_s * 1e6,
               spec.problem.courant(), spec.fields.size());

  // "mirror-symmetric", "not mirror-symmetric" or "mirror-symmetric in x -> -x and y -> -y only".
  auto symmetry_text = [](int axes) {
    if (axes == 7) return std::string("mirror-symmetric");
    if (axes == 0) return std::string("not mirror-symmetric");
    std::string planes;
    for (int a = 0; a < 3; ++a)
      if (axes & (1 << a)) planes += fmt::format("{}{} -> -{}", planes.empty() ? "" : " and ", "xyz"[a], "xyz"[a]);
    return "mirror-symmetric in " + planes + " only";
  };
  if (const auto& m = spec.problem.mesh)
    spdlog::info("solve: mesh {} ({} triangles, hash {}, scale {}): centre of mass at [{:.6g}, {:.6g}, {:.6g}] m moved to "
                 "the origin, bounding radius {:.4g} m, volume {:.4g} m^3, {}",
                 spec.mesh_path, m->triangles().size(), spec.mesh_hash, spec.mesh_scale, m->centre_of_mass_offset_m()[0],
                 m->centre_of_mass_offset_m()[1], m->centre_of_mass_offset_m()[2], m->bounding_radius_m(), m->volume_m3(),
                 symmetry_text(m->mirror_axes()));
  const double cells_per_wavelength = spec.problem.c_m_s / (spec.band_edge_hz * grid.dx_m);
  spdlog::info("solve: scheme {}, {:.3g} cells per shortest wavelength (psi's band edge {:.3g} kHz); predicted "
               "dispersion error {:.2g} % over {:.3g} m to the farthest listener (bound {:.2g} %)",
               fdtd::scheme_name(spec.problem.scheme), cells_per_wavelength, spec.band_edge_hz / 1e3,
               100 * spec.predicted_error, spec.farthest_m, 100 * spec.max_dispersion_error);
  if (spec.predicted_error > spec.max_dispersion_error)
    spdlog::warn("solve: the predicted dispersion error {:.2g} % exceeds solver.max_dispersion_error = {:.2g} %: use a "
                 "finer grid.dx_m, the me4 scheme, or a wider pulse.h_s (docs/fdtd.md, error budget)",
                 100 * spec.predicted_error, 100 * spec.max_dispersion_error);

  SolveResult result;
  result.cells = cells;
  const fdtd::FlushSubnormals flush;
  Progress progress(progress_interval_s, static_cast<long long>(steps) * static_cast<long long>(spec.fields.size()), cells);
  const auto t_begin = std::chrono::steady_clock::now();
  double surface_s = 0;  // rank 0's hearing through the Kirchhoff surface, which the grid waits for
  // One operator and one engine for every field: the cut-cell geometry, the layer and the storage
  // are built once.
  const auto op = build_operator(comm, spec, owned, result);
  fdtd::Engine engine(*op, halo);
  for (std::size_t fi = 0; fi < spec.fields.size(); ++fi) {
    auto record = solve_field(comm, spec, fi, engine, progress, hook);
    surface_s += record.surface_s;
    if (mpi::rank(comm) == 0) {
      result.series.push_back(std::move(record.series));
      result.far.push_back(std::move(record.far));
      result.surface_series.push_back(std::move(record.near));
    }
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  const double updates = static_cast<double>(cells) * steps * static_cast<double>(spec.fields.size());
  result.cell_updates_per_s = updates / std::max(elapsed - surface_s, 1e-9);
  if (surface_s > 0)
    spdlog::info("solve: {:.3g} cell-updates in {:.3g} s: {:.3g} cell-updates/s; {:.3g} s more hearing through the "
                 "Kirchhoff surface", updates, elapsed - surface_s, result.cell_updates_per_s, surface_s);
  else
    spdlog::info("solve: {:.3g} cell-updates in {:.3g} s: {:.3g} cell-updates/s", updates, elapsed,
                 result.cell_updates_per_s);
  return result;
}

namespace {
// What a field's pressure is per: the monopole's volume acceleration, or the body's acceleration.
std::string per_unit_drive(int field) { return field == 0 ? "(m^3/s^2)" : field <= 3 ? "(m/s^2)" : "(rad/s^2)"; }
}  // namespace

void write_raw(const std::string& path, const SolveSpec& spec, const SolveResult& result, const io::Config& config,
               const std::string& command, int n_ranks) {
  const auto& p = spec.problem;
  auto file = io::File::create(path);
  io::write_header(file, kRawFormat, kRawFormatVersion);
  io::create_group(file, "/solve");
  const std::string g = "/solve";
  io::write_attribute<double>(file, g, "c_m_s", p.c_m_s);
  io::write_attribute<double>(file, g, "rho_kg_m3", p.rho_kg_m3);
  io::write_attribute<double>(file, g, "h_s", p.h_s);
  io::write_attribute<double>(file, g, "dt_s", p.dt_s);
  io::write_attribute<double>(file, g, "dx_m", p.grid.dx_m);
  io::write_attribute<double>(file, g, "t_first_s", -spec.i_time_zero * p.dt_s);
  io::write_attribute<std::int32_t>(file, g, "i_time_zero", spec.i_time_zero);
  io::write_attribute(file, g, "time_origin", std::string_view("t = 0 at the centre of psi(t; h); sample k is at "
                                                               "t_first_s + k dt_s"));
  io::write_attribute(file, g, "object", config.string("object.kind"));
  if (p.mesh) {
    // The mesh by content (io::mesh_hash of the file's mesh), its scale, and where its centre of
    // mass was in the file's frame (scaled): the solve's origin, about which rotations turn.
    io::write_attribute(file, g, "mesh_hash", std::string_view(spec.mesh_hash));
    io::write_attribute(file, g, "mesh_file", std::string_view(spec.mesh_path));
    io::write_attribute<double>(file, g, "mesh_scale", spec.mesh_scale);
    const auto& o = p.mesh->centre_of_mass_offset_m();
    io::write_attribute<double>(file, g, "centre_of_mass_x_m", o[0]);
    io::write_attribute<double>(file, g, "centre_of_mass_y_m", o[1]);
    io::write_attribute<double>(file, g, "centre_of_mass_z_m", o[2]);
    io::write_attribute<double>(file, g, "bounding_radius_m", p.mesh->bounding_radius_m());
  } else {
    io::write_attribute<double>(file, g, "a_m", p.body.a_m);
    io::write_attribute<double>(file, g, "b_m", p.body.b_m);
    io::write_attribute<double>(file, g, "c_m", p.body.c_m);
  }
  io::write_attribute<std::int32_t>(file, g, "octant", p.grid.octant ? 1 : 0);
  io::write_attribute<std::int32_t>(file, g, "grid_cells", p.grid.n[0]);
  io::write_attribute<std::int32_t>(file, g, "pml_cells", p.grid.pml);
  io::write_attribute(file, g, "interpolation", std::string_view("tricubic Lagrange (fourth order)"));
  io::write_attribute(file, g, "scheme", std::string_view(fdtd::scheme_name(p.scheme)));
  // The grid's listeners, then those heard through the Kirchhoff surface.
  const std::size_t n_grid = spec.listeners_m.size();
  const hsize_t np = n_grid + spec.surface_listeners_m.size(), ns = static_cast<hsize_t>(spec.n_samples);
  std::vector<double> xyz;
  for (const auto& x : spec.listeners_m) xyz.insert(xyz.end(), x.begin(), x.end());
  for (const auto& x : spec.surface_listeners_m) xyz.insert(xyz.end(), x.begin(), x.end());
  io::write_dataset<double>(file, "/listeners/x_m", xyz, {np, 3}, "m");
  io::write_attribute<std::int32_t>(file, "/listeners", "grid_listeners", static_cast<std::int32_t>(n_grid));
  io::write_attribute<double>(file, "/listeners", "kirchhoff_radius_m", spec.kirchhoff.radius_m);
  for (std::size_t f = 0; f < spec.fields.size(); ++f) {
    const int field = spec.fields[f];
    std::vector<float> all = result.series[f];
    for (const auto& heard : result.surface_series[f])
      for (hsize_t k = 0; k < ns; ++k) all.push_back(static_cast<float>(heard.value[k]));
    io::write_dataset<float>(file, "/fields/p" + std::to_string(field), all, {np, ns}, "Pa/" + per_unit_drive(field));
  }
  if (!spec.far_directions.empty()) {
    // The far field R p against tau = t - R/c, on the solve's step, starting before its record.
    const hsize_t nd = spec.far_directions.size(), nf = result.far.front().front().value.size();
    std::vector<double> dirs;
    for (const auto& d : spec.far_directions) dirs.insert(dirs.end(), d.begin(), d.end());
    io::write_dataset<double>(file, "/far/directions", dirs, {nd, 3}, "1");
    io::write_attribute<double>(file, "/far", "tau_first_s", result.far.front().front().t_first_s);
    for (std::size_t f = 0; f < spec.fields.size(); ++f) {
      const int field = spec.fields[f];
      std::vector<float> all;
      for (const auto& s : result.far[f]) {
        for (hsize_t k = 0; k < nf; ++k) all.push_back(static_cast<float>(k < static_cast<hsize_t>(s.valid_end) ? s.value[k] : 0.0));
      }
      io::write_dataset<float>(file, "/far/p" + std::to_string(field), all, {nd, nf}, "Pa m/" + per_unit_drive(field));
    }
  }
  io::write_provenance(file, command, config.to_toml(), n_ranks);
  file.commit();
}

Command add_solve_command(CLI::App& parent) {
  return add_config_command(
      parent, "solve", "FDTD solves around one rigid ellipsoid or closed mesh for the chosen rigid-body fields, recorded at listener "
                       "points",
      solve_schema(), "raw.h5", "output HDF5 file of raw time series",
      [](const RunContext& context, const io::Config& config, const std::string& out) {
        Stage stage("solve");
        SolveSpec spec;
        mpi::agree(context.world, [&] { spec = make_solve_spec(config); });
        const auto result = run_solve(context.world, spec, context.progress_interval_s);
        if (context.is_root) {
          Stage write("write");
          write_raw(out, spec, result, config, context.command_line, context.n_ranks);
          spdlog::info("solve: wrote {}", out);
        }
      });
}

}  // namespace clatter::jobs
