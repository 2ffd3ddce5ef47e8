import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Protocol, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "os.PathLike[str]"]
_FloatArray = npt.NDArray[np.float64]

class UsageError(ValueError): ...

class Sensors:
    @property
    def tick(self) -> int: ...
    @property
    def damper_disp_m(self) -> float: ...
    @property
    def damper_force_n(self) -> float: ...
    @property
    def ground_accel_m_s2(self) -> float: ...
    @property
    def base_accel_m_s2(self) -> float: ...
    @property
    def coil_current_a(self) -> float: ...

_Command = Union[float, Tuple[float, float]]

class ControllerObject(Protocol):
    def step(self, sensors: Sensors) -> _Command: ...

class Building:
    info: Dict[str, Any]
    path: Optional[str]
    toml: str
    origin: str
    @classmethod
    def from_file(cls, path: _Path) -> Building: ...
    @classmethod
    def from_dict(cls, document: Mapping[str, Any], origin: str = ...) -> Building: ...
    @classmethod
    def shear_chain(
        cls,
        name: str,
        mass_kg: Sequence[float] | _FloatArray,
        stiffness_n_m: Sequence[float] | _FloatArray,
        damping_n_s_m: Optional[Sequence[float] | _FloatArray] = ...,
        *,
        rayleigh: Optional[Mapping[str, Any]] = ...,
        base: str = ...,
        isolators: Sequence[Mapping[str, Any]] = ...,
        dampers: Sequence[Mapping[str, Any]] = ...,
        origin: str = ...,
    ) -> Building: ...
    @property
    def name(self) -> str: ...
    @property
    def dofs(self) -> int: ...
    def file(self) -> str: ...

class Damper:
    info: Dict[str, Any]
    path: Optional[str]
    toml: str
    origin: str
    @classmethod
    def from_file(cls, path: _Path) -> Damper: ...
    @classmethod
    def from_dict(cls, document: Mapping[str, Any], origin: str = ...) -> Damper: ...
    @property
    def name(self) -> str: ...
    def file(self) -> str: ...

class Fluid:
    info: Dict[str, Any]
    path: Optional[str]
    toml: str
    origin: str
    @classmethod
    def from_file(cls, path: _Path) -> Fluid: ...
    @classmethod
    def from_dict(cls, document: Mapping[str, Any], origin: str = ...) -> Fluid: ...
    @property
    def name(self) -> str: ...
    def file(self) -> str: ...

class Record:
    accel_m_s2: _FloatArray
    dt_s: float
    name: str
    path: Optional[str]
    def __init__(self, accel_m_s2: Sequence[float] | _FloatArray, dt_s: float, name: str = ...) -> None: ...
    @classmethod
    def from_file(cls, path: _Path) -> Record: ...
    def file(self) -> str: ...
    def __len__(self) -> int: ...

class Motion:
    accel_m_s2: _FloatArray
    scale_factor: float
    pga_m_s2: float
    name: str
    source: str
    synthetic: bool
    step_s: float

def load_motion(
    record: Union[None, _Path, Record] = ...,
    pga_g: float = ...,
    step_s: float = ...,
    duration_s: Optional[float] = ...,
    seed: int = ...,
) -> Motion: ...
def as_file(value: Any, kind: str) -> str: ...
def relabel(message: str) -> str: ...

class SimResult:
    summary: Dict[str, Any]
    timeseries: Dict[str, _FloatArray]
    peaks: Dict[str, float]
    def __init__(
        self, summary: Dict[str, Any], timeseries: Dict[str, _FloatArray], peaks: Optional[Dict[str, float]] = ...
    ) -> None: ...

def sim(
    record: Union[None, str, Record] = ...,
    pga_g: float = ...,
    control: Optional[str] = ...,
    numeric: Optional[str] = ...,
    board: Optional[str] = ...,
    idle_years: float = ...,
    duration_s: Optional[float] = ...,
    step_s: Optional[float] = ...,
    seed: int = ...,
    plant: str = ...,
    sensor_seed: int = ...,
    offset_mm: float = ...,
    building: Union[None, str, Building] = ...,
    damper: Union[None, str, Damper] = ...,
    fluid: Union[None, str, Fluid] = ...,
    controller: Union[None, Callable[[Sensors], _Command], ControllerObject] = ...,
    drive: Optional[str] = ...,
) -> SimResult: ...

PEAK_FIELDS: Tuple[str, ...]

class BatchResult:
    peaks: Dict[str, _FloatArray]
    values: _FloatArray
    cpp_seconds: float
    cpp_cpu_seconds: float
    seconds: float
    cpu_seconds: float
    simulated_s: float
    lane_isa: str
    def __getitem__(self, field: str) -> _FloatArray: ...
    def __len__(self) -> int: ...

def batch(
    records: Union[Sequence[Union[_FloatArray, Motion]], _FloatArray],
    scale: Union[float, Sequence[float], _FloatArray] = ...,
    idle_years: Union[float, Sequence[float], _FloatArray] = ...,
    control: Union[str, Sequence[str]] = ...,
    *,
    building: Union[None, str, Building] = ...,
    damper: Union[None, str, Damper] = ...,
    fluid: Union[None, str, Fluid] = ...,
    step_s: Optional[float] = ...,
    numeric: Optional[str] = ...,
    story_drift: bool = ...,
    threads: int = ...,
    isa: str = ...,
) -> BatchResult: ...

class CommandResult:
    summary: Dict[str, Any]
    tables: Dict[str, Dict[str, Union[_FloatArray, List[str]]]]
    folder: Any
    stdout: str
    warnings: List[str]

def run_command(command: str, out: Optional[_Path] = ..., **options: Any) -> CommandResult: ...
def fragility(out: Optional[_Path] = ..., **options: Any) -> CommandResult: ...
def risk(out: Optional[_Path] = ..., **options: Any) -> CommandResult: ...
def schedule(out: Optional[_Path] = ..., **options: Any) -> CommandResult: ...
def calibrate(out: Optional[_Path] = ..., **options: Any) -> CommandResult: ...
def discrepancy(out: Optional[_Path] = ..., **options: Any) -> CommandResult: ...
