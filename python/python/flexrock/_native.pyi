"""Typing stubs of flexrock._native, the compiled half of the package (see flexrock)."""

from os import PathLike
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
MAX_SWEEP_TABLE_BYTES: int

Value = Union[bool, int, float, str]
ArrayLike = Union[Sequence[float], npt.NDArray[np.floating[Any]]]

class FlexrockError(ValueError): ...

class GroundMotion:
    def __init__(
        self,
        acceleration: ArrayLike,
        dt: Optional[float] = None,
        *,
        time: Optional[ArrayLike] = None,
        units: str,
        source: Optional[str] = None,
    ) -> None: ...
    @property
    def dt(self) -> float: ...
    @property
    def acceleration(self) -> npt.NDArray[np.float64]: ...
    @property
    def time(self) -> npt.NDArray[np.float64]: ...
    @property
    def units(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def duration(self) -> float: ...
    def to_csv(self, path: Union[str, PathLike[str]]) -> None: ...
    @property
    def metadata(self) -> dict[str, Any]: ...
    @property
    def label(self) -> str: ...
    def __len__(self) -> int: ...

class Model:
    @staticmethod
    def from_file(path: Union[str, PathLike[str]]) -> Model: ...
    @staticmethod
    def from_toml(text: str) -> Model: ...
    @staticmethod
    def from_dict(d: Mapping[str, Mapping[str, Value]]) -> Model: ...
    def set(self, key: str, value: Value) -> None: ...
    def update(self, settings: Mapping[str, Value]) -> None: ...
    def get(self, key: str) -> Optional[Value]: ...
    def to_dict(
        self, record_path: Optional[Union[str, PathLike[str]]] = None
    ) -> dict[str, dict[str, Value]]: ...
    def to_toml(self, record_path: Optional[Union[str, PathLike[str]]] = None) -> str: ...
    def __copy__(self) -> Model: ...
    def __deepcopy__(self, memo: Any) -> Model: ...
    def with_ground_motion(self, ground_motion: GroundMotion) -> Model: ...
    @property
    def ground_motion(self) -> Optional[GroundMotion]: ...
    @property
    def settings(self) -> list[str]: ...
    @property
    def path(self) -> Optional[str]: ...

class Result:
    t: npt.NDArray[np.float64]
    q: npt.NDArray[np.float64]
    qdot: npt.NDArray[np.float64]
    s: npt.NDArray[np.float64]
    r: npt.NDArray[np.float64]
    mode: npt.NDArray[np.str_]
    floor_acc: npt.NDArray[np.float64]
    F: npt.NDArray[np.float64]
    energy_residual: npt.NDArray[np.float64]
    work_input: npt.NDArray[np.float64]
    work_damping: npt.NDArray[np.float64]
    events: list[dict[str, Any]]
    episodes: list[dict[str, Any]]
    summary: dict[str, Any]
    def to_pandas(self) -> Any: ...

def props(model: Model) -> dict[str, Any]: ...
def rigid_block(
    model: Model,
    form: Optional[str] = None,
    overturning: Optional[str] = None,
    restitution: Optional[float] = None,
    find_min: Optional[Tuple[str, float, float]] = None,
    scan: Optional[int] = None,
    tol: Optional[float] = None,
) -> dict[str, Any]: ...
def simulate(
    model: Model,
    method: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    duration: Optional[float] = None,
    output_dt: Optional[float] = None,
) -> Result: ...
class RowResult:
    columns: list[Result]
    impacts: list[dict[str, Any]]
    contacts: Any  # flexrock.Records
    summary: dict[str, Any]

def simulate_row(
    path: Union[str, PathLike[str]], duration: Optional[float] = None
) -> RowResult: ...
def read_record(
    path: Union[str, PathLike[str]],
    format: Optional[str] = None,
    dt: Optional[float] = None,
    units: Optional[str] = None,
) -> GroundMotion: ...
def sweep(
    model: Model,
    axes: Mapping[str, Sequence[Value]],
    find_min: Optional[Tuple[str, float, float]] = None,
    scan: Optional[int] = None,
    tol: Optional[float] = None,
    rigid_form: Optional[str] = None,
    rigid_overturning: Optional[str] = None,
    rigid_restitution: Optional[float] = None,
) -> Any: ...
def compare(
    model: Model,
    dt: Optional[float] = None,
    variant: Optional[str] = None,
    reference_rtol: Optional[float] = None,
) -> dict[str, Any]: ...
def converge(
    model: Model,
    dts: Optional[list[float]] = None,
    rtols: Optional[list[float]] = None,
    reference_rtol: Optional[float] = None,
) -> dict[str, Any]: ...
def fem_check(
    model: Model,
    nx: Optional[int] = None,
    ny: Optional[int] = None,
    dt: Optional[float] = None,
    scheme: Optional[str] = None,
) -> dict[str, Any]: ...
def intensity_measures(
    motion: Union[GroundMotion, Model],
    period: Optional[float] = None,
    damping: float = 0.05,
) -> dict[str, float]: ...
def response_spectrum(
    motion: Union[GroundMotion, Model],
    periods: Optional[Sequence[float]] = None,
    damping: float = 0.05,
) -> dict[str, npt.NDArray[np.float64]]: ...
def fragility(
    model: Model,
    records: str,
    im: str,
    period: Optional[float],
    scale: Tuple[float, float],
    scan: Optional[int],
    tol: Optional[float],
    bootstrap: int,
    seed: int,
) -> str: ...
def fit_capacities(capacity: Sequence[float], censored: Sequence[bool]) -> dict[str, Any]: ...
def fit_stripes(
    levels: Sequence[float], records: Sequence[int], damaged: Sequence[int]
) -> dict[str, Any]: ...
