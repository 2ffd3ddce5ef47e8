"""mrd.batch: each run's peaks equal mrd.sim's (and so `mrd sim`'s) bit for
bit; the batch's options are checked as `mrd sim` checks them."""

import math
import os
import subprocess
import sys

import numpy as np
import pytest

import mrd


def _same(a, b):
    return a == b or (math.isnan(a) and math.isnan(b))


def _assert_equal_peaks(batch_result, i, sim_result):
    for field in mrd.PEAK_FIELDS:
        assert _same(batch_result.peaks[field][i], sim_result.peaks[field]), field


@pytest.mark.parametrize("building", [None, "buildings/lead-rubber-7dof.toml"])
def test_batch_equals_sim_bit_for_bit(building, elcentro, source_dir):
    building = None if building is None else str(source_dir / building)
    duration_s = 4.0
    motion = mrd.load_motion(elcentro, pga_g=0.2, duration_s=duration_s)
    cases = [("passive-off", 0.0), ("passive-on", 0.0), ("semi-active", 0.0), ("passive-on", 2.5),
             ("semi-active", 0.5)]
    result = mrd.batch([motion] * len(cases), idle_years=[c[1] for c in cases], control=[c[0] for c in cases],
                       building=building)
    assert len(result) == len(cases)
    for i, (control, idle_years) in enumerate(cases):
        sim = mrd.sim(record=elcentro, pga_g=0.2, duration_s=duration_s, control=control, idle_years=idle_years,
                      building=building)
        _assert_equal_peaks(result, i, sim)
        assert result.peaks["peak_base_displacement_m"][i] == sim.summary["peak_base_displacement_m"]


@pytest.mark.parametrize("numeric", ["fixed", "double"])
def test_batch_equals_sim_in_each_numeric_build(numeric, elcentro):
    motion = mrd.load_motion(elcentro, duration_s=3.0)
    result = mrd.batch([motion], control="semi-active", numeric=numeric)
    _assert_equal_peaks(result, 0, mrd.sim(record=elcentro, duration_s=3.0, control="semi-active", numeric=numeric))


def test_every_lane_kernel_gives_the_same_runs(elcentro):
    motion = mrd.load_motion(elcentro, duration_s=3.0)
    modes = ["passive-off", "passive-on", "semi-active"]
    generic = mrd.batch([motion] * 3, control=modes, isa="generic")
    assert generic.lane_isa == "generic"
    np.testing.assert_array_equal(generic.values, mrd.batch([motion] * 3, control=modes).values)


def test_scale_is_the_product_of_a_scaled_copy(elcentro):
    """BatchRun's contract: a_g[n] = scale * record[n], the product a scaled copy holds."""
    a = mrd.load_motion(elcentro, duration_s=3.0).accel_m_s2
    by_scale = mrd.batch([a, a], scale=[2.0, 0.7], control="semi-active")
    by_copy = mrd.batch([2.0 * a, 0.7 * a], control="semi-active")
    np.testing.assert_array_equal(by_scale.values, by_copy.values)


def test_threads_and_lengths(elcentro):
    a = mrd.load_motion(elcentro, duration_s=3.0).accel_m_s2
    records = [a, a[:1000], a[:2500], a, a[:10]]
    one = mrd.batch(records, idle_years=[0, 0.1, 0.2, 0.3, 0.4], control="passive-on")
    three = mrd.batch(records, idle_years=[0, 0.1, 0.2, 0.3, 0.4], control="passive-on", threads=3)
    np.testing.assert_array_equal(one.values, three.values)
    # one tick a sample: 3.0 s at 1 ms is 3001 samples
    assert one.peaks["ticks"].tolist() == [3001, 1000, 2500, 3001, 10]


def test_batch_releases_the_gil(elcentro):
    """Another Python thread runs while a batch steps. With a long switch
    interval the other thread gets the GIL only when this one gives it up,
    so it counts inside the batch call only if the batch releases the GIL
    (a call that holds it, such as a long re.match, sees no count)."""
    import sys
    import threading
    import time

    a = mrd.load_motion(elcentro, duration_s=40.0).accel_m_s2
    stamps = []
    done = threading.Event()

    def counter():
        while not done.is_set():
            stamps.append(time.perf_counter())

    interval = sys.getswitchinterval()
    sys.setswitchinterval(0.2)
    try:
        t = threading.Thread(target=counter)
        t.start()
        t0 = time.perf_counter()
        mrd.batch([a] * 16, control="passive-on", threads=1)
        t1 = time.perf_counter()
        done.set()
        t.join()
    finally:
        done.set()
        sys.setswitchinterval(interval)
    assert any(t0 < s < t1 for s in stamps)


def _cli_message(mrd_binary, args):
    p = subprocess.run([str(mrd_binary), "sim", *args], capture_output=True, text=True)
    assert p.returncode == 2
    return p.stderr[len("mrd: error: "):].rstrip("\n")


@pytest.mark.parametrize("keyword, option", [
    (dict(control="active"), ["--control", "active"]),
    (dict(idle_years=-1.0), ["--idle-years", "-1"]),
    (dict(step_s=0.5), ["--step-s", "0.5"]),
    (dict(numeric="half"), ["--numeric", "half"]),
])
def test_batch_refuses_what_sim_refuses(keyword, option, mrd_binary):
    message = _cli_message(mrd_binary, option + ["--duration-s", "1"])
    with pytest.raises(mrd.UsageError) as info:
        mrd.batch([np.zeros(10)], **keyword)
    assert str(info.value) == message


def test_batch_refuses_bad_records():
    with pytest.raises(mrd.UsageError, match=r"records\[1\]\[2\]: expected a finite acceleration"):
        mrd.batch([np.zeros(5), np.array([0.0, 1.0, np.nan])])
    with pytest.raises(mrd.UsageError, match=r"records\[0\]: expected at least one sample"):
        mrd.batch([np.zeros(0)])
    with pytest.raises(mrd.UsageError, match=r"idle_years: expected one value or one per record \(2\), got 3"):
        mrd.batch([np.zeros(5)] * 2, idle_years=[0, 1, 2])
    with pytest.raises(mrd.UsageError, match=r"scale\[0\]: expected a finite number"):
        mrd.batch([np.zeros(5)], scale=float("inf"))
    with pytest.raises(mrd.UsageError, match="isa: expected auto, generic, x86-64-v3 or x86-64-v4, got 'sse'"):
        mrd.batch([np.zeros(5)], isa="sse")


def test_bench_python_batch_within_ten_percent_of_cpp(source_dir):
    """python/bench/batch_bench.py at a small size (32 runs of 10 s): it prints both speeds and
    exits 0 when mrd.batch's CPU time is within 10 % of the C++ call's."""
    p = subprocess.run([sys.executable, str(source_dir / "python" / "bench" / "batch_bench.py"), "--runs", "32",
                        "--duration-s", "10", "--repeat", "5"], capture_output=True, text=True, env=dict(os.environ))
    print(p.stdout)
    assert "python     mrd.batch" in p.stdout and "in-call    C++ batch path" in p.stdout
    assert p.returncode == 0, p.stdout + p.stderr
