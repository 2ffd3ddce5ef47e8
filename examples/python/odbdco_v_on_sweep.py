"""ODBDCO's direction threshold v_on swept, a parameter `mrd sim` has no
option for: each value is a board file written from Python (boards/sim's,
with [controller] velocity_on_m_s = v_on and velocity_off_m_s = v_on / 2, as
the core's defaults 6 and 3 mm/s are), run by mrd.sim(board=...) on every
record (the firmware core configured as that board runs it, behind its CAN
frames' quantization).

    PYTHONPATH=build/host-release/python python3 examples/python/odbdco_v_on_sweep.py --out out/python
"""

import argparse
import pathlib
import tempfile
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mrd  # noqa: E402
from _paths import REPO, record  # noqa: E402

THESIS_RECORDS = ["elcentro_ns.csv", "hachinohe_ns.csv", "kobe_jma_ns.csv", "northridge_sylmar_ns.csv"]  # Table 6.2


def board_file(folder: pathlib.Path, v_on_m_s: float) -> str:
    board = tomllib.loads((REPO / "boards" / "sim" / "board.toml").read_text())
    board["control"]["mode"] = "semi-active"
    board["controller"] = {"velocity_on_m_s": v_on_m_s, "velocity_off_m_s": 0.5 * v_on_m_s}
    path = folder / f"board-v_on-{v_on_m_s:g}.toml"
    path.write_text(mrd._toml.dumps(board))
    return str(path)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--records", default=",".join(record(r) for r in THESIS_RECORDS),
                   help="comma-separated record files (default: Table 6.2's four)")
    p.add_argument("--v-on-mm-s", default="1,2,4,6,10,20,40", help="v_on values, mm/s")
    p.add_argument("--idle-years", type=float, default=0.0, help="idle time before each run, years")
    p.add_argument("--duration-s", type=float, default=None, help="cut every record to this length, s")
    p.add_argument("--out", default="out/python", help="folder of the figure")
    a = p.parse_args()
    v_on_m_s = [float(v) * 1e-3 for v in a.v_on_mm_s.split(",")]
    records = a.records.split(",")

    fields = ("peak_base_displacement_m", "peak_superstructure_accel_m_s2")
    sweep = {f: [] for f in fields}
    with tempfile.TemporaryDirectory() as folder:
        for v in v_on_m_s:
            board = board_file(pathlib.Path(folder), v)
            runs = [mrd.sim(record=r, board=board, idle_years=a.idle_years, duration_s=a.duration_s).peaks
                    for r in records]
            for f in fields:
                sweep[f].append(float(np.mean([run[f] for run in runs])))
    passive = {mode: [mrd.sim(record=r, control=mode, idle_years=a.idle_years, duration_s=a.duration_s).peaks
                      for r in records] for mode in ("passive-off", "passive-on")}

    labels = {"peak_base_displacement_m": (1e3, "peak base displacement [mm]"),
              "peak_superstructure_accel_m_s2": (1.0, "peak floor accel [m/s²]")}
    fig, axes = plt.subplots(1, len(fields), figsize=(11, 4.5))
    for ax, f in zip(axes, fields):
        scale, label = labels[f]
        ax.semilogx([v * 1e3 for v in v_on_m_s], [x * scale for x in sweep[f]], "o-", label="ODBDCO (board file)")
        for mode, style in (("passive-off", ":"), ("passive-on", "--")):
            ax.axhline(np.mean([run[f] for run in passive[mode]]) * scale, color="k", linestyle=style, linewidth=0.8,
                       label=mode)
        ax.axvline(6.0, color="gray", linewidth=0.6)  # the core's default v_on
        ax.set_xlabel("v_on [mm/s] (v_off = v_on / 2)")
        ax.set_ylabel(label + f", mean of {len(records)} records")
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"ODBDCO's direction threshold, idle {a.idle_years:g} years")
    fig.tight_layout()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    png = out / "odbdco_v_on_sweep.png"
    fig.savefig(png, dpi=110)
    for v, d, acc in zip(v_on_m_s, sweep["peak_base_displacement_m"], sweep["peak_superstructure_accel_m_s2"]):
        print(f"v_on {v * 1e3:5.3g} mm/s: {d * 1e3:7.2f} mm, {acc:.3f} m/s^2")
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
