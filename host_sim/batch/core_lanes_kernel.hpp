#pragma once
/// The core in lanes for one kernel file (core_lanes.hpp): included by each
/// lane_kernel_*.cpp after lane_kernel.hpp, in its namespace MRD_BATCH_NS.

#include <cstring>
#include <new>
#include <type_traits>

#include "host_sim/batch/core_lanes.hpp"

namespace mrd::batch::MRD_BATCH_NS {
namespace {

struct CoreIsaTag {};
using CoreLanes = fw::DamperController<fw::LanePolicy<kMaxLanes, CoreIsaTag>>;
static_assert(std::is_trivially_copyable_v<CoreLanes>, "the core is copied from its prototype");

void* core_make(const void* prototype, std::size_t bytes) {
  if (bytes != sizeof(CoreLanes)) return nullptr;
  void* mem = ::operator new(sizeof(CoreLanes), std::align_val_t{alignof(CoreLanes)});
  std::memcpy(mem, prototype, sizeof(CoreLanes));  // creates the trivially copyable object
  return mem;
}

void core_destroy(void* core) { ::operator delete(core, std::align_val_t{alignof(CoreLanes)}); }

void core_reset(void* core, int lane) {
  CoreLanes::Mask only{};
  only[lane] = -1;
  std::launder(static_cast<CoreLanes*>(core))->reset(only);
}

void core_step(void* core, const CoreLanesIn& in, CoreLanesOut& out) {
  CoreLanes::Input i;
  std::memcpy(&i.tick, in.tick, sizeof in.tick);
  std::memcpy(&i.damper_disp_m, in.disp_m, sizeof in.disp_m);
  std::memcpy(&i.damper_force_n, in.force_n, sizeof in.force_n);
  std::memcpy(&i.ground_accel_m_s2, in.ground_accel_m_s2, sizeof in.ground_accel_m_s2);
  std::memcpy(&i.base_accel_m_s2, in.base_accel_m_s2, sizeof in.base_accel_m_s2);
  std::memcpy(&i.coil_current_a, in.coil_current_a, sizeof in.coil_current_a);
  const CoreLanes::Output o = std::launder(static_cast<CoreLanes*>(core))->step(i);
  std::memcpy(out.command_a, &o.current_command_a, sizeof out.command_a);
  std::memcpy(out.desired_force_n, &o.desired_force_n, sizeof out.desired_force_n);
  std::memcpy(out.drive_enable, &o.drive_enable, sizeof out.drive_enable);
}

/// `ticks` closed-loop ticks of the thesis-shape lanes with the core in the
/// loop, the state in registers: sense, the core's step on the sensed values
/// rounded to float (the plant's sensor stage), the command stage (u = the
/// command while the drive is enabled, else 0), advance. Lanes whose
/// `active` is 0 keep their command. Lane l's controller sees ticks
/// tick0[l], tick0[l] + 1, …
template <bool kStoryDrift>
void core_run_ticks(const SharedModel& m, LaneBlock& b, void* core_p, std::size_t ticks, const std::uint32_t* tick0,
                    const std::int32_t* active) {
  if (ticks == 0) return;
  CoreLanes& core = *std::launder(static_cast<CoreLanes*>(core_p));
  Regs r[kInterleave];
  vd roof[kInterleave], floor_peak[kInterleave];
  for (int h = 0; h < kInterleave; ++h) load_regs(b, h * kW, r[h]);
  CoreLanes::Input in;
  std::memcpy(&in.tick, tick0, sizeof in.tick);
  double u[kMaxLanes];
  std::memcpy(u, b.command_a, sizeof u);
  for (std::size_t t = 0; t < ticks; ++t) {
    Sensed s[kInterleave];
    double x[kMaxLanes] = {}, force[kMaxLanes] = {}, ag[kMaxLanes] = {}, base_accel[kMaxLanes] = {},
           current[kMaxLanes] = {};
    for (int h = 0; h < kInterleave; ++h) {
      s[h] = sense_regs(m, r[h]);
      store(x + h * kW, s[h].x);
      store(force + h * kW, s[h].force);
      store(ag + h * kW, s[h].ag);
      store(base_accel + h * kW, r[h].base_accel);
      store(current + h * kW, s[h].current);
    }
    for (int l = 0; l < kMaxLanes; ++l) {
      in.damper_disp_m[l] = static_cast<float>(x[l]);
      in.damper_force_n[l] = static_cast<float>(force[l]);
      in.ground_accel_m_s2[l] = static_cast<float>(ag[l]);
      in.base_accel_m_s2[l] = static_cast<float>(base_accel[l]);
      in.coil_current_a[l] = static_cast<float>(current[l]);
    }
    const CoreLanes::Output o = core.step(in);
    in.tick += 1u;
    for (int l = 0; l < kMaxLanes; ++l) {
      if (active[l] != 0) u[l] = o.drive_enable[l] != 0 ? static_cast<double>(o.current_command_a[l]) : 0.0;
    }
    for (int h = 0; h < kInterleave; ++h) {
      advance_regs<kStoryDrift>(m, s[h], load(u + h * kW), r[h], roof[h], floor_peak[h]);
    }
  }
  std::memcpy(b.command_a, u, sizeof u);
  for (int h = 0; h < kInterleave; ++h) {
    store_regs(b, h * kW, r[h]);
    store(b.roof_accel_m_s2 + h * kW, roof[h]);
    store(b.floor_peak_m_s2 + h * kW, floor_peak[h]);
  }
}

void core_run(const SharedModel& m, LaneBlock& b, void* core, std::size_t ticks, const std::uint32_t* tick0,
              const std::int32_t* active) {
  core_run_ticks<true>(m, b, core, ticks, tick0, active);
}
void core_run_without_drift(const SharedModel& m, LaneBlock& b, void* core, std::size_t ticks,
                            const std::uint32_t* tick0, const std::int32_t* active) {
  core_run_ticks<false>(m, b, core, ticks, tick0, active);
}

}  // namespace
}  // namespace mrd::batch::MRD_BATCH_NS
