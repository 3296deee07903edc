// The modal source (synth/modal_source.hpp) against references derived here: the exact
// response of one damped mode to the half-sine force by Duhamel's integral (Gauss-Legendre
// quadrature, independent of the source's complex closed form), a mode that vanishes at the
// contact point, superposition, and debris lifetimes. Banks: the sphere entry that
// `clatter-bank modal` made (CTest fixture synth_modal_bank), as is or with synthetic modes.
#include <gsl/gsl_integration.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "io/modal_bank.hpp"
#include "synth/modal_source.hpp"
#include "synth/render_scene.hpp"
#include "tests/synth/bank_paths.hpp"
#include "tests/unit/make_material.hpp"

using namespace clatter;

namespace {

constexpr double kPi = std::numbers::pi;

model::ModalBank sphere_bank() {
  EXPECT_FALSE(test::modal_bank_path.empty()) << "usage: clatter-synth-tests PAN.h5 MODAL.h5";
  return io::read_modal_bank(test::modal_bank_path);
}

struct SyntheticMode {
  double f_hz;
  std::function<Vec3(const std::array<double, 3>&)> shape;  // at a surface node
  std::complex<double> monopole;                            // M_0^0 of the transfer
};

// The sphere entry with its modes replaced: shapes given at the nodes, a pure monopole transfer.
model::ModalBank synthetic_bank(const std::vector<SyntheticMode>& modes) {
  model::ModalBank bank = sphere_bank();
  bank.entries.resize(1);
  model::ModalEntry& e = bank.entries[0];
  e.frequencies_hz.clear(), e.damping_ratios.clear(), e.cluster.clear(), e.relative_residuals.clear(), e.shapes.clear();
  e.transfer = {};
  for (const auto& m : modes) {
    e.frequencies_hz.push_back(m.f_hz);
    e.damping_ratios.push_back(0);
    e.cluster.push_back(static_cast<std::int32_t>(e.cluster.size()));
    e.relative_residuals.push_back(0);
    for (const auto& node : e.surface_nodes_m)
      for (double u : m.shape(node)) e.shapes.push_back(u);
    e.transfer.wavenumber_rad_m.push_back(2 * kPi * m.f_hz / bank.header.transfer.sound_speed_m_s);
    e.transfer.order.push_back(0);
    e.transfer.coefficients.push_back(m.monopole.real());
    e.transfer.coefficients.push_back(m.monopole.imag());
  }
  return bank;
}

// One object (an ellipsoid's inertia with distinct moments, so its frame is defined; semi-axes
// 5, 6, 7 cm times `size`), a material with Rayleigh damping, one listener 3 m away along a skew
// direction.
io::Scene one_object_scene(double base_frequency_hz, double size = 1) {
  io::Scene s;
  s.path = "modal-scene";
  s.materials["glass"] = clatter::test::damped(6.2e10, 0.2, 60.0, 2e-6);
  s.ground_material = "glass";
  io::SceneObject o;
  o.id = 1;
  const double a = 0.05 * size, b = 0.06 * size, c = 0.07 * size;
  o.volume_m3 = 4.0 / 3.0 * kPi * a * b * c;
  o.mass_kg = 2600 * o.volume_m3;
  o.inertia_kg_m2 = {{{o.mass_kg / 5 * (b * b + c * c), 0, 0}, {0, o.mass_kg / 5 * (a * a + c * c), 0}, {0, 0, o.mass_kg / 5 * (a * a + b * b)}}};
  o.material = "glass";
  o.base_frequency_hz = base_frequency_hz;
  o.base_frequency_from = base_frequency_hz > 0 ? "scene" : "";
  o.where = "modal-scene: objects[0]";
  s.objects.push_back(o);
  s.listeners_m.push_back({1.2, 2.4, 1.2 + 0.3});  // |(1.2, 2.4, 1.2)| = 2.94 m from the object at z = 0.3
  s.duration_s = 0.25;
  return s;
}

io::SceneEvent fracture_event(double t_s, const Vec3& direction, double impulse_n_s, double tau_s) {
  io::SceneEvent e;
  e.t_s = t_s;
  e.a = 1;
  e.fracture = true;
  e.contact_time_s = tau_s;
  e.pose_a.position_m = {0, 0, 0.3};
  e.impulse_n_s = {impulse_n_s * direction[0], impulse_n_s * direction[1], impulse_n_s * direction[2]};
  e.point_m = e.pose_a.position_m;
  e.where = "modal-scene: events[" + std::to_string(t_s) + "]";
  return e;
}

std::vector<double> render(synth::ModalSource& modal, const io::Scene& scene) {
  return synth::render_scene(scene, {&modal}, {}).front().front();
}

// Duhamel: q(t) = int_0^min(t, tau) G sin(pi t' / tau) h(t - t') dt', h = e^{-xi w t} sin(w_d t) / w_d.
double duhamel(double t, double omega, double xi, double tau, double g) {
  if (t <= 0) return 0;
  static gsl_integration_glfixed_table* table = gsl_integration_glfixed_table_alloc(96);
  const double wd = omega * std::sqrt(1 - xi * xi);
  struct P {
    double t, omega, xi, tau, wd;
  } p{t, omega, xi, tau, wd};
  gsl_function f{[](double s, void* v) {
                   const P& q = *static_cast<P*>(v);
                   return std::sin(kPi * s / q.tau) * std::exp(-q.xi * q.omega * (q.t - s)) * std::sin(q.wd * (q.t - s)) / q.wd;
                 },
                 &p};
  return g * gsl_integration_glfixed(&f, 0, std::min(t, tau), table);
}

double peak(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

}  // namespace

TEST(ModalSynth, OneModeMatchesTheDuhamelIntegralOfTheHalfSine) {
  // One mode at 3 kHz in the bank, shape (0, 0, u0) everywhere (interpolation is exact for a
  // constant), transfer a monopole; the object rings at 1.5 kHz (gamma = 2). Expected at the
  // listener: w q(t - t0 - r / c) with G = F_max sqrt(M_unit / m) u0 (R f)_z and
  // w = sqrt(M_unit / m) |M_00| / (k_bank r sqrt(4 pi)) (|h_0(kr)| = 1 / kr, Y_0^0 = 1 / sqrt(4 pi)).
  const double u0 = 0.37, f_bank = 3000, f0 = 1500;
  const std::complex<double> m00{2.0, -1.5};
  synth::ModalOptions options;
  options.relative_floor = 0;
  synth::ModalSource modal({synthetic_bank({{f_bank, [&](const auto&) { return Vec3{0, 0, u0}; }, m00}})}, {"synthetic"}, options);
  io::Scene scene = one_object_scene(f0);
  const Vec3 dir{0.48, -0.6, 0.64};
  const double j = 0.02, tau = 3e-4;
  scene.events.push_back(fracture_event(0.01, dir, j, tau));
  const std::vector<double> out = render(modal, scene);

  const model::ModalBank& bank = modal.banks()[0];
  const auto& e = bank.entries[0];
  const synth::ModalVoice& v = modal.voice(0);
  EXPECT_NEAR(v.gamma, 2.0, 1e-14);
  const double m = scene.objects[0].mass_kg, unit_mass = bank.header.material.rho_kg_m3 * 4.0 / 3.0 * kPi * e.axes_m[0] * e.axes_m[1] * e.axes_m[2];
  const double s = std::sqrt(unit_mass / m), omega = 2 * kPi * f0, xi = 0.5 * (60 / omega + 2e-6 * omega);
  const Vec3 fp = kernels::modal::to_modal_frame(v.frame, dir);
  const double g = kPi * j / (2 * tau) * s * u0 * fp[2];  // the half-sine that delivers j: int F sin = 2 tau F / pi
  const Vec3& l = scene.listeners_m[0];
  const double r = std::sqrt(l[0] * l[0] + l[1] * l[1] + (l[2] - 0.3) * (l[2] - 0.3));
  const double c = bank.header.transfer.sound_speed_m_s, w = s * std::abs(m00) / (e.transfer.wavenumber_rad_m[0] * r * std::sqrt(4 * kPi));
  std::vector<double> expected(out.size());
  for (std::size_t n = 0; n < out.size(); ++n) expected[n] = w * duhamel(static_cast<double>(n) / 44100 - 0.01 - r / c, omega, xi, tau, g);
  double worst = 0;
  for (std::size_t n = 0; n < out.size(); ++n) worst = std::max(worst, std::abs(out[n] - expected[n]));
  std::printf("modal: one mode (1.5 kHz, xi %.3g, tau 0.3 ms) over %zu samples: max error %.3g of the peak %.4g Pa\n", xi,
              out.size(), worst / peak(expected), peak(expected));
  EXPECT_GT(peak(expected), 0);
  EXPECT_LT(worst, 1e-6 * peak(expected));
}

TEST(ModalSynth, AModeThatVanishesAtTheContactIsNotExcited) {
  // Mode A: (0, 0, 1) everywhere; mode B: (0, 0, x) at each node, zero on the plane x = 0. The
  // force along the proxy's -z puts the Appendix F contact at the pole (0, 0, c), where B's
  // displacement vanishes: its modal force and its sound must be nil.
  auto mode_a = SyntheticMode{2000, [](const auto&) { return Vec3{0, 0, 1}; }, {1, 0}};
  auto mode_b = SyntheticMode{2400, [](const auto& x) { return Vec3{0, 0, x[0]}; }, {1, 0}};
  io::Scene scene = one_object_scene(1000);
  synth::ModalSource both({synthetic_bank({mode_a, mode_b})}, {"synthetic"});
  synth::render_scene(scene, {&both}, {});  // sets up the voice, whose frame the force is built in
  const auto& rot = both.voice(0).frame.rotation;
  const Vec3 dir{-rot[2][0], -rot[2][1], -rot[2][2]};  // R dir = -z
  scene.events.push_back(fracture_event(0.01, dir, 0.02, 3e-4));
  synth::Impact im;
  const auto models = synth::object_models(scene, scene.path);
  im.model = &models[0];
  im.direction_body = dir;
  const std::vector<double> g = both.modal_forces(im);
  std::printf("modal: at the node: modal forces A %.3g, B %.3g\n", g[0], g[1]);
  EXPECT_GT(std::abs(g[0]), 0.5);
  EXPECT_LE(std::abs(g[1]), 1e-6 * std::abs(g[0]));
  synth::ModalSource only_a({synthetic_bank({mode_a})}, {"a"}), only_b({synthetic_bank({mode_b})}, {"b"});
  const double pa = peak(render(only_a, scene)), pb = peak(render(only_b, scene));
  std::printf("modal: at the node: peak of mode A alone %.4g Pa, of mode B alone %.3g Pa\n", pa, pb);
  EXPECT_GT(pa, 0);
  EXPECT_LE(pb, 1e-6 * pa);
}

TEST(ModalSynth, TwoOverlappingImpactsAreTheSumOfEach) {
  // The sphere's real modes (every one to 2 f_1), struck twice 0.3 ms apart in different
  // directions, the second while the first is still in contact: superposition to rounding.
  synth::ModalOptions options;
  options.relative_floor = 0;  // the same spans in all three renders
  synth::ModalSource modal({sphere_bank()}, {test::modal_bank_path}, options);
  io::Scene one = one_object_scene(0, 5), two = one_object_scene(0, 5), both = one_object_scene(0, 5);  // f_1 near 4 kHz
  one.events.push_back(fracture_event(0.010, {0.0, 0.6, 0.8}, 0.02, 5e-4));
  two.events.push_back(fracture_event(0.0103, {0.8, 0.0, -0.6}, 0.015, 4e-4));
  both.events = {one.events[0], two.events[0]};
  const auto a = render(modal, one), b = render(modal, two), ab = render(modal, both);
  double worst = 0;
  for (std::size_t n = 0; n < ab.size(); ++n) worst = std::max(worst, std::abs(ab[n] - a[n] - b[n]));
  std::printf("modal: %zu modes, two overlapping impacts: max deviation from the sum %.3g of the peak\n", modal.stats().modes,
              worst / peak(ab));
  EXPECT_GT(modal.stats().modes, 10u);
  EXPECT_LT(worst, 1e-9 * peak(ab));
}

TEST(ModalSynth, DebrisRingsOnlyWhileAlive) {
  // A piece created at 0.1 s by a fracture impulse and destroyed at 0.2 s; an impact at 0.05 s
  // (before it exists) is skipped. Silence before 0.1 s + r / c, sound after, silence again from
  // 0.2 s + r / c on.
  synth::ModalSource modal({sphere_bank()}, {test::modal_bank_path});
  io::Scene scene = one_object_scene(0, 5);
  scene.objects[0].created_s = 0.1;
  scene.objects[0].destroyed_s = 0.2;
  scene.events.push_back(fracture_event(0.05, {0, 0, 1}, 0.02, 5e-4));
  scene.events.push_back(fracture_event(0.1, {0, 0.6, 0.8}, 0.02, 5e-4));
  synth::RenderStats stats;
  const auto out = synth::render_scene(scene, {&modal}, {}, &stats).front().front();
  const Vec3& l = scene.listeners_m[0];
  const double delay = std::sqrt(l[0] * l[0] + l[1] * l[1] + (l[2] - 0.3) * (l[2] - 0.3)) / modal.banks()[0].header.transfer.sound_speed_m_s;
  const auto on = static_cast<std::size_t>((0.1 + delay) * 44100), off = static_cast<std::size_t>(std::ceil((0.2 + delay) * 44100));
  double before = 0, during = 0, after = 0;
  for (std::size_t n = 0; n < out.size(); ++n) (n < on ? before : n < off ? during : after) += std::abs(out[n]);
  EXPECT_EQ(stats.skipped_inactive, 1u);
  EXPECT_EQ(stats.fracture_impacts, 1u);
  EXPECT_EQ(before, 0.0);
  EXPECT_GT(during, 0.0);
  EXPECT_EQ(after, 0.0);
}
