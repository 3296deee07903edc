#include "banks/modal/modal_kind.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>

#include "banks/modal/modal_job.hpp"
#include "banks/modal/modal_plan.hpp"
#include "banks/modal/modal_samples.hpp"
#include "banks/modal/modal_tools.hpp"
#include "core/errors.hpp"
#include "io/modal_bank.hpp"
#include "petsc/session.hpp"

namespace clatter::jobs {
namespace {

class ModalKind final : public BankKind {
 public:
  const char* name() const override { return "modal"; }
  const char* description() const override {
    return "build a modal bank: FEM modes of the normalized ellipsoids of the patch, SLEPc spectrum slicing "
           "(docs/modal.md, docs/bank-format.md)";
  }
  const char* default_out() const override { return "modal.h5"; }
  const char* file_format() const override { return io::kModalBankFormat; }
  const io::Schema& schema() const override { return modal_schema(); }

  BankSweep sweep(const io::Config& config, const RunContext&) const override {
    ModalSpec made = make_modal_spec(config);
    made.header.solver_libraries = petsc::Session::versions();
    const auto spec = std::make_shared<const ModalSpec>(std::move(made));
    const auto tasks = std::make_shared<const std::vector<ModalTask>>(modal_tasks(*spec));
    BankSweep sweep;
    sweep.manifest = {name(), modal_sweep_toml(config, *spec)};
    const auto& m = spec->header.material;
    sweep.summary = fmt::format("{} ellipsoids of {} (E = {:.4g} Pa, nu = {}, rho = {} kg/m^3); {}; {} with MUMPS",
                                tasks->size(), m.name, m.youngs_pa, m.poisson, m.rho_kg_m3, band_text(spec->header),
                                spec->header.solver_libraries);
    for (const auto& t : *tasks) sweep.task_names.push_back(t.name);
    sweep.run_task = [spec, tasks](MPI_Comm group, std::size_t t) { return run_modal_task(group, *spec, (*tasks)[t]); };
    const std::string& toml = sweep.manifest.config_toml;
    sweep.merge = bank_merge<model::ModalBank>(
        [spec, toml](const std::string& results_dir) { return merge_modal_results(*spec, results_dir, toml); },
        [toml](const std::string& out, const model::ModalBank& bank, const std::string& command, int n_ranks) {
          io::write_modal_bank(out, bank, command, toml, n_ranks);
        });
    return sweep;
  }

  // PETSc and SLEPc, initialized after MPI on the same ranks; solver settings come from the
  // config alone.
  std::shared_ptr<void> start_libraries(const RunContext& context) const override {
    auto session = std::make_shared<petsc::Session>(context.world);
    if (context.is_root && !session->ignored_environment().empty())
      spdlog::warn("modal: ignored (solver settings come from the config only): {}", session->ignored_environment());
    return session;
  }

  FileTool info(CLI::App& app) const override {
    auto entry = std::make_shared<std::optional<std::size_t>>();
    CLI::Option* option = app.add_option("--entry", *entry, "modal or object bank: list this entry's modes (index, frequency, "
                                                            "damping, multiplet, multiplicity, residual) as CSV");
    return {{option}, [entry](const std::string& path) { return modal_bank_info(path, *entry); }};
  }

  FileTool probe(CLI::App& app, const ProbePoint& point) const override {
    auto entry = std::make_shared<std::optional<std::size_t>>();
    CLI::Option* option = app.add_option("--entry", *entry, "modal or object bank: the entry whose modes to evaluate");
    return {{option}, [entry, &point](const std::string& path) {
              if (!entry->has_value()) throw InputError("probe " + path + ": a modal bank needs --entry N");
              return modal_probe_csv(path, **entry, point.point_m, point.scale);
            }};
  }

  PlanEstimate plan(const io::Config& config, const PlanOptions& options) const override {
    return modal_plan_estimate(config, options);
  }

  std::vector<Command> more_commands(CLI::App& parent) const override { return {add_modal_samples_command(parent)}; }
};

}  // namespace

const BankKind& modal_kind() {
  static const ModalKind kind;
  return kind;
}

}  // namespace clatter::jobs
