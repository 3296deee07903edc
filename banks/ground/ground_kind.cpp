#include "banks/ground/ground_kind.hpp"

#include <fmt/format.h>

#include <memory>

#include "banks/ground/ground_job.hpp"
#include "banks/ground/ground_tools.hpp"
#include "io/ground_bank.hpp"

namespace clatter::jobs {
namespace {

class GroundKind final : public BankKind {
 public:
  const char* name() const override { return "ground"; }
  const char* description() const override {
    return "build a ground bank: the regularized Lamb's problem radiated into the air over (material, elevation, "
           "eta) (docs/ground.md, docs/bank-format.md)";
  }
  const char* default_out() const override { return "ground.h5"; }
  const char* file_format() const override { return io::kGroundBankFormat; }
  const io::Schema& schema() const override { return ground_schema(); }
  // The schema's defaults are the full grid, a cluster job; without -c a run builds the demo's.
  const BuiltinConfig* builtin_config() const override {
    static const BuiltinConfig demo{builtin_ground_demo_toml(), kBuiltinGroundDemoSource};
    return &demo;
  }

  BankSweep sweep(const io::Config& config, const RunContext&) const override {
    const auto spec = std::make_shared<const GroundSpec>(make_ground_spec(config));
    const auto tasks = std::make_shared<const std::vector<GroundTask>>(ground_tasks(*spec));
    BankSweep sweep;
    sweep.manifest = {name(), ground_sweep_toml(config, *spec)};
    std::string names;
    for (const auto& m : spec->materials) names += (names.empty() ? "" : ", ") + m.name;
    sweep.summary = fmt::format("{} grounds ({}) x {} elevations = {} tasks; {} etas in [{}, {}], {} samples per eta; "
                                "air c0 = {} m/s",
                                spec->materials.size(), names, spec->elevation_rad.size(), tasks->size(),
                                spec->eta.size(), spec->eta.front(), spec->eta.back(), spec->samples_per_eta,
                                spec->c0_m_s);
    for (const auto& t : *tasks) sweep.task_names.push_back(t.name);
    sweep.run_task = [spec, tasks](MPI_Comm group, std::size_t t) { return run_ground_task(group, *spec, (*tasks)[t]); };
    const std::string& toml = sweep.manifest.config_toml;
    sweep.merge = bank_merge<model::GroundBank>(
        [spec, toml](const std::string& results_dir) { return merge_ground_results(*spec, results_dir, toml); },
        [toml](const std::string& out, const model::GroundBank& bank, const std::string& command, int n_ranks) {
          io::write_ground_bank(out, bank, command, toml, n_ranks);
        });
    return sweep;
  }

  FileTool info(CLI::App&) const override {
    return {{}, [](const std::string& path) { return ground_bank_info(path); }};
  }
};

}  // namespace

const BankKind& ground_kind() {
  static const GroundKind kind;
  return kind;
}

}  // namespace clatter::jobs
