#pragma once
/// The 200 kN MR damper at a constant current command, fully mixed (idle
/// time 0: participant ratio 1), as `mrd sim --control passive-on` (2.5 A)
/// and `passive-off` (0 A) drive it: the coil starts at 0 A when the run
/// starts and follows the command through Eq. 4.5 with unity DC gain, two
/// first-order lags of 0.7 s and 0.03 s weighted ½ each, so for a command
/// I held from t = 0
///
///   i(t) = I·(1 − ½·e^(−t/0.7) − ½·e^(−t/0.03)),
///
/// and the force is the Bingham plastic of Eq. 4.1–4.3 (Table 4.1) times the
/// transition function of Eq. 4.4:
///
///   F(v, i) = TF(v)·(f_c(i)·sgn v + c_0(i)·v),  positive resisting a positive v.
///
/// The laws come from tests/independent_synth/damper_physics.hpp (written
/// from the thesis alone, no project code).

namespace ibuild {

/// Current command of `mrd sim --control passive-on`, A (§6.4's nominal current).
inline constexpr double kPassiveOnCommand_a = 2.5;
/// Current command of `passive-off`, A.
inline constexpr double kPassiveOffCommand_a = 0.0;

/// Coil current at time `t_s` after a command `command_a` starts from a coil at 0 A, A.
double coil_current_a(double command_a, double t_s);

/// Damper force at velocity `velocity_m_s` and coil current `current_a`, fully mixed fluid, N.
double damper_force_n(double velocity_m_s, double current_a);

}  // namespace ibuild
