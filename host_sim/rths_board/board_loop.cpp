#include "host_sim/rths_board/board_loop.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "firmware/app/periodic_schedule.hpp"
#include "host_sim/rths_board/periodic_run.hpp"
#include "host_sim/rths/rths_run.hpp"
#include "host_sim/rths_board/rths_fd_frames.hpp"

namespace mrd::rths_board {
namespace {

double checked_rate_dt(const BoardLoopSpec& s) {
  const double dt_s = checked_loop_step_s(s.ground_accel_m_s2.size(), s.rate_hz);
  const auto n = s.building.m.rows();
  if (s.building.k.rows() != n || s.building.c.rows() != n || s.specimen_dof < 0 || s.specimen_dof >= n)
    throw std::invalid_argument("RTHS runtime: M, C, K of different sizes or the specimen's DOF outside them");
  return dt_s;
}

hal::CanFdBus* loop_fd_bus(hal::CanBus& bus, bool can_fd) {
  if (!can_fd) return nullptr;
  auto* fd = dynamic_cast<hal::CanFdBus*>(&bus);
  if (fd == nullptr || !fd->fd_enabled())
    throw std::invalid_argument("RTHS runtime: CAN FD asked for, but the bus does not carry CAN FD frames");
  return fd;
}

}  // namespace

std::string loop_end_status(LoopEnd e, LabStopReason lab_reason) {
  switch (e) {
    case LoopEnd::kRunning: return "running";
    case LoopEnd::kFinished: return "ok";
    case LoopEnd::kLabStopped: return lab_stop_reason_name(lab_reason);
    case LoopEnd::kLabSilent: return "lab_silent";
    case LoopEnd::kCommandOutOfRange: return "command_out_of_range";
    case LoopEnd::kInterrupted: return "interrupted";
  }
  return "unknown";
}

BoardLoop::BoardLoop(hal::CanBus& bus, const BoardLoopSpec& spec)
    : bus_(bus),
      fd_bus_(loop_fd_bus(bus, spec.can_fd)),
      spec_(spec),
      dt_s_(checked_rate_dt(spec)),
      integrator_(spec.building, rths::without_specimen(spec.building, spec.specimen, spec.specimen_dof),
                  spec.specimen_dof, dt_s_) {
  rths::CompensatorSpec cs = spec.compensator;
  cs.dt_s = dt_s_;
  cs.plant = rths::inverse_expansion(rths::lab_plant_model(spec.identified_plant), 0);
  cs.noise_m = std::sqrt(spec.displacement_noise_power_m2_hz / dt_s_);
  comp_ = rths::make_compensator(cs);
  coefficient_names_ = comp_->coefficient_names();
  const std::size_t n = spec.ground_accel_m_s2.size();
  target_.reserve(n);
  measured_.reserve(n);
  command_.reserve(n);
  force_.reserve(n);
  floors_.assign(static_cast<std::size_t>(spec.building.m.rows()), {});
  for (auto& f : floors_) f.reserve(n);
  coeff_every_ = static_cast<std::size_t>(std::max(1L, std::lround(0.01 / dt_s_)));
  coefficient_time_s_.reserve(n / coeff_every_ + 1);
  coefficient_values_.assign((n / coeff_every_ + 1) * coefficient_names_.size(), 0.0);
  tick_ns_.reserve(n);
}

void BoardLoop::take_measurement(double displacement_m, double force_n, bool for_this_tick, bool first) noexcept {
  meas_.displacement_m = displacement_m;
  meas_.force_n = force_n;
  if (for_this_tick) fresh_ = true;
  if (k_ == 0 && first) have_meas0_ = true;
}

void BoardLoop::drain() noexcept {
  for (;;) {
    hal::CanFrame f;
    if (fd_bus_ != nullptr) {
      hal::CanFdFrame g;
      if (fd_bus_->receive_fd(g) != hal::CanResult::kOk) break;
      ++frames_rx_;
      if (g.fd) {
        RthsFdMeasurement m;
        if (decode_fd(g, spec_.lab_node, m) == protocol::DecodeError::kOk) {
          take_measurement(m.displacement_m, m.force_n, m.counter == static_cast<std::uint16_t>(k_ & 0xFFFF),
                           m.counter == 0);
        } else {
          ++rejected_;
        }
        continue;
      }
      f = hal::as_classic(g);
    } else {
      if (bus_.receive(f) != hal::CanResult::kOk) break;
      ++frames_rx_;
    }
    RthsMeasurement m;
    RthsLabStatus s;
    if (fd_bus_ == nullptr && decode(f, spec_.lab_node, m) == protocol::DecodeError::kOk) {
      take_measurement(m.displacement_m, m.force_n, m.counter == static_cast<std::uint8_t>(k_ & 0xFF), m.counter == 0);
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

bool BoardLoop::send_command(double command_m, double target_m) noexcept {
  if (fd_bus_ != nullptr) {
    RthsFdCommand c{command_m, target_m, static_cast<std::uint16_t>(k_ & 0xFFFF)};
    hal::CanFdFrame f;
    if (!encode_fd(c, spec_.runtime_node, f)) return false;
    if (fd_bus_->send_fd(f) != hal::CanResult::kOk) ++tx_errors_;
    return true;
  }
  RthsCommand c{command_m, target_m, static_cast<std::uint8_t>(k_ & 0xFF)};
  hal::CanFrame f;
  if (!encode(c, spec_.runtime_node, f)) return false;
  if (bus_.send(f) != hal::CanResult::kOk) ++tx_errors_;
  return true;
}

bool BoardLoop::lab_ready() noexcept {
  drain();
  return lab_waiting_ && have_meas0_ && lab_rate_mismatch_hz_ == 0;
}

LoopEnd BoardLoop::tick() noexcept {
  if (end_ != LoopEnd::kRunning) return end_;
  drain();
  if (lab_reason_ != LabStopReason::kNone) return end_ = LoopEnd::kLabStopped;
  if (fresh_) {
    silent_run_ = 0;
    fresh_ = false;  // the next tick's must come
  } else {
    ++stale_ticks_;
    if (++silent_run_ >= spec_.lab_silent_ticks) return end_ = LoopEnd::kLabSilent;
  }
  const std::size_t k = static_cast<std::size_t>(k_);
  target_.push_back(target_now_);
  measured_.push_back(meas_.displacement_m);
  force_.push_back(meas_.force_n);
  for (std::size_t i = 0; i < floors_.size(); ++i)
    floors_[i].push_back(integrator_.displacement_m()(static_cast<Eigen::Index>(i)));
  const double target_next = integrator_.step(spec_.ground_accel_m_s2[k], meas_.force_n);
  const double command = comp_->command(target_next, meas_.displacement_m);
  command_.push_back(command);
  if (k % coeff_every_ == 0 && !coefficient_names_.empty()) {
    comp_->write_coefficients(coefficient_values_.data() + coefficient_time_s_.size() * coefficient_names_.size());
    coefficient_time_s_.push_back(static_cast<double>(k) * dt_s_);
  }
  if (!send_command(command, target_next)) {
    ++k_;
    return end_ = LoopEnd::kCommandOutOfRange;
  }
  target_now_ = target_next;
  ++k_;
  if (k_ >= steps()) end_ = LoopEnd::kFinished;
  return end_;
}

LoopEnd BoardLoop::run_periodic(hal::Clock& clock, std::int64_t period_ns, const std::atomic<bool>& stop) noexcept {
  run_ticks_periodic(clock, period_ns, stop, end_, timing_, tick_ns_, [] {}, [this] { tick(); });
  send_run_status();
  record_tick_percentiles(tick_ns_, timing_);
  return end_;
}

void BoardLoop::send_run_status() noexcept {
  tx_errors_ += send_run_status_frames(bus_, spec_.runtime_node, end_, k_, run_status_counter_);
}

void record_tick_percentiles(const std::vector<std::int64_t>& tick_ns, LoopTimingRecord& timing) {
  if (tick_ns.empty()) return;
  std::vector<std::int64_t> sorted = tick_ns;
  std::sort(sorted.begin(), sorted.end());
  timing.median_tick_ns = sorted[sorted.size() / 2];
  timing.p99_tick_ns = sorted[std::min(sorted.size() - 1, sorted.size() * 99 / 100)];
}

std::uint32_t send_run_status_frames(hal::CanBus& bus, std::uint8_t node, LoopEnd end, std::uint64_t ticks,
                                     std::uint8_t& counter) noexcept {
  RthsRunStatus r;
  r.state = end == LoopEnd::kFinished     ? RunState::kFinished
            : end == LoopEnd::kLabStopped ? RunState::kLabStopped
                                          : RunState::kAborted;
  r.ticks = static_cast<std::uint32_t>(ticks);
  std::uint32_t refused = 0;
  for (int i = 0; i < 3; ++i) {
    r.counter = counter++;
    hal::CanFrame f;
    if (encode(r, node, f) && bus.send(f) != hal::CanResult::kOk) ++refused;
  }
  return refused;
}

rths::Criteria BoardLoop::criteria() const {
  const std::size_t n = measured_.size();
  const std::vector<double> record(spec_.ground_accel_m_s2.begin(),
                                   spec_.ground_accel_m_s2.begin() + static_cast<std::ptrdiff_t>(n));
  const auto ref = rths::reference_response(spec_.building, record, dt_s_);
  return rths::evaluate_criteria(measured_, target_, floors_, ref, dt_s_);
}

}  // namespace mrd::rths_board
