from typing import Any, Callable, Dict, Optional, Protocol, Union

import numpy as np
import numpy.typing as npt

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

class ControllerObject(Protocol):
    def step(self, sensors: Sensors) -> float: ...

class SimResult:
    summary: Dict[str, Any]
    timeseries: Dict[str, npt.NDArray[np.float64]]
    def __init__(self, summary: Dict[str, Any], timeseries: Dict[str, npt.NDArray[np.float64]]) -> None: ...

def sim(
    record: Optional[str] = ...,
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
    building: Optional[str] = ...,
    damper: Optional[str] = ...,
    fluid: Optional[str] = ...,
    controller: Union[None, Callable[[Sensors], float], ControllerObject] = ...,
) -> SimResult: ...
