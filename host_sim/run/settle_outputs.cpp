#include "host_sim/run/settle_outputs.hpp"

#include "host_sim/report/summary_json.hpp"
#include "mrd/units.hpp"

namespace mrd::run {

nlohmann::json settle_summary_json(double idle_years, const SettleSummary& s) {
  return nlohmann::json{
      {"idle_years", idle_years},
      {"settling_velocity_m_s", s.settling_velocity_m_s},
      {"hindered_settling_velocity_m_s", s.hindered_settling_velocity_m_s},
      {"settled_layer_height_m", s.settled_layer_height_m},
      {"max_settling_time_years", units::s_to_years(s.max_settling_time_s)},
      {"sq", s.sq},
      {"a_pr", s.pr.a_pr},
      {"b_pr", s.pr.b_pr},
      {"c_pr", s.pr.c_pr},
  };
}

void write_settle_outputs(const std::filesystem::path& dir, double idle_years, const SettleSummary& s) {
  report::write_summary_json(dir, settle_summary_json(idle_years, s));
}

}  // namespace mrd::run
