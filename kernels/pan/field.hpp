#pragma once
// Evaluating a fitted PAN field p_i^(h)(x, t) of one proxy (Chadwick et al. 2012, sections 4.2-4.3,
// eq. 10): anywhere outside the proxy's bounding sphere, in any octant (eqs. 16-21), for the proxy
// scaled by beta, reconstructed at a rate within a factor 2 of an output rate (Algorithm 1).
#include <array>
#include <vector>

#include "kernels/pan/directions.hpp"
#include "kernels/pan/fit.hpp"

namespace clatter::kernels::pan {

struct ProxyField {
  int field = 1;            // 1..6 (eq. 9)
  int terms = 2;            // N
  std::size_t length = 0;   // T, wavelet length (power of two)
  double dt_s = 0;          // sample interval of q_k: 1 / (PAN sample rate)
  double t_first_s = 0;     // retarded time t - R/c of sample 0 (t = 0: centre of psi)
  double c_m_s = 343.2;
  std::vector<SparseTerms> directions;  // one per direction vertex (45)
  std::vector<int> delay_steps;         // per vertex: its alignment advance (support_delay_steps)
};

struct Series {
  double t0_s = 0;  // time of the first sample
  double dt_s = 0;
  std::vector<double> p;  // pressure per unit (angular) acceleration
};

// output_rate_hz = 0: the full PAN rate. The caller checks that |x| / beta lies outside the
// unscaled proxy's bounding sphere (where the series (8) holds).
Series evaluate(const ProxyField& f, const std::array<double, 3>& x_m, double beta = 1.0, double output_rate_hz = 0.0,
                Interpolation interpolation = Interpolation::quadratic);

// sum_i weight_i p_i^(beta h)(x, t) over several fields of one proxy (null entries are skipped),
// added in coefficient space: one inverse transform whatever the number of fields. The fields must
// come from one proxy of one bank (same length, rate, time origin, directions and delays).
Series evaluate_sum(const std::array<const ProxyField*, 6>& fields, const std::array<double, 6>& weights,
                    const std::array<double, 3>& x_m, double beta = 1.0, double output_rate_hz = 0.0,
                    Interpolation interpolation = Interpolation::quadratic);

}  // namespace clatter::kernels::pan
