#include "banks/modal/object_kind.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>

#include "banks/modal/object_job.hpp"
#include "banks/modal/object_tools.hpp"
#include "core/errors.hpp"
#include "io/object_bank.hpp"
#include "petsc/session.hpp"

namespace clatter::jobs {
namespace {

class ObjectKind final : public BankKind {
 public:
  const char* name() const override { return "object"; }
  const char* description() const override {
    return "build an object bank: FEM modes and acoustic transfer of given closed meshes, or of a scene's objects below "
           "the proxy threshold (003 section 5.4; docs/modal.md \"Objects with their own models\")";
  }
  const char* default_out() const override { return "objects.h5"; }
  const char* file_format() const override { return io::kObjectBankFormat; }
  const io::Schema& schema() const override { return object_schema(); }

  BankSweep sweep(const io::Config& config, const RunContext&) const override {
    ObjectSpec made = make_object_spec(config);
    made.header.solver_libraries = petsc::Session::versions();
    const auto spec = std::make_shared<const ObjectSpec>(std::move(made));
    const auto tasks = std::make_shared<const std::vector<ObjectTask>>(object_tasks(*spec));
    BankSweep sweep;
    sweep.manifest = {name(), object_sweep_toml(config, *spec)};
    sweep.summary = fmt::format("{} objects; modes to {} Hz; {} with MUMPS", tasks->size(), spec->header.f_max_hz,
                                spec->header.solver_libraries);
    if (spec->scene_bodies > 0)
      sweep.summary += fmt::format(" (of the scene's {} objects: {} without a mesh, {} at or above {} Hz left to their "
                                   "proxies, {} sharing another's mesh and material)",
                                   spec->scene_bodies, spec->scene_without_mesh, spec->scene_above_threshold,
                                   spec->header.proxy_above_hz, spec->scene_duplicates);
    for (const auto& t : *tasks) sweep.task_names.push_back(t.name);
    sweep.run_task = [spec, tasks](MPI_Comm group, std::size_t t) { return run_object_task(group, *spec, (*tasks)[t]); };
    const std::string& toml = sweep.manifest.config_toml;
    sweep.merge = bank_merge<model::ObjectBank>(
        [spec, toml](const std::string& results_dir) { return merge_object_results(*spec, results_dir, toml); },
        [toml](const std::string& out, const model::ObjectBank& bank, const std::string& command, int n_ranks) {
          io::write_object_bank(out, bank, command, toml, n_ranks);
        });
    return sweep;
  }

  std::shared_ptr<void> start_libraries(const RunContext& context) const override {
    auto session = std::make_shared<petsc::Session>(context.world);
    if (context.is_root && !session->ignored_environment().empty())
      spdlog::warn("object: ignored (solver settings come from the config only): {}", session->ignored_environment());
    return session;
  }

  // `--entry` is the modal kind's option, shared: both kinds index entries alike. Read from the
  // option itself, so that the kind registered first owns it and the other does not declare it twice.
  FileTool info(CLI::App& app) const override {
    CLI::Option* option = entry_option(app, "list this entry's modes as CSV");
    return {{option}, [option](const std::string& path) { return object_bank_info(path, entry_of(option)); }};
  }

  FileTool probe(CLI::App& app, const ProbePoint& point) const override {
    CLI::Option* option = entry_option(app, "the entry whose modes to evaluate");
    return {{option}, [option, &point](const std::string& path) {
              const auto entry = entry_of(option);
              if (!entry) throw InputError("probe " + path + ": an object bank needs --entry N");
              return object_probe_csv(path, *entry, point.point_m);
            }};
  }

 private:
  static CLI::Option* entry_option(CLI::App& app, const std::string& help) {
    if (CLI::Option* o = app.get_option_no_throw("--entry")) return o;
    return app.add_option("--entry")->description("object bank: " + help)->check(CLI::NonNegativeNumber);
  }
  static std::optional<std::size_t> entry_of(const CLI::Option* option) {
    if (option->count() == 0) return std::nullopt;
    return option->as<std::size_t>();
  }
};

}  // namespace

const BankKind& object_kind() {
  static const ObjectKind kind;
  return kind;
}

}  // namespace clatter::jobs
