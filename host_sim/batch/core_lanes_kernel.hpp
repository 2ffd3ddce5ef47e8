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

typedef float vf __attribute__((vector_size(kW * 4)));
typedef std::int32_t vm __attribute__((vector_size(kW * 4)));

/// The kW doubles of `v` rounded to float (as static_cast<float>) into
/// lanes o … o + kW − 1 of `dst`.
[[gnu::always_inline]] inline void put_floats(CoreLanes::Sample& dst, int o, vd v) {
  const vf f = __builtin_convertvector(v, vf);
  std::memcpy(reinterpret_cast<float*>(&dst) + o, &f, sizeof f);
}

/// `ticks` closed-loop ticks of the thesis-shape lanes with the core in the
/// loop, the state in registers: sense, the core's step on the sensed values
/// rounded to float (the plant's sensor stage), the command stage (u = the
/// command while the drive is enabled, else 0), advance. The kInterleave
/// register sets of kW lanes share the core's one step a tick (set h in its
/// lanes h·kW …). Lanes whose `active` is 0 keep their command. Lane l's
/// controller sees ticks tick0[l], tick0[l] + 1, …
template <bool kStoryDrift>
void core_run_ticks(const SharedModel& m, LaneBlock& b, void* core_p, std::size_t ticks, const std::uint32_t* tick0,
                    const std::int32_t* active) {
  static_assert(kW * kInterleave <= kMaxLanes, "the register sets fit the core's lanes");
  if (ticks == 0) return;
  CoreLanes& core = *std::launder(static_cast<CoreLanes*>(core_p));
  Regs r[kInterleave];
  vd u[kInterleave], x[kInterleave];
  vi active_wide[kInterleave];
  CoreLanes::Input in;
  std::memcpy(&in.tick, tick0, sizeof in.tick);
  for (int h = 0; h < kInterleave; ++h) {
    const int o = h * kW;
    load_regs(b, o, r[h]);
    vm active_m;
    std::memcpy(&active_m, active + o, sizeof active_m);
    active_wide[h] = __builtin_convertvector(active_m, vi);
    u[h] = load(b.command_a + o);
    x[h] = base_disp(m, r[h]);
  }
  const vd zero{};
  for (std::size_t t = 0; t < ticks; ++t) {
    Sensed s[kInterleave];
    for (int h = 0; h < kInterleave; ++h) {
      const int o = h * kW;
      s[h] = sense_regs(m, r[h], x[h]);
      put_floats(in.damper_disp_m, o, s[h].x);
      put_floats(in.damper_force_n, o, s[h].force);
      put_floats(in.ground_accel_m_s2, o, s[h].ag);
      put_floats(in.base_accel_m_s2, o, r[h].base_accel);
      put_floats(in.coil_current_a, o, s[h].current);
    }
    const CoreLanes::Output out = core.step(in);
    in.tick += 1u;
    for (int h = 0; h < kInterleave; ++h) {
      const int o = h * kW;
      vf command;
      std::memcpy(&command, reinterpret_cast<const float*>(&out.current_command_a) + o, sizeof command);
      vm enable;
      std::memcpy(&enable, reinterpret_cast<const std::int32_t*>(&out.drive_enable) + o, sizeof enable);
      // run::coil_drive and plant::command_stage_a: the command while the drive is enabled, else 0 A.
      const vd stage = __builtin_convertvector(enable, vi) ? __builtin_convertvector(command, vd) : zero;
      u[h] = active_wide[h] ? stage : u[h];
      advance_regs<kStoryDrift>(m, s[h], u[h], r[h], x[h]);
    }
  }
  for (int h = 0; h < kInterleave; ++h) {
    store(b.command_a + h * kW, u[h]);
    store_regs(b, h * kW, r[h]);
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
