#include "banks/commands.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <utility>

#include "banks/registry.hpp"
#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "io/content_hash.hpp"
#include "io/h5.hpp"
#include "mpi/comm.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

// Serial work that every rank does (so all agree on errors) and rank 0 prints.
int print_on_root(const RunContext& context, const std::function<std::string()>& make_text) {
  std::string text;
  mpi::agree(context.world, [&] { text = make_text(); });
  if (context.is_root) std::fputs(text.c_str(), stdout);
  return kExitOk;
}

using KindTools = std::vector<std::pair<const BankKind*, FileTool>>;

// `info` or `probe` on a bank: the tool of the file's kind, after refusing the options of the others.
std::string run_tool(const KindTools& tools, const std::string& path, const char* command) {
  const BankKind& kind = kind_of_file(path);
  // An option may be declared by one kind and shared by others (`--entry`): it is refused only when
  // the file's kind does not list it.
  auto listed = [&](const CLI::Option* o) {
    for (const auto& [k, tool] : tools)
      if (k == &kind && std::find(tool.options.begin(), tool.options.end(), o) != tool.options.end()) return true;
    return false;
  };
  for (const auto& [k, tool] : tools)
    for (const CLI::Option* o : tool.options)
      if (o->count() > 0 && !listed(o))
        throw InputError(fmt::format("{}: only for a {} bank; {} is not one", o->get_name(), k->name(), path));
  for (const auto& [k, tool] : tools)
    if (k == &kind && tool.run) return tool.run(path);
  throw InputError(fmt::format("{} {}: not available for a {} bank", command, path, kind.name()));
}

// The sweep that made `results_dir`, rebuilt by its kind from its manifest. A rebuilt config that
// differs from the stored one (a materials table edited since) would merge under another sweep id.
BankSweep sweep_of_results(const std::string& results_dir, const RunContext& context) {
  const SweepManifest stored = read_sweep_manifest(results_dir);
  const std::string source = (fs::path(results_dir) / "sweep.toml").string();
  const BankKind& kind = kind_named(stored.kind, source);
  io::Config config(kind.schema());
  config.merge_toml(stored.config_toml, source);
  BankSweep sweep = kind.sweep(config, context);
  if (sweep.manifest.config_toml != stored.config_toml)
    throw InputError(source + ": the sweep's inputs changed since it started (for a modal or ground bank: a material's "
                              "entry in its table); merge with the inputs it was run with, or run the sweep again");
  return sweep;
}

}  // namespace

std::vector<Command> add_commands(CLI::App& app) {
  std::vector<Command> commands{add_field_command(app)};
  for (const BankKind* kind : bank_kinds()) {
    commands.push_back(add_sweep_command(app, *kind));
    for (auto& c : kind->more_commands(app)) commands.push_back(std::move(c));
  }
  for (const auto add : {add_plan_command, add_merge_command, add_info_command, add_probe_command, add_checksum_command})
    commands.push_back(add(app));
  return commands;
}

Command add_sweep_command(CLI::App& parent, const BankKind& kind) {
  auto* app = parent.add_subcommand(kind.name(), kind.description());
  auto config_options = std::make_shared<ConfigOptions>();
  auto options = std::make_shared<SweepOptions>();
  options->out = kind.default_out();
  add_config_options(*app, *config_options);
  add_out_option(*app, options->out, fmt::format("output {} bank", kind.name()));
  add_sweep_options(*app, *options);
  return {app, [&kind, config_options, options](const RunContext& context) -> int {
            const auto config = job_config(context.world, kind.schema(), *config_options, kind.builtin_config());
            if (!config) return kExitOk;
            Stage stage(kind.name());
            BankSweep sweep;
            mpi::agree(context.world, [&] { sweep = kind.sweep(*config, context); });
            const auto libraries = kind.start_libraries(context);
            return run_bank_sweep(context.world, sweep, *options, context.command_line);
          }};
}

Command add_merge_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("merge", "merge a sweep's results folder into its bank, of the kind its sweep.toml "
                                             "names (after job array slices)");
  auto results = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>("bank.h5");
  auto force = std::make_shared<bool>(false);
  app->add_option("--results", *results, "the sweep's results folder")->required();
  add_out_option(*app, *out, "output bank");
  app->add_flag("--force", *force, "replace the bank at OUT even if it holds more of this sweep or another sweep");
  return {app, [results, out, force](const RunContext& context) -> int {
            Stage stage("merge");
            BankSweep sweep;
            mpi::agree(context.world, [&] { sweep = sweep_of_results(*results, context); });
            return run_bank_merge(context.world, sweep, *results, *out, context.command_line, *force);
          }};
}

Command add_info_command(CLI::App& parent) {
  std::string kinds;
  for (const BankKind* k : bank_kinds()) kinds += (kinds.empty() ? "" : ", ") + std::string(k->name());
  auto* app = parent.add_subcommand("info", fmt::format("describe a bank ({}): its contents, size, provenance and "
                                                        "sweep",
                                                        kinds));
  auto path = std::make_shared<std::string>();
  app->add_option("bank", *path, "bank file")->required();
  auto tools = std::make_shared<KindTools>();
  for (const BankKind* k : bank_kinds()) tools->emplace_back(k, k->info(*app));
  return {app, [path, tools](const RunContext& context) -> int {
            return print_on_root(context, [&] { return run_tool(*tools, *path, "info"); });
          }};
}

Command add_probe_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("probe", "print a bank's field at a listener: p_i(x, t) of one proxy of a PAN bank "
                                             "as t_s,p_Pa CSV, or |p_i(x)| of every mode of one modal-bank entry");
  auto path = std::make_shared<std::string>();
  auto point = std::make_shared<ProbePoint>();
  app->add_option("bank", *path, "bank file")->required();
  app->add_option("--point", point->point_m, "listener x,y,z [m], proxy centred on the origin")->delimiter(',')->required();
  app->add_option("--scale", point->scale, "the proxy scaled by this factor (PAN: beta of eq. 10; modal: gamma)")
      ->capture_default_str();
  auto tools = std::make_shared<KindTools>();
  for (const BankKind* k : bank_kinds()) tools->emplace_back(k, k->probe(*app, *point));
  return {app, [path, point, tools](const RunContext& context) -> int {
            return print_on_root(context, [&] { return run_tool(*tools, *path, "probe"); });
          }};
}

Command add_checksum_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("checksum", "print a content hash of a Clatter HDF5 file that leaves out "
                                                "/provenance/run (who ran it, when, on how many ranks)");
  auto path = std::make_shared<std::string>();
  app->add_option("file", *path, "HDF5 file")->required();
  return {app, [path](const RunContext& context) -> int {
            return print_on_root(context, [&] {
              auto file = io::File::open(*path);
              return io::hash_hex(io::content_hash(file, {{"/provenance/run"}, {}})) + "  " + *path + "\n";
            });
          }};
}

}  // namespace clatter::jobs
