#pragma once
/// Physical ranges of an MR damper's quantities, SI: what a damper.toml
/// (baseline_file.hpp) may hold, each with the reason for its ends. A number
/// outside its range is refused naming the file, line, field and the range;
/// the calibration searches inside the same ranges (calibrate.cpp checks its
/// search bounds against them at compile time), so that every damper.toml it
/// writes reads back.
///
/// Where a measured record reaches a quantity (forces, displacements,
/// velocities, currents), the range is the measured-record reader's own limit
/// (kMaxMeasured*, measured_data.hpp): a baseline's validity range describes
/// records.

#include <cstddef>

#include "host_sim/discrepancy/measured_data.hpp"

namespace mrd::discrepancy {

/// A closed interval [min, max] of one quantity, its unit (as written in
/// messages; empty for a ratio) and what it is ("a force").
struct PhysicalRange {
  double min;
  double max;
  const char* unit;
  const char* what;

  [[nodiscard]] constexpr bool contains(double v) const noexcept { return v >= min && v <= max; }
};

/// Largest half stroke of any damper, m: over three times that of the
/// thesis's 200 kN damper (±0.2921 m, §3.1); base-isolation dampers reach
/// about ±0.6 m.
inline constexpr double kMaxHalfStroke_m = 1.0;
/// Fastest motion of any damper, m/s: forty times the thesis damper's rating
/// (0.2491 m/s, Table 3.1); seismic dampers are tested up to 1-2 m/s.
inline constexpr double kMaxDamperVelocity_m_s = 10.0;

// ---- the current laws (Eq. 4.2-4.3) ------------------------------------------

/// A yield force: from 1 mN, below the resolution of any damper's load cell
/// (the thesis's ±250 kN cell over 16 bits resolves 7.6 N, a laboratory cell
/// about 0.1 N), so that a smaller one is none, to ten times the largest
/// force a record may hold (kMaxMeasuredForce_n, 1e8 N, beyond any structure's
/// damper): room for a current law's limit extrapolated beyond the records'
/// currents.
inline constexpr PhysicalRange kYieldForceRange{1e-3, 10.0 * kMaxMeasuredForce_n, "N", "a force"};
/// A viscous coefficient: from 1 mN at 1 m/s (below any load cell) to the
/// largest force a record may hold (1e8 N) at 1 mm/s.
inline constexpr PhysicalRange kViscousRange{1e-3, kMaxMeasuredForce_n / 1e-3, "N s/m", "a viscous coefficient"};
/// rate_per_a: 0 is a law constant in the current; 1000 per ampere saturates
/// within 5 mA, below the resolution of any coil drive (the thesis: 0.7 and
/// 1.15 per A, Table 4.1).
inline constexpr PhysicalRange kCurrentRateRange{0.0, 1e3, "1/A", "a rate"};

// ---- the law's shape -----------------------------------------------------------

/// A velocity band (Eq. 4.4's v_TF, the lost motion's band): from 1 µm/s,
/// below any velocity a record resolves (10 µm of LVDT noise leaves about
/// 50 µm/s after smoothing, measured_data.hpp), to the fastest damper.
inline constexpr PhysicalRange kVelocityBandRange{1e-6, kMaxDamperVelocity_m_s, "m/s", "a velocity"};
/// The Bouc-Wen x_y: from 1 nm, below any displacement sensor, to the
/// largest half stroke.
inline constexpr PhysicalRange kYieldDispRange{1e-9, kMaxHalfStroke_m, "m", "a displacement"};
/// The Bouc-Wen k_0 (an accumulator's gas spring, §3.1): 0 is none; at most
/// the largest force (1e8 N) over 1 cm, stiffer than any accumulator.
inline constexpr PhysicalRange kStiffnessRange{0.0, kMaxMeasuredForce_n / 0.01, "N/m", "a stiffness"};
/// The lost motion's play per newton of yield force: from 1e-18 m/N, a play
/// of 0.1 nm even at the largest force (1e8 N), below any sensor, to 1 m/N,
/// a metre of play at one newton, beyond any stroke.
inline constexpr PhysicalRange kPlayRange{1e-18, 1.0, "m/N", "a play per newton"};
/// The share of the force a lost motion holds up: at most all of it; a
/// millionth of the force is below any load cell's resolution of its range.
/// A compliance in series with the law, m/N: from rigid (0) to 1 mm per newton.
inline constexpr PhysicalRange kSeriesComplianceRange{0.0, 1e-3, "m/N", "a compliance"};
inline constexpr PhysicalRange kShareRange{1e-6, 1.0, "", "a share"};
/// The force channel's lag: 0 (none) to 100 ms, longer than any anti-alias
/// filter or logger of a damper test (the time_delay effect's bound).
inline constexpr PhysicalRange kForceDelayRange{0.0, 0.1, "s", "a lag"};
/// Eq. 4.4's transition time: from 1 µs (none: 10 µm/s at 10 m/s²) to
/// 100 ms, twenty times the few milliseconds the fluid's chains and the
/// valve's pressure take to form again.
inline constexpr PhysicalRange kTransitionTimeRange{1e-6, 0.1, "s", "a time"};
/// The Bingham law's viscous exponent (baseline.hpp): shear thinning below 1,
/// thickening above; MR fluids past yield lie between about 0.2 and 2.
/// A current law's exponent q (baseline.hpp, CurrentLaw).
inline constexpr PhysicalRange kCurrentExponentRange{0.01, 10.0, "", "an exponent"};
inline constexpr PhysicalRange kViscousExponentRange{0.01, 10.0, "", "an exponent"};

// ---- the spencer law (Spencer et al. 1997, physics/spencer_law.hpp) ------------------

/// α's change per ampere (and per ampere squared), k_1 and k_0 being
/// stiffnesses of kStiffnessRange: either sign, at most the largest stiffness
/// per ampere (a law that changes by more within 1 A leaves that range).
inline constexpr PhysicalRange kSpencerAlphaSlopeRange{-kStiffnessRange.max, kStiffnessRange.max, "N/m per A^k",
                                                       "a stiffness change"};
/// c_0's and c_1's change per ampere: either sign, at most the largest
/// viscous coefficient per ampere.
inline constexpr PhysicalRange kSpencerViscousSlopeRange{-kViscousRange.max, kViscousRange.max, "N s/m per A",
                                                         "a viscous coefficient change"};
/// γ at 0 A, 1/m^n: 0 is no saturation; 1e30 saturates z (a length) below
/// 1 nm with A up to 1e6 and n = 2, below any sensor (the laboratory damper:
/// 1.9e6 1/m², z saturating at 9 mm).
inline constexpr PhysicalRange kSpencerGammaRange{0.0, 1e30, "1/m^n", "a Bouc-Wen coefficient"};
/// β/γ: 0 (β = 0) to 1000; β + γ must stay positive for z to saturate
/// (Spencer et al. 1997 fit β = γ).
inline constexpr PhysicalRange kSpencerBetaRatioRange{0.0, 1e3, "", "a ratio"};
/// A: from 1e-6 to 1e6 (dimensionless; the laboratory damper's 300).
inline constexpr PhysicalRange kSpencerARange{1e-6, 1e6, "", "a Bouc-Wen coefficient"};
/// n: 1 to 10 (the paper's and the laboratory's 2).
inline constexpr PhysicalRange kSpencerExponentRange{1.0, 10.0, "", "an exponent"};
/// x_0, the accumulator spring's rest stroke: within the largest half stroke.
inline constexpr PhysicalRange kSpencerRestStrokeRange{-kMaxHalfStroke_m, kMaxHalfStroke_m, "m", "a stroke"};

// ---- the coil (Eq. 4.5) ----------------------------------------------------------

/// A time constant of the coil and its drive: from 1 µs, shorter than the
/// period of any PWM drive (50 µs at 20 kHz), to 1000 s, a field that takes a
/// quarter of an hour to settle is no damper's coil (the thesis: 0.7 s and
/// 0.03 s).
inline constexpr PhysicalRange kCoilTimeConstantRange{1e-6, 1e3, "s", "a time constant"};
/// A branch's weight: its share of the unity DC gain.
inline constexpr PhysicalRange kCoilWeightRange{0.0, 1.0, "", "a weight"};

// ---- the participant ratio (Eq. 5.6-5.11, Table 5.6) ----------------------------

/// a_initial, b_initial, a_final, b_final: participant ratios, the share of
/// the MR particles that take part (§5.3).
inline constexpr PhysicalRange kParticipantRatioRange{0.0, 1.0, "", "a participant ratio"};
/// c_initial, c_final, c_rise: rates per unit of the settling quotient SQ
/// (a fraction, Eq. 5.5): 100 completes the change within the first 5 % of
/// SQ (e^-5), a step no idle time resolves (the thesis: 3.65 to 7).
inline constexpr PhysicalRange kSettlingRateRange{0.0, 100.0, "", "a rate per unit of SQ"};
/// a_rise, b_rise: rates per volume unit of ∫Q dt (Eq. 5.9): with the
/// thesis's litre, 1e4 recovers the ratio within 0.1 mL of flow, 10 µm of the
/// thesis piston's travel (the thesis: 5.474 and 0).
inline constexpr PhysicalRange kMixingRateRange{0.0, 1e4, "", "a rate per volume unit"};
/// The mixing flow area: from 1 mm², the annulus of a 1 mm piston, to 1 m²,
/// a piston 1.1 m across, beyond any damper (the thesis: 0.01062 m²).
inline constexpr PhysicalRange kFlowAreaRange{1e-6, 1.0, "m2", "an area"};
/// The volume unit of ∫Q dt: from 1 mm³ to 1 m³ (the thesis counts litres).
inline constexpr PhysicalRange kVolumeUnitRange{1e-9, 1.0, "m3", "a volume"};

// ---- what the damper is rated for ([rating]) -------------------------------------

/// A rated coil current: from 1 mA, below which no coil's field takes up a
/// damper's fluid (MR dampers are rated 0.5–3 A; the thesis's 2.5 A, §3.1), to
/// the largest current a record may hold (1000 A).
inline constexpr PhysicalRange kRatedCurrentRange{1e-3, kMaxMeasuredCurrent_a, "A", "a current"};
/// A rated force: from 1 N, below the force of any MR damper made (small ones,
/// for seats and prosthetic knees, give tens to hundreds of newtons), to the
/// largest force a record may hold (1e8 N; the thesis's 200 kN).
inline constexpr PhysicalRange kRatedForceRange{1.0, kMaxMeasuredForce_n, "N", "a force"};
/// A rated half stroke: from 0.1 mm, below any damper's stroke, to the
/// largest half stroke (the thesis's ±0.2921 m).
inline constexpr PhysicalRange kRatedStrokeRange{1e-4, kMaxHalfStroke_m, "m", "a half stroke"};
/// A rated velocity: from 1 µm/s, below any velocity a record resolves, to
/// the fastest damper (the thesis's 0.2491 m/s, Table 3.1).
inline constexpr PhysicalRange kRatedVelocityRange{1e-6, kMaxDamperVelocity_m_s, "m/s", "a velocity"};

// ---- the cylinder the fluid settles in ([geometry], Eq. 5.3, Table 3.1, 5.4) ----

/// The cylinder's inner diameter: from 1 mm to 2 m, far beyond the largest
/// MR dampers' bores (the thesis's 0.2032 m).
inline constexpr PhysicalRange kBoreDiameterRange{1e-3, 2.0, "m", "a diameter"};
/// The shaft's radius: 0 (none) to half the largest bore (the thesis's 0.04 m);
/// the reader also refuses a shaft as wide as the bore.
inline constexpr PhysicalRange kShaftRadiusRange{0.0, 1.0, "m", "a radius"};
/// The settling cylinder's length: from 1 mm to 5 m, twice the largest stroke
/// (2 m) with the piston and the heads (the thesis's 0.5842 m).
inline constexpr PhysicalRange kFluidLengthRange{1e-3, 5.0, "m", "a length"};
/// The fluid's volume: from 1 mm³ to 16 m³, the largest cylinder above (2 m
/// bore, 5 m long: 15.7 m³; the thesis's 0.0166 m³, Table 5.4).
inline constexpr PhysicalRange kFluidVolumeRange{1e-9, 16.0, "m3", "a volume"};

// ---- the coil's circuit ([coil], optional; the hardware plant) ----------------------

/// The coil's resistance: from 1 mΩ, below the leads of any coil, to 10 kΩ, at
/// which 1 A would take 10 kV (the thesis's 4.8 Ω, Table 3.1).
inline constexpr PhysicalRange kCoilResistanceRange{1e-3, 1e4, "ohm", "a resistance"};
/// The coil's inductance: from 1 µH to 1000 H, whose L/R over the smallest
/// resistance would pass the coil time constant's top (the thesis's 5.0 H at
/// 1 A and 3.0 H at 2 A, Table 3.1).
inline constexpr PhysicalRange kCoilInductanceRange{1e-6, 1e3, "H", "an inductance"};
/// The coil's thermal resistance to its surroundings: from 1 mK/W, below a
/// water-cooled coil of a large damper, to 1000 K/W, above a small solenoid
/// in still air (the thesis coil's assumed 2 K/W, mrd/physics/coil_heat.hpp).
inline constexpr PhysicalRange kCoilThermalResistanceRange{1e-3, 1e3, "K/W", "a thermal resistance"};
/// The coil's thermal time constant: from 1 s, a bare winding of a few grams,
/// to 1e5 s (28 h), beyond a coil of hundreds of kilograms in a steel housing
/// (the thesis coil's assumed 20 min); the firmware's fixed-point I²t counts
/// up to 8.6e6 s at 1 kHz (firmware/core/controller_config.hpp).
inline constexpr PhysicalRange kCoilThermalTimeConstantRange{1.0, 1e5, "s", "a time constant"};

// ---- what the records cover -------------------------------------------------------

/// Currents a record may hold (the reader's limit, either sign).
inline constexpr PhysicalRange kRecordCurrentRange{-kMaxMeasuredCurrent_a, kMaxMeasuredCurrent_a, "A", "a current"};
/// The largest |v| of records that move: from 1 nm/s to the reader's limit.
inline constexpr PhysicalRange kRecordVelocityRange{1e-9, kMaxMeasuredVelocity_m_s, "m/s", "a velocity"};
/// The largest |F| of records whose force changes: from the smallest yield
/// force to the reader's limit.
inline constexpr PhysicalRange kRecordForceRange{kYieldForceRange.min, kMaxMeasuredForce_n, "N", "a force"};
/// Displacement half ranges (0: not stated) up to the reader's limit.
inline constexpr PhysicalRange kRecordAmplitudeRange{0.0, kMaxMeasuredDisplacement_m, "m", "a displacement"};
/// Dominant frequencies (0: not stated): MR fluid forms its chains in about
/// a millisecond, so a damper's motion above 10 kHz is a vibration of the rig
/// the fluid cannot follow (damper tests reach some 50 Hz).
inline constexpr PhysicalRange kRecordFrequencyRange{0.0, 1e4, "Hz", "a frequency"};
/// A normalized RMS gap (a fraction of the record's RMS force). A joint fit
/// is never worse than a damper of no force, whose gap is 1 on every record,
/// so its worst record's gap stays below the square root of the number of
/// records; 100 allows ten thousand records.
inline constexpr PhysicalRange kGapRange{0.0, 100.0, "", "a gap"};
/// Samples of one record: at most one per 8 bytes ("0,0,0,0\n") of the
/// largest record file read.
inline constexpr std::size_t kMaxRecordSamples = kMaxMeasuredFileBytes / 8;

/// The range of a standard error of a quantity of range `r`: 0 to the
/// quantity's largest value (a larger one says no more than "anywhere in the
/// range": not identified).
[[nodiscard]] constexpr PhysicalRange sigma_range(const PhysicalRange& r) noexcept {
  return {0.0, r.max, r.unit, "a standard error"};
}

}  // namespace mrd::discrepancy
