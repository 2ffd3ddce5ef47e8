#include "host_sim/excitation/synthetic_motion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::excitation {
using io::UsageError;

namespace {

constexpr std::size_t kStates = 4;    // x_g, ẋ_g, x_f, ẋ_f
constexpr std::size_t kAugmented = 5; // states + the held noise input
using Matrix = std::array<std::array<double, kAugmented>, kAugmented>;

/// Warm-up length in slowest filter time constants 1/(ζω), and its cap.
constexpr double kWarmUpTimeConstants = 10.0;
constexpr double kMaxWarmUp_s = 200.0;
constexpr double kMaxSamples = 1e9;
constexpr double kMaxWarmUpSteps = 1e7;

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (std::size_t i = 0; i < kAugmented; ++i) {
    for (std::size_t k = 0; k < kAugmented; ++k) {
      for (std::size_t j = 0; j < kAugmented; ++j) c[i][j] += a[i][k] * b[k][j];
    }
  }
  return c;
}

/// e^M by scaling and squaring: M/2^s has 1-norm ≤ 0.5, then an 18-term
/// Taylor series (truncation below 0.5^19/19! ≈ 1.6e-23), squared s times.
Matrix matrix_exponential(Matrix m) {
  double norm = 0.0;
  for (std::size_t j = 0; j < kAugmented; ++j) {
    double column = 0.0;
    for (std::size_t i = 0; i < kAugmented; ++i) column += std::abs(m[i][j]);
    norm = std::max(norm, column);
  }
  if (!std::isfinite(norm)) throw UsageError("synthetic motion: filter parameters overflow at this time step");
  int squarings = 0;
  while (norm > 0.5) {
    norm *= 0.5;
    ++squarings;
  }
  const double scale = std::ldexp(1.0, -squarings);
  for (auto& row : m) {
    for (double& v : row) v *= scale;
  }
  Matrix result{};
  Matrix term{};
  for (std::size_t i = 0; i < kAugmented; ++i) result[i][i] = term[i][i] = 1.0;
  for (int n = 1; n <= 18; ++n) {
    term = multiply(term, m);
    const double inv_n = 1.0 / n;
    for (auto& row : term) {
      for (double& v : row) v *= inv_n;
    }
    for (std::size_t i = 0; i < kAugmented; ++i) {
      for (std::size_t j = 0; j < kAugmented; ++j) result[i][j] += term[i][j];
    }
  }
  for (int s = 0; s < squarings; ++s) result = multiply(result, result);
  return result;
}

/// x[k+1] = Φ x[k] + Γ w[k],  y[k] = C x[k].
struct DiscreteFilter {
  std::array<std::array<double, kStates>, kStates> phi{};
  std::array<double, kStates> gamma{};
  std::array<double, kStates> c{};
};

DiscreteFilter discretize(const SyntheticMotionParams& p) {
  const double wg = p.ground_frequency_rad_s;
  const double zg = p.ground_damping_ratio;
  // Without the high-pass the x_f states still run (driven, stable) but do
  // not reach the output.
  const double wf = p.high_pass ? p.high_pass_frequency_rad_s : 1.0;
  const double zf = p.high_pass ? p.high_pass_damping_ratio : 1.0;
  const double dt = p.dt_s;

  // Augmented [A B; 0 0]·dt, so that e^(that) = [Φ Γ; 0 1].
  Matrix m{};
  m[0][1] = dt;
  m[1][0] = -wg * wg * dt;
  m[1][1] = -2.0 * zg * wg * dt;
  m[1][4] = -dt;  // −w drives the soil column
  m[2][3] = dt;
  m[3][0] = wg * wg * dt;  // −a_KT drives the high-pass stage
  m[3][1] = 2.0 * zg * wg * dt;
  m[3][2] = -wf * wf * dt;
  m[3][3] = -2.0 * zf * wf * dt;
  const Matrix e = matrix_exponential(m);

  DiscreteFilter f;
  for (std::size_t i = 0; i < kStates; ++i) {
    for (std::size_t j = 0; j < kStates; ++j) f.phi[i][j] = e[i][j];
    f.gamma[i] = e[i][kStates];
  }
  if (p.high_pass) {
    // y = −ẍ_f = ω_f² x_f + 2ζ_f ω_f ẋ_f − ω_g² x_g − 2ζ_g ω_g ẋ_g
    f.c = {-wg * wg, -2.0 * zg * wg, wf * wf, 2.0 * zf * wf};
  } else {
    f.c = {-wg * wg, -2.0 * zg * wg, 0.0, 0.0};  // y = a_KT
  }
  return f;
}

void advance(const DiscreteFilter& f, std::array<double, kStates>& x, double w) {
  std::array<double, kStates> next{};
  for (std::size_t i = 0; i < kStates; ++i) {
    double v = f.gamma[i] * w;
    for (std::size_t j = 0; j < kStates; ++j) v += f.phi[i][j] * x[j];
    next[i] = v;
  }
  x = next;
}

double output(const DiscreteFilter& f, const std::array<double, kStates>& x) {
  double y = 0.0;
  for (std::size_t j = 0; j < kStates; ++j) y += f.c[j] * x[j];
  return y;
}

std::string format_short(double value) { return io::format_number("%.6g", value); }

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

void require_positive(double v, const char* what) {
  if (!positive(v)) {
    throw UsageError(std::string("synthetic motion: ") + what + " must be a positive number, got " + format_short(v));
  }
}

void validate(const SyntheticMotionParams& p) {
  require_positive(p.dt_s, "time step dt_s");
  require_positive(p.duration_s, "duration_s");
  require_positive(p.target_pga_m_s2, "target PGA (m/s^2)");
  require_positive(p.ground_frequency_rad_s, "Kanai-Tajimi frequency omega_g (rad/s)");
  require_positive(p.ground_damping_ratio, "Kanai-Tajimi damping ratio zeta_g");
  if (p.high_pass) {
    require_positive(p.high_pass_frequency_rad_s, "Clough-Penzien frequency omega_f (rad/s)");
    require_positive(p.high_pass_damping_ratio, "Clough-Penzien damping ratio zeta_f");
  }
  const double nyquist_rad_s = units::kPi / p.dt_s;
  if (p.ground_frequency_rad_s >= nyquist_rad_s) {
    throw UsageError("synthetic motion: Kanai-Tajimi frequency omega_g (" + format_short(p.ground_frequency_rad_s) +
                     " rad/s) must be below the Nyquist frequency pi/dt (" + format_short(nyquist_rad_s) + " rad/s)");
  }
  if (!std::isfinite(p.rise_time_s) || p.rise_time_s < 0.0) {
    throw UsageError("synthetic motion: envelope rise time t1 must be >= 0 s, got " + format_short(p.rise_time_s));
  }
  if (!std::isfinite(p.plateau_end_s) || p.plateau_end_s < p.rise_time_s) {
    throw UsageError("synthetic motion: envelope plateau end t2 (" + format_short(p.plateau_end_s) +
                     " s) must not come before the rise time t1 (" + format_short(p.rise_time_s) + " s)");
  }
  if (!std::isfinite(p.decay_rate_1_s) || p.decay_rate_1_s < 0.0) {
    throw UsageError("synthetic motion: envelope decay rate must be >= 0 1/s, got " +
                     format_short(p.decay_rate_1_s));
  }
  const double steps = p.duration_s / p.dt_s;
  if (!(steps >= 1.0) || !(steps < kMaxSamples)) {
    throw UsageError("synthetic motion: duration " + format_short(p.duration_s) + " s at dt " +
                     format_short(p.dt_s) + " s must give between 2 and 1e9 samples");
  }
}

std::string describe(const SyntheticMotionParams& p) {
  std::string s = "Kanai-Tajimi filtered white noise (omega_g=" + format_short(p.ground_frequency_rad_s) +
                  " rad/s, zeta_g=" + format_short(p.ground_damping_ratio) + ")";
  if (p.high_pass) {
    s += ", Clough-Penzien high-pass (omega_f=" + format_short(p.high_pass_frequency_rad_s) +
         " rad/s, zeta_f=" + format_short(p.high_pass_damping_ratio) + ")";
  }
  s += ", envelope t1=" + format_short(p.rise_time_s) + " s, t2=" + format_short(p.plateau_end_s) +
       " s, c=" + format_short(p.decay_rate_1_s) + " 1/s, dt=" + format_short(p.dt_s) +
       " s, duration=" + format_short(p.duration_s) + " s, PGA=" + format_short(p.target_pga_m_s2) +
       " m/s^2, seed=" + std::to_string(p.seed);
  return s;
}

}  // namespace

double StandardNormal::next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  constexpr double kTwoToMinus53 = 1.0 / 9007199254740992.0;
  const double u1 = static_cast<double>((engine_() >> 11) + 1) * kTwoToMinus53;  // (0, 1]
  const double u2 = static_cast<double>(engine_() >> 11) * kTwoToMinus53;        // [0, 1)
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * units::kPi * u2;
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

double jennings_envelope(double t_s, const SyntheticMotionParams& params) noexcept {
  if (t_s < 0.0) return 0.0;
  if (t_s < params.rise_time_s) {
    const double r = t_s / params.rise_time_s;
    return r * r;
  }
  if (t_s <= params.plateau_end_s) return 1.0;
  return std::exp(-params.decay_rate_1_s * (t_s - params.plateau_end_s));
}

double filter_power_gain(double omega_rad_s, const SyntheticMotionParams& params) noexcept {
  const double w2 = omega_rad_s * omega_rad_s;
  const double wg2 = params.ground_frequency_rad_s * params.ground_frequency_rad_s;
  const double two_zg_wg = 2.0 * params.ground_damping_ratio * params.ground_frequency_rad_s;
  const double kt = (wg2 * wg2 + two_zg_wg * two_zg_wg * w2) / ((wg2 - w2) * (wg2 - w2) + two_zg_wg * two_zg_wg * w2);
  if (!params.high_pass) return kt;
  const double wf2 = params.high_pass_frequency_rad_s * params.high_pass_frequency_rad_s;
  const double two_zf_wf = 2.0 * params.high_pass_damping_ratio * params.high_pass_frequency_rad_s;
  const double cp = (w2 * w2) / ((wf2 - w2) * (wf2 - w2) + two_zf_wf * two_zf_wf * w2);
  return kt * cp;
}

GroundMotion synthetic_motion(const SyntheticMotionParams& params) {
  validate(params);
  const DiscreteFilter filter = discretize(params);

  double slowest_time_constant_s = 1.0 / (params.ground_damping_ratio * params.ground_frequency_rad_s);
  if (params.high_pass) {
    slowest_time_constant_s = std::max(slowest_time_constant_s,
                                       1.0 / (params.high_pass_damping_ratio * params.high_pass_frequency_rad_s));
  }
  const double warm_up_s = std::min(kWarmUpTimeConstants * slowest_time_constant_s, kMaxWarmUp_s);
  const auto warm_up_steps =
      static_cast<std::size_t>(std::min(std::ceil(warm_up_s / params.dt_s), kMaxWarmUpSteps));

  StandardNormal noise(params.seed);
  std::array<double, kStates> x{};
  for (std::size_t k = 0; k < warm_up_steps; ++k) advance(filter, x, noise.next());

  const auto count = static_cast<std::size_t>(std::floor(params.duration_s / params.dt_s + 1e-9)) + 1;
  GroundMotion motion;
  motion.name = "synthetic-kanai-tajimi(seed=" + std::to_string(params.seed) + ")";
  motion.source = "synthetic: " + describe(params);
  motion.dt_s = params.dt_s;
  motion.accel_m_s2.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double t_s = static_cast<double>(k) * params.dt_s;
    motion.accel_m_s2[k] = jennings_envelope(t_s, params) * output(filter, x);
    advance(filter, x, noise.next());
  }
  return scaled_to_pga(motion, params.target_pga_m_s2);
}

}  // namespace mrd::excitation
