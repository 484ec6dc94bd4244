"""`SweepResult`: the table of a sweep as typed numpy columns, pandas and xarray."""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

import numpy as np

_DTYPES = {"int": np.int64, "float": np.float64, "bool": np.bool_, "str": object}


def _typed(kind: str, values: Any, missing: Any = None) -> Tuple[np.ndarray, Optional[np.ndarray]]:
    """One column as an array of its kind's dtype, and where it is missing (None if nowhere).

    `values` is a numpy array of the kind's dtype (as the compiled sweep gives it, with
    `missing` a bool array or None), or a sequence of values with None where one is missing.
    """
    dtype = _DTYPES[kind]
    if isinstance(values, np.ndarray):
        array = values if values.dtype == dtype else values.astype(dtype)
        mask = None if missing is None else np.asarray(missing, dtype=bool)
        return array, (mask if mask is not None and mask.any() else None)
    values = list(values)
    absent = np.array([v is None for v in values], dtype=bool)
    if kind == "float":
        return np.array([np.nan if v is None else v for v in values], dtype=np.float64), None
    if kind == "str":
        out = np.empty(len(values), dtype=object)
        out[:] = values
        return out, None
    filled = np.array([0 if v is None else v for v in values], dtype=dtype)
    return filled, (absent if absent.any() else None)


def _frame(pd: Any, columns: List[str], kinds: List[str], data: List[Any]) -> Any:
    """Typed columns (as `_typed` gives them) as a pandas DataFrame: int and bool columns with
    a missing value in pandas' nullable dtypes, text as "string", missing floats as NaN."""
    frame = {}
    for name, kind, (array, mask) in zip(columns, kinds, data):
        if kind == "str":
            frame[name] = pd.array(array, dtype="string")
        elif mask is not None and kind == "int":
            frame[name] = pd.arrays.IntegerArray(array.copy(), mask.copy())
        elif mask is not None and kind == "bool":
            frame[name] = pd.arrays.BooleanArray(array.copy(), mask.copy())
        elif mask is not None:
            frame[name] = np.where(mask, np.nan, array)
        else:
            frame[name] = array
    return pd.DataFrame(frame, columns=columns)


class SweepResult:
    """The result of `flexrock.sweep`: one row per point, the columns of ``sweep.csv``.

    Columns are typed: ``point`` and counts are int64, numbers float64, ``overturned`` bool,
    text (``status``, ``reason``, ``final_mode``, a record path) object arrays of str.

    Parameters
    ----------
    table : dict
        ``{"columns": [name, ...], "kinds": ["int" | "float" | "bool" | "str", ...],
        "values": [[value or None, ...] per column], "axes": [(key, [values]), ...]}``, as the
        compiled sweep returns it. Users get a SweepResult from `flexrock.sweep` rather than
        building one.

    Examples
    --------
    >>> import flexrock
    >>> model = flexrock.Model.from_file("models/pulse-map.toml")
    >>> result = flexrock.sweep(model, {"excitation.period": [0.5, 1.0],
    ...                                 "excitation.amplitude": [2.0, 4.0]})
    >>> result.shape, len(result)
    ((2, 2), 4)
    >>> result["overturned"].dtype
    dtype('bool')
    """

    def __init__(self, table: Dict[str, Any]):
        self._columns: List[str] = list(table["columns"])
        self._kinds: List[str] = list(table["kinds"])
        values = list(table["values"])
        missing = list(table.get("missing") or [None] * len(values))
        self._axes: List[Tuple[str, List[Any]]] = [(k, list(v)) for k, v in table["axes"]]
        if not (len(self._columns) == len(self._kinds) == len(values) == len(missing)):
            raise ValueError("a sweep table needs one kind and one list of values per column")
        for name, kind in zip(self._columns, self._kinds):
            if kind not in _DTYPES:
                raise ValueError(f"column {name!r}: unknown kind {kind!r}")
        self._data = [_typed(k, v, m) for k, v, m in zip(self._kinds, values, missing)]

    @property
    def columns(self) -> List[str]:
        """The column names, in the order of ``sweep.csv``."""
        return list(self._columns)

    @property
    def axes(self) -> List[Tuple[str, List[Any]]]:
        """The axes, ``(key, values)``, in the order given (the last varies fastest)."""
        return [(k, list(v)) for k, v in self._axes]

    @property
    def shape(self) -> Tuple[int, ...]:
        """The lengths of the axes: the grid the rows fill, last axis fastest."""
        return tuple(len(v) for _, v in self._axes)

    def __len__(self) -> int:
        return len(self._data[0][0]) if self._data else 0

    def __contains__(self, name: object) -> bool:
        return name in self._columns

    def __iter__(self):
        return iter(self._columns)

    def __getitem__(self, name: str) -> np.ndarray:
        """One column as a numpy array.

        float columns are float64 with NaN where ``sweep.csv`` is empty; int and bool columns
        are int64 and bool, and a numpy masked array (of the same dtype) when a value is missing;
        text columns are object arrays of str (None where empty).

        Raises
        ------
        KeyError
            For a name that is not a column; the message lists the columns.
        """
        try:
            i = self._columns.index(name)
        except ValueError:
            raise KeyError(f"{name!r} is not a column of the sweep; columns: {self._columns}") from None
        array, mask = self._data[i]
        if mask is not None:
            return np.ma.masked_array(array.copy(), mask=mask.copy())
        return array.copy()

    def to_dict(self) -> Dict[str, np.ndarray]:
        """The columns by name, as `__getitem__` gives them (the old flat dict of a sweep)."""
        return {name: self[name] for name in self._columns}

    def to_pandas(self):
        """The table as a pandas DataFrame, one row per point.

        Columns with a missing value get pandas' nullable dtypes: "Int64" for int, "boolean"
        for bool; text columns are "string". float columns are float64 with NaN.

        Raises
        ------
        ImportError
            Without pandas (``pip install pandas``).
        """
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("SweepResult.to_pandas() needs pandas: pip install pandas") from None
        return _frame(pd, self._columns, self._kinds, self._data)

    def to_xarray(self):
        """The table as an xarray Dataset with one dimension per axis.

        The coordinates are the axes' values; every other column is a variable over the grid
        (``point`` included). An int or bool column with a missing value becomes float64 with
        NaN there (xarray has no nullable integers).

        Raises
        ------
        ImportError
            Without xarray (``pip install xarray``).
        """
        try:
            import xarray as xr
        except ImportError:
            raise ImportError("SweepResult.to_xarray() needs xarray: pip install xarray") from None
        shape = self.shape
        dims = [k for k, _ in self._axes]
        coords = {k: np.asarray(v) for k, v in self._axes}
        variables = {}
        for name in self._columns:
            if name in coords:
                continue
            column = self[name]
            if isinstance(column, np.ma.MaskedArray):
                column = column.astype(np.float64).filled(np.nan)
            variables[name] = (dims, np.asarray(column).reshape(shape))
        return xr.Dataset(variables, coords=coords)

    def __repr__(self) -> str:
        axes = ", ".join(f"{k}: {len(v)}" for k, v in self._axes)
        return f"SweepResult({len(self)} points; axes {axes}; {len(self._columns)} columns)"
