// 004's trends for a ball dropped on the ground (kernels/ground/drop_study.hpp): at a fixed drop
// height the ground's sound scales as rho_ball / E_ground while the ball's does not change, and a
// listener at a lower elevation hears relatively more ground. Coarse quadrature (the trends are
// exact scalings or large ratios; the table's accuracy is studied in test_ground_response.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "kernels/ground/drop_study.hpp"
#include "tests/unit/make_material.hpp"

using namespace clatter::kernels::ground;
using clatter::test::ground;

namespace {

constexpr double kPi = std::numbers::pi;

BallDrop steel_ball(double elevation_deg) {
  BallDrop d;
  d.elevation_rad = elevation_deg * kPi / 180;
  return d;
}

const clatter::model::Material kConcrete = ground(2.4e10, 0.2, 2400);

}  // namespace

TEST(DropStudy, GroundScalesWithBallDensityBallSoundDoesNot) {
  BallDrop light = steel_ball(90), heavy = light;
  heavy.ball_density_kg_m3 = 2 * light.ball_density_kg_m3;
  const DropSound a = drop_sound(light, kConcrete, 4), b = drop_sound(heavy, kConcrete, 4);
  EXPECT_NEAR(b.ground_peak_pa / a.ground_peak_pa, 2.0, 1e-12);
  EXPECT_NEAR(b.ground_energy_pa2_s / a.ground_energy_pa2_s, 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(b.ball_energy_pa2_s, a.ball_energy_pa2_s);
}

TEST(DropStudy, GroundScalesInverselyWithGroundStiffness) {
  // Twice E and twice the density: the same c_s, nu, so the same phi and eta; only mu doubles.
  const clatter::model::Material stiff = ground(4.8e10, 0.2, 4800);
  const BallDrop d = steel_ball(30);
  const DropSound a = drop_sound(d, kConcrete, 4), b = drop_sound(d, stiff, 4);
  EXPECT_NEAR(a.ground_peak_pa / b.ground_peak_pa, 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(b.ball_energy_pa2_s, a.ball_energy_pa2_s);
}

TEST(DropStudy, LowerElevationHearsRelativelyMoreGround) {
  const DropSound up = drop_sound(steel_ball(90), kConcrete, 4), low = drop_sound(steel_ball(5), kConcrete, 4);
  std::printf("steel ball on concrete: ground/ball %.2f dB overhead, %.2f dB at 5 degrees\n", up.relative_db(), low.relative_db());
  EXPECT_GT(low.relative_db(), up.relative_db() + 6);  // the ball's dipole alone loses 21 dB at 5 degrees
}

TEST(DropStudy, BallDipoleFarField) {
  // Far away the ball's sound is its dipole rho0 a^3 sin(el) U''/(c0 D), doubled by its image.
  BallDrop d = steel_ball(90);
  d.distance_m = 1000;
  const double t = d.distance_m / d.c0_m_s + 1e-9, dv = std::sqrt(2 * 9.81 * d.drop_height_m);
  const double far = d.rho0_kg_m3 * std::pow(d.ball_radius_m, 3) * kPi * kPi * dv / (2 * std::pow(d.contact_time_s, 2)) /
                     (d.c0_m_s * d.distance_m);
  EXPECT_NEAR(ball_pressure(d, t), far, 1e-4 * far);
}

TEST(DropStudy, BadInput) {
  BallDrop d = steel_ball(90);
  d.elevation_rad = 0;
  EXPECT_THROW(drop_sound(d, kConcrete), std::invalid_argument);
  d = steel_ball(90);
  d.contact_time_s = 0;
  EXPECT_THROW(drop_sound(d, kConcrete), std::invalid_argument);
  EXPECT_THROW(drop_sound(steel_ball(90), ground(0, 0.2, 2400)), std::invalid_argument);
}
