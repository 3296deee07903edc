#pragma once
// `clatter-bank info` and `probe` of a PAN bank: reading it back (serial work, rank 0 prints).
#include <array>
#include <string>

#include "kernels/pan/directions.hpp"

namespace clatter::jobs {

// A summary of the bank: proxies, fields, epsilon, sizes, provenance. Throws InputError.
std::string pan_bank_info(const std::string& path);

struct ProbeRequest {
  std::string bank_path;
  std::array<double, 2> proxy_bc_m{};
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
