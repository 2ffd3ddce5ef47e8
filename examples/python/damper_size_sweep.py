"""A damper-size sweep `mrd` cannot express: the thesis damper's force laws
(yield force and viscous coefficient of Eq. 4.2-4.3, and its rated force)
scaled by a factor, each size a damper made in Python (mrd.Damper.from_dict)
and run over every record, control mode and idle time in one mrd.batch call.

    PYTHONPATH=build/host-release/python python3 examples/python/damper_size_sweep.py --out out/python
"""

import argparse
import copy
import pathlib
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mrd  # noqa: E402
from _paths import REPO, record  # noqa: E402

THESIS_RECORDS = ["elcentro_ns.csv", "hachinohe_ns.csv", "kobe_jma_ns.csv", "northridge_sylmar_ns.csv"]  # Table 6.2
MODES = ["passive-off", "passive-on", "semi-active"]


def scaled_damper(thesis: dict, factor: float) -> mrd.Damper:
    """The thesis damper with its force laws and rated force times `factor`."""
    d = copy.deepcopy(thesis)
    for table in ("yield_n", "viscous_ns_m"):
        d[table]["at_zero"] *= factor
        d[table]["limit"] *= factor
    d["rating"]["force_n"] *= factor
    d["validity"]["force_peak_n"] *= factor
    d["model"]["name"] = f"thesis-x{factor:g}"
    return mrd.Damper.from_dict(d, origin=f"thesis damper x{factor:g}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--records", default=",".join(record(r) for r in THESIS_RECORDS),
                   help="comma-separated record files (default: Table 6.2's four)")
    p.add_argument("--factors", default="0.25,0.5,0.75,1,1.5,2,3", help="damper sizes, times the thesis damper")
    p.add_argument("--idle-years", default="0,2.5", help="comma-separated idle times, years")
    p.add_argument("--duration-s", type=float, default=None, help="cut every record to this length, s")
    p.add_argument("--out", default="out/python", help="folder of the figure")
    a = p.parse_args()
    factors = [float(f) for f in a.factors.split(",")]
    idle = [float(y) for y in a.idle_years.split(",")]
    motions = [mrd.load_motion(r, duration_s=a.duration_s) for r in a.records.split(",")]
    thesis = tomllib.loads((REPO / "dampers" / "thesis-200kn.toml").read_text())

    # one batch per damper size: every record x mode x idle time
    cases = [(m, mode, y) for m in motions for mode in MODES for y in idle]
    peaks = {}  # (factor, mode, idle) -> mean over records of the peaks
    simulated_s = seconds = 0.0
    for factor in factors:
        r = mrd.batch([c[0] for c in cases], control=[c[1] for c in cases], idle_years=[c[2] for c in cases],
                      damper=scaled_damper(thesis, factor), story_drift=False)
        simulated_s += r.simulated_s
        seconds += r.seconds
        for mode in MODES:
            for y in idle:
                pick = [i for i, c in enumerate(cases) if c[1] == mode and c[2] == y]
                peaks[factor, mode, y] = {f: float(np.mean(r.peaks[f][pick])) for f in
                                          ("peak_base_displacement_m", "peak_superstructure_accel_m_s2")}

    metrics = [("peak_base_displacement_m", 1e3, "peak base displacement [mm]"),
               ("peak_superstructure_accel_m_s2", 1.0, "peak floor accel [m/s²]")]
    fig, axes = plt.subplots(1, len(metrics), figsize=(11, 4.5))
    for ax, (field, scale, label) in zip(axes, metrics):
        for mode, color in zip(MODES, ("tab:gray", "tab:blue", "tab:red")):
            for y, style, marker in zip(idle, ("-", "--", ":", "-."), "os^v"):
                ax.plot(factors, [peaks[f, mode, y][field] * scale for f in factors], color=color, linestyle=style,
                        marker=marker, label=f"{mode}, idle {y:g} y")
        ax.set_xlabel("damper size [x thesis 200 kN damper]")
        ax.set_ylabel(label + f", mean of {len(motions)} records")
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("damper size sweep (mrd.batch)")
    fig.tight_layout()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    png = out / "damper_size_sweep.png"
    fig.savefig(png, dpi=110)
    for factor in factors:
        row = ", ".join(f"{mode} {peaks[factor, mode, idle[0]]['peak_base_displacement_m'] * 1e3:6.2f} mm"
                        for mode in MODES)
        print(f"damper x{factor:<5g} idle {idle[0]:g} y: {row}")
    print(f"{len(factors) * len(cases)} runs, {simulated_s:.0f} s simulated in {seconds:.2f} s "
          f"({simulated_s / seconds:.0f} x real time)")
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
