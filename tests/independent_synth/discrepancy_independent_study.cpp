// The discrepancy workflow on records it did not make: the independent
// generator of this folder (its own physics, continuous-time integration,
// its own forms of each effect, coloured noise, drift, quantization, jitter)
// hides one catalogue effect, none, or one effect outside the catalogue,
// sized to an effect-to-noise ratio drawn log-uniform from 0.25 to 64.
//
// Tallied and printed as a table:
//   (a) single catalogue effects: the right set named and "explained", per ENR bin;
//   (b) clean records: anything named, or a verdict other than "none", is a false positive;
//   (c) out-of-catalogue effects: no catalogue effect named, per ENR bin, and
//       above the limit the verdict "unexplained".
// Which effects count as catalogued is read from the workflow's catalogue by
// name; a test checks that the generator's own split agrees with it. A
// low-pass or a series compliance counts by its ENR beyond the best pure
// delay (independent_synth.hpp), what a time_delay cannot reproduce.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "host_sim/discrepancy/measured_data.hpp"
#include "host_sim/discrepancy/workflow.hpp"
#include "independent_synth.hpp"

#ifndef MRD_INDEPENDENT_STUDY_CASES
#define MRD_INDEPENDENT_STUDY_CASES 60
#endif

namespace {

// ---- Targets and floors --------------------------------------------------------
// The targets are the project's goals for the workflow; the study prints the
// rates against them. The floors come from seed sets CI does not run,
// measured with this generator and workflow: seeds 7000-7059 gave right set
// 20/20, out-of-catalogue unexplained 7/7; seeds 9000-9059 gave 16/16 and
// 8/8 (false positives 0/10 on both). Each floor is the lower of the two less
// one case (15/16 = 0.9375, 6/7 = 0.857), rounded down, so that more than
// one miss on the CI set (5000-5059: 17/17, 8/8, with the compliant stop of
// the backlash effect) fails the test.
/// Stated detection limit: effects at or above this ENR must be found.
constexpr double kDetectionLimitEnr = 4.0;
/// Right set named, single catalogue effects at or above the limit.
constexpr double kTargetRightSetRate = 0.95;
constexpr double kFloorRightSetRate = 0.93;
/// Clean records with anything named.
constexpr double kMaxFalsePositiveRate = 0.05;
/// Out-of-catalogue effects at or above the limit answered "unexplained".
constexpr double kTargetOutOfCatalogueUnexplainedRate = 0.90;
constexpr double kFloorOutOfCatalogueUnexplainedRate = 0.85;

constexpr std::size_t kCases = MRD_INDEPENDENT_STUDY_CASES;
/// ENR bin edges: <1, 1–2, 2–4, 4–8, 8–16, ≥16.
constexpr std::array<double, 5> kBinEdges{1.0, 2.0, 4.0, 8.0, 16.0};
constexpr std::array<const char*, 6> kBinNames{"<1", "1-2", "2-4", "4-8", "8-16", ">16"};

std::size_t enr_bin(double enr) {
  return static_cast<std::size_t>(std::upper_bound(kBinEdges.begin(), kBinEdges.end(), enr) - kBinEdges.begin());
}

std::string verdict_of(const mrd::discrepancy::DiscrepancyResult& r) {
  return mrd::discrepancy::verdict_name(r.verdict);
}

/// Case i: clean (2 in 12), one catalogue effect alone (7 in 12, the eight
/// in turn), an effect outside the catalogue (3 in 12, the four in turn).
std::vector<indep::Effect> truth_for_case(std::size_t i) {
  const std::size_t slot = i % 12;
  if (slot < 2) return {};
  if (slot < 9) return {indep::kCatalogueEffects[((i / 12) * 7 + (slot - 2)) % indep::kCatalogueEffects.size()]};
  return {indep::kOutOfCatalogueEffects[((i / 12) * 3 + (slot - 9)) % indep::kOutOfCatalogueEffects.size()]};
}

/// Whether the workflow's catalogue has an effect of this name (the
/// generator's names for catalogue effects are the workflow's).
bool workflow_knows(indep::Effect e) {
  return mrd::discrepancy::effect_from_name(indep::effect_name(e)).has_value();
}

/// The generator's effects the workflow has (catalogued) or has not.
std::vector<indep::Effect> generator_effects(bool catalogued) {
  std::vector<indep::Effect> out;
  for (const auto e : indep::kCatalogueEffects) {
    if (workflow_knows(e) == catalogued) out.push_back(e);
  }
  for (const auto e : indep::kOutOfCatalogueEffects) {
    if (workflow_knows(e) == catalogued) out.push_back(e);
  }
  return out;
}

mrd::discrepancy::MeasuredData to_measured(const indep::Case& c, std::uint64_t seed) {
  mrd::discrepancy::MeasuredData d;
  d.source = "independent-synth seed " + std::to_string(seed);
  d.time_s = c.time_s;
  d.displacement_m = c.displacement_m;
  d.current_cmd_a = c.current_cmd_a;
  d.force_n = c.force_n;
  return d;
}

std::string named_label(const mrd::discrepancy::DiscrepancyResult& r) {
  std::vector<std::string> names;
  for (const auto e : r.effects) names.emplace_back(mrd::discrepancy::effect_name(e));
  std::sort(names.begin(), names.end());
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : "+") + n;
  return s.empty() ? "none" : s;
}

// The generator's split of its effects into catalogued and not must be the
// workflow's: an effect the workflow learns has to move in the generator too,
// with the form the study then expects it to name.
TEST(DiscrepancyIndependentStudy, GeneratorAndWorkflowAgreeOnTheCatalogue) {
  for (const auto e : indep::kCatalogueEffects) EXPECT_TRUE(workflow_knows(e)) << indep::effect_name(e);
  for (const auto e : indep::kOutOfCatalogueEffects) EXPECT_FALSE(workflow_knows(e)) << indep::effect_name(e);
}

struct Tally {
  int hit = 0, total = 0;
  void add(bool ok) {
    hit += ok;
    ++total;
  }
  [[nodiscard]] double rate() const { return total ? static_cast<double>(hit) / total : 0.0; }
  [[nodiscard]] std::string text() const {
    if (total == 0) return "-";
    char b[32];
    std::snprintf(b, sizeof b, "%d/%d", hit, total);
    return b;
  }
};

TEST(DiscrepancyIndependentStudy, DetectionFalsePositivesAndUnexplained) {
  const char* base_env = std::getenv("MRD_INDEPENDENT_STUDY_SEED_BASE");
  const std::uint64_t seed_base = base_env ? std::strtoull(base_env, nullptr, 10) : 5000u;
  // MRD_INDEPENDENT_STUDY_ONLY=<seed>: that case alone, with the workflow's findings printed.
  const char* only_env = std::getenv("MRD_INDEPENDENT_STUDY_ONLY");
  const std::uint64_t only = only_env ? std::strtoull(only_env, nullptr, 10) : 0u;
  const mrd::discrepancy::DiscrepancyOptions opt;

  std::map<std::string, std::array<Tally, 6>> detect;      // effect → per ENR bin: right set named
  std::map<std::string, Tally> detect_above;               // effect → at or above the limit
  std::array<Tally, 6> detect_all{};
  Tally detect_all_above, clean_fp, ooc_none_above, ooc_unexplained_above;
  std::map<std::string, std::array<Tally, 6>> ooc_none;    // effect → per bin: no catalogue effect named
  std::map<std::string, std::map<std::string, int>> named_for;  // truth → named → count
  std::vector<std::string> misses;
  double workflow_s = 0.0, generate_s = 0.0;

  std::size_t cases_run = 0;
  for (std::size_t i = 0; i < kCases; ++i) {
    if (only_env && seed_base + i != only) continue;
    ++cases_run;
    indep::Spec spec;
    spec.effects = truth_for_case(i);
    spec.seed = seed_base + i;
    const auto t0 = std::chrono::steady_clock::now();
    const indep::Case c = indep::generate(spec);
    const auto t1 = std::chrono::steady_clock::now();
    const mrd::discrepancy::DiscrepancyResult r = mrd::discrepancy::run_discrepancy(to_measured(c, spec.seed), opt);
    const auto t2 = std::chrono::steady_clock::now();
    generate_s += std::chrono::duration<double>(t1 - t0).count();
    workflow_s += std::chrono::duration<double>(t2 - t1).count();

    if (only_env) {
      std::printf("seed %llu: %s\n", static_cast<unsigned long long>(spec.seed), c.description.c_str());
      for (const auto& f : r.findings) std::printf("  %s\n", f.c_str());
      std::printf("  baseline residual: structured %.3f;", r.signatures_before.structured_share);
      for (const auto& sg : r.signatures_before.signatures) std::printf(" %s %.3f", sg.name.c_str(), sg.held_out_share);
      std::printf("\n");
      if (r.filter_check.checked) {
        std::printf("  delay %.4f s against a low-pass: tau %.4f s, delta BIC %.1f, held-out %.3f\n",
                    r.filter_check.delay_s, r.filter_check.tau_s, r.filter_check.delta_bic,
                    r.filter_check.held_out_reduction);
      }
      if (r.filter_check.compliance_checked)
        std::printf("  selected against a series compliance: %.3g m/N, delta BIC %.1f, held-out %.3f\n",
                    r.filter_check.compliance_m_per_n, r.filter_check.compliance_delta_bic,
                    r.filter_check.compliance_held_out_reduction);
    }
    const std::string named = named_label(r);
    const std::string verdict = verdict_of(r);
    const std::string truth = c.effects.empty() ? "none" : std::string(indep::effect_name(c.effects[0]));
    // A low-pass or a series compliance counts by what no pure delay reproduces
    // (independent_synth.hpp): below the noise, time_delay describes it.
    const double enr = c.enr.empty()                       ? 0.0
                       : std::isnan(c.enr_beyond_delay[0]) ? c.enr[0]
                                                           : c.enr_beyond_delay[0];
    named_for[truth][named]++;
    bool ok = true;
    if (c.effects.empty()) {
      const bool fp = named != "none" || verdict != "none";
      clean_fp.add(fp);
      ok = !fp;
    } else if (workflow_knows(c.effects[0])) {
      ok = named == truth && verdict == "explained";
      detect[truth][enr_bin(enr)].add(ok);
      detect_all[enr_bin(enr)].add(ok);
      if (enr >= kDetectionLimitEnr) {
        detect_above[truth].add(ok);
        detect_all_above.add(ok);
      }
    } else {
      const bool none = r.effects.empty();
      ooc_none[truth][enr_bin(enr)].add(none);
      if (enr >= kDetectionLimitEnr) {
        ooc_none_above.add(none);
        ooc_unexplained_above.add(verdict == "unexplained");
        ok = verdict == "unexplained";
      }
    }
    if (!ok) {
      char b[512];
      std::snprintf(b, sizeof b, "  seed %llu: %s (ENR %.2f) -> %s [%s]; gap %.4f -> %.4f; %s",
                    static_cast<unsigned long long>(spec.seed), truth.c_str(), enr, named.c_str(), verdict.c_str(),
                    r.gap_before, r.gap_after, c.description.c_str());
      misses.emplace_back(b);
    }
  }

  // The table.
  std::printf("\nIndependent discrepancy study: %zu cases, seeds %llu-%llu, detection limit ENR >= %.0f\n", kCases,
              static_cast<unsigned long long>(seed_base), static_cast<unsigned long long>(seed_base + kCases - 1),
              kDetectionLimitEnr);
  std::printf("\n(a) single catalogue effect: right set named, by ENR\n");
  std::printf("%-20s", "effect");
  for (const char* b : kBinNames) std::printf("%8s", b);
  std::printf("%12s\n", ">=limit");
  for (const auto e : generator_effects(true)) {
    const std::string name(indep::effect_name(e));
    std::printf("%-20s", name.c_str());
    for (const auto& t : detect[name]) std::printf("%8s", t.text().c_str());
    std::printf("%12s\n", detect_above[name].text().c_str());
  }
  std::printf("%-20s", "all");
  for (const auto& t : detect_all) std::printf("%8s", t.text().c_str());
  std::printf("%12s  (%.0f %%; target %.0f %%, floor %.0f %%)\n", detect_all_above.text().c_str(),
              100.0 * detect_all_above.rate(), 100.0 * kTargetRightSetRate, 100.0 * kFloorRightSetRate);
  std::printf("\n(b) clean records with anything named: %s (%.0f %%, allowed %.0f %%)\n", clean_fp.text().c_str(),
              100.0 * clean_fp.rate(), 100.0 * kMaxFalsePositiveRate);
  std::printf("\n(c) out-of-catalogue effect: no catalogue effect named, by ENR (low-pass, compliance: beyond the best delay)\n");
  std::printf("%-20s", "effect");
  for (const char* b : kBinNames) std::printf("%8s", b);
  std::printf("\n");
  for (const auto e : generator_effects(false)) {
    const std::string name(indep::effect_name(e));
    std::printf("%-20s", name.c_str());
    for (const auto& t : ooc_none[name]) std::printf("%8s", t.text().c_str());
    std::printf("\n");
  }
  std::printf(
      "at or above the limit: no catalogue effect %s (%.0f %%); verdict unexplained %s (%.0f %%; target %.0f %%, "
      "floor %.0f %%)\n",
      ooc_none_above.text().c_str(), 100.0 * ooc_none_above.rate(), ooc_unexplained_above.text().c_str(),
      100.0 * ooc_unexplained_above.rate(), 100.0 * kTargetOutOfCatalogueUnexplainedRate,
      100.0 * kFloorOutOfCatalogueUnexplainedRate);
  std::printf("\nnamed, per truth:\n");
  for (const auto& [truth, row] : named_for) {
    std::printf("  %-20s", truth.c_str());
    for (const auto& [named, n] : row) std::printf(" %s x%d;", named.c_str(), n);
    std::printf("\n");
  }
  std::printf("\nmisses (%zu):\n", misses.size());
  for (std::size_t k = 0; k < misses.size() && k < 60; ++k) std::printf("%s\n", misses[k].c_str());
  std::printf("\ntime: generator %.2f s/case, workflow %.2f s/case\n", generate_s / kCases, workflow_s / kCases);
  std::fflush(stdout);

  EXPECT_LE(clean_fp.rate(), kMaxFalsePositiveRate) << "false positives on clean records";
  // Rates over fewer cases (the sanitizer build's 12) are too coarse for the floors.
  if (cases_run >= 60) {
    EXPECT_GE(detect_all_above.rate(), kFloorRightSetRate) << "right set above ENR " << kDetectionLimitEnr;
    EXPECT_GE(ooc_unexplained_above.rate(), kFloorOutOfCatalogueUnexplainedRate)
        << "out-of-catalogue effects unexplained";
  }
}

}  // namespace
