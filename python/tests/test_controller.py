"""A control law written in Python in the loop."""

import time

import pytest

import mrd

# The passive-on command: the thesis's nominal current, 2.5 A (§6.4;
# firmware/core/controller_config.hpp kPassiveOnCurrent_a).
PASSIVE_ON_A = 2.5
PEAKS = [
    "peak_base_displacement_m",
    "peak_damper_force_kn",
    "peak_superstructure_accel_m_s2",
    "peak_base_accel_m_s2",
    "peak_story_drift_m",
    "peak_damper_stroke_m",
    "peak_current_a",
    "peak_coil_current_a",
    "peak_damper_velocity_m_s",
]


def test_python_passive_on_gives_the_passive_on_peaks(elcentro):
    core = mrd.sim(record=elcentro, control="passive-on", duration_s=10.0)
    python = mrd.sim(record=elcentro, duration_s=10.0, controller=lambda sensors: PASSIVE_ON_A)
    for peak in PEAKS:
        assert python.summary[peak] == core.summary[peak], peak
    assert python.summary["peak_base_displacement_m"] > 0.0


def test_a_pair_gives_the_desired_force_column(elcentro):
    core = mrd.sim(record=elcentro, control="passive-on", duration_s=2.0)
    python = mrd.sim(record=elcentro, duration_s=2.0, controller=lambda sensors: (PASSIVE_ON_A, 1234.5))
    assert python.peaks == core.peaks
    assert (python.timeseries["desired_force_n"] == 1234.5).all()  # 1234.5 is exact in float
    with pytest.raises(mrd.UsageError, match="controller: step returned a tuple of 3 values"):
        mrd.sim(record=elcentro, duration_s=1.0, controller=lambda s: (1.0, 2.0, 3.0))


class CountingController:
    """An object with step and reset: reset is called before the run."""

    def __init__(self):
        self.ticks = []
        self.resets = 0

    def reset(self):
        self.resets += 1

    def step(self, sensors):
        self.ticks.append(sensors.tick)
        return 0.0


def test_object_with_step_sees_every_tick(elcentro):
    c = CountingController()
    r = mrd.sim(record=elcentro, duration_s=1.0, controller=c)
    assert c.resets == 1
    assert c.ticks == list(range(len(c.ticks)))
    assert len(c.ticks) == len(r.timeseries["time_s"])


def test_controller_errors_reach_python(elcentro):
    def broken(sensors):
        raise RuntimeError("law failed")

    with pytest.raises(RuntimeError, match="law failed"):
        mrd.sim(record=elcentro, duration_s=1.0, controller=broken)
    with pytest.raises(TypeError):
        mrd.sim(record=elcentro, duration_s=1.0, controller=lambda s: None)
    with pytest.raises(mrd.UsageError, match="controller: expected a callable"):
        mrd.sim(record=elcentro, duration_s=1.0, controller=42)


def _best_of(n, run):
    """Best CPU time of the calling thread over n runs, s (other work on the machine does not count)."""
    best = float("inf")
    for _ in range(n):
        t0 = time.thread_time()
        run()
        best = min(best, time.thread_time() - t0)
    return best


def test_python_controller_overhead(elcentro, capsys):
    """Prints the CPU cost of a Python controller per tick against the
    firmware core's passive-on (no timing asserted)."""
    duration_s = 10.0
    ticks = len(mrd.sim(record=elcentro, duration_s=duration_s).timeseries["time_s"])
    core_s = _best_of(3, lambda: mrd.sim(record=elcentro, control="passive-on", duration_s=duration_s))
    python_s = _best_of(3, lambda: mrd.sim(record=elcentro, duration_s=duration_s, controller=lambda s: PASSIVE_ON_A))
    semi_s = _best_of(3, lambda: mrd.sim(record=elcentro, control="semi-active", duration_s=duration_s))
    with capsys.disabled():
        print(
            f"\nper tick over {ticks} ticks: firmware core passive-on {core_s / ticks * 1e9:.0f} ns, "
            f"semi-active {semi_s / ticks * 1e9:.0f} ns, Python controller {python_s / ticks * 1e9:.0f} ns "
            f"(overhead {(python_s - core_s) / ticks * 1e9:.0f} ns a tick)"
        )
