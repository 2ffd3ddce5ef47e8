"""Chapter 6's comparison (Fig. 6.9-6.11): one record, fully mixed against
2.5 years idle, the response over time of the base, the damper, the floors
and the coil.

    PYTHONPATH=build/host-release/python python3 examples/python/chapter6_comparison.py --out out/python
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import mrd  # noqa: E402
from _paths import record  # noqa: E402


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--record", default=record(), help="ground-motion record (default: El Centro NS)")
    p.add_argument("--control", default="semi-active", help="passive-off | passive-on | semi-active")
    p.add_argument("--idle-years", type=float, default=2.5, help="idle time of the second run, years")
    p.add_argument("--out", default="out/python", help="folder of the figure")
    a = p.parse_args()

    runs = {
        "fully mixed": mrd.sim(record=a.record, control=a.control),
        f"{a.idle_years:g} years idle": mrd.sim(record=a.record, control=a.control, idle_years=a.idle_years),
    }
    panels = [
        ("base_disp_m", 1e3, "base displacement [mm]"),
        ("damper_force_n", 1e-3, "damper force [kN]"),
        ("peak_floor_accel_m_s2", 1.0, "max |floor accel| [m/s²]"),
        ("current_a", 1.0, "coil current [A]"),
    ]
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(9, 10))
    for ax, (column, scale, label) in zip(axes, panels):
        for name, r in runs.items():
            ax.plot(r.timeseries["time_s"], r.timeseries[column] * scale, label=name, linewidth=0.8)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend()
    axes[-1].set_xlabel("time [s]")
    first = next(iter(runs.values())).summary
    fig.suptitle(f"{pathlib.Path(first['record']).name}, {a.control}, PGA {first['pga_m_s2'] / 9.80665:.4g} g")
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    png = out / "chapter6_comparison.png"
    fig.savefig(png, dpi=110)
    for name, r in runs.items():
        s = r.summary
        print(f"{name:>16}: peak base displacement {s['peak_base_displacement_m'] * 1e3:.2f} mm, "
              f"damper force {s['peak_damper_force_kn']:.1f} kN, SQ {s['sq']:.3f}")
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
