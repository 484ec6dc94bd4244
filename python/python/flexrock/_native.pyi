"""Typing stubs of flexrock's Python bindings (the compiled module `flexrock`)."""

from os import PathLike
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class FlexrockError(ValueError):
    """An error of flexrock, with the message the command line prints."""

Value = Union[bool, int, float, str]

class Model:
    @staticmethod
    def from_file(path: Union[str, PathLike[str]]) -> Model: ...
    @staticmethod
    def from_toml(text: str) -> Model: ...
    def set(self, key: str, value: Value) -> None:
        """Set a model-file key; raises FlexrockError, naming the key, on a bad key or value."""
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
    summary: dict[str, Any]
    def to_pandas(self) -> Any:
        """The history as a pandas DataFrame (ImportError without pandas)."""

def props(model: Model) -> dict[str, Any]: ...
def simulate(
    model: Model,
    method: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    duration: Optional[float] = None,
    output_dt: Optional[float] = None,
) -> Result: ...
def sweep(
    model: Model,
    axes: Mapping[str, Sequence[Value]],
    find_min: Optional[Tuple[str, float, float]] = None,
    scan: Optional[int] = None,
    tol: Optional[float] = None,
) -> dict[str, Union[npt.NDArray[np.float64], npt.NDArray[np.int64], list[str]]]: ...
