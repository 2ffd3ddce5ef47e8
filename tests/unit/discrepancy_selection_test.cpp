// The discrepancy workflow on hidden effects: records generated from the
// baseline plus none, one or two catalogue effects with random parameters,
// inputs, currents and sensor noise. The workflow is not told what was added;
// it must name the right set in at least 90 % of the cases and, whenever an
// effect is present, at least halve the gap. Prints the confusion matrix.
//
// And the thesis's own gap: the Table 5.1 sine tests simulated with idle time
// (host_sim/run/sine_rig) must be recognised as idle_settling.
#include <gtest/gtest.h>

#include "test_normals.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "host_sim/discrepancy/synth.hpp"
#include "host_sim/discrepancy/workflow.hpp"
#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/settling.hpp"
#include "mrd/units.hpp"
#include "host_sim/run/sine_rig.hpp"

#ifndef MRD_DISCREPANCY_CASES
#define MRD_DISCREPANCY_CASES 56
#endif

namespace mrd::discrepancy {
namespace {

constexpr std::size_t kCases = MRD_DISCREPANCY_CASES;

/// Case i: none (2 in 14), each single effect (7 in 14), a pair (5 in 14).
std::vector<Effect> truth_for_case(std::size_t i) {
  const std::size_t slot = i % 14;
  if (slot < 2) return {};
  if (slot < 9) return {kAllEffects[slot - 2]};
  // Pairs: walk through all 21 pairs in a fixed scrambled order.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < kEffectCount; ++a) {
    for (std::size_t b = a + 1; b < kEffectCount; ++b) pairs.emplace_back(a, b);
  }
  const std::size_t p = ((i / 14) * 5 + (slot - 9)) * 8 % pairs.size();
  return {kAllEffects[pairs[p].first], kAllEffects[pairs[p].second]};
}

std::string set_label(std::vector<Effect> s) {
  std::sort(s.begin(), s.end());
  return EffectSet{s}.label();
}

TEST(DiscrepancyStudy, NamesHiddenEffectsAndShrinksTheGap) {
  std::size_t correct = 0;
  std::size_t halved_ok = 0, with_effect = 0;
  std::map<std::string, std::map<std::string, int>> confusion;  // truth → named → count
  std::map<std::string, std::array<int, 3>> per_effect;          // TP, FN, FP
  std::vector<std::string> misses;
  DiscrepancyOptions opt;
  // Seeds 1000 + i by default; MRD_DISCREPANCY_SEED_BASE draws a fresh set.
  const char* base_env = std::getenv("MRD_DISCREPANCY_SEED_BASE");
  const std::uint64_t seed_base = base_env ? std::strtoull(base_env, nullptr, 10) : 1000u;
  for (std::size_t i = 0; i < kCases; ++i) {
    SynthSpec spec;
    spec.effects = truth_for_case(i);
    spec.seed = seed_base + i;
    spec.duration_s = 20.0;
    const SynthCase c = synthesize(spec);
    const DiscrepancyResult r = run_discrepancy(c.data, opt);
    const std::string truth = set_label(c.effects);
    const std::string named = set_label(r.effects);
    const bool ok = truth == named;
    correct += ok;
    confusion[truth][named]++;
    for (const Effect e : kAllEffects) {
      const bool t = std::find(c.effects.begin(), c.effects.end(), e) != c.effects.end();
      const bool n = std::find(r.effects.begin(), r.effects.end(), e) != r.effects.end();
      auto& pe = per_effect[std::string(effect_name(e))];
      if (t && n) pe[0]++;
      if (t && !n) pe[1]++;
      if (!t && n) pe[2]++;
    }
    if (!c.effects.empty()) {
      ++with_effect;
      const bool halved = r.gap_after <= 0.5 * r.gap_before;
      halved_ok += halved;
      if (!halved) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "case %zu (%s): gap %.4f -> %.4f not halved", i, truth.c_str(), r.gap_before,
                      r.gap_after);
        ADD_FAILURE() << buf;
      }
    }
    if (!ok) {
      char buf[300];
      std::snprintf(buf, sizeof buf, "case %zu seed %llu: truth %s, named %s (%s; %s; gap %.4f -> %.4f)", i,
                    static_cast<unsigned long long>(spec.seed), truth.c_str(), named.c_str(),
                    c.input_description.c_str(), c.current_description.c_str(), r.gap_before, r.gap_after);
      misses.emplace_back(buf);
    }
  }
  std::printf("\nHidden-effect study: %zu cases, %zu named exactly (%.1f %%); gap at least halved in %zu of %zu\n",
              kCases, correct, 100.0 * static_cast<double>(correct) / static_cast<double>(kCases), halved_ok,
              with_effect);
  std::printf("\nConfusion (truth -> named: count)\n");
  for (const auto& [t, row] : confusion) {
    std::printf("  %-28s", t.c_str());
    for (const auto& [n, count] : row) std::printf("  %s:%d", n == t ? "OK" : n.c_str(), count);
    std::printf("\n");
  }
  std::printf("\nPer effect: present&named / present&missed / absent&named\n");
  for (const auto& [e, c] : per_effect) std::printf("  %-14s %3d %3d %3d\n", e.c_str(), c[0], c[1], c[2]);
  for (const auto& m : misses) std::printf("  miss: %s\n", m.c_str());
  std::fflush(stdout);
  EXPECT_GE(static_cast<double>(correct), 0.9 * static_cast<double>(kCases));
}

TEST(DiscrepancyStudy, CoversEveryEffectAndNone) {
  std::map<std::string, int> seen;
  for (std::size_t i = 0; i < kCases; ++i) {
    const auto t = truth_for_case(i);
    if (t.empty()) seen["none"]++;
    for (const Effect e : t) seen[std::string(effect_name(e))]++;
  }
  EXPECT_GE(seen["none"], 1);
  for (const Effect e : kAllEffects) EXPECT_GE(seen[std::string(effect_name(e))], 1) << effect_name(e);
}

using test::Normals;

// The thesis's own gap: the three sine tests of Table 5.1, simulated with
// their idle times (chapter 5, host_sim/run/sine_rig), sampled at 500 Hz
// with 0.5 kN load-cell and 10 µm LVDT noise, are compared with the chapter-4
// model. The workflow must name idle_settling alone and recover the SQ of
// Eq. 5.5 (0.25/0.8534, 0.5/0.8534 years, and 1 for 2.5 years).
TEST(DiscrepancyThesis, IdleSineTestsOfTable51AreIdleSettling) {
  Normals noise(51);
  for (const auto& c : run::thesis_sine_cases()) {
    run::SineRigSpec spec = c.spec;
    spec.duration_s = std::min(spec.duration_s, 60.0);
    spec.step_s = 2e-3;
    run::SineRecord rec;
    const run::SineMetrics m = run::run_sine_rig(spec, {}, {}, &rec);
    MeasuredData d;
    d.source = c.name;
    d.time_s = rec.time_s;
    for (std::size_t k = 0; k < rec.time_s.size(); ++k) {
      d.displacement_m.push_back(rec.disp_m[k] + 10e-6 * noise.next());
      d.force_n.push_back(rec.force_n[k] + 500.0 * noise.next());
      d.current_cmd_a.push_back(spec.current_a);
    }
    const DiscrepancyResult r = run_discrepancy(d);
    ASSERT_EQ(r.effects.size(), 1u) << c.name << ": " << EffectSet{r.effects}.label();
    EXPECT_EQ(r.effects[0], Effect::idle_settling) << c.name;
    EXPECT_NEAR(r.params[0], m.sq, 0.02) << c.name;
    EXPECT_LT(r.gap_after, 0.5 * r.gap_before) << c.name;
    std::printf("%s: SQ %.3f (Eq. 5.5: %.3f), gap %.1f %% -> %.2f %%\n", c.name, r.params[0], m.sq,
                100.0 * r.gap_before, 100.0 * r.gap_after);
  }
}

// Table 5.2's fully mixed forces against the chapter-4 model: 163.61 kN
// measured against 169.02 kN (25.4 mm, 0.5 Hz, 2.5 A) and 139.23 kN against
// 157.88 kN (7.62 mm, 1 Hz). The thesis gives only these peaks, so the
// records here are a reconstruction: the fully mixed model force scaled to
// the measured peak. Of the catalogue, only a participant ratio below 1
// (idle_settling) or thermal fade lowers a steady peak at constant current,
// and only the first can hold it down from the start, so idle_settling must
// come first, with b_PR near the PR that matches the peak. By hand, at 2.5 A
// (e_fc = e^{−1.75} = 0.1738, e_c0 = e^{−2.875} = 0.0564, Eq. 5.10–5.11):
//   F(PR) = 0.713 kN + 4.653 kN·s/m·v + PR (140.45 kN + 344.4 kN·s/m·v)
//   v = 79.8 mm/s: PR = (163.61 − 1.084)/167.94 = 0.968
//   v = 47.9 mm/s: PR = (139.23 − 0.936)/156.95 = 0.881
TEST(DiscrepancyThesis, FullyMixedForcesOfTable52PointToAParticipantRatioBelowOne) {
  Normals noise(52);
  const auto& cases = run::thesis_sine_cases();
  const double pr_by_hand[2] = {0.968, 0.881};
  for (std::size_t i = 0; i < 2; ++i) {
    run::SineRigSpec spec = cases[i].spec;
    spec.idle_time_s = 0.0;
    spec.duration_s = 20.0;
    spec.step_s = 2e-3;
    run::SineRecord rec;
    const run::SineMetrics m = run::run_sine_rig(spec, {}, {}, &rec);
    const double scale = units::kn_to_n(cases[i].fully_mixed_force_kn) / m.fully_mixed_force_n;
    MeasuredData d;
    d.source = cases[i].name;
    d.time_s = rec.time_s;
    for (std::size_t k = 0; k < rec.time_s.size(); ++k) {
      d.displacement_m.push_back(rec.disp_m[k] + 10e-6 * noise.next());
      d.force_n.push_back(scale * rec.force_n[k] + 500.0 * noise.next());
      d.current_cmd_a.push_back(spec.current_a);
    }
    const DiscrepancyResult r = run_discrepancy(d);
    ASSERT_FALSE(r.effects.empty()) << cases[i].name;
    EXPECT_EQ(r.effects[0], Effect::idle_settling) << cases[i].name;
    const auto pr = physics::pr_coefficients(physics::ParticipantRatioParams{}, r.params[0]);
    EXPECT_NEAR(pr.b_pr, pr_by_hand[i], 0.03) << cases[i].name;
    EXPECT_LT(r.gap_after, 0.5 * r.gap_before) << cases[i].name;
    std::printf("%s fully mixed: model %.2f kN, measured %.2f kN; named %s, SQ %.3f (b_PR %.3f), gap %.2f %% -> "
                "%.2f %%\n",
                cases[i].name, m.fully_mixed_force_n / 1e3, cases[i].fully_mixed_force_kn,
                EffectSet{r.effects}.label().c_str(), r.params[0], pr.b_pr, 100.0 * r.gap_before, 100.0 * r.gap_after);
  }
}

}  // namespace
}  // namespace mrd::discrepancy
