#include "host_sim/run/motions.hpp"

#include <cstdlib>
#include <utility>

#include "host_sim/excitation/ground_motion.hpp"
#include "host_sim/excitation/scaled_motion.hpp"
#include "host_sim/excitation/synthetic_motion.hpp"
#include "mrd/units.hpp"

#ifndef MRD_SHARED_DIR
#define MRD_SHARED_DIR ""
#endif

namespace mrd::run {
namespace fs = std::filesystem;

namespace {
struct ThesisRecord {
  const char* file;
  const char* label;
};
// Table 6.2, cases a–d.
constexpr ThesisRecord kThesisRecords[] = {
    {"hachinohe_ns.csv", "Case a: Hachinohe"},
    {"northridge_sylmar_ns.csv", "Case b: Northridge"},
    {"kobe_jma_ns.csv", "Case c: Kobe"},
    {"elcentro_ns.csv", "Case d: El Centro"},
};

bool has_all_records(const fs::path& dir) {
  std::error_code ec;
  for (const auto& r : kThesisRecords) {
    if (!fs::is_regular_file(dir / r.file, ec)) return false;
  }
  return true;
}
}  // namespace

std::optional<fs::path> find_shared_ground_motions() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("MRD_SHARED_DIR"); env && *env) candidates.emplace_back(fs::path(env) / "ground_motions");
  candidates.emplace_back(fs::path("..") / "shared" / "ground_motions");
  if (*MRD_SHARED_DIR) candidates.emplace_back(fs::path(MRD_SHARED_DIR) / "ground_motions");
  for (const auto& c : candidates) {
    if (has_all_records(c)) return c;
  }
  return std::nullopt;
}

StudyMotion load_study_motion(const fs::path& path, double pga_g, double step_s, double duration_s) {
  excitation::ScaledMotion scaled = excitation::load_scaled_motion(path, pga_g, step_s, duration_s);
  StudyMotion m;
  m.name = scaled.name;
  m.label = scaled.name;
  for (const auto& r : kThesisRecords) {
    if (path.filename() == r.file) m.label = r.label;
  }
  m.source = scaled.source;
  m.scale_factor = scaled.scale_factor;
  m.pga_m_s2 = scaled.pga_m_s2;
  m.accel_m_s2 = std::move(scaled.accel_m_s2);
  return m;
}

StudyMotion synthetic_study_motion(std::uint64_t seed, double pga_g, double step_s, double duration_s) {
  excitation::SyntheticMotionParams p;
  p.seed = seed;
  p.duration_s = duration_s;
  p.target_pga_m_s2 = pga_g * units::kStandardGravity_m_s2;
  const excitation::GroundMotion g = excitation::synthetic_motion(p);
  StudyMotion m;
  m.name = g.name;
  m.label = "synthetic, seed " + std::to_string(seed);
  m.source = g.source;
  m.synthetic = true;
  m.pga_m_s2 = g.pga_m_s2();
  m.accel_m_s2 = excitation::resample_linear(g, step_s, duration_s);
  return m;
}

std::vector<StudyMotion> thesis_study_motions(double pga_g, double step_s) {
  std::vector<StudyMotion> out;
  if (const auto dir = find_shared_ground_motions()) {
    for (const auto& r : kThesisRecords) out.push_back(load_study_motion(*dir / r.file, pga_g, step_s));
  } else {
    for (unsigned seed = 1; seed <= 4; ++seed) out.push_back(synthetic_study_motion(seed, pga_g, step_s, 40.0));
  }
  return out;
}

}  // namespace mrd::run
