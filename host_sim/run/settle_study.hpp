#pragma once
/// The idle-time settling state of a damper after a given idle time
/// (thesis §5.3): the quantities of Eq. 5.1–5.8 in one record.

#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::run {

struct SettleSummary {
  double idle_time_s = 0.0;
  double settling_velocity_m_s = 0.0;           ///< Eq. 5.1
  double hindered_settling_velocity_m_s = 0.0;  ///< Eq. 5.2
  double settled_layer_height_m = 0.0;          ///< Eq. 5.3, Table 5.5
  double max_settling_time_s = 0.0;             ///< Eq. 5.4
  double sq = 0.0;                              ///< Eq. 5.5, fraction in [0, 1]
  physics::PrCoefficients pr;                   ///< Eq. 5.6–5.8
};

/// Computes the summary. `idle_time_s` must be finite and ≥ 0 (callers check).
SettleSummary settle_study(double idle_time_s, const physics::SettlingParams& sp = {},
                           const physics::ParticipantRatioParams& pp = {});

}  // namespace mrd::run
