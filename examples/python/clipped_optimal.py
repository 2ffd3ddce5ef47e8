"""A control law written in Python against the firmware core's ODBDCO: a
clipped-optimal law with a fixed gain (the desired force is a viscous force
c * v on the damper's stroke velocity; the coil is switched to the rated
current when the measured force is short of it in the same direction, else
0 A), swept over its gain, a sweep `mrd sim` cannot express.

    PYTHONPATH=build/host-release/python python3 examples/python/clipped_optimal.py --out out/python
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import mrd  # noqa: E402
from _paths import record  # noqa: E402

RATED_CURRENT_A = 2.5  # the thesis damper's rating (Table 4.1's laws span 0-2.5 A)
STEP_S = 1e-3          # mrd.sim's default control period


class ClippedOptimal:
    """f_d = gain_n_s_m * v, v the stroke's backward difference; I = I_r when
    f_d * f > 0 and |f_d| > |f|, else 0 A."""

    def __init__(self, gain_n_s_m: float) -> None:
        self.gain_n_s_m = gain_n_s_m
        self.reset()

    def reset(self) -> None:
        self.last_disp_m = None

    def step(self, s: mrd.Sensors) -> tuple:
        disp_m = s.damper_disp_m
        v_m_s = 0.0 if self.last_disp_m is None else (disp_m - self.last_disp_m) / STEP_S
        self.last_disp_m = disp_m
        desired_n = self.gain_n_s_m * v_m_s
        force_n = s.damper_force_n
        current_a = RATED_CURRENT_A if desired_n * force_n > 0.0 and abs(desired_n) > abs(force_n) else 0.0
        return current_a, desired_n  # the desired force fills the run's desired_force_n column


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--record", default=record(), help="ground-motion record (default: El Centro NS)")
    p.add_argument("--idle-years", type=float, default=0.0, help="idle time before the earthquake, years")
    p.add_argument("--gains", default="0.2e6,0.5e6,1e6,2e6,4e6,8e6", help="gains to sweep, N s/m")
    p.add_argument("--out", default="out/python", help="folder of the figure")
    a = p.parse_args()
    gains = [float(g) for g in a.gains.split(",")]

    def run(**kw):
        return mrd.sim(record=a.record, idle_years=a.idle_years, **kw).summary

    reference = {mode: run(control=mode) for mode in ("passive-off", "passive-on", "semi-active")}
    clipped = [run(controller=ClippedOptimal(g)) for g in gains]

    metrics = [("peak_base_displacement_m", 1e3, "peak base displacement [mm]"),
               ("peak_superstructure_accel_m_s2", 1.0, "peak floor accel [m/s²]")]
    fig, axes = plt.subplots(1, len(metrics), figsize=(11, 4.5))
    for ax, (field, scale, label) in zip(axes, metrics):
        ax.semilogx(gains, [c[field] * scale for c in clipped], "o-", label="clipped-optimal (Python)")
        for mode, style in (("passive-off", ":"), ("passive-on", "--"), ("semi-active", "-")):
            name = "ODBDCO (firmware core)" if mode == "semi-active" else mode
            ax.axhline(reference[mode][field] * scale, linestyle=style, color="k", linewidth=0.8, label=name)
        ax.set_xlabel("gain [N s/m]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{pathlib.Path(reference['semi-active']['record']).name}, idle {a.idle_years:g} years")
    fig.tight_layout()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    png = out / "clipped_optimal.png"
    fig.savefig(png, dpi=110)
    for mode, s in reference.items():
        print(f"{mode:>24}: {s['peak_base_displacement_m'] * 1e3:7.2f} mm, {s['peak_superstructure_accel_m_s2']:.3f} m/s^2")
    for g, s in zip(gains, clipped):
        print(f"clipped-optimal {g:8.3g} N s/m: {s['peak_base_displacement_m'] * 1e3:7.2f} mm, "
              f"{s['peak_superstructure_accel_m_s2']:.3f} m/s^2")
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
