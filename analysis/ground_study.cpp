// clatter-ground-study: the numbers behind analysis/ground_tables.py (docs/ground.md): Lamb's
// response at one distance with and without 004's regularization, and the ball-drop study of the
// poster's relative-intensity tables. Serial; prints CSV on stdout.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/materials.hpp"
#include "kernels/ground/drop_study.hpp"

namespace {

using namespace clatter;
using namespace clatter::kernels::ground;

// The step displacement mu r u / P at distance r, unregularized and for each eps.
void print_response(double nu, double cs, double r, const std::vector<double>& eps, double t_end, int n) {
  const LambSurface s(nu);
  std::printf("t_s,unregularized");
  for (double e : eps) std::printf(",eps_%g_m", e);
  std::printf("\n");
  for (int i = 1; i <= n; ++i) {
    const double t = t_end * i / n, tau = cs * t / r;
    std::printf("%.6e,%.8e", t, s.step(tau));
    for (double e : eps) std::printf(",%.8e", s.regularized(tau, e / r, 0));
    std::printf("\n");
  }
}

void print_drop(const BallDrop& base, const std::vector<double>& elevations_deg) {
  // The eight grounds (and balls) of Qu & James's poster, seed 004.
  std::vector<model::Material> mats;
  for (const char* name : {"steel", "ceramic", "granite", "concrete", "wood", "plastic", "soil", "wax"})
    mats.push_back(io::find_material(io::builtin_materials(), name, io::kBuiltinMaterialsSource));
  std::printf(
      "elevation_deg,ball,ground,relative_db,ground_energy_pa2_s,ball_energy_pa2_s,ground_peak_pa,ball_peak_pa,eta,knee_ratio\n");
  for (double el : elevations_deg)
    for (const auto& g : mats) {
      BallDrop d = base;
      d.elevation_rad = el * std::numbers::pi / 180;
      const model::Material& ground = g;
      // The ground's sound is linear in the impulse, so one solve per ground serves every ball.
      const DropSound unit = drop_sound(d, ground);
      // c_s^2 t_c / (2 D c0): above 1 the direct sound's surface patch is bounded by the air's delay
      // rather than by the ground's waves (docs/ground.md, "The ball drop").
      const double cs = ground.shear_speed_m_s(), knee = cs * cs * d.contact_time_s / (2 * d.distance_m * d.c0_m_s);
      for (const auto& b : mats) {
        d.ball_density_kg_m3 = b.rho_kg_m3;
        const double j_ratio = d.impulse_n_s() / base.impulse_n_s();
        DropSound s = unit;
        s.ground_energy_pa2_s *= j_ratio * j_ratio;
        s.ground_peak_pa *= j_ratio;
        std::printf("%g,%s,%s,%.4f,%.6e,%.6e,%.6e,%.6e,%.4e,%.3f\n", el, b.name.c_str(), g.name.c_str(), s.relative_db(),
                    s.ground_energy_pa2_s, s.ball_energy_pa2_s, s.ground_peak_pa, s.ball_peak_pa, s.eta, knee);
      }
      std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"clatter-ground-study: Lamb's response and the ball-drop study of seed 004 (CSV on stdout)"};
  app.require_subcommand(1);
  double nu = 0.25, cs = 10, r = 1, t_end = 0.2;
  int n = 2000;
  std::vector<double> eps{0.02, 0.1, 0.25};
  auto* resp = app.add_subcommand("response", "mu r u_H / P at distance r, unregularized and regularized");
  resp->add_option("--nu", nu, "Poisson's ratio")->capture_default_str();
  resp->add_option("--cs", cs, "shear speed [m/s]")->capture_default_str();
  resp->add_option("--r", r, "distance [m]")->capture_default_str();
  resp->add_option("--eps", eps, "regularization lengths [m]")->capture_default_str();
  resp->add_option("--t-end", t_end, "last time [s]")->capture_default_str();
  resp->add_option("--samples", n, "number of times")->capture_default_str();
  BallDrop drop;
  std::vector<double> elevations{90, 5};
  auto* dr = app.add_subcommand("drop", "ground-to-ball relative intensity for every ball and ground material");
  dr->add_option("--radius", drop.ball_radius_m, "ball radius [m]")->capture_default_str();
  dr->add_option("--height", drop.drop_height_m, "drop height [m]")->capture_default_str();
  dr->add_option("--distance", drop.distance_m, "listener distance [m]")->capture_default_str();
  dr->add_option("--contact-time", drop.contact_time_s, "contact time t_c [s]")->capture_default_str();
  dr->add_option("--restitution", drop.restitution, "coefficient of restitution")->capture_default_str();
  dr->add_option("--elevations", elevations, "listener elevations [deg]")->capture_default_str();
  try {
    app.parse(argc, argv);
    if (resp->parsed()) print_response(nu, cs, r, eps, t_end, n);
    if (dr->parsed()) print_drop(drop, elevations);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clatter-ground-study: %s\n", e.what());
    return 2;
  }
  return 0;
}
