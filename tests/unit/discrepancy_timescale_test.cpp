// How fast a record moves, and the smoothing window that follows it
// (motion_timescale.hpp). Expected values from the sines' closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "host_sim/discrepancy/damper_model.hpp"
#include "host_sim/discrepancy/motion_timescale.hpp"
#include "mrd/units.hpp"

namespace mrd::discrepancy {
namespace {

constexpr double kPi = units::kPi;

MeasuredData sine_record(double amplitude_m, double freq_hz, double duration_s, double rate_hz) {
  MeasuredData d;
  d.source = "sine";
  const auto n = static_cast<std::size_t>(duration_s * rate_hz);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    d.time_s.push_back(t);
    d.displacement_m.push_back(amplitude_m * std::sin(2.0 * kPi * freq_hz * t));
    d.current_cmd_a.push_back(0.0);
    d.force_n.push_back(0.0);
  }
  return d;
}

// sin(2π·2 t) over 2 s at 1 kHz: it first leaves the ±10 % band upwards at
// t0 = asin(0.1)/(4π) = 7.97 ms (no crossing: nothing before), then crosses
// at 0.25 k + t0 (first sample at or after), k = 1 … 7; 8 would be past 2 s.
TEST(MotionTimescale, CrossingsOfASine) {
  const MeasuredData d = sine_record(0.01, 2.0, 2.0, 1000.0);
  const std::vector<double> c = mean_crossings_s(d.time_s, d.displacement_m);
  ASSERT_EQ(c.size(), 7u);
  const double t0 = std::asin(0.1) / (4.0 * kPi);
  for (std::size_t k = 0; k < c.size(); ++k) EXPECT_NEAR(c[k], 0.25 * static_cast<double>(k + 1) + t0, 1e-3) << k;
  EXPECT_NEAR(dominant_frequency_hz(d.time_s, d.displacement_m), 2.0, 0.01);
}

// The window is a tenth of the shortest period (crossings are one sample,
// 1 ms, from exact: 2 × 1 ms × 0.1 = 0.2 ms), and never above the cap.
TEST(MotionTimescale, WindowFollowsTheShortestPeriod) {
  const MeasuredData fast = sine_record(0.002, 5.0, 3.0, 1000.0);
  EXPECT_NEAR(smoothing_half_window_for(fast.time_s, fast.displacement_m, 0.075), 0.1 / 5.0, 2e-4);
  const MeasuredData chirp_top = sine_record(0.001, 20.0, 2.0, 1000.0);
  EXPECT_NEAR(smoothing_half_window_for(chirp_top.time_s, chirp_top.displacement_m, 0.075), 0.1 / 20.0, 2e-4);
  const MeasuredData slow = sine_record(0.025, 0.25, 12.0, 200.0);  // 0.1 × 4 s = 0.4 s > cap
  EXPECT_DOUBLE_EQ(smoothing_half_window_for(slow.time_s, slow.displacement_m, 0.075), 0.075);
  MeasuredData still = sine_record(0.0, 1.0, 2.0, 1000.0);  // no motion, no crossing
  EXPECT_DOUBLE_EQ(smoothing_half_window_for(still.time_s, still.displacement_m, 0.075), 0.075);
}

// One brief dip in a 2 Hz sine (a stroke interrupted for 30 ms at t = 1.1 s,
// where the sine is at 0.95 of its amplitude, by a pulse 1.2 amplitudes deep
// that takes it through the band around the mean and back) cuts one of the
// record's half periods of 250 ms into three: up to the dip, the dip itself
// (about 30 ms), and on to the next crossing. The window follows
// the motion's period, a tenth of 0.5 s, not the dip: sized to the shortest
// interval it would be about 0.2 × 30 ms = 6 ms, and the sensor's noise on
// the whole record would pass almost unsmoothed.
TEST(MotionTimescale, WindowIgnoresARareShortInterval) {
  MeasuredData d = sine_record(0.01, 2.0, 10.0, 1000.0);
  for (std::size_t k = 0; k < d.time_s.size(); ++k) {
    if (std::fabs(d.time_s[k] - 1.1) <= 0.015) d.displacement_m[k] -= 0.012;
  }
  const std::vector<double> c = mean_crossings_s(d.time_s, d.displacement_m);
  double shortest_s = 1.0;
  for (std::size_t k = 1; k < c.size(); ++k) shortest_s = std::min(shortest_s, c[k] - c[k - 1]);
  ASSERT_LT(shortest_s, 0.04) << "the dip must cross the band";
  // An interval is within one sample (1 ms) of 250 ms: 0.2 × 1 ms, and the rounding of the time stamps' difference.
  EXPECT_NEAR(smoothing_half_window_for(d.time_s, d.displacement_m, 0.075), 0.1 / 2.0, 2e-4 + 1e-12);
}

// A linear chirp 1 → 20 Hz over 4 s, 1 mm, at 1 kHz: x = A sin φ,
// φ = 2π (f0 t + ½ k t²), v = A φ' cos φ. The derived velocity follows the
// analytic one to within 1 % of the local amplitude A φ' everywhere away
// from the ends (±75 ms of smoothing would pass 6 % of it at 20 Hz: a
// quartic least-squares fit of a sine over ±1.5 periods).
TEST(MotionTimescale, ModelInputFollowsAChirp) {
  const double a = 0.001, f0 = 1.0, f1 = 20.0, dur = 4.0, k = (f1 - f0) / dur;
  MeasuredData d;
  d.source = "chirp";
  for (int i = 0; i < 4000; ++i) {
    const double t = i * 1e-3;
    d.time_s.push_back(t);
    d.displacement_m.push_back(a * std::sin(2.0 * kPi * (f0 * t + 0.5 * k * t * t)));
    d.current_cmd_a.push_back(0.0);
    d.force_n.push_back(0.0);
  }
  const ModelInput in = model_input(d);
  ASSERT_TRUE(in.velocity_derived);
  for (std::size_t i = 100; i < 3900; i += 7) {
    const double t = d.time_s[i];
    const double dphi = 2.0 * kPi * (f0 + k * t);
    const double v = a * dphi * std::cos(2.0 * kPi * (f0 * t + 0.5 * k * t * t));
    EXPECT_NEAR(in.vel_m_s[i], v, 0.01 * a * dphi) << "t = " << t;
  }
}

}  // namespace
}  // namespace mrd::discrepancy
