// The ground source (synth/ground_source.hpp) on banks built here with known series: Pi a smooth
// step 0.5 (1 - cos(pi (t_hat - t0) / w)) on [t0, t0 + w], so p = A dPi/dt_hat is the half-sine
// A pi / (2 w) sin(pi (t_hat - t0) / w), whose amplitude, arrival and area are known in closed form.
// No bank file: these run without the CTest fixtures (ctest -R synth_ground).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "synth/ground_source.hpp"
#include "synth/render_scene.hpp"
#include "tests/unit/make_material.hpp"

using namespace clatter;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kRate = 44100;

// The smooth step of height `height`, sampled every dt_hat from t0 - 1 to t0 + w + 1.
model::GroundSeries smooth_step(double t0, double w, double height, double dt_hat = 0.01) {
  model::GroundSeries s;
  s.t_hat_start = t0 - 1;
  s.dt_hat = dt_hat;
  for (double t = s.t_hat_start; t <= t0 + w + 1; t = s.t_hat_start + static_cast<double>(s.pi.size()) * dt_hat) {
    const double u = std::clamp((t - t0) / w, 0.0, 1.0);
    s.pi.push_back(height * 0.5 * (1 - std::cos(kPi * u)));
  }
  return s;
}

model::GroundMaterial material(const std::string& name, double youngs_pa, double poisson, double rho_kg_m3) {
  model::GroundMaterial m;
  m.name = name;
  m.youngs_pa = youngs_pa, m.poisson = poisson, m.rho_kg_m3 = rho_kg_m3;
  m.elevation_rad = {0.2, 0.6, 1.0};
  m.eta = {0.05, 0.1, 0.2};
  return m;
}

// Concrete and soil, every grid point the same smooth step (t0 = 8, w = 10): the sound cannot
// depend on elevation or eta, only on the scaling.
model::GroundBank uniform_bank(double t0 = 8, double w = 10) {
  model::GroundBank bank;
  for (auto m : {material("concrete", 3e10, 0.2, 2400), material("soil", 1e8, 0.3, 1600)}) {
    m.series.assign(m.elevation_rad.size() * m.eta.size(), smooth_step(t0, w, 1.0));
    bank.materials.push_back(m);
  }
  return bank;
}

io::Scene ground_scene(const std::string& ground, std::vector<Vec3> listeners) {
  io::Scene s;
  s.path = "ground-scene.json";
  s.materials["concrete"] = test::elastic(3e10, 0.2);
  s.materials["soil"] = test::elastic(1e8, 0.3);
  s.ground_material = ground;
  s.listeners_m = std::move(listeners);
  return s;
}

// A listener at distance d_m and elevation theta from the point (x0, 0, 0).
Vec3 at(double d_m, double elevation_rad, double x0 = 0.4) {
  return {x0 + d_m * std::cos(elevation_rad), 0, d_m * std::sin(elevation_rad)};
}

synth::Impact ground_impact(double t_s, double j_n_s, double tau_s, double x0 = 0.4) {
  synth::Impact im;
  im.on_ground = true;
  im.t_s = t_s, im.tau_s = tau_s;
  im.point_world_m = {x0, 0, 0};
  im.impulse_world_n_s = {0.1 * j_n_s, -0.05 * j_n_s, j_n_s};  // the tangential part is not the ground's
  return im;
}

// The source's output at every listener of `scene` for the impacts, `seconds` long.
std::vector<std::vector<double>> render(synth::GroundSource& g, const io::Scene& scene, const std::vector<synth::Impact>& impacts,
                                        double seconds = 0.5) {
  std::vector<std::vector<double>> out(scene.listeners_m.size(), std::vector<double>(static_cast<std::size_t>(seconds * kRate), 0.0));
  g.begin(scene, {}, kRate);
  for (const auto& im : impacts) g.add(im, scene.listeners_m, kRate, out);
  return out;
}

// tau for a given eta at distance d: 4 eps = c_s tau, eta = eps / d.
double tau_for(const synth::GroundSource& g, double eta, double d_m) { return 4 * eta * d_m / g.medium().shear_speed_m_s; }

double peak(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

double amplitude(const synth::GroundSource& g, double j_n_s, double d_m) {
  const synth::GroundMedium& m = g.medium();
  const double mu_pa = m.material->youngs_pa / (2 * (1 + m.material->poisson));  // from the definition
  return m.air_density_kg_m3 * std::pow(m.shear_speed_m_s, 3) * j_n_s / (mu_pa * std::pow(d_m, 3));
}

}  // namespace

TEST(GroundSynth, AmplitudeScalesAsImpulseTimesShearSpeedCubedOverModulusTimesDistanceCubed) {
  // Peaks against A pi / (2 w), A = rho0 c_s^3 J / (mu D^3): two distances (eta 0.1 and 0.05, both
  // on the grid), two impulses, two grounds (c_s^3 / mu 1.7e-1 and 1.1e-5 m^2 / (s^3 Pa) apart).
  const double w = 10;
  for (const std::string ground : {"concrete", "soil"}) {
    synth::GroundSource g(uniform_bank(8, w), "uniform-bank");
    const io::Scene scene = ground_scene(ground, {at(3, 0.6), at(6, 0.6)});
    g.begin(scene, {}, kRate);
    const double tau = tau_for(g, 0.1, 3), seconds = 0.05 + 20 * 6 / g.medium().shear_speed_m_s;
    const auto one = render(g, scene, {ground_impact(0.01, 0.02, tau)}, seconds);
    const auto two = render(g, scene, {ground_impact(0.01, 0.04, tau)}, seconds);
    for (std::size_t l = 0; l < 2; ++l) {
      const double d = l ? 6 : 3, expected = amplitude(g, 0.02, d) * kPi / (2 * w);
      std::printf("ground %s: D = %g m: peak %.6g Pa, A pi / 2w = %.6g Pa (relative %.2g); doubled J: ratio %.9f\n", ground.c_str(),
                  d, peak(one[l]), expected, peak(one[l]) / expected - 1, peak(two[l]) / peak(one[l]));
      EXPECT_NEAR(peak(one[l]) / expected, 1.0, 1e-4);
      EXPECT_NEAR(peak(two[l]) / peak(one[l]), 2.0, 1e-12);
    }
    std::printf("ground %s: peak(3 m) / peak(6 m) = %.6f\n", ground.c_str(), peak(one[0]) / peak(one[1]));
    EXPECT_NEAR(peak(one[0]) / peak(one[1]), 8.0, 8e-4);
    EXPECT_EQ(g.stats().impacts, 1u);
    EXPECT_EQ(g.stats().eta_below_grid + g.stats().eta_above_grid + g.stats().eta_below_sample + g.stats().elevation_outside, 0u);
  }
}

TEST(GroundSynth, ThePulseArrivesAtTheImpactPlusTHatTimesDistanceOverShearSpeed) {
  // The half-sine is centred on t_hat = t0 + w / 2; sample n averages [t_n, t_n+1), so the
  // samples' centroid is at the pulse's centre; before the sample holding t0 all is exactly zero.
  const double t0 = 8, w = 10, t_impact = 0.0123, d = 4;
  synth::GroundSource g(uniform_bank(t0, w), "uniform-bank");
  const io::Scene scene = ground_scene("concrete", {at(d, 1.0)});
  g.begin(scene, {}, kRate);
  const double c_s = g.medium().shear_speed_m_s;
  const auto out = render(g, scene, {ground_impact(t_impact, 0.02, tau_for(g, 0.1, d))}, 0.1).front();
  double first = 0, moment = 0;
  for (std::size_t n = 0; n < out.size(); ++n) first += out[n], moment += (static_cast<double>(n) + 0.5) / kRate * out[n];
  const double centre_s = moment / first, expected_s = t_impact + (t0 + w / 2) * d / c_s;
  const auto onset = static_cast<std::size_t>(std::floor((t_impact + t0 * d / c_s) * kRate));
  std::printf("ground: centroid %.9f s, t_impact + t_hat d / c_s = %.9f s (%.3g samples off); onset sample %zu\n", centre_s,
              expected_s, (centre_s - expected_s) * kRate, onset);
  EXPECT_NEAR(centre_s, expected_s, 1e-3 / kRate);
  for (std::size_t n = 0; n < onset; ++n) ASSERT_EQ(out[n], 0.0) << "sample " << n;
  EXPECT_GT(std::abs(out[onset + 1]), 0.0);
}

namespace {

// A 3 x 3 grid whose series differ in height and in sampling (dt_hat, start), so interpolation
// is not of one shape.
model::GroundBank varied_bank() {
  model::GroundBank bank;
  model::GroundMaterial m = material("concrete", 3e10, 0.2, 2400);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      m.series.push_back(smooth_step(7.5 + 0.3 * static_cast<double>(i), 6 + static_cast<double>(j), 1 + static_cast<double>(3 * i + j) * 0.37,
                                     0.008 + 0.001 * static_cast<double>(i + j)));
  bank.materials.push_back(m);
  return bank;
}

// The same ground with one grid point's series alone (a 1 x 1 grid).
model::GroundBank single_point(const model::GroundBank& full, std::size_t i, std::size_t j) {
  model::GroundBank bank = full;
  model::GroundMaterial& m = bank.materials[0];
  const model::GroundSeries s = m.at(i, j);
  m.elevation_rad = {m.elevation_rad[i]}, m.eta = {m.eta[j]}, m.series = {s};
  return bank;
}

std::vector<double> render_at(const model::GroundBank& bank, double elevation_rad, double eta) {
  const double d = 3;
  synth::GroundSource g(bank, "bank");
  const io::Scene scene = ground_scene("concrete", {at(d, elevation_rad)});
  g.begin(scene, {}, kRate);
  return render(g, scene, {ground_impact(0.005, 0.03, tau_for(g, eta, d))}, 0.05).front();
}

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t n = 0; n < a.size(); ++n) m = std::max(m, std::abs(a[n] - b[n]));
  return m / peak(b);
}

}  // namespace

TEST(GroundSynth, BilinearInElevationAndLogEtaIsExactAtGridPointsAndAveragesBetween) {
  const model::GroundBank bank = varied_bank();
  const auto& m = bank.materials[0];
  double worst_grid = 0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      worst_grid = std::max(worst_grid, distance(render_at(bank, m.elevation_rad[i], m.eta[j]),
                                                 render_at(single_point(bank, i, j), m.elevation_rad[i], m.eta[j])));
  auto alone = [&](std::size_t i, std::size_t j) { return render_at(single_point(bank, i, j), m.elevation_rad[i], m.eta[j]); };
  auto mean = [](const std::vector<std::vector<double>>& xs) {
    std::vector<double> r(xs[0].size(), 0.0);
    for (const auto& x : xs)
      for (std::size_t n = 0; n < r.size(); ++n) r[n] += x[n] / static_cast<double>(xs.size());
    return r;
  };
  const double e_mid = 0.5 * (m.elevation_rad[0] + m.elevation_rad[1]), eta_mid = std::sqrt(m.eta[1] * m.eta[2]);
  const double in_elevation = distance(render_at(bank, e_mid, m.eta[1]), mean({alone(0, 1), alone(1, 1)}));
  const double in_eta = distance(render_at(bank, m.elevation_rad[2], eta_mid), mean({alone(2, 1), alone(2, 2)}));
  const double in_cell = distance(render_at(bank, e_mid, eta_mid), mean({alone(0, 1), alone(0, 2), alone(1, 1), alone(1, 2)}));
  std::printf("ground: bilinear: at the 9 grid points %.2g of the peak from the grid series alone; midpoints in elevation "
              "%.2g, in log eta %.2g, of a cell %.2g from the average\n",
              worst_grid, in_elevation, in_eta, in_cell);
  EXPECT_LT(worst_grid, 1e-9);
  EXPECT_LT(in_elevation, 1e-9);
  EXPECT_LT(in_eta, 1e-9);
  EXPECT_LT(in_cell, 1e-9);
}

TEST(GroundSynth, TheBoxAverageKeepsTheAreaOfThePulseEvenBelowOneSample) {
  // sum p_n / rate = A D / c_s (Pi_end - Pi_start), telescoping; for a pulse far shorter than a
  // sample (w = 0.004 in t_hat, 0.2 of a sample at 3 m) and for the resolved one.
  for (const double w : {10.0, 0.004}) {
    model::GroundBank bank = uniform_bank(8, w);
    for (auto& s : bank.materials[0].series) s = smooth_step(8, w, 2.5, w / 50);
    synth::GroundSource g(bank, "bank");
    const double d = 3;
    const io::Scene scene = ground_scene("concrete", {at(d, 0.6)});
    g.begin(scene, {}, kRate);
    const auto out = render(g, scene, {ground_impact(0.0071, 0.02, tau_for(g, 0.1, d))}, 0.1).front();
    double area = 0;
    for (double v : out) area += v / kRate;
    const double expected = amplitude(g, 0.02, d) * d / g.medium().shear_speed_m_s * 2.5;
    std::printf("ground: w = %g: sum p dt = %.12g Pa s, A D / c_s Delta Pi = %.12g Pa s (relative %.2g); peak %.4g Pa\n", w, area,
                expected, area / expected - 1, peak(out));
    EXPECT_NEAR(area / expected, 1.0, 1e-12);
  }
}

TEST(GroundSynth, ClampsAreCountedAndOnlyGroundImpactsSound) {
  synth::GroundSource g(uniform_bank(), "uniform-bank");
  const io::Scene scene = ground_scene("concrete", {at(3, 0.1), at(3, 0.6)});  // 0.1 rad: below the grid's 0.2
  g.begin(scene, {}, kRate);
  synth::Impact pair = ground_impact(0.01, 0.02, 1e-4), up = pair;
  pair.on_ground = false;
  up.impulse_world_n_s[2] = -0.02;
  const auto out = render(g, scene, {ground_impact(0.01, 0.02, tau_for(g, 0.5, 3)), ground_impact(0.02, 0.02, tau_for(g, 0.06, 3)),
                                     ground_impact(0.03, 0.02, tau_for(g, 0.001, 3)), pair, up});
  const synth::GroundStats& s = g.stats();
  EXPECT_EQ(s.impacts, 3u);
  EXPECT_EQ(s.skipped_upward, 1u);
  EXPECT_EQ(s.eta_above_grid, 2u);    // eta 0.5 at both listeners
  EXPECT_EQ(s.eta_below_sample, 2u);  // eta 0.001 < c_s / (rate D) = 0.017 ...
  EXPECT_EQ(s.eta_below_grid, 2u);    // ... and that still below the grid's 0.05
  EXPECT_EQ(s.elevation_outside, 3u);
  EXPECT_GT(peak(out[0]), 0);
}

TEST(GroundSynth, RenderSceneFeedsGroundEventsOnly) {
  // Through the event loop: a ground event sounds; a pair event and a fracture event do not.
  io::Scene scene = ground_scene("concrete", {at(3, 0.6)});
  for (int id : {1, 2}) {
    io::SceneObject o;
    o.id = id;
    o.mass_kg = 0.5, o.volume_m3 = 2e-4, o.material = "concrete";
    o.inertia_kg_m2 = {{{1e-4, 0, 0}, {0, 1.2e-4, 0}, {0, 0, 1.4e-4}}};
    scene.objects.push_back(o);
  }
  io::SceneEvent e;
  e.a = 1, e.t_s = 0.01, e.normal_speed_m_s = 1, e.point_m = {0.4, 0, 0}, e.impulse_n_s = {0, 0, 0.02};
  e.pose_a.position_m = {0.4, 0, 0.04};
  scene.events = {e};
  e.b = 2, e.t_s = 0.02, e.pose_b.position_m = {0.4, 0, 0.12};
  scene.events.push_back(e);
  e.b = 0, e.fracture = true, e.contact_time_s = 1e-4, e.t_s = 0.03;
  scene.events.push_back(e);
  scene.duration_s = 0.2;
  synth::GroundSource all(uniform_bank(), "uniform-bank"), first(uniform_bank(), "uniform-bank");
  const auto a = synth::render_scene(scene, {&all}, {}).front().front();
  scene.events.resize(1);
  const auto b = synth::render_scene(scene, {&first}, {}).front().front();
  EXPECT_EQ(all.stats().impacts, 1u);
  EXPECT_GT(peak(b), 0);
  EXPECT_EQ(distance(a, b), 0.0);
}

TEST(GroundSynth, BadGroundsAndListenersAreInputErrorsNamingTheKeyAndValues) {
  auto message = [](io::Scene scene) {
    synth::GroundSource g(uniform_bank(), "ground.h5");
    try {
      g.begin(scene, {}, kRate);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  io::Scene scene = ground_scene("concrete", {at(3, 0.6)});
  scene.materials["Concrete"] = scene.materials["concrete"];
  scene.ground_material = "Concrete";  // names are case-sensitive
  const std::string missing = message(scene);
  scene = ground_scene("concrete", {at(3, 0.6), {1, 2, 0}});
  const std::string below = message(scene);
  scene = ground_scene("concrete", {at(3, 0.6)});
  scene.materials["concrete"].youngs_pa = 3.1e10;
  const std::string modulus = message(scene);
  scene.materials["concrete"].youngs_pa = 3.02e10;  // within 1 %
  scene.materials["concrete"].poisson = 0.25;
  const std::string poisson = message(scene);
  scene.materials["concrete"].poisson = 0.2;
  scene.materials["concrete"].rho_kg_m3 = 2000;
  const std::string density = message(scene);
  scene.materials["concrete"].rho_kg_m3 = 2410;
  const std::string fine = message(scene);
  for (const auto& m : {missing, below, modulus, poisson, density}) std::printf("ground: error: %s\n", m.c_str());
  EXPECT_EQ(missing, "ground-scene.json: ground_material: 'Concrete' is not a material of the ground bank ground.h5, which "
                     "holds 'concrete', 'soil'");
  EXPECT_NE(below.find("listeners[1].position_m: (1, 2, 0) is not above the ground"), std::string::npos) << below;
  EXPECT_NE(modulus.find("materials.concrete.youngs_modulus_pa: 31000000000 differs from the ground bank's 30000000000"),
            std::string::npos) << modulus;
  EXPECT_NE(poisson.find("poisson_ratio: 0.25 differs from the ground bank's 0.2"), std::string::npos) << poisson;
  EXPECT_NE(density.find("density_kg_m3: 2000 differs from the ground bank's 2400"), std::string::npos) << density;
  EXPECT_EQ(fine, "no error");
}
