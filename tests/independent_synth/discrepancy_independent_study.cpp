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
// delay (independent_synth.hpp), what a time_delay cannot reproduce; a gas
// spring with its preload by its ENR beyond a constant, what a force_offset
// cannot.
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
// measured with this generator and workflow, every effect drawn at ENR >= 4
// (MRD_INDEPENDENT_STUDY_ENR_MIN=4, 150 cases each): seeds 20000-20149 gave
// right set 77/80 on all forms (the workflow's models now carry every form
// the generator draws), out-of-catalogue unexplained 22/22, false positives
// 0/26; seeds 30000-30149 gave 79/80, 25/25 and 0/26. The lower of the two
// less one case (76/80 = 0.95, 24/25 = 0.96) is above the floors, which stay
// at 0.93 and 0.85, so that more than one miss on the CI set (5000-5059:
// 16/17, 10/10, 0/10) fails the test.
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

constexpr std::size_t kDefaultCases = MRD_INDEPENDENT_STUDY_CASES;
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

/// Forms whose physics the workflow's effect models do not carry
/// (host_sim/discrepancy/damper_model.cpp): drawn and reported per form, the
/// floor asserted over the other forms. None at present: the models carry a
/// single-lag coil (coil_lag's single_lag form), a settled layer that
/// recovers fully over its own volume (idle_settling's full_recovery) and free
/// play ending in a contact spring (backlash's impact_spring), which the
/// selection chooses by BIC.
constexpr std::array<const char*, 0> kFormsBeyondTheModels{};

bool beyond_the_models(const std::string& effect_form) {
  return std::find(kFormsBeyondTheModels.begin(), kFormsBeyondTheModels.end(), effect_form) !=
         kFormsBeyondTheModels.end();
}

/// Whether `named` is the right answer for a single catalogue effect in its
/// form: the effect alone; for a gas spring with its preload, also with a
/// force_offset beside it (the preload is a constant force the catalogue's
/// gas_spring, k x, does not carry).
bool right_set(const std::string& truth, const std::string& form, const std::string& named) {
  if (named == truth) return true;
  return truth == "gas_spring" && form == "preload" && named == "force_offset+gas_spring";
}

/// Per form (effect/form, noise colour, quantization, motion): right or not,
/// and what a wrong answer named.
struct FormTally {
  int cases = 0, right = 0;
  std::map<std::string, int> wrong_named;
  void add(bool ok, const std::string& named) {
    ++cases;
    if (ok) {
      ++right;
    } else {
      ++wrong_named[named];
    }
  }
};

void print_form_table(const char* title, const std::map<std::string, FormTally>& rows) {
  std::printf("\n%s\n%-42s %6s %6s %6s  %s\n", title, "form", "cases", "right", "%", "wrong: named");
  for (const auto& [form, t] : rows) {
    std::string wrong;
    for (const auto& [named, n] : t.wrong_named) wrong += (wrong.empty() ? "" : "; ") + named + " x" + std::to_string(n);
    std::printf("%-42s %6d %6d %6.0f  %s\n", form.c_str(), t.cases, t.right,
                t.cases ? 100.0 * t.right / t.cases : 0.0, wrong.c_str());
  }
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

/// The first case from `seed` on (at most 16 tries) whose backlash is drawn
/// in the form `form`, without quantization: a 10 s record, every effect
/// sized to ENR `enr`. (The seeds the test starts from are the first such.)
indep::Case first_with_play_form(std::vector<indep::Effect> effects, std::uint64_t seed, const std::string& form,
                                 double enr, std::uint64_t& seed_used) {
  for (std::uint64_t s = seed; s < seed + 16; ++s) {
    indep::Spec spec;
    spec.effects = effects;
    spec.seed = s;
    spec.duration_s = 10.0;
    spec.target_enr = enr;
    indep::Case c = indep::generate(spec);
    if (c.forms[0] == form && c.quantization_form == "none") {
      seed_used = s;
      return c;
    }
  }
  seed_used = 0;
  return {};
}

// Free play against a transport delay, by what each acts on. A delay shifts
// the whole force, also where the rod has crossed the play and taken up its
// stop; free play changes the force only while the rod takes it up. A play
// that engages more smoothly than the catalogue's stop leaves a trace at the
// engagements that a sub-millisecond delay partly absorbs: that delay must
// go (workflow.cpp, drop_engagement_delay), and a true delay beside the same
// play must stay.
TEST(DiscrepancyIndependentStudy, ASmoothPlayIsNotGivenADelayAndATrueDelayBesideItIsKept) {
  const mrd::discrepancy::DiscrepancyOptions opt;
  std::uint64_t seed = 0;
  const indep::Case play = first_with_play_form({indep::Effect::backlash}, 71003, "smooth", 24.0, seed);
  ASSERT_NE(seed, 0u) << "no smooth play drawn in 16 seeds from 71003";
  const auto r_play = mrd::discrepancy::run_discrepancy(to_measured(play, seed), opt);
  EXPECT_EQ(named_label(r_play), "backlash") << "seed " << seed << ": " << play.description;
  const indep::Case both =
      first_with_play_form({indep::Effect::backlash, indep::Effect::time_delay}, 72003, "smooth", 24.0, seed);
  ASSERT_NE(seed, 0u) << "no smooth play drawn in 16 seeds from 72003";
  const auto r_both = mrd::discrepancy::run_discrepancy(to_measured(both, seed), opt);
  EXPECT_EQ(named_label(r_both), "backlash+time_delay") << "seed " << seed << ": " << both.description;
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
  // MRD_INDEPENDENT_STUDY_CASES=<n>: the number of cases (default: the build's);
  // MRD_INDEPENDENT_STUDY_ENR_MIN=<enr>: the lowest ENR drawn (default indep::kEnrMin),
  // e.g. 4 to spend a long per-form run on effects at or above the limit.
  const char* cases_env = std::getenv("MRD_INDEPENDENT_STUDY_CASES");
  const std::size_t kCases = cases_env ? std::strtoull(cases_env, nullptr, 10) : kDefaultCases;
  const char* enr_min_env = std::getenv("MRD_INDEPENDENT_STUDY_ENR_MIN");
  const double enr_min = enr_min_env ? std::strtod(enr_min_env, nullptr) : indep::kEnrMin;
  // MRD_INDEPENDENT_STUDY_EFFECTS=<name,name>: only these effects, in turn (no clean records).
  std::vector<indep::Effect> only_effects;
  if (const char* list = std::getenv("MRD_INDEPENDENT_STUDY_EFFECTS")) {
    const std::string text = std::string(",").append(list).append(",");
    for (const auto e : generator_effects(true)) {
      const std::string item = std::string(",").append(indep::effect_name(e)).append(",");
      if (text.find(item) != std::string::npos) only_effects.push_back(e);
    }
  }
  const mrd::discrepancy::DiscrepancyOptions opt;
  // At or above the limit: per effect form; per noise colour, quantization and
  // motion (catalogue effects and clean records together, a clean record
  // right when nothing is named and the verdict is none).
  std::map<std::string, FormTally> by_effect_form, by_noise, by_quantization, by_motion;

  std::map<std::string, std::array<Tally, 6>> detect;      // effect → per ENR bin: right set named
  std::map<std::string, Tally> detect_above;               // effect → at or above the limit
  std::array<Tally, 6> detect_all{};
  Tally detect_all_above, detect_modelled_above, clean_fp, ooc_none_above, ooc_unexplained_above;
  std::map<std::string, std::array<Tally, 6>> ooc_none;    // effect → per bin: no catalogue effect named
  std::map<std::string, std::map<std::string, int>> named_for;  // truth → named → count
  std::vector<std::string> misses;
  double workflow_s = 0.0, generate_s = 0.0;

  std::size_t cases_run = 0;
  for (std::size_t i = 0; i < kCases; ++i) {
    if (only_env && seed_base + i != only) continue;
    ++cases_run;
    indep::Spec spec;
    spec.effects = only_effects.empty() ? truth_for_case(i)
                                        : std::vector<indep::Effect>{only_effects[i % only_effects.size()]};
    spec.seed = seed_base + i;
    spec.enr_min = enr_min;
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
      for (std::size_t k = 0; k < r.rounds.size(); ++k) {
        for (const auto& cand : r.rounds[k].candidates) {
          std::printf("  round %zu %-20s dBIC %9.1f rss -%.3f held -%.3f gap %.4f: %s\n", k + 1,
                      mrd::discrepancy::EffectSet{cand.model}.label().c_str(), cand.delta_bic, cand.rss_reduction,
                      cand.held_out_reduction, cand.gap, cand.verdict.c_str());
        }
      }
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
    // A gas spring's preload likewise counts by its part beyond a constant (a force_offset).
    const double enr = c.enr.empty()                         ? 0.0
                       : !std::isnan(c.enr_beyond_delay[0])  ? c.enr_beyond_delay[0]
                       : !std::isnan(c.enr_beyond_offset[0]) ? c.enr_beyond_offset[0]
                                                             : c.enr[0];
    named_for[truth][named]++;
    bool ok = true;
    if (c.effects.empty()) {
      const bool fp = named != "none" || verdict != "none";
      clean_fp.add(fp);
      ok = !fp;
      const std::string label = fp ? named + " [" + verdict + "]" : named;
      by_effect_form["none (clean)"].add(ok, label);
      by_noise[c.noise_form].add(ok, "clean: " + label);
      by_quantization[c.quantization_form].add(ok, "clean: " + label);
      by_motion[c.motion_form].add(ok, "clean: " + label);
    } else if (workflow_knows(c.effects[0])) {
      ok = right_set(truth, c.forms[0], named) && verdict == "explained";
      detect[truth][enr_bin(enr)].add(ok);
      detect_all[enr_bin(enr)].add(ok);
      if (enr >= kDetectionLimitEnr) {
        detect_above[truth].add(ok);
        detect_all_above.add(ok);
        const std::string label = named == truth ? named + " [" + verdict + "]" : named;
        const std::string effect_form = std::string(truth).append("/").append(c.forms[0]);
        by_effect_form[effect_form].add(ok, label);
        if (!beyond_the_models(effect_form)) detect_modelled_above.add(ok);
        by_noise[c.noise_form].add(ok, truth + ": " + label);
        by_quantization[c.quantization_form].add(ok, truth + ": " + label);
        by_motion[c.motion_form].add(ok, truth + ": " + label);
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
      std::snprintf(b, sizeof b, "  seed %llu: %s/%s (ENR %.2f) -> %s [%s]; gap %.4f -> %.4f; %s; %s %s",
                    static_cast<unsigned long long>(spec.seed), truth.c_str(),
                    c.forms.empty() ? "-" : c.forms[0].c_str(), enr, named.c_str(), verdict.c_str(), r.gap_before,
                    r.gap_after, c.description.c_str(), c.noise_form.c_str(), c.quantization_form.c_str());
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
  std::printf("%12s  (%.0f %%; target %.0f %%)\n", detect_all_above.text().c_str(), 100.0 * detect_all_above.rate(),
              100.0 * kTargetRightSetRate);
  std::printf("%-20s%60s  (%.0f %%; target %.0f %%, floor %.0f %%)\n", "forms the models carry",
              detect_modelled_above.text().c_str(), 100.0 * detect_modelled_above.rate(), 100.0 * kTargetRightSetRate,
              100.0 * kFloorRightSetRate);
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
  print_form_table("(d) per effect form, at or above the limit (gas_spring/preload: force_offset beside it is right)",
                   by_effect_form);
  print_form_table("(e) per force-noise colour, at or above the limit and clean", by_noise);
  print_form_table("(f) per quantization, at or above the limit and clean", by_quantization);
  print_form_table("(g) per test motion, at or above the limit and clean", by_motion);
  std::printf("\nnamed, per truth:\n");
  for (const auto& [truth, row] : named_for) {
    std::printf("  %-20s", truth.c_str());
    for (const auto& [named, n] : row) std::printf(" %s x%d;", named.c_str(), n);
    std::printf("\n");
  }
  std::printf("\nmisses (%zu):\n", misses.size());
  for (std::size_t k = 0; k < misses.size() && k < 200; ++k) std::printf("%s\n", misses[k].c_str());
  std::printf("\ntime: generator %.2f s/case, workflow %.2f s/case\n", generate_s / static_cast<double>(kCases),
              workflow_s / static_cast<double>(kCases));
  std::fflush(stdout);

  EXPECT_LE(clean_fp.rate(), kMaxFalsePositiveRate) << "false positives on clean records";
  // Rates over fewer cases (the sanitizer build's 12) are too coarse for the floors;
  // a draw of chosen effects (MRD_INDEPENDENT_STUDY_EFFECTS) may hold no case a floor judges.
  if (cases_run >= 60 && detect_modelled_above.total > 0) {
    EXPECT_GE(detect_modelled_above.rate(), kFloorRightSetRate)
        << "right set above ENR " << kDetectionLimitEnr << ", forms the workflow's models carry";
  }
  if (cases_run >= 60 && ooc_unexplained_above.total > 0) {
    EXPECT_GE(ooc_unexplained_above.rate(), kFloorOutOfCatalogueUnexplainedRate)
        << "out-of-catalogue effects unexplained";
  }
}

}  // namespace
