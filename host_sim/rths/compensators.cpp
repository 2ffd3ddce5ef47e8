#include "host_sim/rths/compensators.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrd::rths {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The last four samples of a signal, newest first, with backward-difference
/// derivatives: ẋ second order, ẍ second order, x⃛ first order.
class History {
 public:
  explicit History(double dt_s) : dt_s_(dt_s) {}
  void push(double x) {
    if (count_ == 0) v_.fill(x);  // start from rest at the first value
    for (int i = 3; i > 0; --i) v_[i] = v_[i - 1];
    v_[0] = x;
    ++count_;
  }
  double at(int back) const { return v_[static_cast<std::size_t>(back)]; }
  std::array<double, 4> derivatives() const {
    const double h = dt_s_;
    return {v_[0], (3.0 * v_[0] - 4.0 * v_[1] + v_[2]) / (2.0 * h),
            (2.0 * v_[0] - 5.0 * v_[1] + 4.0 * v_[2] - v_[3]) / (h * h),
            (v_[0] - 3.0 * v_[1] + 3.0 * v_[2] - v_[3]) / (h * h * h)};
  }

 private:
  double dt_s_;
  std::array<double, 4> v_{};
  long count_ = 0;
};

/// The critically damped third-order low-pass ω³/(s + ω)³ in the
/// controllable form whose states are the output and its first two
/// derivatives (exact, no differencing), discretized by exact ZOH.
class DerivativeFilter {
 public:
  DerivativeFilter(double corner_hz, double dt_s) {
    const double w = 2.0 * kPi * corner_hz;
    ContinuousSystem s;
    s.a = Matrix::Zero(3, 3);
    s.a(0, 1) = 1.0;
    s.a(1, 2) = 1.0;
    s.a(2, 0) = -w * w * w;
    s.a(2, 1) = -3.0 * w * w;
    s.a(2, 2) = -3.0 * w;
    s.b = Matrix::Zero(3, 1);
    s.b(2, 0) = w * w * w;
    s.c = Matrix::Identity(3, 3);
    s.d = Matrix::Zero(3, 1);
    const DiscreteSystem d = zero_order_hold(s, dt_s);
    phi_ = d.phi;
    gamma_ = d.gamma.col(0);
    z_.setZero();
  }
  /// Feeds one sample; returns [y, ẏ, ÿ] after it.
  const Eigen::Vector3d& push(double u) {
    z_ = phi_ * z_ + gamma_ * u;
    return z_;
  }

 private:
  Eigen::Matrix3d phi_;
  Eigen::Vector3d gamma_;
  Eigen::Vector3d z_;
};

class NoCompensation final : public Compensator {
 public:
  double command(double target_m, double) override { return target_m; }
};

/// Phase lead on the target, then a PI on (lead output − measured).
class SampleController final : public Compensator {
 public:
  explicit SampleController(double dt_s) : dt_s_(dt_s), lead_(lead(dt_s)) {}
  double command(double target_m, double measured_m) override {
    const double led = lead_.step(target_m);
    // The measurement now answers the previous lead output.
    const double error = previous_led_ - measured_m;
    integral_ += kKi * error * dt_s_;
    previous_led_ = led;
    return led + kKp * error + integral_;
  }
  std::vector<std::string> coefficient_names() const override { return {"pi_integral_m"}; }
  std::vector<double> coefficients() const override { return {integral_}; }
  void write_coefficients(double* out) const noexcept override { out[0] = integral_; }

 private:
  static constexpr double kKp = 2.0;
  static constexpr double kKi = 95.0;
  /// (b1 s + b0)/(s + a0) = b1 + (b0 − b1·a0)/(s + a0).
  static DiscreteSystem lead(double dt_s) {
    const double b1 = 50.8316, b0 = 8570.397, a0 = 8570.397;
    ContinuousSystem s;
    s.a = Matrix::Constant(1, 1, -a0);
    s.b = Matrix::Constant(1, 1, 1.0);
    s.c = Matrix::Constant(1, 1, b0 - b1 * a0);
    s.d = Matrix::Constant(1, 1, b1);
    return zero_order_hold(s, dt_s);
  }
  double dt_s_;
  DiscreteBlock lead_;
  double previous_led_ = 0.0;
  double integral_ = 0.0;
};

/// Third-order polynomial extrapolation τ ahead (Lagrange through the
/// samples at 0, −1, −2, −3 steps, evaluated at n = τ/Δt).
class PolynomialExtrapolation final : public Compensator {
 public:
  PolynomialExtrapolation(double dt_s, double delay_s) : history_(dt_s), delay_s_(delay_s) {
    const double n = delay_s / dt_s;
    const std::array<double, 4> nodes{0.0, -1.0, -2.0, -3.0};
    for (int j = 0; j < 4; ++j) {
      double w = 1.0;
      for (int m = 0; m < 4; ++m)
        if (m != j) w *= (n - nodes[m]) / (nodes[j] - nodes[m]);
      weights_[static_cast<std::size_t>(j)] = w;
    }
  }
  double command(double target_m, double) override {
    history_.push(target_m);
    double u = 0.0;
    for (int j = 0; j < 4; ++j) u += weights_[static_cast<std::size_t>(j)] * history_.at(j);
    return u;
  }
  std::vector<std::string> coefficient_names() const override { return {"delay_s"}; }
  std::vector<double> coefficients() const override { return {delay_s_}; }
  void write_coefficients(double* out) const noexcept override { out[0] = delay_s_; }

 private:
  History history_;
  double delay_s_;
  std::array<double, 4> weights_{};
};

/// The filtered pairs (command, measured derivatives) both adaptive
/// compensators learn from: the command issued one step ago against the
/// displacement measured now.
class FilteredPairs {
 public:
  FilteredPairs(double corner_hz, double dt_s) : u_(corner_hz, dt_s), x_(corner_hz, dt_s) {}
  void push(double previous_command_m, double measured_m) {
    uf_ = u_.push(previous_command_m)(0);
    xf_ = x_.push(measured_m);
  }
  double command() const { return uf_; }
  const Eigen::Vector3d& measured() const { return xf_; }

 private:
  DerivativeFilter u_, x_;
  double uf_ = 0.0;
  Eigen::Vector3d xf_ = Eigen::Vector3d::Zero();
};

/// Coefficient bounds and per-update rate limits shared by the adaptive
/// compensators: a0 within ±25 % of unity; a1 (s) a delay of 0–60 ms; a2
/// (s²) within ±2e-3 (a 60 ms delay's τ²/2 is 1.8e-3). Per update (10 ms):
/// a0 by 0.01, a1 by 0.2 ms, a2 by 1e-5 s² at most.
constexpr std::array<double, 3> kLow{0.75, 0.0, -2e-3};
constexpr std::array<double, 3> kHigh{1.25, 0.06, 2e-3};
constexpr std::array<double, 3> kMaxChangePerUpdate{0.01, 2e-4, 1e-5};

/// Adaptive time series (Chae et al. 2013).
class AdaptiveTimeSeries final : public Compensator {
 public:
  explicit AdaptiveTimeSeries(const CompensatorSpec& s)
      : spec_(s),
        history_(s.dt_s),
        pairs_(s.filter_hz, s.dt_s),
        window_(std::max<long>(16, std::lround(s.window_s / s.dt_s))),
        update_every_(std::max<long>(1, std::lround(s.update_s / s.dt_s))) {
    for (int i = 0; i < 3; ++i) a_[static_cast<std::size_t>(i)] = std::clamp(s.plant.c[static_cast<std::size_t>(i)], kLow[i], kHigh[i]);
    r_.setZero();
    p_.setZero();
    // Column scales: a displacement, a velocity and an acceleration at 5 Hz.
    const double w = 2.0 * kPi * 5.0;
    scale_ << 1.0, 1.0 / w, 1.0 / (w * w);
  }

  double command(double target_m, double measured_m) override {
    pairs_.push(last_command_, measured_m);
    learn();
    history_.push(target_m);
    const auto d = history_.derivatives();
    last_command_ = a_[0] * d[0] + a_[1] * d[1] + a_[2] * d[2];
    return last_command_;
  }
  std::vector<std::string> coefficient_names() const override { return {"a0", "a1_s", "a2_s2"}; }
  std::vector<double> coefficients() const override { return {a_[0], a_[1], a_[2]}; }
  void write_coefficients(double* out) const noexcept override {
    for (std::size_t i = 0; i < 3; ++i) out[i] = a_[i];
  }

 private:
  void learn() {
    const Eigen::Vector3d phi = pairs_.measured().cwiseProduct(scale_);
    const double y = pairs_.command();
    r_ += phi * phi.transpose();
    p_ += phi * y;
    ring_.push_back({phi, y});
    if (static_cast<long>(ring_.size()) > window_) {
      const auto& [old_phi, old_y] = ring_.front();
      r_ -= old_phi * old_phi.transpose();
      p_ -= old_phi * old_y;
      ring_.pop_front();
    }
    if (++since_update_ < update_every_ || static_cast<long>(ring_.size()) < window_) return;
    since_update_ = 0;
    const double rms_m = std::sqrt(std::max(r_(0, 0), 0.0) / static_cast<double>(ring_.size()));
    if (rms_m < 10.0 * spec_.noise_m) return;  // too little motion to learn from
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(r_);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return;
    const Eigen::Vector3d scaled = ldlt.solve(p_);
    if (!scaled.allFinite()) return;
    for (int i = 0; i < 3; ++i) {
      const double want = std::clamp(scaled(i) * scale_(i), kLow[i], kHigh[i]);
      const double step = std::clamp(want - a_[static_cast<std::size_t>(i)], -kMaxChangePerUpdate[i], kMaxChangePerUpdate[i]);
      a_[static_cast<std::size_t>(i)] += step;
    }
  }

  CompensatorSpec spec_;
  History history_;
  FilteredPairs pairs_;
  long window_;
  long update_every_;
  long since_update_ = 0;
  std::array<double, 3> a_{};
  Eigen::Matrix3d r_;
  Eigen::Vector3d p_;
  Eigen::Vector3d scale_;
  std::deque<std::pair<Eigen::Vector3d, double>> ring_;
  double last_command_ = 0.0;
};

/// Model-based feedforward from the identified plant, c0..c2 adapted by a
/// normalized gradient (NLMS) step on the filtered relation.
class ModelFeedforward final : public Compensator {
 public:
  explicit ModelFeedforward(const CompensatorSpec& s)
      : spec_(s), history_(s.dt_s), pairs_(s.filter_hz, s.dt_s), c_(s.plant.c) {
    const double w = 2.0 * kPi * 5.0;
    scale_ << 1.0, 1.0 / w, 1.0 / (w * w);
    // A gradient step whose memory is about one window.
    mu_ = std::min(1.0, s.dt_s / s.window_s);
  }
  double command(double target_m, double measured_m) override {
    pairs_.push(last_command_, measured_m);
    adapt();
    history_.push(target_m);
    const auto d = history_.derivatives();
    last_command_ = c_[0] * d[0] + c_[1] * d[1] + c_[2] * d[2] + c_[3] * d[3];
    return last_command_;
  }
  std::vector<std::string> coefficient_names() const override { return {"c0", "c1_s", "c2_s2", "c3_s3"}; }
  std::vector<double> coefficients() const override { return {c_[0], c_[1], c_[2], c_[3]}; }
  void write_coefficients(double* out) const noexcept override {
    for (std::size_t i = 0; i < 4; ++i) out[i] = c_[i];
  }

 private:
  void adapt() {
    const Eigen::Vector3d phi = pairs_.measured().cwiseProduct(scale_);
    const double norm2 = phi.squaredNorm();
    const double floor2 = 100.0 * spec_.noise_m * spec_.noise_m;  // (10 σ)²
    if (norm2 < floor2) return;
    const double predicted = c_[0] * pairs_.measured()(0) + c_[1] * pairs_.measured()(1) + c_[2] * pairs_.measured()(2);
    const double error = pairs_.command() - predicted;
    for (int i = 0; i < 3; ++i) {
      const double scaled = c_[static_cast<std::size_t>(i)] / scale_(i) + mu_ * error * phi(i) / norm2;
      c_[static_cast<std::size_t>(i)] = std::clamp(scaled * scale_(i), kLow[i], kHigh[i]);
    }
  }
  CompensatorSpec spec_;
  History history_;
  FilteredPairs pairs_;
  std::array<double, 4> c_;
  Eigen::Vector3d scale_;
  double mu_;
  double last_command_ = 0.0;
};

}  // namespace

const char* compensator_name(CompensatorKind k) {
  switch (k) {
    case CompensatorKind::kNone: return "none";
    case CompensatorKind::kSample: return "sample";
    case CompensatorKind::kPolynomial: return "polynomial";
    case CompensatorKind::kAdaptive: return "adaptive";
    case CompensatorKind::kModel: return "model";
  }
  return "?";
}

bool compensator_from_name(const std::string& name, CompensatorKind& out) {
  for (const CompensatorKind k : {CompensatorKind::kNone, CompensatorKind::kSample, CompensatorKind::kPolynomial,
                                  CompensatorKind::kAdaptive, CompensatorKind::kModel})
    if (name == compensator_name(k)) {
      out = k;
      return true;
    }
  return false;
}

InverseExpansion inverse_expansion(const ContinuousSystem& g, int out) {
  const Eigen::PartialPivLU<Matrix> lu(g.a);
  std::array<double, 4> m{};
  Matrix v = g.b;
  for (int i = 0; i < 4; ++i) {
    v = lu.solve(v);  // A^{−(i+1)} B
    m[static_cast<std::size_t>(i)] = -(g.c.row(out) * v)(0);
  }
  m[0] += g.d(out, 0);
  if (!(std::fabs(m[0]) > 0.0)) throw std::invalid_argument("inverse_expansion: the plant has no DC gain");
  InverseExpansion h;
  h.c[0] = 1.0 / m[0];
  for (int n = 1; n < 4; ++n) {
    double s = 0.0;
    for (int j = 1; j <= n; ++j) s += m[static_cast<std::size_t>(j)] * h.c[static_cast<std::size_t>(n - j)];
    h.c[static_cast<std::size_t>(n)] = -s / m[0];
  }
  return h;
}

std::unique_ptr<Compensator> make_compensator(const CompensatorSpec& spec) {
  switch (spec.kind) {
    case CompensatorKind::kNone: return std::make_unique<NoCompensation>();
    case CompensatorKind::kSample: return std::make_unique<SampleController>(spec.dt_s);
    case CompensatorKind::kPolynomial:
      // The held command already leads by half a step (the ZOH of a target
      // one step ahead), so the extrapolation covers the rest of the delay.
      return std::make_unique<PolynomialExtrapolation>(spec.dt_s, spec.plant.c[1] / spec.plant.c[0] - 0.5 * spec.dt_s);
    case CompensatorKind::kAdaptive: return std::make_unique<AdaptiveTimeSeries>(spec);
    case CompensatorKind::kModel: return std::make_unique<ModelFeedforward>(spec);
  }
  throw std::invalid_argument("make_compensator: unknown kind");
}

}  // namespace mrd::rths
