// How much a save of the idle-time estimator's state delays the control loop:
// the board runtime ticking at 1 kHz on CLOCK_MONOTONIC (in-memory bus, float
// control core and mixing task, the real wall clock) for a few seconds in
// three set-ups, each printing the loop's worst lateness past a deadline and
// its missed periods:
//   none        the mixing task runs, nothing is saved;
//   inline      saved every 10 ms straight through FileStateStore (write,
//               fsync, rename, fsync the folder) on the control thread;
//   background  saved every 10 ms through BackgroundStateStore (mrd-firmware's
//               set-up): the control thread only hands 64 bytes over.
// Usage: mrd_bench_save_lateness [SECONDS [DIR]] (default 5 s, DIR /var/tmp).
// The figures depend on the machine's load and its disk; run it quiet.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "firmware/app/runtime.hpp"
#include "firmware/core/damper_controller.hpp"
#include "firmware/platform/linux/background_state_store.hpp"
#include "firmware/platform/linux/file_state_store.hpp"
#include "firmware/platform/linux/posix_clock.hpp"
#include "firmware/platform/sim/memory_bus.hpp"
#include "firmware/platform/sim/memory_io.hpp"

namespace {

using namespace mrd;
using Core = fw::DamperController<num::Float32Policy>;
using Mixing = app::BasicMixingTask<num::Float32Policy>;

struct Result {
  double worst_late_us = 0.0;
  std::uint32_t overruns = 0;
  std::uint32_t saves = 0;
};

Result run(hal::StateStore* store, double seconds) {
  sim::MemoryBus bus;
  auto& ctrl = bus.attach(1024);
  ctrl.set_filters(app::control_task_filters({}));
  sim::MemoryIo io;
  auto core = std::make_unique<Core>();
  (void)core->init(fw::default_controller_config(control::ControlMode::kPassiveOn, 1e-3));
  posix::PosixClock clock;
  posix::PosixWallClock rtc;
  app::RuntimePorts ports{clock, ctrl, io};
  ports.store = store;
  ports.rtc = &rtc;
  app::RuntimeConfig rc;
  rc.max_ticks = static_cast<std::uint64_t>(seconds * 1000.0);
  auto mixing = std::make_unique<Mixing>();
  app::MixingTaskConfig mc;
  mc.estimator.save_interval_s = 0.01;
  if (!mixing->init(mc)) std::abort();
  double now_s = 0.0;
  (void)rtc.now_s(now_s);
  mixing->boot_with(0.0, 0, static_cast<std::int64_t>(now_s * 1e3));
  auto rt = std::make_unique<app::BoardRuntime<Core, Mixing>>(*core, ports, app::ControlTaskConfig{}, rc);
  rt->attach_mixing(mixing.get());
  std::atomic<bool> stop{false};
  rt->run_periodic(stop);
  return {static_cast<double>(rt->timing().worst_late_ns) / 1e3, rt->timing().overruns, rt->saves()};
}

void print(const char* name, const Result& r, std::uint64_t written) {
  std::printf("%-10s worst_late_us=%.1f overruns=%u saves_handed=%u written=%llu\n", name, r.worst_late_us, r.overruns,
              r.saves, static_cast<unsigned long long>(written));
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 5.0;
  const std::filesystem::path dir = argc > 2 ? argv[2] : "/var/tmp";
  if (!(seconds > 0.0) || seconds > 3600.0 || !std::filesystem::is_directory(dir)) {
    std::fprintf(stderr, "usage: mrd_bench_save_lateness [SECONDS (0, 3600]] [DIR (an existing folder)]\n");
    return 2;
  }
  const std::string path = (dir / "mrd_bench_state.bin").string();
  std::printf("1 kHz for %.1f s, state file %s, saves every 10 ms\n", seconds, path.c_str());
  print("none", run(nullptr, seconds), 0);
  {
    posix::FileStateStore file(path);
    const Result r = run(&file, seconds);
    print("inline", r, r.saves);
  }
  {
    posix::FileStateStore file(path);
    Result r;
    std::uint64_t written = 0;
    {
      posix::BackgroundStateStore bg(file);
      r = run(&bg, seconds);
      bg.flush();
      written = bg.writes();
    }
    print("background", r, written);
  }
  std::filesystem::remove(path);
  return 0;
}
