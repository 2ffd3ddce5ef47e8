"""Buildings, dampers, fluids and ground-motion records, from files or built
in Python. Every object is read by the file reader of the CLI (a dict is
written as the TOML table the reader takes, an array as the record CSV), so
a bad value raises :class:`mrd.UsageError` with the reader's message; the
origin (a file's path, or ``origin=``) names it there."""

from __future__ import annotations

import atexit
import os
import pathlib
import shutil
import tempfile
from typing import Any, Dict, Mapping, Optional, Sequence, Union

import numpy as np

from . import _toml
from ._mrd import (
    UsageError,
    _motion,
    _parse_building,
    _parse_damper,
    _parse_fluid,
    _parse_record_csv,
    _read_building,
    _read_damper,
    _read_fluid,
    _read_record,
)

PathLike = Union[str, "os.PathLike[str]"]

_temp_dir: Optional[str] = None
#: The files written for objects built in Python, and what messages call them.
_labels: Dict[str, str] = {}


def relabel(message: str) -> str:
    """`message` with each file written for an object built in Python named by its origin."""
    for path, label in _labels.items():
        message = message.replace(path, label)
    return message


def _scratch() -> pathlib.Path:
    """A folder of this process for the files of objects built in Python (removed at exit)."""
    global _temp_dir
    if _temp_dir is None:
        _temp_dir = tempfile.mkdtemp(prefix="mrd-python-")
        atexit.register(shutil.rmtree, _temp_dir, True)
    return pathlib.Path(_temp_dir)


class _TomlObject:
    """A building, damper or fluid: the file it came from, or its TOML text."""

    _kind = ""
    _suffix = ".toml"

    def __init__(self, info: Dict[str, Any], path: Optional[str], text: Optional[str], origin: str) -> None:
        self.info = info
        self.path = path
        self.toml = text if text is not None else pathlib.Path(path).read_text()  # type: ignore[arg-type]
        self.origin = origin

    @property
    def name(self) -> str:
        return self.info["name"]

    def file(self) -> str:
        """The file the CLI's reader takes: the original file, or the TOML
        text written once into a temporary folder of this process."""
        if self.path is None:
            folder = _scratch() / f"{self._kind}-{id(self):x}"
            folder.mkdir(exist_ok=True)
            target = folder / (_safe(self.name) + self._suffix)
            target.write_text(self.toml)
            self.path = str(target)
            _labels[self.path] = self.origin
        return self.path

    def __repr__(self) -> str:
        where = self.path if self.path is not None else self.origin
        return f"{type(self).__name__}(name={self.name!r}, from={where!r})"


def _safe(name: str) -> str:
    s = "".join(c if c.isalnum() or c in "-_." else "_" for c in name).strip(".")
    return s or "unnamed"


class Building(_TomlObject):
    """A planar shear building with its isolators and dampers (README "Your
    building"; host_sim/structure/building_file.hpp lists every field).

    ``info`` holds what the reader made of it: name, dofs, base, mass_kg,
    stiffness_n_m, isolators (groups), dampers (tables).
    """

    _kind = "building"

    @classmethod
    def from_file(cls, path: PathLike) -> "Building":
        """Reads a building file (``mrd sim --building``'s reader)."""
        p = os.fspath(path)
        return cls(_read_building(p), p, None, p)

    @classmethod
    def from_dict(cls, document: Mapping[str, Any], origin: str = "building (dict)") -> "Building":
        """The building file's tables as a dict: ``{"building": {...},
        "isolator": [{...}, ...], "damper": [{...}, ...]}`` (lists and NumPy
        arrays for the per-DOF arrays). ``origin`` names it in messages."""
        text = _toml.dumps(document)
        return cls(_parse_building(text, origin), None, text, origin)

    @classmethod
    def shear_chain(
        cls,
        name: str,
        mass_kg: Sequence[float],
        stiffness_n_m: Sequence[float],
        damping_n_s_m: Optional[Sequence[float]] = None,
        *,
        rayleigh: Optional[Mapping[str, Any]] = None,
        base: str = "isolated",
        isolators: Sequence[Mapping[str, Any]] = (),
        dampers: Sequence[Mapping[str, Any]] = (),
        origin: str = "building (dict)",
    ) -> "Building":
        """A building from its arrays, DOF / element 0 (the base) first.

        Args:
            name: the building's name.
            mass_kg, stiffness_n_m: one value per DOF / element, kg and N/m.
            damping_n_s_m: element dashpots, N s/m; or ``rayleigh``
                ``{"ratio": 0.02, "modes": [1, 2]}`` (exactly one of the two).
            base: "isolated" | "fixed".
            isolators: ``[[isolator]]`` tables, e.g. ``{"kind": "lead_rubber",
                "count": 24, "characteristic_strength_n": 72e3,
                "post_yield_stiffness_n_m": 0.74e6, "yield_displacement_m": 0.011}``.
            dampers: ``[[damper]]`` tables ``{"element": 0, "count": 1}``;
                none: one damper at element 0.
        """
        table: Dict[str, Any] = {"name": name, "base": base, "mass_kg": list(np.asarray(mass_kg, dtype=float)),
                                 "stiffness_n_m": list(np.asarray(stiffness_n_m, dtype=float))}
        if damping_n_s_m is not None:
            table["damping_n_s_m"] = list(np.asarray(damping_n_s_m, dtype=float))
        if rayleigh is not None:
            table["rayleigh"] = dict(rayleigh)
        document: Dict[str, Any] = {"building": table}
        if isolators:
            document["isolator"] = [dict(i) for i in isolators]
        if dampers:
            document["damper"] = [dict(d) for d in dampers]
        return cls.from_dict(document, origin)

    @property
    def dofs(self) -> int:
        return self.info["dofs"]


class Damper(_TomlObject):
    """An MR damper: the damper.toml ``mrd calibrate`` writes (README "Your
    damper and fluid"; dampers/thesis-200kn.toml shows every table).

    ``info``: name, rated_current_a, rated_force_n, rated_stroke_m,
    rated_velocity_m_s, coil_resistance_ohm, coil_thermal_resistance_k_w,
    coil_thermal_time_constant_s (the coil's heating), coil_inductance_1a_h,
    coil_inductance_2a_h (its L(i), which the hardware plant's drive works
    against), warnings (what the
    closed loop leaves out or assumes).
    """

    _kind = "damper"

    @classmethod
    def from_file(cls, path: PathLike) -> "Damper":
        """Reads a damper file (``mrd sim --damper``'s reader); its warnings are in ``info``."""
        p = os.fspath(path)
        return cls(_read_damper(p), p, None, p)

    @classmethod
    def from_dict(cls, document: Mapping[str, Any], origin: str = "damper (dict)") -> "Damper":
        """The damper file's tables as a dict: ``{"model": {...}, "yield_n":
        {...}, "viscous_ns_m": {...}, "bingham": {...}, "coil": {...},
        "participant_ratio": {...}, "validity": {...}, "rating": {...}}``."""
        text = _toml.dumps(document)
        return cls(_parse_damper(text, origin), None, text, origin)


class Fluid(_TomlObject):
    """An MR fluid (fluids/thesis-model-fluid.toml shows the tables).

    ``info``: name, source, solid_fraction, warnings.
    """

    _kind = "fluid"

    @classmethod
    def from_file(cls, path: PathLike) -> "Fluid":
        """Reads a fluid file (``mrd sim --fluid``'s reader); its warnings are in ``info``."""
        p = os.fspath(path)
        return cls(_read_fluid(p), p, None, p)

    @classmethod
    def from_dict(cls, document: Mapping[str, Any], origin: str = "fluid (dict)") -> "Fluid":
        """The fluid file's tables as a dict: ``{"fluid": {...},
        "participant_ratio": {...}}``."""
        text = _toml.dumps(document)
        return cls(_parse_fluid(text, origin), None, text, origin)


class Record:
    """A ground-motion record: uniformly sampled ground acceleration, m/s^2.

    Attributes:
        accel_m_s2: the samples (read-only float64 array).
        dt_s: the sample step, s.
        name: the record's name (the file stem for a file).
        path: the file it came from (or its CSV, once ``file()`` wrote it).
    """

    def __init__(self, accel_m_s2: Any, dt_s: float, name: str = "record") -> None:
        """A record from an array of accelerations, m/s^2, sampled every
        ``dt_s`` s. It is checked as the CSV reader checks a record file
        (the message names ``name``.csv, the row and the field)."""
        a = np.array(accel_m_s2, dtype=np.float64)
        if a.ndim != 1:
            raise UsageError(f"{name}: expected a 1-D array of accelerations, m/s^2, got {a.ndim} dimensions")
        self.name = name
        self.dt_s = float(dt_s)
        self._csv = _record_csv(a, self.dt_s)
        read_dt_s, _ = _parse_record_csv(self._csv, name + ".csv", name)
        self.accel_m_s2 = a
        self.accel_m_s2.flags.writeable = False
        self.path: Optional[str] = None
        self._read_dt_s = read_dt_s

    @classmethod
    def from_file(cls, path: PathLike) -> "Record":
        """Reads a record file (CSV time_s,accel_m_s2 or PEER .AT2), as ``mrd sim --record`` does."""
        p = os.fspath(path)
        name, dt_s, accel = _read_record(p)
        r = cls.__new__(cls)
        r.name, r.dt_s, r.path, r._csv = name, dt_s, p, None
        accel.flags.writeable = False
        r.accel_m_s2 = accel
        return r

    def file(self) -> str:
        """The record file the CLI's reader takes (this record's CSV written
        once into a temporary folder of this process, for one built in Python)."""
        if self.path is None:
            folder = _scratch() / f"record-{id(self):x}"
            folder.mkdir(exist_ok=True)
            target = folder / (_safe(self.name) + ".csv")
            target.write_text(self._csv)
            self.path = str(target)
            _labels[self.path] = self.name + ".csv"
        return self.path

    def __len__(self) -> int:
        return len(self.accel_m_s2)

    def __repr__(self) -> str:
        return f"Record(name={self.name!r}, samples={len(self)}, dt_s={self.dt_s!r})"


def _record_csv(accel: np.ndarray, dt_s: float) -> str:
    rows = ["time_s,accel_m_s2"]
    rows += [f"{i * dt_s!r},{float(v)!r}" for i, v in enumerate(accel.tolist())]
    return "\n".join(rows) + "\n"


def as_file(value: Any, kind: str) -> str:
    """A file name for a CLI option: "" for None, a path as it is, or the
    file of a Building, Damper, Fluid or Record."""
    if value is None:
        return ""
    if isinstance(value, (_TomlObject, Record)):
        expected = {"building": Building, "damper": Damper, "fluid": Fluid, "record": Record}[kind]
        if not isinstance(value, expected):
            raise UsageError(f"{kind}: expected a file name or an mrd.{expected.__name__}, got an mrd.{type(value).__name__}")
        return value.file()
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise UsageError(f"{kind}: expected a file name or an mrd object, got {type(value).__name__}")


class Motion:
    """A ground motion as a closed loop takes it: scaled to a PGA and
    resampled to the run's step (what ``mrd sim`` runs).

    Attributes:
        accel_m_s2: ground acceleration at the run's step, m/s^2 (float64,
            owned by the array, no copy made).
        scale_factor: applied to the record to reach the PGA.
        pga_m_s2: the PGA after scaling, m/s^2.
        name, source: the record's name and file (or the generator's description).
        synthetic: True for a synthetic motion (no record given).
        step_s: the step the motion is sampled at, s.
    """

    __slots__ = ("accel_m_s2", "scale_factor", "pga_m_s2", "name", "source", "synthetic", "step_s")

    def __repr__(self) -> str:
        return (f"Motion(name={self.name!r}, samples={len(self.accel_m_s2)}, step_s={self.step_s!r}, "
                f"pga_m_s2={self.pga_m_s2!r})")


def load_motion(
    record: Union[None, PathLike, Record] = None,
    pga_g: float = 0.1127,
    step_s: float = 1e-3,
    duration_s: Optional[float] = None,
    seed: int = 1,
) -> Motion:
    """The ground motion ``mrd sim`` runs for these options: ``record`` (a
    file or a Record; None: the synthetic motion of ``seed``) scaled to
    ``pga_g`` and resampled to ``step_s``, over ``duration_s`` (zero-padded
    or cut; None: the record's length, 40 s synthetic). Its ``accel_m_s2``
    fed to :func:`mrd.batch` with scale 1 gives mrd.sim's run bit for bit.

    Raises:
        UsageError: a bad record or option, with the CLI's message.
    """
    d = _motion(as_file(record, "record"), pga_g, step_s, duration_s, seed)
    m = Motion()
    m.accel_m_s2 = d["accel_m_s2"]
    m.scale_factor = d["scale_factor"]
    m.pga_m_s2 = d["pga_m_s2"]
    m.name = d["name"]
    m.source = d["source"]
    m.synthetic = d["synthetic"]
    m.step_s = float(step_s)
    return m
