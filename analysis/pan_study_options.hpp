#pragma once
// The command line of the PAN studies (clatter-pan-direction-study; the held-out check is each bank
// task's own, banks/pan/pan_job.hpp):
// a PAN config (the built-in defaults, the paper's resolution, when none is given), overrides, and
// the one proxy (B, C) studied.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "banks/pan/pan_spec.hpp"
#include "io/config.hpp"

namespace clatter::analysis {

struct PanStudyOptions {
  std::string config_path;
  std::vector<double> bc{0.2625, 0.12};
  std::vector<std::string> sets;

  void add_to(CLI::App& app) {
    app.add_option("-c,--config", config_path, "PAN config (default: the built-in defaults, the paper's resolution)");
    app.add_option("--proxy", bc, "B,C [m]")->delimiter(',')->expected(2);
    app.add_option("--set", sets, "config override key=value");
  }

  // The config with the overrides and the proxy as its only one.
  io::Config config() const {
    io::Config out(jobs::pan_schema());
    if (!config_path.empty()) {
      std::ifstream in(config_path);
      std::stringstream text;
      text << in.rdbuf();
      out.merge_toml(text.str(), config_path);
    }
    for (const auto& s : sets) out.set(s);
    out.set("proxies.list_m=[[" + std::to_string(bc[0]) + ", " + std::to_string(bc[1]) + "]]");
    return out;
  }
};

// The q-quantile of v (0: smallest, 1: largest), the nearest sample below.
inline double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(static_cast<double>(v.size()) - 1, q * static_cast<double>(v.size())))];
}

}  // namespace clatter::analysis
