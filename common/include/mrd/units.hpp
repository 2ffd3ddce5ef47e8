#pragma once
/// SI units and the few conversions the thesis tables need.
///
/// Inside the project every quantity is SI and says its unit in its name
/// (`force_n`, `disp_m`, `current_a`, `time_s`). kN, mm, inch and years appear
/// only at the edges (CLI, reports), through these constants.

namespace mrd::units {

inline constexpr double kNewtonPerKilonewton = 1000.0;
inline constexpr double kMeterPerMillimeter = 1.0e-3;
inline constexpr double kMeterPerInch = 0.0254;
inline constexpr double kMeterPerMicrometer = 1.0e-6;
/// kN·s/mm (Table 4.1) to N·s/m.
inline constexpr double kNsPerM_per_kNsPerMm = 1.0e6;
/// Standard gravity, m/s² (used to express PGA in g).
inline constexpr double kStandardGravity_m_s2 = 9.80665;
/// A day, s.
inline constexpr double kSecondsPerDay = 86400.0;
/// A year of idle time is a Julian year (365.25 days). The thesis does not say
/// which year it uses; with the Julian year Eq. 5.4 gives 0.8534 years against
/// the thesis's 0.8531 (0.04 %), with a 365-day year 0.8540 (0.1 %).
inline constexpr double kSecondsPerYear = 365.25 * kSecondsPerDay;
inline constexpr double kPi = 3.14159265358979323846;

constexpr double kn_to_n(double f_kn) noexcept { return f_kn * kNewtonPerKilonewton; }
constexpr double n_to_kn(double f_n) noexcept { return f_n / kNewtonPerKilonewton; }
constexpr double mm_to_m(double x_mm) noexcept { return x_mm * kMeterPerMillimeter; }
constexpr double m_to_mm(double x_m) noexcept { return x_m / kMeterPerMillimeter; }
constexpr double years_to_s(double t_years) noexcept { return t_years * kSecondsPerYear; }
constexpr double s_to_years(double t_s) noexcept { return t_s / kSecondsPerYear; }

}  // namespace mrd::units
