#pragma once
/// The core in lanes for one kernel file (core_lanes.hpp): included by each
/// lane_kernel_*.cpp after lane_kernel.hpp, in its namespace MRD_BATCH_NS.

#include <cstring>
#include <new>
#include <type_traits>

#include "host_sim/batch/core_lanes.hpp"

namespace mrd::batch::MRD_BATCH_NS {
namespace {

#ifndef MRD_BATCH_CORE_LANES
#define MRD_BATCH_CORE_LANES kMaxLanes
#endif
/// Lanes of one core object: its float vectors are one register of this
/// file's instruction set (8 floats with AVX; 4 on SSE2 or NEON, where GCC
/// expands the conditions of wider vectors lane by lane). kCores objects
/// cover the kMaxLanes lanes, lane l in object l / kCoreLanes.
constexpr int kCoreLanes = MRD_BATCH_CORE_LANES;
constexpr int kCores = kMaxLanes / kCoreLanes;
static_assert(kCores * kCoreLanes == kMaxLanes && kCoreLanes % kW == 0, "the cores' lanes hold whole register sets");

struct CoreIsaTag {};
using CoreLanes = fw::DamperController<fw::LanePolicy<kCoreLanes, CoreIsaTag>>;
struct Cores {
  CoreLanes c[kCores];
};
static_assert(std::is_trivially_copyable_v<Cores>, "the core is copied from its prototype");
static_assert(kCoreLanes != kMaxLanes || sizeof(Cores) == sizeof(CoreLanesPrototype), "the prototype's layout");
// Narrower cores are configured in the kernel from the prototype's
// configuration: only where the file is built for the baseline instruction
// set, as the prototype is, so that init()'s design arithmetic gives the
// same numbers.
static_assert(kCoreLanes == kMaxLanes || MRD_BATCH_X86 == 0, "narrower cores only in the baseline build");

void* core_make(const void* prototype_p, std::size_t bytes) {
  if (bytes != sizeof(CoreLanesPrototype)) return nullptr;
  void* mem = ::operator new(sizeof(Cores), std::align_val_t{alignof(Cores)});
  if constexpr (kCoreLanes == kMaxLanes) {
    std::memcpy(mem, prototype_p, sizeof(Cores));  // creates the trivially copyable object
  } else {
    const auto& prototype = *static_cast<const CoreLanesPrototype*>(prototype_p);
    Cores* cores = new (mem) Cores;
    for (CoreLanes& c : cores->c) {
      if (c.init(prototype.config()) != fw::ConfigError::kNone) {
        ::operator delete(mem, std::align_val_t{alignof(Cores)});
        return nullptr;
      }
    }
  }
  return mem;
}

void core_destroy(void* core) { ::operator delete(core, std::align_val_t{alignof(Cores)}); }

[[gnu::always_inline]] inline Cores& cores_of(void* core) { return *std::launder(static_cast<Cores*>(core)); }

void core_reset(void* core, int lane) {
  CoreLanes::Mask only{};
  only[lane % kCoreLanes] = -1;
  cores_of(core).c[lane / kCoreLanes].reset(only);
}

void core_step(void* core, int lanes, const CoreLanesIn& in, CoreLanesOut& out) {
  Cores& cores = cores_of(core);
  for (int c = 0; c < kCores && c * kCoreLanes < lanes; ++c) {
    const int o = c * kCoreLanes;
    CoreLanes::Input i;
    std::memcpy(&i.tick, in.tick + o, sizeof i.tick);
    std::memcpy(&i.damper_disp_m, in.disp_m + o, sizeof i.damper_disp_m);
    std::memcpy(&i.damper_force_n, in.force_n + o, sizeof i.damper_force_n);
    std::memcpy(&i.ground_accel_m_s2, in.ground_accel_m_s2 + o, sizeof i.ground_accel_m_s2);
    std::memcpy(&i.base_accel_m_s2, in.base_accel_m_s2 + o, sizeof i.base_accel_m_s2);
    std::memcpy(&i.coil_current_a, in.coil_current_a + o, sizeof i.coil_current_a);
    const CoreLanes::Output r = cores.c[c].step(i);
    std::memcpy(out.command_a + o, &r.current_command_a, sizeof r.current_command_a);
    std::memcpy(out.desired_force_n + o, &r.desired_force_n, sizeof r.desired_force_n);
    std::memcpy(out.drive_enable + o, &r.drive_enable, sizeof r.drive_enable);
  }
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
/// register sets of kW lanes share the cores' one step a tick (set h in
/// lanes h·kW …). Lanes whose `active` is 0 keep their command. Lane l's
/// controller sees ticks tick0[l], tick0[l] + 1, …
template <bool kStoryDrift>
void core_run_ticks(const SharedModel& shared, LaneBlock& b, void* core_p, std::size_t ticks,
                    const std::uint32_t* tick0, const std::int32_t* active) {
  constexpr int kRunCores = (kW * kInterleave + kCoreLanes - 1) / kCoreLanes;
  static_assert(kRunCores <= kCores, "the register sets fit the cores' lanes");
  if (ticks == 0) return;
  LoopModel wide;
  const auto& m = loop_model(shared, wide);
  Cores& cores = cores_of(core_p);
  Regs r[kInterleave];
  vd u[kInterleave], x[kInterleave];
  vi active_wide[kInterleave];
  CoreLanes::Input in[kRunCores];
  for (int c = 0; c < kRunCores; ++c) std::memcpy(&in[c].tick, tick0 + c * kCoreLanes, sizeof in[c].tick);
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
      CoreLanes::Input& i = in[h * kW / kCoreLanes];
      const int o = h * kW % kCoreLanes;
      s[h] = sense_regs(m, r[h], x[h]);
      put_floats(i.damper_disp_m, o, s[h].x);
      put_floats(i.damper_force_n, o, s[h].force);
      put_floats(i.ground_accel_m_s2, o, s[h].ag);
      put_floats(i.base_accel_m_s2, o, r[h].base_accel);
      put_floats(i.coil_current_a, o, s[h].current);
    }
    CoreLanes::Output out[kRunCores];
    for (int c = 0; c < kRunCores; ++c) {
      out[c] = cores.c[c].step(in[c]);
      in[c].tick += 1u;
    }
    for (int h = 0; h < kInterleave; ++h) {
      const CoreLanes::Output& k = out[h * kW / kCoreLanes];
      const int o = h * kW % kCoreLanes;
      vf command;
      std::memcpy(&command, reinterpret_cast<const float*>(&k.current_command_a) + o, sizeof command);
      vm enable;
      std::memcpy(&enable, reinterpret_cast<const std::int32_t*>(&k.drive_enable) + o, sizeof enable);
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
