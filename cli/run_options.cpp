#include "cli/run_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.hpp"
#include "io/text_file.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {

void add_config_options(CLI::App& sub, ConfigOptions& options) {
  sub.add_option("-c,--config", options.config_path, "TOML config file (default: the built-in config; see --print-config)");
  sub.add_option("--set", options.sets, "override one config key, e.g. --set grid.n_cells=128 (repeatable)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
  sub.add_flag("--print-config", options.print_config, "print the effective config as TOML and exit");
}

void add_out_option(CLI::App& sub, std::string& out, const std::string& help) {
  sub.add_option("-o,--out", out, help)->capture_default_str();
}

void add_global_options(CLI::App& app, GlobalOptions& options) {
  app.add_flag("--log-view", options.log_view, "print the stage-timing table (min/avg/max over ranks) at the end");
  app.add_flag("--log-all-ranks", options.log_all_ranks, "every rank logs, tagged [rank r/n] (default: rank 0 only)");
  app.add_option("--log-level", options.log_level, "error, warn, info or debug")
      ->check(CLI::IsMember({"error", "warn", "info", "debug"}))
      ->capture_default_str();
  app.add_option("--progress-interval", options.progress_interval_s,
                 "seconds between the progress lines of a long stage (0: none)")
      ->capture_default_str();
}

io::Config load_config(MPI_Comm comm, const io::Schema& schema, const ConfigOptions& options,
                       const BuiltinConfig* builtin) {
  std::string text;
  mpi::agree(comm, [&] {
    if (mpi::rank(comm) == 0 && !options.config_path.empty()) text = io::read_text_file(options.config_path);
  });
  text = mpi::broadcast(comm, text);
  io::Config config(schema);
  mpi::agree(comm, [&] {
    if (!options.config_path.empty())
      config.merge_toml(text, options.config_path);
    else if (builtin)
      config.merge_toml(builtin->toml, builtin->source);
    for (const auto& s : options.sets) config.set(s);
  });
  return config;
}

std::optional<io::Config> job_config(MPI_Comm comm, const io::Schema& schema, const ConfigOptions& options,
                                     const BuiltinConfig* builtin) {
  auto config = load_config(comm, schema, options, builtin);
  if (!options.print_config) return config;
  if (mpi::rank(comm) == 0) std::fputs(config.to_toml().c_str(), stdout);
  return std::nullopt;
}

Command add_config_command(CLI::App& parent, const std::string& name, const std::string& help,
                           const io::Schema& schema, const std::string& default_out, const std::string& out_help,
                           ConfigRun run) {
  auto* app = parent.add_subcommand(name, help);
  auto options = std::make_shared<ConfigOptions>();
  auto out = std::make_shared<std::string>(default_out);
  add_config_options(*app, *options);
  add_out_option(*app, *out, out_help);
  return {app, [&schema, options, out, run = std::move(run)](const RunContext& context) -> int {
            const auto config = job_config(context.world, schema, *options);
            if (config) run(context, *config, *out);
            return kExitOk;
          }};
}

std::string clock_text(double seconds) {
  const long s = static_cast<long>(std::ceil(std::max(seconds, 0.0)));
  return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
}

std::string command_line(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

}  // namespace clatter::jobs
