#pragma once
/// The board runtime: the loop around the control task, on the HAL only.
///
/// <pre>
///   fixed period:  run_tick() → serve the state store → deadline = schedule.after_tick(now)
///                  → sleep until the deadline → summary line when one is due
///   lockstep:      poll the bus; a complete input set (one plant tick) → step; nothing for a
///                  while → the plant has finished
///   every tick:    control task (rx → core → command, lines, heartbeat) → drive-enable log
///                  → mixing task, when attached: sample in, request, maintenance and IdleStatus out
/// </pre>
///
/// The mixing task may be any numeric build (BasicMixingTask<Policy>): the
/// runtime's second template parameter. Its scheduler's transitions and
/// requests are logged after the tick that made them (no I/O inside a tick);
/// the summary line adds its estimate.
///
/// The same runtime runs `mrd-firmware` on a Linux board (SocketCAN, libgpiod,
/// CLOCK_MONOTONIC) and the in-process `sim` board (in-memory bus and lines,
/// a manual clock): only the adapters behind the HAL differ. Nothing in a
/// tick allocates or throws; the state store, which may block on its medium,
/// is served after the tick's command has gone out, never inside the tick.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>

#include "firmware/app/control_task.hpp"
#include "firmware/app/mixing_link.hpp"
#include "firmware/app/mixing_task.hpp"
#include "firmware/app/periodic_schedule.hpp"
#include "firmware/app/runtime_log.hpp"
#include "mrd/hal/can_bus.hpp"
#include "mrd/hal/clock.hpp"
#include "mrd/hal/digital_io.hpp"
#include "mrd/hal/state_store.hpp"

namespace mrd::app {

/// The hardware a runtime runs on.
struct RuntimePorts {
  hal::Clock& clock;
  hal::CanBus& bus;
  hal::DigitalIo& io;
  hal::StateStore* store = nullptr;     ///< where the mixing task's state is saved; none: never saved
  const hal::WallClock* rtc = nullptr;  ///< the mixing task's wall clock; none: never valid
  RuntimeLog* log = nullptr;            ///< none: the runtime writes nothing
};

struct RuntimeConfig {
  std::int64_t period_ns = 1'000'000;  ///< control period, ns
  std::uint64_t max_ticks = 0;         ///< stop after this many ticks; 0: until stopped
  std::int64_t report_every_ns = 0;    ///< fixed period: summary this often; 0: at the end only
  /// Lockstep: stop when no tick completes for this long (before the first
  /// tick, kFirstTickWaitFactor times as long: the plant may start late).
  std::int64_t lockstep_idle_exit_ns = 2'000'000'000;
  const char* name = "mrd-firmware";  ///< first word of every line
};

inline constexpr std::int64_t kFirstTickWaitFactor = 30;
/// Lockstep: longest single wait for the bus.
inline constexpr std::chrono::milliseconds kLockstepPoll{100};

template <ControlCore Core, class Mixing = MixingTask>
class BoardRuntime {
 public:
  /// Builds the control task on `ports.bus` and `ports.io` and resets it
  /// (and the core).
  BoardRuntime(Core& core, const RuntimePorts& ports, const ControlTaskConfig& task, const RuntimeConfig& config) noexcept
      : ports_(ports), config_(config), task_(core, ports.bus, ports.io, task) {
    reset();
  }

  /// Runs `mixing` with every tick from now on (null: none). It must be
  /// initialised and booted; it stays the caller's.
  void attach_mixing(Mixing* mixing) noexcept {
    mixing_ = mixing;
    request_ = MixingRequestEdge{};
    scheduler_state_ = fw::SchedulerState::kIdle;
  }

  /// Saves the mixing task's state now, due or not (at the end of a run).
  /// False when nothing is attached or the save did not happen.
  bool save_now() noexcept { return mixing_ && ports_.store && save(); }

  /// Back to the state after construction.
  void reset() noexcept {
    task_.reset();
    timing_ = LoopTiming{};
    enable_ = DriveEnableWatch{};
    request_ = MixingRequestEdge{};
    scheduler_state_ = fw::SchedulerState::kIdle;
    events_ = MixingEvents{};
    saves_ = save_failures_ = 0;
  }

  /// One tick on whatever has arrived: drain the bus, step, serve the store.
  control::ControllerOutput run_tick() noexcept {
    task_.poll_rx();
    const control::ControllerOutput out = step();
    serve_store();
    return out;
  }

  /// Ticks on the clock at the configured period, with absolute deadlines
  /// (no drift) and missed periods counted, until `stop` or max_ticks; then
  /// the summary line.
  void run_periodic(const std::atomic<bool>& stop) noexcept {
    const std::int64_t report_ns = config_.report_every_ns;
    std::int64_t next_report_ns = ports_.clock.now_ns() + report_ns;
    PeriodicSchedule schedule(config_.period_ns, ports_.clock.now_ns());
    while (more(stop)) {
      run_tick();
      const std::int64_t deadline_ns = schedule.after_tick(ports_.clock.now_ns());
      timing_.overruns = schedule.overruns();
      timing_.worst_late_ns = schedule.worst_late_ns();
      task_.set_overruns(timing_.overruns);
      ports_.clock.sleep_until_ns(deadline_ns);
      if (report_ns > 0 && ports_.clock.now_ns() >= next_report_ns) {
        log_summary();
        next_report_ns += report_ns;
      }
    }
    log_summary();
  }

  /// Ticks once per complete input set (a simulated plant's tick) until
  /// `stop`, max_ticks, or no tick for lockstep_idle_exit_ns; then the
  /// summary line.
  void run_lockstep(const std::atomic<bool>& stop) noexcept {
    std::int64_t last_tick_ns = ports_.clock.now_ns();
    while (more(stop)) {
      task_.poll_rx();
      if (task_.lockstep_ready()) {
        step();
        serve_store();
        last_tick_ns = ports_.clock.now_ns();
        continue;
      }
      if (!ports_.bus.wait_readable(kLockstepPoll) && plant_finished(last_tick_ns)) break;
    }
    log_summary();
  }

  /// Writes the summary line.
  void log_summary() const noexcept {
    if (!ports_.log) return;
    char text[kLogLineSize];
    format_summary(text, config_.name, task_.status(), timing_, enable_.changes());
    if (mixing_) append_mixing_summary(text, *mixing_, saves_, save_failures_);
    ports_.log->line(text);
  }

  /// Saves completed (handed to the store without error) and failed.
  std::uint32_t saves() const noexcept { return saves_; }
  std::uint32_t save_failures() const noexcept { return save_failures_; }

  const ControlTask<Core>& task() const noexcept { return task_; }
  ControlTask<Core>& task() noexcept { return task_; }
  const LoopTiming& timing() const noexcept { return timing_; }
  std::uint64_t enable_changes() const noexcept { return enable_.changes(); }

 private:
  bool more(const std::atomic<bool>& stop) const noexcept {
    return !stop.load() && (config_.max_ticks == 0 || task_.tick() < config_.max_ticks);
  }

  /// The control task's tick on the samples polled, then what follows it.
  control::ControllerOutput step() noexcept {
    const control::ControllerOutput out = task_.step_tick();
    note_enable(out.drive_enable);
    if (mixing_) step_mixing();
    return out;
  }

  void note_enable(bool enable) noexcept {
    const std::uint64_t tick = task_.tick() - 1;
    if (!enable_.note(tick, enable) || !ports_.log) return;
    char text[kLogLineSize];
    std::snprintf(text, sizeof text, "%s: tick %llu: drive-enable line %s", config_.name,
                  static_cast<unsigned long long>(tick), enable ? "active" : "inactive");
    ports_.log->line(text);
  }

  /// The mixing task on this tick's sample; its request and maintenance
  /// output go to the control task (sent and driven from the next tick on).
  void step_mixing() noexcept {
    double rtc_s = 0.0;
    const bool rtc_valid = ports_.rtc != nullptr && ports_.rtc->now_s(rtc_s);
    const auto& out = mixing_->step(mixing_input<typename Mixing::PolicyType>(task_.status(), rtc_s, rtc_valid));
    protocol::MixingCommand cmd;
    if (request_.changed(out, cmd)) {
      task_.request_mixing(cmd);
      events_.request = {true, task_.tick() - 1, cmd, out.plan.cycles};
    }
    task_.set_maintenance_due(out.maintenance_required);
    task_.set_idle_status(idle_status_of(*mixing_));
    if (out.state != scheduler_state_) {
      events_.transition = {true, task_.tick() - 1, scheduler_state_, out.state, out.reason};
      scheduler_state_ = out.state;
    }
  }

  /// After the tick: the mixing task's log lines of this tick, then its
  /// save when due (I/O stays out of the tick).
  void serve_store() noexcept {
    log_mixing_events();
    if (mixing_ && ports_.store && mixing_->save_due()) (void)save();
  }

  /// What the mixing task did in a tick, logged after it.
  struct MixingEvents {
    struct Request {
      bool pending = false;
      std::uint64_t tick = 0;
      protocol::MixingCommand cmd{};
      std::uint32_t cycles = 0;
    } request;
    struct Transition {
      bool pending = false;
      std::uint64_t tick = 0;
      fw::SchedulerState from = fw::SchedulerState::kIdle, to = fw::SchedulerState::kIdle;
      fw::MixingEndReason why = fw::MixingEndReason::kNone;
    } transition;
  };

  void log_mixing_events() noexcept {
    if (events_.transition.pending) log_transition(events_.transition);
    if (events_.request.pending) log_request(events_.request);
    events_ = MixingEvents{};
  }

  bool save() noexcept {
    const bool ok = mixing_->save(*ports_.store) == fw::SaveOutcome::kSaved;
    if (ok) {
      ++saves_;
    } else {
      ++save_failures_;
    }
    return ok;
  }

  void log_request(const typename MixingEvents::Request& r) const noexcept {
    if (!ports_.log) return;
    const protocol::MixingCommand& cmd = r.cmd;
    char text[kLogLineSize];
    if (cmd.action == protocol::MixingAction::kStart) {
      std::snprintf(text, sizeof text,
                    "%s: tick %llu: mixing requested: cycles=%u amplitude_m=%.5f frequency_hz=%.2f duration_s=%.0f",
                    config_.name, static_cast<unsigned long long>(r.tick), r.cycles,
                    static_cast<double>(cmd.amplitude_m), static_cast<double>(cmd.frequency_hz),
                    static_cast<double>(cmd.duration_s));
    } else {
      std::snprintf(text, sizeof text, "%s: tick %llu: mixing request withdrawn", config_.name,
                    static_cast<unsigned long long>(r.tick));
    }
    ports_.log->line(text);
  }

  void log_transition(const typename MixingEvents::Transition& t) const noexcept {
    if (!ports_.log) return;
    char text[kLogLineSize];
    std::snprintf(text, sizeof text, "%s: tick %llu: scheduler %s -> %s (%s)", config_.name,
                  static_cast<unsigned long long>(t.tick), fw::scheduler_state_name(t.from),
                  fw::scheduler_state_name(t.to), fw::mixing_end_reason_name(t.why));
    ports_.log->line(text);
  }

  /// Lockstep: nothing arrived for long enough (says so in the log).
  bool plant_finished(std::int64_t last_tick_ns) const noexcept {
    const std::int64_t quiet_ns = ports_.clock.now_ns() - last_tick_ns;
    const std::int64_t limit_ns = config_.lockstep_idle_exit_ns * (task_.tick() > 0 ? 1 : kFirstTickWaitFactor);
    if (quiet_ns <= limit_ns) return false;
    if (ports_.log) {
      char text[kLogLineSize];
      std::snprintf(text, sizeof text,
                    "%s: lockstep: no complete tick for %.1f s after tick %llu: the plant has finished",
                    config_.name, static_cast<double>(quiet_ns) / 1e9, static_cast<unsigned long long>(task_.tick()));
      ports_.log->line(text);
    }
    return true;
  }

  RuntimePorts ports_;
  RuntimeConfig config_;
  ControlTask<Core> task_;
  Mixing* mixing_ = nullptr;
  MixingRequestEdge request_{};
  fw::SchedulerState scheduler_state_ = fw::SchedulerState::kIdle;
  MixingEvents events_{};
  std::uint32_t saves_ = 0, save_failures_ = 0;
  LoopTiming timing_{};
  DriveEnableWatch enable_{};
};

}  // namespace mrd::app
