#pragma once
// Evaluating a fitted PAN field p_i^(h)(x, t) of one proxy (Chadwick et al. 2012, sections 4.2-4.3,
// eq. 10): anywhere outside the proxy's bounding sphere, in any octant (eqs. 16-21), for the proxy
// scaled by beta, reconstructed at a rate within a factor 2 of an output rate (Algorithm 1).
#include <array>
#include <vector>

#include "kernels/pan/directions.hpp"
#include "model/pan_bank.hpp"

namespace clatter::kernels::pan {

// One field of one proxy of a bank, as the evaluator reads it: a view into the bank (header
// scalars, the proxy's delays and sparse terms), nothing copied. Both must outlive the view.
struct FieldView {
  const model::PanBankHeader* bank = nullptr;
  const model::PanProxy* proxy = nullptr;
  int field = 1;  // 1..6 (eq. 9)
};

struct Series {
  double t0_s = 0;  // time of the first sample
  double dt_s = 0;
  std::vector<double> p;  // pressure per unit (angular) acceleration
};

// output_rate_hz = 0: the full PAN rate. The caller checks that |x| / beta lies outside the
// unscaled proxy's bounding sphere (the radial model, kernels/pan/radial.hpp, is most accurate
// from the innermost stored radius out). The field must be solved.
Series evaluate(const FieldView& f, const std::array<double, 3>& x_m, double beta = 1.0, double output_rate_hz = 0.0,
                Interpolation interpolation = Interpolation::quadratic);

// sum_i weight_i p_i^(beta h)(x, t) over the fields of one proxy of `bank` (fields not solved and
// zero weights are skipped), added in coefficient space: one inverse transform whatever the number
// of fields. weights[i] is field i + 1's.
Series evaluate_sum(const model::PanBankHeader& bank, const model::PanProxy& proxy, const std::array<double, 6>& weights,
                    const std::array<double, 3>& x_m, double beta = 1.0, double output_rate_hz = 0.0,
                    Interpolation interpolation = Interpolation::quadratic);

// Throws std::invalid_argument naming the proxy and field unless every solved field's direction set
// is a refinement of the bank's layout on its lattice (DirectionMesh's replay, which io cannot do:
// io::read_pan_bank checks only that its indices are in range).
void check_direction_sets(const model::PanBank& bank);

}  // namespace clatter::kernels::pan
