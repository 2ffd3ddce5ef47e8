"""mrd.sim against `mrd sim --out` with the same inputs: the same summary.json
and the same time series (timeseries.csv prints 9 significant digits, so each
array value is compared as the CSV prints it, '%.9g')."""

import csv
import json
import subprocess

import numpy as np
import pytest

import mrd


def _cli_run(mrd_binary, out_dir, args):
    subprocess.run([str(mrd_binary), "sim", *args, "--out", str(out_dir)], check=True, capture_output=True)
    summary = json.loads((out_dir / "summary.json").read_text())
    with open(out_dir / "timeseries.csv", newline="") as f:
        rows = list(csv.reader(f))
    return summary, rows[0], rows[1:]


def _assert_same_run(result, summary, header, rows):
    assert result.summary == summary
    assert list(result.timeseries) == header
    for c, name in enumerate(header):
        values = result.timeseries[name]
        assert values.dtype == np.float64
        assert len(values) == len(rows), name
        printed = [format(v, ".9g") for v in values.tolist()]
        assert printed == [row[c] for row in rows], name


CASES = {
    "thesis-semi-active": dict(control="semi-active", duration_s=10.0),
    "lead-rubber-building": dict(control="semi-active", duration_s=5.0, building="buildings/lead-rubber-7dof.toml"),
    "fixed-base-building-idle": dict(control="passive-on", duration_s=5.0, idle_years=2.5,
                                     building="buildings/fixed-base-8dof.toml"),
}


def _cli_args(record, kw):
    args = ["--record", record]
    for key, value in kw.items():
        args += ["--" + key.replace("_", "-"), str(value)]
    return args


@pytest.mark.parametrize("case", sorted(CASES))
def test_sim_equals_cli(case, mrd_binary, elcentro, source_dir, tmp_path):
    kw = dict(CASES[case])
    if "building" in kw:
        kw["building"] = str(source_dir / kw["building"])
    summary, header, rows = _cli_run(mrd_binary, tmp_path / "out", _cli_args(elcentro, kw))
    _assert_same_run(mrd.sim(record=elcentro, **kw), summary, header, rows)


def test_a_drive_file_runs_as_in_the_cli(mrd_binary, elcentro, source_dir, tmp_path):
    # A 24 V bus in place of the thesis drive's 72 V: the coil slews a third as fast.
    text = (source_dir / "drives" / "thesis-pwm.toml").read_text()
    drive = tmp_path / "bus-24v.toml"
    drive.write_text(text.replace("bus_v = 72.0", "bus_v = 24.0").replace('"thesis-pwm"', '"bus-24v"'))
    kw = dict(control="semi-active", duration_s=5.0, plant="hardware", drive=str(drive))
    summary, header, rows = _cli_run(mrd_binary, tmp_path / "out", _cli_args(elcentro, kw))
    result = mrd.sim(record=elcentro, **kw)
    _assert_same_run(result, summary, header, rows)
    assert summary["drive"] == "bus-24v"
    thesis = mrd.sim(record=elcentro, control="semi-active", duration_s=5.0, plant="hardware")
    assert thesis.summary["drive"] == "thesis-pwm"
    assert result.summary["rms_coil_current_a"] != thesis.summary["rms_coil_current_a"]
    with pytest.raises(mrd.UsageError, match="only --plant hardware"):
        mrd.sim(record=elcentro, duration_s=1.0, drive=str(drive))


def test_timeseries_is_a_view_of_the_run(elcentro):
    r = mrd.sim(record=elcentro, duration_s=1.0)
    a = r.timeseries["base_disp_m"]
    assert not a.flags["OWNDATA"]  # numpy views the run's vector
    assert not a.flags["WRITEABLE"]
    del r
    assert np.isfinite(a).all()  # the view keeps the run alive
