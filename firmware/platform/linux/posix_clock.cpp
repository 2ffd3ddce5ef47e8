#include "firmware/platform/linux/posix_clock.hpp"

#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace mrd::posix {

std::int64_t PosixClock::now_ns() const noexcept {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

bool PosixWallClock::now_s(double& unix_s) const noexcept {
  timespec ts{};
  if (::clock_gettime(CLOCK_REALTIME, &ts) != 0) return false;
  const double t = static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
  if (t < kEarliestValidUnixS) return false;
  unix_s = t;
  return true;
}

void PosixClock::sleep_until_ns(std::int64_t deadline_ns) noexcept {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline_ns / 1000000000);
  ts.tv_nsec = static_cast<long>(deadline_ns % 1000000000);
  while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

std::string apply_realtime(const RealtimeRequest& r) {
  std::string log;
  auto why = [](int err) {
    std::string s = std::string(std::strerror(err));
    if (err == EPERM) s += " (EPERM): run as root or grant CAP_SYS_NICE / CAP_IPC_LOCK (systemd: LimitRTPRIO, LimitMEMLOCK)";
    return s;
  };
  if (r.lock_memory) {
    if (::mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      log += "realtime: memory locked (mlockall)\n";
    } else {
      log += "realtime: mlockall not permitted: " + why(errno) + "; running with pageable memory\n";
    }
  }
  if (r.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(r.cpu, &set);
    if (::sched_setaffinity(0, sizeof set, &set) == 0) {
      log += "realtime: pinned to CPU " + std::to_string(r.cpu) + "\n";
    } else {
      log += "realtime: cannot pin to CPU " + std::to_string(r.cpu) + ": " + why(errno) + "\n";
    }
  }
  if (r.sched_fifo_priority > 0) {
    sched_param p{};
    p.sched_priority = r.sched_fifo_priority;
    if (::sched_setscheduler(0, SCHED_FIFO, &p) == 0) {
      log += "realtime: SCHED_FIFO priority " + std::to_string(r.sched_fifo_priority) + "\n";
    } else {
      log += "realtime: SCHED_FIFO " + std::to_string(r.sched_fifo_priority) + " not permitted: " + why(errno) +
             "; running under the default scheduler\n";
    }
  }
  if (log.empty()) log = "realtime: not requested by the board file\n";
  return log;
}

}  // namespace mrd::posix
