// Settling during idle time, Eq. 5.1–5.5, Tables 5.3–5.5.
#include "mrd/physics/settling.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mrd/units.hpp"

namespace mrd::physics {
namespace {

// Eq. 5.1 by hand with Table 5.3: 9.81 · (5e−6)² · (7870 − 820) / (18 · 2.0)
//   = 9.81 · 25e−12 · 7050 / 36 = 4.80281e−8 m/s
TEST(Settling, StokesVelocityTable53) {
  EXPECT_NEAR(stokes_velocity_m_s({}), 4.80281e-8, 1e-12);
}

// Stokes' law needs Re_p = ρ_l V_t d_p / η < 0.3 (thesis §5.1.1); here it is
// 820 · 4.8e−8 · 5e−6 / 2 ≈ 1e−10.
TEST(Settling, StokesRegimeHolds) {
  const SettlingParams p;
  const double re = p.liquid_density_kg_m3 * stokes_velocity_m_s(p) * p.particle_diameter_m / p.viscosity_pa_s;
  EXPECT_LT(re, 0.3);
}

// Eq. 5.2: (1 − 0.4)^4.65 = exp(4.65 · ln 0.6) = exp(−2.375339) = 0.0929825
//   V_ts = 4.80281e−8 · 0.0929825 = 4.46578e−9 m/s
TEST(Settling, HinderedVelocity) {
  EXPECT_NEAR(hindered_velocity_m_s({}), 4.46578e-9, 2e-13);
}

TEST(Settling, CircularSegmentArea) {
  const double r = 0.1;
  EXPECT_DOUBLE_EQ(circular_segment_area_m2(r, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(circular_segment_area_m2(r, -1.0), 0.0);
  EXPECT_NEAR(circular_segment_area_m2(r, r), 0.5 * units::kPi * r * r, 1e-15);
  EXPECT_NEAR(circular_segment_area_m2(r, 2 * r), units::kPi * r * r, 1e-15);
  EXPECT_NEAR(circular_segment_area_m2(r, 5 * r), units::kPi * r * r, 1e-15);
}

// Table 5.5: max height of settled solids 0.0831 m, height to bottom of
// shaft 0.0616 m (= R − r_s = 0.1016 − 0.04), solid around shaft 0.0215 m,
// volume 0.00665 m³ (40 % of 0.0166 m³).
TEST(Settling, SettledLayerHeightTable55) {
  const SettlingParams p;
  const double h = settled_layer_height_m(p);
  EXPECT_NEAR(h, 0.0831, 0.0005);
  const double shaft_bottom = 0.5 * p.inner_diameter_m - p.shaft_radius_m;
  EXPECT_NEAR(shaft_bottom, 0.0616, 1e-12);
  EXPECT_NEAR(h - shaft_bottom, 0.0215, 0.0005);
  EXPECT_NEAR(settled_volume_m3(p, h), 0.4 * 0.0166, 1e-9);
}

// The shaft is what lifts the layer: without it the same volume fills only
// to a lower height.
TEST(Settling, ShaftRaisesTheLayer) {
  SettlingParams no_shaft;
  no_shaft.shaft_radius_m = 0.0;
  EXPECT_LT(settled_layer_height_m(no_shaft), settled_layer_height_m({}) - 0.003);
}

// Eq. 5.4; thesis §6.5: 0.8531 years. Within 0.5 %.
TEST(Settling, MaxSettlingTimeThesis) {
  const double years = units::s_to_years(max_settling_time_s({}));
  EXPECT_NEAR(years, 0.8531, 0.005 * 0.8531);
}

// Eq. 5.5 as a fraction, saturating at 1 past the maximum settling time.
TEST(Settling, SettlingQuotientSaturates) {
  const double tmax = units::years_to_s(0.8531);
  EXPECT_DOUBLE_EQ(settling_quotient(0.0, tmax), 0.0);
  EXPECT_DOUBLE_EQ(settling_quotient(-5.0, tmax), 0.0);
  EXPECT_NEAR(settling_quotient(units::years_to_s(0.25), tmax), 0.25 / 0.8531, 1e-12);
  EXPECT_DOUBLE_EQ(settling_quotient(tmax, tmax), 1.0);
  EXPECT_DOUBLE_EQ(settling_quotient(units::years_to_s(0.9), tmax), 1.0);
  EXPECT_DOUBLE_EQ(settling_quotient(units::years_to_s(2.5), tmax), 1.0);
}

// SQ after an idle time with the fluid's own maximum settling time (Eq. 5.4:
// 0.8531 years in the thesis, within 0.5 %): none idle is fully mixed, half of
// T_max is half settled, T_max and beyond is fully settled.
TEST(Settling, SettlingQuotientAfterIdle) {
  const SettlingParams p;
  const double tmax = max_settling_time_s(p);
  EXPECT_NEAR(units::s_to_years(tmax), 0.8531, 0.005 * 0.8531);
  EXPECT_DOUBLE_EQ(settling_quotient_after_idle(0.0, p), 0.0);
  EXPECT_DOUBLE_EQ(settling_quotient_after_idle(-5.0, p), 0.0);
  EXPECT_DOUBLE_EQ(settling_quotient_after_idle(0.5 * tmax, p), 0.5);
  EXPECT_NEAR(settling_quotient_after_idle(units::years_to_s(0.25), p), 0.25 / 0.8531, 0.005 * 0.25 / 0.8531);
  EXPECT_DOUBLE_EQ(settling_quotient_after_idle(tmax, p), 1.0);
  EXPECT_DOUBLE_EQ(settling_quotient_after_idle(units::years_to_s(0.9), p), 1.0);
  EXPECT_DOUBLE_EQ(settling_quotient_after_idle(units::years_to_s(2.5), p), 1.0);
  // The same as Eq. 5.5 with Eq. 5.4 written out.
  EXPECT_EQ(settling_quotient_after_idle(units::years_to_s(0.4), p), settling_quotient(units::years_to_s(0.4), tmax));
}

// The maximum settling time scales with viscosity (Eq. 5.1: V_t ∝ 1/η), as
// §6.5 says: doubling η doubles it.
TEST(Settling, MaxSettlingTimeScalesWithViscosity) {
  SettlingParams thick;
  thick.viscosity_pa_s = 4.0;
  EXPECT_NEAR(max_settling_time_s(thick), 2.0 * max_settling_time_s({}), 1e-6 * max_settling_time_s({}));
}

}  // namespace
}  // namespace mrd::physics
