#pragma once
// `clatter-bank info` and `probe` of a PAN bank: reading it back (serial work, rank 0 prints).
#include <array>
#include <string>

#include "kernels/pan/directions.hpp"
#include "model/pan_bank.hpp"

namespace clatter::jobs {

// A summary of the bank: entries (proxies, meshes), fields, epsilon, sizes, provenance, the held-out checks. Throws InputError.
std::string pan_bank_info(const std::string& path);

// The bank's held-out checks (model::PanHeldOut) as issue 32's acceptance reads them: per (proxy,
// field) the share of the proxy's strongest field's energy at the points (a rotation field per unit
// surface acceleration, over A^2); below kExcludedEnergy a field is listed as not radiated and
// excluded; the error's median, worst and points above 5 %, and the worst "floored" (against the
// larger of the point's raw L2 and a tenth of the field's largest at that radius: a miss where the
// field hardly radiates told from one where it does). `table`: a row per (proxy, field); else
// one line, the worst radiated field.
inline constexpr double kExcludedEnergy = 0.01;
std::string held_out_summary(const model::PanBank& bank, bool table);

// "(B, C)" of a proxy, "mesh KEY" (its first 12 characters) of a mesh entry.
std::string entry_label(const model::PanProxy& entry);

struct ProbeRequest {
  std::string bank_path;
  std::array<double, 2> proxy_bc_m{};
  std::string mesh_key;  // a mesh entry's key or its start; replaces proxy_bc_m when set
  int field = 1;
  std::array<double, 3> point_m{};
  double rate_hz = 0;  // 0: the bank's own rate
  double scale = 1.0;  // beta of eq. (10)
  kernels::pan::Interpolation interpolation = kernels::pan::Interpolation::quadratic;  // over directions
};

// "t_s,p_Pa" CSV lines of p_i^(beta h)(x, t). Throws InputError for a proxy or field not in the
// bank or a point inside the (scaled) proxy's bounding sphere.
std::string probe_csv(const ProbeRequest& request);

}  // namespace clatter::jobs
