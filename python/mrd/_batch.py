"""mrd.batch: many closed loops on one plant, stepped side by side in SIMD
lanes by the C++ batch path (host_sim/batch), the GIL released while they run."""

from __future__ import annotations

import time
from typing import Any, Dict, Optional, Sequence, Union

import numpy as np

from ._mrd import UsageError, _batch, _lane_isa
from ._objects import Building, Damper, Fluid, Motion, as_file, relabel

#: The arrays of a BatchResult, one per plant::PlantSummary field, in order.
PEAK_FIELDS = (
    "peak_base_displacement_m",
    "peak_damper_force_n",
    "peak_base_velocity_m_s",
    "peak_superstructure_accel_m_s2",
    "peak_base_accel_m_s2",
    "peak_current_a",
    "peak_isolator_force_n",
    "peak_story_drift_m",
    "peak_damper_stroke_m",
    "final_participant_ratio",
    "sq",
    "duration_s",
    "ticks",
    "peak_coil_current_a",
    "rms_coil_current_a",
    "time_above_rated_s",
    "command_changes_per_s",
    "peak_coil_temperature_rise_k",
)


class BatchResult:
    """The runs of a batch, field by field.

    Attributes:
        peaks: dict of float64 arrays, one per field of PEAK_FIELDS, entry i
            the run i's (views of one 2-D array, ``values``).
        values: the 2-D array [field, run].
        cpp_seconds: wall time of the C++ batch calls alone, s.
        cpp_cpu_seconds: their CPU time (summed over the threads), s.
        seconds: wall time of the whole mrd.batch call, s.
        cpu_seconds: CPU time of the calling thread over the whole call, s
            (with threads=1 it includes the C++ runs; a benchmark's measure
            on a loaded machine).
        simulated_s: simulated time over all runs, s.
        lane_isa: the lane kernel that ran ("x86-64-v4", ...).
    """

    __slots__ = ("peaks", "values", "cpp_seconds", "cpp_cpu_seconds", "seconds", "cpu_seconds", "simulated_s",
                 "lane_isa")

    def __getitem__(self, field: str) -> np.ndarray:
        return self.peaks[field]

    def __len__(self) -> int:
        return self.values.shape[1]

    def __repr__(self) -> str:
        return (f"BatchResult(runs={len(self)}, simulated_s={self.simulated_s:.6g}, "
                f"seconds={self.seconds:.4g}, lane_isa={self.lane_isa!r})")


def _per_run(name: str, value: Any, n: int, kind: type) -> list:
    if isinstance(value, (str, int, float, np.floating, np.integer)):
        return [kind(value)] * n
    values = [kind(v) for v in (value.tolist() if isinstance(value, np.ndarray) else value)]
    if len(values) != n:
        raise UsageError(f"{name}: expected one value or one per record ({n}), got {len(values)}")
    return values


def batch(
    records: Union[Sequence[Union[np.ndarray, Motion]], np.ndarray],
    scale: Union[float, Sequence[float], np.ndarray] = 1.0,
    idle_years: Union[float, Sequence[float], np.ndarray] = 0.0,
    control: Union[str, Sequence[str]] = "passive-off",
    *,
    building: Union[None, str, Building] = None,
    damper: Union[None, str, Damper] = None,
    fluid: Union[None, str, Fluid] = None,
    step_s: Optional[float] = None,
    numeric: Optional[str] = None,
    story_drift: bool = True,
    threads: int = 1,
    isa: str = "auto",
) -> BatchResult:
    """Many closed-loop runs on one plant, in SIMD lanes.

    Run i steps the ground motion ``scale[i] * records[i]`` (one sample a
    tick, at ``step_s``) after ``idle_years[i]`` idle, with the firmware
    control core in mode ``control[i]``: what ``mrd sim`` runs, its peaks
    equal bit for bit (``records[i]`` from :func:`mrd.load_motion`, scale 1).

    Args:
        records: 1-D float64 arrays of ground acceleration at ``step_s``,
            m/s^2 (or Motions, or the rows of a 2-D array); runs may differ
            in length. They are read in place, not copied.
        scale: factor on each record (one value, or one per record).
        idle_years: idle time before each run, years (one, or one per record).
        control: "passive-off" | "passive-on" | "semi-active" (one, or one per record).
        building, damper, fluid: files or mrd objects (None: the thesis's);
            checked as ``mrd sim`` checks them.
        step_s: simulation and control step, s (None: 1e-3).
        numeric: firmware core build "float" | "fixed" | "double" (None: float).
        story_drift: False skips the story drifts (peak_story_drift_m NaN, faster).
        threads: worker threads, each a batch of its share of the runs (0: all cores).
        isa: lane kernel "auto" | "generic" | "x86-64-v3" | "x86-64-v4".

    Returns:
        BatchResult: one float64 array per PlantSummary field.

    Raises:
        UsageError: a bad option, file or record, with the CLI's message.
    """
    t0 = time.perf_counter()
    cpu0 = time.thread_time()
    if isinstance(records, np.ndarray) and records.ndim == 2:
        arrays = list(records)
    else:
        arrays = [r.accel_m_s2 if isinstance(r, Motion) else r for r in records]
    arrays = [np.ascontiguousarray(a, dtype=np.float64) for a in arrays]
    n = len(arrays)
    try:
        raw = _batch(
            arrays,
            _per_run("scale", scale, n, float),
            _per_run("idle_years", idle_years, n, float),
            _per_run("control", control, n, str),
            as_file(building, "building"),
            as_file(damper, "damper"),
            as_file(fluid, "fluid"),
            step_s,
            numeric,
            story_drift,
            threads,
            isa,
        )
    except UsageError as e:
        raise UsageError(relabel(str(e))) from None
    seconds = time.perf_counter() - t0
    cpu_seconds = time.thread_time() - cpu0
    r = BatchResult()
    r.values = raw.values
    r.peaks = {name: raw.values[i] for i, name in enumerate(raw.names)}
    r.cpp_seconds = raw.cpp_seconds
    r.cpp_cpu_seconds = raw.cpp_cpu_seconds
    r.seconds = seconds
    r.cpu_seconds = cpu_seconds
    r.simulated_s = float(np.sum(r.peaks["duration_s"]))
    r.lane_isa = _lane_isa() if isa == "auto" else isa
    return r
