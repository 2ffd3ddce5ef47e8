#pragma once
/// The float build's control core stepped in the kernel's lanes
/// (fw::LanePolicy): the semi-active lanes' controllers, lane l for lane l,
/// compiled with each kernel's instruction set.
///
/// Each kernel file builds its own lane type (a tag of its unnamed
/// namespace), so no function of the core compiled for AVX-512 can be chosen
/// by the linker for another file. The controller is configured once, in the
/// baseline build (`CoreLanesPrototype`, init() and its design arithmetic),
/// and the kernel copies that object into its own: the two types differ in
/// their tag only and have the same layout (checked by size). The kernel's
/// functions are LaneKernel's core_make, core_destroy, core_reset and
/// core_step (lane_block.hpp).

#include <cstddef>
#include <cstdint>

#include "firmware/core/damper_controller.hpp"
#include "host_sim/batch/lane_block.hpp"

namespace mrd::batch {

/// The configured core as the baseline build holds it.
using CoreLanesPrototype = fw::DamperController<fw::LanePolicy<kMaxLanes>>;

/// One tick's sensor values per lane (flags all valid: the plant's ideal sensors).
struct CoreLanesIn {
  std::uint32_t tick[kMaxLanes] = {};
  float disp_m[kMaxLanes] = {};
  float force_n[kMaxLanes] = {};
  float ground_accel_m_s2[kMaxLanes] = {};
  float base_accel_m_s2[kMaxLanes] = {};
  float coil_current_a[kMaxLanes] = {};
};

/// One tick's outputs per lane.
struct CoreLanesOut {
  float command_a[kMaxLanes] = {};
  float desired_force_n[kMaxLanes] = {};
  std::int32_t drive_enable[kMaxLanes] = {};  ///< 0 or −1
};

}  // namespace mrd::batch
