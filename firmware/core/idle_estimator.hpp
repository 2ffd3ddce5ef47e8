#pragma once
/// Onboard idle-time estimator: tracks how settled the MR fluid is from the
/// measured damper displacement and time, and predicts the damper's force
/// capacity. Builds freestanding: no heap, no exceptions, no I/O in step().
///
/// State model (SettlingModel). The thesis (§5.3) models one episode: after an
/// idle time IT the fluid starts with SQ = min(IT/T_max, 1) (Eq. 5.4–5.5),
/// which fixes a_PR, b_PR, c_PR (Eq. 5.6–5.8); motion then raises
/// PR = b_PR + (a_PR − b_PR)·exp(−c_PR ∫Q dt) (Eq. 5.9). It has no law for
/// settling again after mixing. We track an *equivalent idle time* τ: the idle
/// time after which a fully mixed fluid would be as settled as ours.
/// <pre>
///   settled phase (no episode):  τ(t)  = min(τ_b + (t − t_b), T_max)
///                                PR(t) = a_PR(SQ(τ(t)))                       Eq. 5.5, 5.6
///   episode opens at t_o (the start of the first sample interval with motion):
///                                SQ_e = SQ(τ(t_o)); a, b, c = Eq. 5.6–5.8 at SQ_e, frozen
///                                V    = Σ |Δy|·A   (y: displacement through the dead band)
///                                PR   = b + (a − b)·exp(−c·V/unit)              Eq. 5.9
///   episode closes at t_c (quiet for quiet_close_s, or open for max_episode_s):
///                                τ_b  = min(a_PR⁻¹(PR) + (t_c − t_o), T_max),  t_b = t_c
///   a_PR⁻¹(PR) = T_max · min(1, max(0, −ln((PR − b_initial)/(a_initial − b_initial)) / c_initial))
/// </pre>
/// Consequences, each tested: one idle-then-excite episode is the thesis model
/// exactly (physics::MrDamper on the same velocity history); idle periods add
/// (0.3 y + 0.3 y = 0.6 y, also across a reboot); within one episode PR cannot
/// pass the ceiling b_PR(SQ_e) (the thesis's "false ceiling"), so long motion
/// ends at τ = a_PR⁻¹(b_PR(SQ_e)); each later episode starts from a smaller τ and
/// a higher ceiling, so repeated motion converges to the fully mixed state.
/// The fluid does not settle inside an episode (as in the thesis); the
/// episode's whole length is added as idle time when it closes, so continuous
/// ambient motion cannot hide settling for longer than max_episode_s.
///
/// Capacity: the damper force at the nominal current (2.5 A) and a reference
/// velocity with the present PR, relative to the same force with PR = 1:
/// F(I_nom, v_ref, PR) / F(I_nom, v_ref, 1) with physics::damper_force_n
/// (Eq. 5.10–5.12 with Eq. 4.4). F is affine in PR.
///
/// Time: inside one boot, time is integer control ticks × period (monotonic).
/// The wall clock (RTC) only measures the time the board was off (the gap to
/// the persisted stamp) and is checked for backward jumps. With no or a
/// corrupt record, an invalid clock at boot, or a clock that went backwards,
/// the estimator assumes the worst (τ = T_max, fully settled) and sets a flag.
///
/// Numeric builds: the estimator is one template, BasicIdleEstimator<Policy>,
/// built in double (Float64Policy, the reference: `IdleEstimator`), float
/// (num::Float32Policy) and fixed point (num::Fixed32Policy), with the
/// formats of idle_estimator_formats.hpp. Inside, every build counts time in
/// 64-bit ticks and the wall clock in milliseconds; SettlingModel below is
/// the same state model in double on a continuous time axis in seconds (the
/// simulator's truth and the design-time figures).
///
/// Rate: step() may run at the control rate or be decimated (every N-th
/// sample, with the tick still in control ticks). Displacement counted from
/// coarser samples misses motion between them, never adds any: decimation
/// and the dead band only make the estimate more conservative.

#include <cstdint>

#include "firmware/core/idle_estimator_formats.hpp"
#include "firmware/core/state_store.hpp"
#include "mrd/physics/bingham.hpp"
#include "mrd/physics/participant_ratio.hpp"
#include "mrd/physics/settling.hpp"

namespace mrd::fw {

/// Physics and episode rules of the state model.
struct IdleModelConfig {
  physics::SettlingParams settling{};          ///< Table 5.3, 5.4; gives T_max (Eq. 5.4)
  physics::ParticipantRatioParams pr{};        ///< Table 5.6, flow area and ∫Q unit
  physics::BinghamParams bingham{};            ///< Table 4.1, for the capacity
  double nominal_current_a = 2.5;              ///< current of the capacity definition, A
  double reference_velocity_m_s = 0.1;         ///< velocity of the capacity definition, m/s
  double quiet_close_s = 60.0;                 ///< an episode closes after this long without motion, s
  double max_episode_s = 3600.0;               ///< and at the latest after this long, s
};

/// The pure state model above, on one continuous time axis in seconds.
/// Times passed in must not decrease.
class SettlingModel {
 public:
  /// Returns false (and leaves a fully settled model) when the configuration
  /// is unusable: non-positive periods, area, unit or velocity.
  bool init(const IdleModelConfig& config) noexcept;

  /// Settled phase with equivalent idle time `equivalent_idle_s` at `t_s`.
  void reset(double equivalent_idle_s, double t_s) noexcept;
  /// Fully settled at `t_s` (τ = T_max): the worst case.
  void assume_settled(double t_s) noexcept { reset(t_max_s_, t_s); }

  /// Motion displaced `volume_m3` during [t0_s, t1_s]. Opens an episode at
  /// t0_s if none is open; closes it at t1_s if it has lasted max_episode_s.
  void add_motion(double t0_s, double t1_s, double volume_m3) noexcept;
  /// No motion until `t_s`: closes an open episode once it has been quiet
  /// for quiet_close_s (at last motion + quiet_close_s).
  void advance(double t_s) noexcept;

  /// τ at `t_s`; during an episode, τ as if the episode closed at `t_s`.
  double equivalent_idle_s(double t_s) const noexcept;
  /// PR at `t_s` (Eq. 5.6 in the settled phase, Eq. 5.9 in an episode).
  double participant_ratio(double t_s) const noexcept;
  double capacity_fraction(double t_s) const noexcept { return capacity_of_pr(participant_ratio(t_s)); }
  /// Capacity after `horizon_s` more without motion (the episode, if open,
  /// closed at `t_s`).
  double predicted_capacity_fraction(double t_s, double horizon_s) const noexcept;
  /// a, b, c that motion starting at `t_s` follows: the open episode's, or
  /// those a new episode would get.
  physics::PrCoefficients coefficients_at(double t_s) const noexcept;
  /// Displaced volume that brings PR to within `gap_fraction`·b_PR of the
  /// ceiling b_PR (Eq. 5.9 solved for ∫Q dt), counting what the open episode
  /// already displaced. m³; 0 when already there.
  double volume_to_ceiling_m3(double t_s, double gap_fraction) const noexcept;

  bool episode_open() const noexcept { return open_; }
  double episode_volume_m3() const noexcept { return open_ ? episode_m3_ : 0.0; }
  double last_motion_s() const noexcept { return last_motion_s_; }
  std::uint32_t episodes_closed() const noexcept { return episodes_closed_; }

  /// Eq. 5.4, s.
  double max_settling_time_s() const noexcept { return t_max_s_; }
  /// SQ of an equivalent idle time, Eq. 5.5.
  double sq_of_idle(double idle_s) const noexcept;
  /// a_PR(SQ(τ)), Eq. 5.5–5.6.
  double pr_of_idle(double idle_s) const noexcept;
  /// a_PR⁻¹: the equivalent idle time whose a_PR equals `pr`, s.
  double idle_of_pr(double pr) const noexcept;
  /// F(I_nom, v_ref, PR)/F(I_nom, v_ref, 1), Eq. 5.10–5.12 with Eq. 4.4.
  double capacity_of_pr(double pr) const noexcept;
  /// Inverse of capacity_of_pr (F is affine in PR).
  double pr_of_capacity(double capacity_fraction) const noexcept;
  const IdleModelConfig& config() const noexcept { return c_; }

 private:
  void close(double t_close_s) noexcept;

  IdleModelConfig c_{};
  double t_max_s_ = 1.0;
  double force_pr0_n_ = 0.0;  ///< F(I_nom, v_ref, PR = 0)
  double force_pr1_n_ = 1.0;  ///< F(I_nom, v_ref, PR = 1)
  // Settled phase.
  double base_idle_s_ = 0.0;
  double base_t_s_ = 0.0;
  // Episode.
  bool open_ = false;
  double open_t_s_ = 0.0;
  double last_motion_s_ = 0.0;
  double episode_m3_ = 0.0;
  physics::PrCoefficients coeff_{};
  double pr_ = 1.0;
  std::uint32_t episodes_closed_ = 0;
};

/// Status flags of the estimator (bit mask). The causes stay set for the
/// rest of the boot; kIdleAssumedSettled says the present estimate started
/// from the worst case.
enum IdleFlag : std::uint32_t {
  kIdleNoSavedState = 1u << 0,    ///< no record at boot
  kIdleCorruptState = 1u << 1,    ///< record refused: size, magic, version, CRC or values
  kIdleClockBackwards = 1u << 2,  ///< the RTC went backwards (at boot against the stamp, or while running)
  kIdleClockInvalid = 1u << 3,    ///< no valid RTC at boot: the time off is unknown
  kIdleAssumedSettled = 1u << 4,  ///< the estimate was reset to fully settled for one of the above
  kIdleSaveFailed = 1u << 5,      ///< the last save failed
  kIdleStoreIoError = 1u << 6,    ///< the store could not be read at boot
};

struct IdleEstimatorConfig {
  IdleModelConfig model{};
  double period_s = 1.0e-3;            ///< duration of one control tick, s (a whole number of µs)
  /// Half-width of the play (backlash) operator the displacement passes
  /// through before it is counted: sensor noise and motion smaller than
  /// this earn no mixing credit, and noise cannot keep an episode open.
  /// Set it above the stroke sensor's noise. 0 counts every |Δx| (the
  /// thesis model exactly). m.
  double dead_band_m = 1.0e-4;
  double clock_tolerance_s = 2.0;      ///< RTC steps back by more than this count as a backward jump, s
  double save_interval_s = 600.0;      ///< save at least this often while running, s
};

/// The tick-based state model of SettlingModel (the diagram above) in the
/// numbers of one build. Times are control ticks and must not decrease.
template <class Policy>
class BasicIdleModel {
 public:
  using A = IdleArith<Policy>;
  using Ratio = typename A::Ratio;
  using Coef = typename A::Coef;
  using Rate = typename A::Rate;
  using Volume = typename A::Volume;

  /// Eq. 5.6–5.8 and the rate c_PR/unit of Eq. 5.9 in this build's numbers.
  struct Coefficients {
    Ratio a{};
    Ratio b{};
    Coef c{};
    Rate rate{};  ///< c/volume_unit, per m³
  };

  /// Converts the configuration (design time, in double); false when it is
  /// unusable or a constant does not fit its format.
  bool init(const IdleModelConfig& config, double period_s) noexcept;
  void reset(std::uint64_t equivalent_idle_ticks, std::uint64_t t) noexcept;
  void assume_settled(std::uint64_t t) noexcept { reset(t_max_, t); }
  void add_motion(std::uint64_t t0, std::uint64_t t1, Volume volume) noexcept;
  void advance(std::uint64_t t) noexcept;

  std::uint64_t equivalent_idle_ticks(std::uint64_t t) const noexcept;
  Ratio participant_ratio(std::uint64_t t) const noexcept;
  Ratio sq_of_idle(std::uint64_t idle_ticks) const noexcept { return A::sq_of(idle_ticks, t_max_); }
  Ratio pr_of_idle(std::uint64_t idle_ticks) const noexcept;
  std::uint64_t idle_of_pr(Ratio pr) const noexcept;
  Ratio capacity_of_pr(Ratio pr) const noexcept { return cap0_ + A::mul(cap1_, pr); }
  Ratio predicted_capacity(std::uint64_t t, std::uint64_t horizon_ticks) const noexcept;
  Coefficients coefficients_at(std::uint64_t t) const noexcept;
  Volume volume_to_ceiling(std::uint64_t t, Ratio gap_fraction) const noexcept;

  bool episode_open() const noexcept { return open_; }
  Volume episode_volume() const noexcept { return open_ ? episode_ : A::vol_zero(); }
  std::uint64_t last_motion_tick() const noexcept { return last_motion_; }
  std::uint32_t episodes_closed() const noexcept { return episodes_closed_; }
  std::uint64_t max_settling_ticks() const noexcept { return t_max_; }
  /// Eq. 5.4, s (host side).
  double max_settling_time_s() const noexcept { return static_cast<double>(t_max_) * period_s_; }

 private:
  Coefficients coefficients_of(Ratio sq) const noexcept;
  void close(std::uint64_t t_close) noexcept;

  double period_s_ = 1.0e-3;
  std::uint64_t t_max_ = 1;
  std::uint64_t quiet_close_ = 1;
  std::uint64_t max_episode_ = 1;
  // Table 5.6 in this build's numbers: b + (a − b)·exp(−c·SQ) for a_PR, b_PR, c_PR.
  Ratio b_init_{}, span_init_{};
  Coef c_init_{};
  Ratio b_final_{}, span_final_{};
  Coef c_final_{};
  Coef b_rise_{}, span_rise_{};
  Coef c_rise_{};
  Rate per_unit_{};  ///< 1/volume_unit_m3, per m³
  Ratio cap0_{}, cap1_{};  ///< capacity = cap0 + cap1·PR (F is affine in PR)
  // Settled phase.
  std::uint64_t base_idle_ = 0;
  std::uint64_t base_t_ = 0;
  // Episode.
  bool open_ = false;
  std::uint64_t open_t_ = 0;
  std::uint64_t last_motion_ = 0;
  Volume episode_{};
  Coefficients coeff_{};
  Ratio pr_{};
  std::uint32_t episodes_closed_ = 0;
};

/// One sample for the estimator. The wall clock is `rtc_s` (double seconds)
/// in the reference build and `rtc_ms` (integer milliseconds) in the float
/// and fixed builds.
template <class Policy>
struct BasicIdleEstimatorInput : IdleArith<Policy>::RtcInput {
  using Sample = typename IdleArith<Policy>::Sample;
  std::uint64_t tick = 0;        ///< control ticks since boot
  bool rtc_valid = true;
  Sample damper_disp_m = 0;      ///< damper stroke, m
  bool disp_valid = true;
  bool mixing_active = false;    ///< a mixing cycle is running (credits go to the mixing counter)
};

/// What the estimator knows after a step, as the build's boundary numbers
/// (double in the reference, float in the float and fixed builds).
template <class Sample>
struct BasicIdleEstimate {
  Sample equivalent_idle_s = 0;    ///< τ (as if motion stopped now), s
  Sample sq = 0;                   ///< SQ of τ, Eq. 5.5
  Sample participant_ratio = 1;    ///< PR now
  Sample capacity_fraction = 1;    ///< force capacity relative to fully mixed
  Sample time_since_motion_s = 0;
  bool episode_open = false;
  Sample episode_volume_m3 = 0;    ///< displaced in the open episode, m³
  Sample lifetime_volume_m3 = 0;   ///< credited since commissioning, m³
  Sample mixing_volume_m3 = 0;     ///< of which while mixing, m³
  std::uint32_t mixing_cycles = 0; ///< confirmed mixing cycles since commissioning
  std::uint32_t flags = 0;         ///< IdleFlag bits
};

/// How boot() went.
struct IdleBootReport {
  hal::StoreStatus load = hal::StoreStatus::kOk;
  DecodeStatus decode = DecodeStatus::kOk;
  double offline_s = 0.0;          ///< time off by the RTC (0 when unknown), s
  std::uint32_t flags = 0;
};

enum class SaveOutcome : std::uint8_t {
  kSaved = 0,
  kSkippedNoClock,  ///< no RTC seen this boot: the old record (older stamp) is the safer one
  kFailed,          ///< the store reported an error; kIdleSaveFailed is set
};

template <class Policy>
class BasicIdleEstimator {
 public:
  using A = IdleArith<Policy>;
  using Sample = typename A::Sample;
  using Ratio = typename A::Ratio;
  using Volume = typename A::Volume;
  using Disp = typename A::Disp;
  using Rtc = typename A::Rtc;
  using Input = BasicIdleEstimatorInput<Policy>;
  using Estimate = BasicIdleEstimate<Sample>;
  using Model = BasicIdleModel<Policy>;

  /// Returns false for an unusable configuration (see SettlingModel::init,
  /// plus a period that is not a positive whole number of µs, non-positive
  /// save interval, negative dead band, a constant outside its format).
  bool init(const IdleEstimatorConfig& config) noexcept;

  /// Restores the state from `store` (I/O: call before the control loop,
  /// not from it). The time off is the RTC minus the stored stamp and counts
  /// as idle time. Missing or refused record, invalid RTC, or an RTC behind
  /// the stamp: fully settled, with the flag saying why.
  IdleBootReport boot(hal::StateStore& store, std::uint64_t tick, Rtc rtc, bool rtc_valid) noexcept;
  /// Starts from a known state without a store (commissioning right after
  /// a full mixing, tests, simulation).
  void boot_with(double equivalent_idle_s, std::uint64_t tick, Rtc rtc) noexcept;

  /// One sample: O(1), no heap, no I/O. Without boot(), the first step
  /// boots into the worst case (kIdleNoSavedState).
  void step(const Input& in) noexcept;

  /// A save is due: save_interval_s passed, an episode closed, a mixing
  /// cycle was confirmed, or the state was reset to the worst case.
  bool save_due() const noexcept { return save_due_; }
  /// Writes the state through `store` (I/O: call from a low-priority
  /// context when save_due()). The stamp is the last RTC reading advanced
  /// by the ticks since.
  SaveOutcome save(hal::StateStore& store) noexcept;

  /// The mixing scheduler confirmed a cycle: counted and saved soon.
  void note_mixing_confirmed() noexcept;

  const Estimate& estimate() const noexcept { return est_; }
  /// Capacity after `horizon_ticks` more without motion (per tick).
  Ratio predicted_capacity(std::uint64_t horizon_ticks) const noexcept;
  /// Volume that brings PR within `gap_fraction`·b_PR of b_PR now (per tick).
  Volume volume_to_ceiling(Ratio gap_fraction) const noexcept;
  /// Displaced volume credited since commissioning.
  Volume lifetime_volume() const noexcept { return lifetime_; }
  /// Host-side forms of the two queries above, in double.
  double predicted_capacity_fraction(double horizon_s) const noexcept;
  double volume_to_ceiling_m3(double gap_fraction) const noexcept;
  const Model& model() const noexcept { return model_; }
  /// Ticks since boot.
  std::uint64_t ticks() const noexcept { return t_; }
  /// Time since boot on the tick clock, s (host side).
  double time_s() const noexcept { return static_cast<double>(t_) * c_.period_s; }
  const IdleEstimatorConfig& config() const noexcept { return c_; }

 private:
  void start(std::uint64_t tick) noexcept;
  void assume_worst(std::uint32_t cause) noexcept;
  void refresh() noexcept;
  void restore_counters(const PersistedIdleState& s) noexcept;
  /// Milliseconds as ticks, saturated (a record's τ may be any 62-bit value).
  std::uint64_t ticks_of_ms(std::uint64_t ms) const noexcept {
    return ms < (std::uint64_t{1} << 53) ? ms * 1000u / period_us_ : (std::uint64_t{1} << 63) / period_us_;
  }
  std::uint64_t ms_of_ticks(std::uint64_t ticks) const noexcept { return ticks * period_us_ / 1000u; }

  IdleEstimatorConfig c_{};
  Model model_{};
  Estimate est_{};
  std::uint64_t period_us_ = 1000;
  Sample period_s_{};
  Disp dead_band_{};
  typename A::Area area_{};
  std::int64_t clock_tolerance_ms_ = 2000;
  std::uint64_t save_interval_ = 600000;
  Volume lifetime_{};
  Volume mixing_{};
  bool booted_ = false;
  std::uint64_t tick0_ = 0;
  std::uint64_t last_tick_ = 0;
  std::uint64_t t_ = 0;  ///< ticks since boot
  // RTC
  bool rtc_seen_ = false;
  std::int64_t last_rtc_ms_ = 0;
  std::uint64_t last_rtc_t_ = 0;
  // Displacement through the play operator.
  bool anchored_ = false;
  Disp play_{};
  std::uint64_t prev_sample_t_ = 0;
  // Persistence.
  bool save_due_ = false;
  std::uint64_t last_save_t_ = 0;
  std::uint32_t save_sequence_ = 0;
  std::uint32_t episodes_seen_ = 0;
};

/// The reference build (double) that the host simulator and the board's
/// runtime use, and the float and fixed-point builds (instantiated in
/// idle_estimator.cpp, idle_estimator_float.cpp, idle_estimator_fixed.cpp).
using IdleEstimator = BasicIdleEstimator<Float64Policy>;
using IdleEstimatorInput = BasicIdleEstimatorInput<Float64Policy>;
using IdleEstimate = BasicIdleEstimate<double>;

extern template class BasicIdleModel<Float64Policy>;
extern template class BasicIdleModel<num::Float32Policy>;
extern template class BasicIdleModel<num::Fixed32Policy>;
extern template class BasicIdleEstimator<Float64Policy>;
extern template class BasicIdleEstimator<num::Float32Policy>;
extern template class BasicIdleEstimator<num::Fixed32Policy>;

}  // namespace mrd::fw
