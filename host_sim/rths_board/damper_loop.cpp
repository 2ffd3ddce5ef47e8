#include "host_sim/rths_board/damper_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "firmware/app/periodic_schedule.hpp"
#include "host_sim/rths_board/periodic_run.hpp"
#include "host_sim/plant/stages.hpp"

namespace mrd::rths_board {
namespace {

double checked_damper_loop_dt(const DamperLoopSpec& s) {
  const double dt_s = checked_loop_step_s(s.ground_accel_m_s2.size(), s.rate_hz);
  if (s.building.dampers.size() != 1)
    throw std::invalid_argument("RTHS runtime: the building needs one damper placement (the physical part)");
  return dt_s;
}

}  // namespace

DamperLoop::DamperLoop(hal::CanBus& bus, const DamperLoopSpec& spec, ControlTick control_tick)
    : bus_(bus),
      spec_(spec),
      dt_s_(checked_damper_loop_dt(spec)),
      control_tick_(std::move(control_tick)),
      actuator_model_(spec.delay_s, spec.lag_s, dt_s_) {
  building_.init(spec_.building, dt_s_);
  model_.init(spec_.damper, dt_s_, spec_.settling_quotient);
  element_ = static_cast<int>(spec_.building.dampers.front().element);
  count_ = spec_.building.dampers.front().count;
  const auto& elements = building_.force_elements();
  slot_ = static_cast<std::size_t>(std::lower_bound(elements.begin(), elements.end(), element_) - elements.begin());
  if (spec_.building.isolators.empty())
    predictor_.emplace(spec_.building, building_.linear(), spec_.delay_s, spec_.lag_s);
  else
    isolated_predictor_.emplace(spec_.building, building_, dt_s_, spec_.delay_s, spec_.lag_s);
  forces_.assign(elements.size(), 0.0);
  accel_.assign(static_cast<std::size_t>(building_.linear().dofs()), 0.0);
  const std::size_t n = spec_.ground_accel_m_s2.size();
  for (auto* v : {&target_, &measured_, &force_, &command_, &current_, &base_}) v->reserve(n);
  tick_ns_.reserve(n);
}

void DamperLoop::drain() noexcept {
  hal::CanFrame f;
  while (bus_.receive(f) == hal::CanResult::kOk) {
    protocol::DaqMotion m;
    RthsLabStatus s;
    if (protocol::decode(f, spec_.nodes.daq, m) == protocol::DecodeError::kOk) {
      meas_ = m;
      if (spec_.lab_own_clock ? (k_ == 0 || m.counter != taken_counter_) : m.counter == static_cast<std::uint8_t>(k_ & 0xFF))
        fresh_ = true;
      if (k_ == 0 && m.counter == 0) have_meas0_ = true;
    } else if (decode(f, spec_.lab_node, s) == protocol::DecodeError::kOk) {
      const auto rate = static_cast<std::uint16_t>(spec_.rate_hz + 0.5);
      if (s.rate_hz != rate) lab_rate_mismatch_hz_ = s.rate_hz;
      if (s.state == LabState::kWaiting) lab_waiting_ = true;
      if (s.state == LabState::kStopped && lab_reason_ == LabStopReason::kNone) lab_reason_ = s.stop;
    } else {
      ++rejected_;
    }
  }
}

void DamperLoop::send_accel(std::size_t n) noexcept {
  building_.linear().abs_accel_m_s2(accel_.data());
  protocol::DaqAccel a;
  a.ground_accel_m_s2 = static_cast<float>(n < spec_.ground_accel_m_s2.size() ? spec_.ground_accel_m_s2[n] : 0.0);
  a.base_accel_m_s2 = static_cast<float>(accel_[0]);
  a.counter = static_cast<std::uint8_t>(n & 0xFF);
  hal::CanFrame f;
  if (!protocol::encode(a, spec_.nodes.daq, f) || bus_.send(f) != hal::CanResult::kOk) ++tx_errors_;
}

bool DamperLoop::lab_ready() noexcept {
  if (k_ != 0) return true;
  drain();
  const bool ready = lab_waiting_ && have_meas0_ && lab_rate_mismatch_hz_ == 0;
  if (ready && !sent_accel0_) {
    send_accel(0);
    sent_accel0_ = true;
  }
  return ready;
}

LoopEnd DamperLoop::tick() noexcept {
  if (end_ != LoopEnd::kRunning) return end_;
  drain();
  if (lab_reason_ != LabStopReason::kNone) return end_ = LoopEnd::kLabStopped;
  if (fresh_) {
    silent_run_ = 0;
    fresh_ = false;
    taken_counter_ = meas_.counter;
  } else {
    ++stale_ticks_;
    if (++silent_run_ >= spec_.lab_silent_ticks) return end_ = LoopEnd::kLabSilent;
  }
  const std::size_t n = static_cast<std::size_t>(k_);
  const structure::DiscreteBuilding& linear = building_.linear();
  const double force_n = static_cast<double>(meas_.damper_force_n);
  target_.push_back(linear.element_deformation_m(element_));
  measured_.push_back(static_cast<double>(meas_.damper_disp_m));
  force_.push_back(force_n);
  base_.push_back(linear.base_disp_m());
  peak_base_m_ = std::max(peak_base_m_, std::fabs(linear.base_disp_m()));

  const control::ControllerOutput out = control_tick_();
  const double current_a =
      plant::command_stage_a(plant::CoilDrive{static_cast<double>(out.current_command_a), out.drive_enable});
  current_.push_back(current_a);
  model_.step(current_a, actuator_model_.velocity_m_s(), actuator_model_.position_m());
  forces_[slot_] = count_ * force_n;
  building_.step(spec_.ground_accel_m_s2[n], forces_.data());
  send_accel(n + 1);
  const double target_next = linear.element_deformation_m(element_);
  double command = target_next;
  if (spec_.compensate)
    command = predictor_ ? predictor_->predict(linear, spec_.ground_accel_m_s2, n + 1, model_, current_a).position_m
                         : isolated_predictor_->predict(building_, spec_.ground_accel_m_s2, n + 1, model_, current_a)
                               .position_m;
  actuator_model_.step(command);
  command_.push_back(command);
  RthsCommand c{command, target_next, static_cast<std::uint8_t>(k_ & 0xFF)};
  hal::CanFrame f;
  ++k_;
  if (!encode(c, spec_.nodes.controller, f)) return end_ = LoopEnd::kCommandOutOfRange;
  if (bus_.send(f) != hal::CanResult::kOk) ++tx_errors_;
  if (k_ >= steps()) {
    peak_base_m_ = std::max(peak_base_m_, std::fabs(building_.linear().base_disp_m()));
    end_ = LoopEnd::kFinished;
  }
  return end_;
}

void DamperLoop::await_sample(hal::Clock& clock, std::int64_t until_ns) noexcept {
  drain();
  // Bounded: a bus that reports frames which are not this tick's sample
  // cannot keep the loop here past `until_ns` (nor, with a clock that does
  // not move, for more than a few rounds).
  for (int round = 0; round < 64 && !fresh_ && lab_reason_ == LabStopReason::kNone; ++round) {
    const std::int64_t left_ns = until_ns - clock.now_ns();
    if (left_ns <= 0) break;
    bus_.wait_readable(std::chrono::nanoseconds(left_ns));
    drain();
  }
}

LoopEnd DamperLoop::run_periodic(hal::Clock& clock, std::int64_t period_ns, const std::atomic<bool>& stop,
                                 std::int64_t sample_wait_ns) noexcept {
  run_ticks_periodic(
      clock, period_ns, stop, end_, timing_, tick_ns_,
      [this, &clock, sample_wait_ns] { await_sample(clock, clock.now_ns() + sample_wait_ns); }, [this] { tick(); });
  send_run_status();
  record_tick_percentiles(tick_ns_, timing_);
  return end_;
}

void DamperLoop::send_run_status() noexcept {
  tx_errors_ += send_run_status_frames(bus_, spec_.nodes.controller, end_, k_, run_status_counter_);
}

double DamperLoop::rms_tracking_error_pct() const noexcept {
  double e2 = 0.0, x2 = 0.0;
  for (std::size_t i = 0; i < measured_.size(); ++i) {
    e2 += (measured_[i] - target_[i]) * (measured_[i] - target_[i]);
    x2 += target_[i] * target_[i];
  }
  return x2 > 0.0 ? 100.0 * std::sqrt(e2 / x2) : 0.0;
}

}  // namespace mrd::rths_board
