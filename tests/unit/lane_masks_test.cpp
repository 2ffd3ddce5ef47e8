// num::any and num::all on lane masks (mrd/num/policy.hpp) for every lane
// count the lanes use, each lane alone set or alone clear, none and all:
// the answers a loop over the lanes gives; num::bump_where's saturating
// count per lane, against the one-counter rule and its hand values at the
// top of the range. The file is compiled twice, for
// the baseline (SSE2's byte masks; bump_where's comparison with 2^32 − 1)
// and, on x86-64, for x86-64-v3 (AVX's vptest on 32 bytes; bump_where's
// unsigned max), the instruction sets the controller's lanes are built for
// (host_sim/batch).
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>

#include "mrd/num/policy.hpp"

#ifndef MRD_LANE_MASKS_ISA
#define MRD_LANE_MASKS_ISA Baseline
#endif
#define MRD_LANE_MASKS_CAT2(a, b) a##b
#define MRD_LANE_MASKS_CAT(a, b) MRD_LANE_MASKS_CAT2(a, b)
#define MRD_LANE_MASKS_SUITE MRD_LANE_MASKS_CAT(LaneMasks, MRD_LANE_MASKS_ISA)

namespace {

template <int N>
void check_every_pattern() {
  using Mask = mrd::num::LaneMask<N>;
  const auto loop_any = [](const Mask& m) {
    for (int l = 0; l < N; ++l) {
      if (m[l] != 0) return true;
    }
    return false;
  };
  const auto loop_all = [](const Mask& m) {
    for (int l = 0; l < N; ++l) {
      if (m[l] == 0) return false;
    }
    return true;
  };
  const Mask none{};
  const Mask every = mrd::num::all_set<Mask>();
  EXPECT_FALSE(mrd::num::any(none));
  EXPECT_FALSE(mrd::num::all(none));
  EXPECT_TRUE(mrd::num::any(every));
  EXPECT_TRUE(mrd::num::all(every));
  for (int l = 0; l < N; ++l) {
    Mask one{};
    one[l] = -1;
    EXPECT_EQ(mrd::num::any(one), loop_any(one)) << "lane " << l << " alone set";
    EXPECT_EQ(mrd::num::all(one), loop_all(one)) << "lane " << l << " alone set";
    EXPECT_TRUE(mrd::num::any(one));
    EXPECT_FALSE(mrd::num::all(one));
    Mask all_but = every;
    all_but[l] = 0;
    EXPECT_TRUE(mrd::num::any(all_but)) << "lane " << l << " alone clear";
    EXPECT_FALSE(mrd::num::all(all_but)) << "lane " << l << " alone clear";
  }
  // Masks from comparisons, as the controller makes them.
  typename mrd::num::LaneVectors<N>::Float x{};
  for (int l = 0; l < N; ++l) x[l] = static_cast<float>(l) - 1.5f;
  EXPECT_EQ(mrd::num::any(x > 100.0f), false);
  EXPECT_EQ(mrd::num::all(x > -2.0f), true);
  EXPECT_EQ(mrd::num::any(x > static_cast<float>(N) - 3.0f), true);  // the last lane, N − 2.5
  EXPECT_EQ(mrd::num::all(x < static_cast<float>(N) - 3.0f), false);
}

template <int N>
void check_bump_where() {
  using Mask = mrd::num::LaneMask<N>;
  using Count = mrd::num::LaneCount<N>;
  // Each lane a start count and a mask: every pair of {0, 1, 2^32 − 2, 2^32 − 1} × {clear, set}
  // over the lanes, shifted by `s` so that each lane meets each pair.
  constexpr std::uint32_t kStarts[] = {0u, 1u, 0xfffffffeu, 0xffffffffu};
  // Hand values: one more where set, except at 2^32 − 1, which stays.
  constexpr std::uint32_t kAfterSet[] = {1u, 2u, 0xffffffffu, 0xffffffffu};
  for (int s = 0; s < 8; ++s) {
    Count c{};
    Mask m{};
    for (int l = 0; l < N; ++l) {
      c[l] = kStarts[(l + s) % 4];
      m[l] = ((l + s) / 4) % 2 == 0 ? 0 : -1;
    }
    Count lanes = c;
    mrd::num::bump_where(lanes, m);
    for (int l = 0; l < N; ++l) {
      std::uint32_t one = c[l];
      mrd::num::bump_where(one, m[l] != 0);
      EXPECT_EQ(lanes[l], one) << "lane " << l << " from " << c[l] << (m[l] != 0 ? ", set" : ", clear");
      EXPECT_EQ(lanes[l], m[l] != 0 ? kAfterSet[(l + s) % 4] : c[l]) << "lane " << l;
    }
  }
}

TEST(MRD_LANE_MASKS_SUITE, BumpWhereCountsOneMoreWhereSetAndStopsAtTheTop) {
  check_bump_where<2>();
  check_bump_where<4>();
  check_bump_where<8>();
  check_bump_where<16>();
}

TEST(MRD_LANE_MASKS_SUITE, AnyAndAllAgreeWithALoopOverTheLanes) {
  check_every_pattern<2>();
  check_every_pattern<4>();
  check_every_pattern<8>();
  check_every_pattern<16>();
}

}  // namespace
