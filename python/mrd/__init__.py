"""mrd from Python: the closed loop of ``mrd sim`` as a function, many in
SIMD lanes, your own objects and control law, and the study commands.

- ``mrd.sim(...)`` runs one closed-loop earthquake run exactly as ``mrd sim``
  does (same options, same checks, same numbers) and returns its summary as a
  dict (summary.json's fields), its PlantSummary as ``peaks`` and its time
  series as NumPy arrays (timeseries.csv's columns, lent by the run without a
  copy). ``controller=`` puts a control law written in Python in the loop in
  place of the firmware core: a callable returning a constant costs about
  0.2 us of CPU a tick more than the core's passive-on (330 ns a tick for
  the whole passive-on run, 540 ns with the Python law, El Centro 20 s at
  1 kHz; python/tests/test_controller.py prints the figure on each run).
- ``mrd.batch(records, scale, idle_years, control, building=...)`` runs many
  closed loops on one plant in the C++ batch path's SIMD lanes, with the GIL
  released, and returns one NumPy array per PlantSummary field; its peaks
  equal mrd.sim's bit for bit (records from ``mrd.load_motion``).
- ``mrd.Building``, ``mrd.Damper``, ``mrd.Fluid`` (from files or dicts that
  mirror the files' tables) and ``mrd.Record`` (from an array and its step):
  checked by the CLI's file readers, accepted wherever a file is.
- ``mrd.fragility``, ``mrd.risk``, ``mrd.schedule``, ``mrd.calibrate``,
  ``mrd.discrepancy``: the ``mrd`` program's commands with keyword options,
  their summary.json as a dict and CSV tables as NumPy arrays.

Bad input raises :class:`mrd.UsageError` (a ValueError) with the message
``mrd`` prints after ``mrd: error:``.
"""

from __future__ import annotations

import json
from typing import Any, Callable, Dict, Optional, Union

import numpy as np

from ._batch import PEAK_FIELDS, BatchResult, batch
from ._cli import CommandResult, calibrate, discrepancy, fragility, risk, run_command, schedule
from ._mrd import Sensors, UsageError, _sim
from ._objects import Building, Damper, Fluid, Motion, Record, as_file, load_motion, relabel

__all__ = [
    "sim",
    "SimResult",
    "Sensors",
    "UsageError",
    "batch",
    "BatchResult",
    "PEAK_FIELDS",
    "load_motion",
    "Motion",
    "Building",
    "Damper",
    "Fluid",
    "Record",
    "fragility",
    "risk",
    "schedule",
    "calibrate",
    "discrepancy",
    "run_command",
    "CommandResult",
]


class SimResult:
    """One closed-loop run.

    Attributes:
        summary: dict with the fields of ``mrd sim --out``'s summary.json
            (``mrd sim --help`` lists them; units in the names).
        timeseries: dict of read-only float64 NumPy arrays, one per column of
            timeseries.csv, in its order (time_s, ground_accel_m_s2,
            base_disp_m, ..., story_<k>_drift_m); one value per control tick.
        peaks: the run's plant::PlantSummary as a dict of floats, the fields
            of mrd.PEAK_FIELDS in SI units (what mrd.batch returns per run).
    """

    __slots__ = ("summary", "timeseries", "peaks")

    def __init__(self, summary: Dict[str, Any], timeseries: Dict[str, np.ndarray],
                 peaks: Optional[Dict[str, float]] = None) -> None:
        self.summary = summary
        self.timeseries = timeseries
        self.peaks = {} if peaks is None else peaks

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"SimResult(record={s.get('record')!r}, control={s.get('control')!r}, "
            f"peak_base_displacement_m={s.get('peak_base_displacement_m')!r}, "
            f"ticks={len(self.timeseries.get('time_s', ()))})"
        )


def sim(
    record: Union[None, str, Record] = None,
    pga_g: float = 0.1127,
    control: Optional[str] = None,
    numeric: Optional[str] = None,
    board: Optional[str] = None,
    idle_years: float = 0.0,
    duration_s: Optional[float] = None,
    step_s: Optional[float] = None,
    seed: int = 1,
    plant: str = "thesis",
    sensor_seed: int = 1,
    offset_mm: float = 3.0,
    building: Union[None, str, Building] = None,
    damper: Union[None, str, Damper] = None,
    fluid: Union[None, str, Fluid] = None,
    controller: Union[None, Callable[[Sensors], float], Any] = None,
    drive: Optional[str] = None,
) -> SimResult:
    """Run one closed loop as ``mrd sim`` does; each argument is its option.

    Args:
        record: ground-motion file (CSV time_s,accel_m_s2 or PEER .AT2) or
            an mrd.Record; None:
            a synthetic Kanai-Tajimi motion (``seed``); "none": no ground motion.
        pga_g: PGA the record is scaled to, g (Table 6.3: 0.1127).
        control: "passive-off" | "passive-on" | "semi-active"; None: passive-off,
            or the board file's mode with ``board``.
        numeric: firmware core build "float" | "fixed" | "double"; None: float
            (refused with ``board``, as --numeric is).
        board: board file whose controller, damper, fluid and period the run uses.
        idle_years: idle time before the earthquake, years.
        duration_s: simulated time, s; None: the record's length (40 s synthetic).
        step_s: simulation and control step, s; None: 1e-3 (refused with ``board``).
        seed: seed of the synthetic motion.
        plant: "thesis" | "hardware".
        sensor_seed: seed of the hardware plant's sensor noise.
        offset_mm: hardware plant: damper parked this far off its stroke centre, mm.
        building, damper, fluid: building, damper and fluid files, or
            mrd.Building, mrd.Damper, mrd.Fluid (None: the thesis's).
        controller: None for the firmware control core (``control`` mode), or
            a Python control law: a callable, or an object with a
            ``step(sensors)`` method (and optionally ``reset()``, called before
            the run), given each tick's :class:`Sensors` and returning the coil
            current command, A, or a pair (current command, A; desired force,
            N: the desired_force_n column, else 0), each converted to the
            core's float, the drive enabled. It runs in
            the same plant as the core; the summary's "control" field still
            names ``control``.
        drive: drive file of the hardware plant (``plant="hardware"``; README
            "Your drive"); None: the thesis's PWM drive.

    Returns:
        SimResult with ``summary`` (summary.json's dict) and ``timeseries``.

    Raises:
        UsageError: a bad option value or file, with the CLI's message.
    """
    try:
        raw = _sim(
            as_file(record, "record"),
            pga_g,
            control,
            numeric,
            "" if board is None else board,
            idle_years,
            duration_s,
            step_s,
            seed,
            plant,
            sensor_seed,
            offset_mm,
            as_file(building, "building"),
            as_file(damper, "damper"),
            as_file(fluid, "fluid"),
            "" if drive is None else str(drive),
            controller,
        )
    except UsageError as e:
        raise UsageError(relabel(str(e))) from None
    summary = json.loads(raw.summary_json)
    if isinstance(summary.get("record"), str):  # a Record made in Python: its name, not its scratch file
        summary["record"] = relabel(summary["record"])
    timeseries = {name: np.asarray(column) for name, column in raw.columns}
    return SimResult(summary, timeseries, dict(raw.peaks))
