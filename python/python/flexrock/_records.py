"""`Records`: the rows of a long table (a row's contacts, a comparison's grid, the finite element
history) kept as typed numpy columns, read as a sequence of dicts or by column."""

from __future__ import annotations

from typing import Any, Dict, Iterator, List, Union

import numpy as np

from ._sweep import _frame, _typed


class Records:
    """Rows of a table, one dict per row, kept as typed numpy columns.

    A sequence: ``len(records)``, ``records[i]`` (a dict of the row's values, None where a
    value is missing), ``records[i:j]`` (a list of such dicts) and iteration over the rows.
    ``records["name"]`` is a whole column as a numpy array (float64 with NaN where missing; an
    int or bool column with a missing value is a numpy masked array; text an object array).
    A list of dicts of a million rows takes about ten times the memory of its columns; ask
    for the columns (or ``to_pandas()``) when the table is long.

    Parameters
    ----------
    table : dict
        ``{"columns": [...], "kinds": [...], "values": [...], "missing": [...]}``, as the
        compiled functions return it. Users get Records from `simulate_row` (``contacts``),
        `compare` (``"grid"``) and `fem_check` (``"history"``) rather than building them.

    Examples
    --------
    >>> row = flexrock.simulate_row("models/row-friction.toml")
    >>> row.contacts[0]["state"], row.contacts["gap"].min()
    """

    def __init__(self, table: Dict[str, Any]):
        self._columns: List[str] = list(table["columns"])
        kinds = list(table["kinds"])
        values = list(table["values"])
        missing = list(table.get("missing") or [None] * len(values))
        if not (len(self._columns) == len(kinds) == len(values) == len(missing)):
            raise ValueError("a table needs one kind and one list of values per column")
        self._data = [_typed(k, v, m) for k, v, m in zip(kinds, values, missing)]
        self._kinds = kinds

    @property
    def columns(self) -> List[str]:
        """The column names, in the order of the table's CSV file."""
        return list(self._columns)

    def __len__(self) -> int:
        return len(self._data[0][0]) if self._data else 0

    def _row(self, i: int) -> Dict[str, Any]:
        row = {}
        for name, (array, mask) in zip(self._columns, self._data):
            if mask is not None and mask[i]:
                row[name] = None
            else:
                value = array[i]
                row[name] = value.item() if isinstance(value, np.generic) else value
        return row

    def __getitem__(self, key: Union[int, slice, str]) -> Any:
        if isinstance(key, str):
            try:
                i = self._columns.index(key)
            except ValueError:
                raise KeyError(f"{key!r} is not a column; columns: {self._columns}") from None
            array, mask = self._data[i]
            if mask is None:
                return array.copy()
            if self._kinds[i] == "float":
                return np.where(mask, np.nan, array)
            return np.ma.masked_array(array.copy(), mask=mask.copy())
        if isinstance(key, slice):
            return [self._row(i) for i in range(*key.indices(len(self)))]
        n = len(self)
        i = key.__index__()
        if not -n <= i < n:
            raise IndexError(f"row {key} of {n}")
        return self._row(i % n)

    def __iter__(self) -> Iterator[Dict[str, Any]]:
        return (self._row(i) for i in range(len(self)))

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Records):
            other = list(other)
        return isinstance(other, list) and list(self) == other

    __hash__ = None  # type: ignore[assignment]

    def to_dict(self) -> Dict[str, np.ndarray]:
        """The columns by name, as ``records["name"]`` gives them."""
        return {name: self[name] for name in self._columns}

    def to_pandas(self):
        """The table as a pandas DataFrame; an int or bool column with a missing value gets
        pandas' nullable dtype ("Int64", "boolean"), text "string".

        Raises
        ------
        ImportError
            Without pandas (``pip install pandas``).
        """
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Records.to_pandas() needs pandas: pip install pandas") from None
        return _frame(pd, self._columns, self._kinds, self._data)

    def __repr__(self) -> str:
        return f"Records({len(self)} rows; columns {', '.join(self._columns)})"
