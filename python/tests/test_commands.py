"""fragility, risk, schedule, calibrate and discrepancy from Python: the
mrd program's commands, their summary.json as a dict and CSV tables as
arrays; bad input as mrd.UsageError with the command's message."""

import csv
import json
import subprocess

import numpy as np
import pytest

import mrd

LAB = "lab_data/quiroz_utfsm"


def _columns(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


@pytest.fixture(scope="module")
def small_fragility(elcentro):
    return mrd.fragility(record=[elcentro], pga_g=[0.1, 0.4], idle_years=[0.0, 1.0], control=["passive-on"],
                         bootstrap=0, threads=1)


def test_fragility_equals_the_cli(small_fragility, elcentro, mrd_binary, tmp_path):
    out = tmp_path / "cli"
    subprocess.run([str(mrd_binary), "fragility", "--record", elcentro, "--pga-g", "0.1,0.4", "--idle-years", "0,1",
                    "--control", "passive-on", "--bootstrap", "0", "--threads", "1", "--out", str(out)],
                   check=True, capture_output=True)
    runs = small_fragility.tables["runs"]
    assert len(runs["pga_g"]) == 4  # 1 record x 2 PGAs x 2 idle times x 1 mode
    with open(out / "runs.csv", newline="") as f:
        cli_rows = list(csv.DictReader(f))
    peaks = [float(r["peak_base_displacement_m"]) for r in cli_rows]
    assert runs["peak_base_displacement_m"].tolist() == peaks
    assert small_fragility.summary["pga_g"] == json.loads((out / "summary.json").read_text())["pga_g"]


def test_risk_and_schedule(small_fragility):
    r = mrd.risk(fragility=small_fragility, years=5.0)
    assert [p["name"] for p in r.summary["policies"]][:1] == ["none"]
    s = mrd.schedule(years=2.0)
    capacity = s.tables["capacity"]
    assert capacity["time_years"][0] == 0.0 and capacity["time_years"][-1] <= 2.0 + 1e-9
    assert np.all((capacity["none_capacity_fraction"] > 0.0) & (capacity["none_capacity_fraction"] <= 1.0))


def test_calibrate_and_discrepancy_on_arrays(shared_dir):
    lab = shared_dir / LAB
    if not lab.is_dir():
        pytest.skip(f"{lab} is missing")
    c = mrd.calibrate(measured=[_columns(lab / "5mm_3Hz_0p50A.csv"), lab / "5mm_3Hz_1p00A.csv"], law="bingham",
                      transition="linear", no_plots=True, no_lost_motion=True, no_transition_time=True)
    assert c.summary["chosen_law"] == "bingham"
    damper = mrd.Damper.from_file(c.folder / "damper.toml")
    d = mrd.discrepancy(measured=_columns(lab / "5mm_3Hz_0p75A.csv"), baseline=damper, no_plots=True, threads=1)
    assert d.summary["verdict"] in ("none", "explained", "unexplained", "baseline_mismatch")
    assert "fit" in d.tables


def _cli_message(mrd_binary, command, args):
    p = subprocess.run([str(mrd_binary), command, *args], capture_output=True, text=True)
    assert p.returncode == 2, p.stderr
    return p.stderr.splitlines()[-1][len("mrd: error: "):]


@pytest.mark.parametrize("command, keywords, args", [
    ("fragility", dict(pga_g=[-1.0]), ["--pga-g", "-1.0"]),
    ("fragility", dict(control=["active"]), ["--control", "active"]),
    ("schedule", dict(years=0.0), ["--years", "0.0"]),
    ("risk", dict(fragility="no-such-folder"), ["--fragility", "no-such-folder"]),
    ("calibrate", dict(measured=["no-such.csv"]), ["--measured", "no-such.csv"]),
    ("discrepancy", dict(measured="no-such.csv"), ["--measured", "no-such.csv"]),
])
def test_errors_are_the_cli_messages(command, keywords, args, mrd_binary, tmp_path):
    message = _cli_message(mrd_binary, command, args + ["--out", str(tmp_path / "cli")])
    with pytest.raises(mrd.UsageError) as info:
        getattr(mrd, command)(**keywords)
    assert str(info.value) == message


def test_measured_arrays_of_unequal_length():
    with pytest.raises(mrd.UsageError, match=r"measured: expected columns of one length, got lengths \[2, 3\]"):
        mrd.discrepancy(measured={"time_s": [0.0, 1.0], "force_N": [1.0, 2.0, 3.0]})
