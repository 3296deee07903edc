#include "banks/pan/pan_kind.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <map>
#include <memory>

#include "banks/pan/pan_job.hpp"
#include "banks/pan/pan_plan.hpp"
#include "banks/pan/pan_tools.hpp"
#include "banks/pan/solve_job.hpp"
#include "core/errors.hpp"
#include "io/pan_bank.hpp"
#include "kernels/pan/directions.hpp"

namespace clatter::jobs {
namespace {

// The sweep of either kind: one task per (entry, field), merged into one PAN bank file.
BankSweep pan_sweep(const char* kind, const io::Config& config, std::shared_ptr<const PanSpec> spec,
                    const RunContext& context) {
  const auto tasks = std::make_shared<const std::vector<PanTask>>(pan_tasks(*spec));
  BankSweep sweep;
  sweep.manifest = {kind, config.to_toml()};
  const bool meshes = !spec->bodies.empty() && spec->bodies[0].mesh;
  sweep.summary = fmt::format("{} {} x {} fields = {} tasks; {} directions{} x ({} radii + the far field), "
                              "epsilon = {}",
                              spec->bodies.size(), meshes ? "meshes" : "proxies", spec->solve.fields.size(), tasks->size(),
                              kernels::pan::vertex_count(spec->divisions),
                              spec->direction_tolerance > 0
                                  ? fmt::format(", refined per field to {:g} % (at most {})",
                                                100 * spec->direction_tolerance, spec->max_directions)
                                  : std::string(),
                              spec->radii_m.size(), spec->epsilon);
  for (const auto& t : *tasks) sweep.task_names.push_back(t.name);
  sweep.run_task = [spec, tasks, progress_s = context.progress_interval_s](MPI_Comm group, std::size_t t) {
    return run_pan_task(group, *spec, (*tasks)[t], progress_s);
  };
  const std::string& toml = sweep.manifest.config_toml;
  sweep.merge = bank_merge<model::PanBank>(
      [spec, toml](const std::string& results_dir) { return merge_pan_results(*spec, results_dir, toml); },
      [toml, kind](const std::string& out, const model::PanBank& bank, const std::string& command, int n_ranks) {
        io::write_pan_bank(out, bank, command, toml, n_ranks);
        spdlog::info("{}: {}", kind, held_out_summary(bank, false));
      });
  return sweep;
}

class PanKind final : public BankKind {
 public:
  const char* name() const override { return "pan"; }
  const char* description() const override {
    return "build a PAN proxy bank: FDTD solves over the (B, C) proxies, wavelet fit, compression "
           "(docs/bank-format.md)";
  }
  const char* default_out() const override { return "bank.h5"; }
  const char* file_format() const override { return io::kPanBankFormat; }
  const io::Schema& schema() const override { return pan_schema(); }

  BankSweep sweep(const io::Config& config, const RunContext& context) const override {
    return pan_sweep(name(), config, std::make_shared<const PanSpec>(make_pan_spec(config)), context);
  }

  FileTool info(CLI::App&) const override { return {{}, [](const std::string& path) { return pan_bank_info(path); }}; }

  FileTool probe(CLI::App& app, const ProbePoint& point) const override {
    auto request = std::make_shared<ProbeRequest>();
    ProbeRequest& r = *request;
    CLI::Option* proxy = app.add_option("--proxy", r.proxy_bc_m, "PAN: proxy semi-axes B,C [m]")->delimiter(',');
    CLI::Option* mesh = app.add_option("--mesh", r.mesh_key, "PAN: a mesh entry, by its key or the key's start "
                                                             "(clatter-bank info lists them)")
                            ->excludes(proxy);
    CLI::Option* field = app.add_option("--field", r.field, "PAN: rigid-body field 1-6");
    CLI::Option* rate = app.add_option("--rate", r.rate_hz, "PAN: output sample rate [Hz]: reconstruct within 2x of it "
                                                            "(Algorithm 1); 0: the bank's rate")
                            ->capture_default_str();
    CLI::Option* interpolation =
        app.add_option("--interpolation", r.interpolation, "PAN: between directions: quadratic (default) or linear "
                                                           "(the paper's)")
            ->transform(CLI::CheckedTransformer(std::map<std::string, kernels::pan::Interpolation>{
                {"linear", kernels::pan::Interpolation::linear}, {"quadratic", kernels::pan::Interpolation::quadratic}}));
    return {{proxy, mesh, field, rate, interpolation}, [request, &point, proxy, mesh, field](const std::string& path) {
              if ((proxy->count() == 0 && mesh->count() == 0) || field->count() == 0)
                throw InputError("probe " + path + ": a PAN bank needs --proxy B,C (or --mesh KEY) and --field N");
              ProbeRequest q = *request;
              q.bank_path = path;
              q.point_m = point.point_m;
              q.scale = point.scale;
              return probe_csv(q);
            }};
  }

  PlanEstimate plan(const io::Config& config, const PlanOptions& options) const override {
    return pan_plan_estimate(parse_pan_params(config), options);
  }

  std::vector<Command> more_commands(CLI::App& parent) const override { return {add_solve_command(parent)}; }
};

// 000 section 5's per-object PAN: the same sweep over given meshes. Its files are PAN banks
// (format clatter-pan-bank), so `info` and `probe` are the pan kind's; `plan` costs each entry's
// grid (an entry of eight octants solves the full domain).
class PanObjectKind final : public BankKind {
 public:
  const char* name() const override { return "pan-object"; }
  const char* description() const override {
    return "build a PAN bank of given closed meshes (per-object PAN): the pan bank's solves, directions and fit "
           "around each mesh, keyed by its hash (docs/pan.md \"Objects with their own PAN\")";
  }
  const char* default_out() const override { return "objects-pan.h5"; }
  const char* file_format() const override { return io::kPanBankFormat; }
  const io::Schema& schema() const override { return pan_object_schema(); }

  BankSweep sweep(const io::Config& config, const RunContext& context) const override {
    PanParams params = parse_pan_object_params(config);
    read_scene_meshes(params);
    auto spec = std::make_shared<const PanSpec>(make_pan_spec(params));
    for (const PanBody& body : spec->bodies)
      if (const double width = mesh_width_cells(body, params.grid_dx_m); width < kMinMeshWidthCells)
        spdlog::warn("pan-object: {} is {:.3g} cells wide at grid.dx_m = {} (its equivalent ellipsoid's middle axis, "
                     "scaled to bounding radius {} m): a thin sharp-edged body radiates too little below {} cells "
                     "(about 1.5 / width too little for a plate's fracture piece: 42 % at 3.4 cells, 16 % at 10; "
                     "docs/pan.md \"Proxy validation\"): use a finer grid.dx_m",
                     body.label(), width, params.grid_dx_m, params.proxies_a_m, kMinMeshWidthCells);
    return pan_sweep(name(), config, spec, context);
  }
  FileTool info(CLI::App& app) const override { return pan_kind().info(app); }

  PlanEstimate plan(const io::Config& config, const PlanOptions& options) const override {
    PanParams params = parse_pan_object_params(config);
    read_scene_meshes(params);
    return pan_plan_estimate(params, options);
  }
};

}  // namespace

const BankKind& pan_kind() {
  static const PanKind kind;
  return kind;
}

const BankKind& pan_object_kind() {
  static const PanObjectKind kind;
  return kind;
}

}  // namespace clatter::jobs
