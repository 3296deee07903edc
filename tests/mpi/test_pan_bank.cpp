// The PAN bank against the raw FDTD signal it was fitted from and against the exact sphere
// solution (docs/validation.md). Banks go through the file (write, read) so quantization counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "io/pan_bank.hpp"
#include "jobs/pan_job.hpp"
#include "kernels/pan/directions.hpp"
#include "kernels/pan/field.hpp"
#include "mpi/comm.hpp"
#include "tests/reference/sphere_exact.hpp"

using namespace clatter;

namespace {

bool root() { return mpi::rank(MPI_COMM_WORLD) == 0; }

io::PanProxy through_file(const jobs::PanSpec& spec, const io::PanProxy& proxy, const std::string& name) {
  io::PanBank bank;
  bank.header = jobs::pan_header(spec);
  bank.proxies.push_back(proxy);
  const std::string path = (std::filesystem::current_path() / name).string();
  io::write_pan_bank(path, bank, "test", "", 1);
  return io::read_pan_bank(path).proxies.at(0);
}

}  // namespace

namespace {

// Relative L2 of the bank (through the file) against the raw FDTD signal at a held-out radius and
// a direction strictly inside a triangle, for every field, at epsilon = 0.01.
std::vector<double> held_out_errors(int divisions) {
  io::Config config(jobs::pan_schema());
  config.set("proxies.list_m=[[0.35, 0.2]]");
  config.set("fit.divisions=" + std::to_string(divisions));
  const auto spec = jobs::make_pan_spec(config);
  const double step = spec.solve.problem.c_m_s * spec.solve.problem.dt_s;
  const double r = std::round(0.85 / step) * step;  // between fitted radii 0.74 and 0.94; whole steps
  const std::array<double, 3> d{0.37, 0.52, 0.77};
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const std::array<double, 3> x{r * d[0] / n, r * d[1] / n, r * d[2] / n};
  auto result = jobs::build_proxy(MPI_COMM_WORLD, spec, 0, {x}, 0.0);
  std::vector<double> errors;
  if (!root()) return errors;
  const auto proxy = through_file(spec, result.proxy, "pan_heldout.h5");
  const auto header = jobs::pan_header(spec);
  const std::size_t ns = static_cast<std::size_t>(spec.solve.n_samples);
  for (std::size_t f = 0; f < spec.solve.fields.size(); ++f) {
    const int field = spec.solve.fields[f];
    const auto s = kernels::pan::evaluate(jobs::proxy_field(header, proxy, field), x);
    // PAN sample k is at t0 + k dt; t0 is a whole number of steps from raw sample 0 up to the
    // interpolated direction delay, rounded here (both series are smooth at this rate).
    const long offset = std::lround((s.t0_s + spec.solve.i_time_zero * spec.solve.problem.dt_s) / spec.solve.problem.dt_s);
    double num = 0, den = 0;
    for (std::size_t k = 0; k < ns; ++k) {
      const long j = static_cast<long>(k) - offset;
      const double pan = j >= 0 && j < static_cast<long>(s.p.size()) ? s.p[static_cast<std::size_t>(j)] : 0.0;
      const double raw = result.extra_series[f][k];
      num += (pan - raw) * (pan - raw);
      den += raw * raw;
    }
    errors.push_back(std::sqrt(num / den));
    std::printf("%d divisions, field %d: held-out r = %.3f m, direction between vertices: relative L2 %.4f\n",
                divisions, field, r, errors.back());
  }
  return errors;
}

}  // namespace

TEST(PanBank, HeldOutRadiusAndDirectionWithin5PercentAtEpsilon001) {
  // 153 directions (fit.divisions = 16): every field within 5 %.
  const auto errors = held_out_errors(16);
  for (std::size_t f = 0; f < errors.size(); ++f) EXPECT_LT(errors[f], 0.05) << "field " << f + 1;
}

TEST(PanBank, PaperDirectionLayoutHeldOut) {
  // The paper's 45 directions: translations within 5 %. Rotations reach 6-9 % between vertices for
  // this elongated proxy (their patterns vary faster than linear interpolation over ~11 degree
  // triangles follows); guarded so that it cannot get worse unnoticed. docs/pan.md.
  const auto errors = held_out_errors(8);
  for (std::size_t f = 0; f < errors.size(); ++f) EXPECT_LT(errors[f], f < 3 ? 0.05 : 0.10) << "field " << f + 1;
}

TEST(PanBank, SphereProxyReproducesTheExactTranslatingSphere) {
  io::Config config(jobs::pan_schema());
  config.set("proxies.list_m=[[0.5, 0.5]]");
  config.set("grid.dx_m=0.03");
  config.set("solve.fields=[1]");
  const auto spec = jobs::make_pan_spec(config);
  auto result = jobs::build_proxy(MPI_COMM_WORLD, spec, 0, {}, 0.0);
  if (!root()) return;
  const auto proxy = through_file(spec, result.proxy, "pan_sphere.h5");
  const auto field = jobs::proxy_field(jobs::pan_header(spec), proxy, 1);
  const auto& p = spec.solve.problem;
  const reference::TranslatingSphere exact{0.5, p.c_m_s, p.rho_kg_m3, p.h_s};
  const double r_max = spec.radii_m.back();
  for (double r : {0.5 * (spec.radii_m[1] + spec.radii_m[2]), 3 * r_max}) {
    const std::array<double, 3> x{0.6 * r, 0.48 * r, 0.64 * r};  // |x| = r, cos(theta_x) = 0.6
    const auto s = kernels::pan::evaluate(field, x);
    double num = 0, den = 0;
    for (std::size_t k = 0; k < s.p.size(); ++k) {
      // Field 1 translates along x: the dipole axis is x.
      const double want = exact.pressure(r, 0.6, s.t0_s + static_cast<double>(k) * s.dt_s);
      num += (s.p[k] - want) * (s.p[k] - want);
      den += want * want;
    }
    const double err = std::sqrt(num / den);
    std::printf("sphere proxy at r = %.3f m: relative L2 %.4f vs the exact solution\n", r, err);
    EXPECT_LT(err, 0.05) << "r = " << r;
  }
}
