"""`FragilityResult`: the summary of a fragility study (fragility.json) with its records as numpy
columns and pandas."""

from __future__ import annotations

import json
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from ._sweep import _frame, _typed

# The per-record columns: name, kind, and how each comes from a record of fragility.json.
_RECORD_COLUMNS = [
    ("path", "str", lambda r: r["path"]),
    ("label", "str", lambda r: r["label"]),
    ("im_unscaled", "float", lambda r: r["im_unscaled"]),
    ("min_overturning_scale", "float", lambda r: r["min_overturning_scale"]),
    ("capacity", "float", lambda r: r["capacity"]["value"]),
    ("censored", "bool", lambda r: r["capacity"]["kind"] == "censored"),
    ("overturning_bands", "str", lambda r: r["overturning_bands"]),
    ("n_bands", "int", lambda r: r["n_bands"]),
]


class FragilityResult:
    """The result of `flexrock.fragility`: the fit of overturning and each record's capacity.

    The numbers are those of ``flexrock fragility``'s fragility.json, which `summary` holds
    whole (the same keys).

    Attributes
    ----------
    theta, beta : float
        The fitted median (in the intensity measure's unit, `im_unit`) and dispersion (the
        maximum likelihood form, divisor n).
    beta_unbiased : float or None
        beta with the divisor n - 1 where no record is censored.
    method : str
        ``"moments"`` (no censored record) or ``"censored-mle"``.
    theta_interval, beta_interval : (float, float) or None
        The bootstrap's 5 and 95 % percentiles (None with ``bootstrap=0``).
    im, im_unit : str
        The intensity measure and its unit.
    warnings : list of str
        What the reader must know (too few records, censored records, failed resamples).

    Examples
    --------
    >>> study = flexrock.fragility(model, "validation/records/records.list", scale=(0.1, 20))
    >>> study.theta, study.beta, study.theta_interval
    >>> study.to_pandas()[["label", "capacity", "censored"]]
    """

    def __init__(self, summary: Dict[str, Any]):
        self.summary: Dict[str, Any] = summary
        fit = summary["fits"][0]
        self.theta: float = fit["theta"]
        self.beta: float = fit["beta"]
        self.beta_unbiased: Optional[float] = fit["beta_unbiased"]
        self.method: str = fit["method"]
        self.theta_interval = _interval(fit["theta_interval"])
        self.beta_interval = _interval(fit["beta_interval"])
        self.im: str = summary["im"]
        self.im_unit: str = summary["im_unit"]
        self.warnings: List[str] = list(summary["warnings"])
        records = summary["records"]
        self._columns = [name for name, _, _ in _RECORD_COLUMNS]
        self._kinds = [kind for _, kind, _ in _RECORD_COLUMNS]
        self._data = [_typed(kind, [get(r) for r in records]) for _, kind, get in _RECORD_COLUMNS]

    @classmethod
    def from_json(cls, text: str) -> "FragilityResult":
        """The result of a fragility.json written by ``flexrock fragility``."""
        return cls(json.loads(text))

    @property
    def columns(self) -> List[str]:
        """The per-record columns."""
        return list(self._columns)

    def __len__(self) -> int:
        return len(self.summary["records"])

    def __getitem__(self, name: str) -> np.ndarray:
        """One per-record column as a numpy array: ``capacity`` (float64, in `im_unit`),
        ``censored`` (bool: the capacity lies above the value), ``label`` (event, station and
        component where the record file gives them, else its name), ``path`` ...
        """
        try:
            array, _ = self._data[self._columns.index(name)]
        except ValueError:
            raise KeyError(f"{name!r}: no such column; the columns are {self._columns}") from None
        return array

    def to_pandas(self):
        """The records as a pandas DataFrame, one row per record, in the suite's order.

        Text columns are "string"; ``min_overturning_scale`` is NaN for a censored record.

        Raises
        ------
        ImportError
            Without pandas (``pip install pandas``).
        """
        try:
            import pandas as pd
        except ImportError:
            raise ImportError(
                "FragilityResult.to_pandas() needs pandas: pip install pandas"
            ) from None
        return _frame(pd, self._columns, self._kinds, self._data)

    def __repr__(self) -> str:
        return (
            f"FragilityResult({self.im}: theta = {self.theta:.4g} {self.im_unit}, "
            f"beta = {self.beta:.3g}, {self.method}; {len(self)} records, "
            f"{self.summary['fits'][0]['censored']} censored)"
        )


def _interval(value: Optional[Dict[str, float]]) -> Optional[Tuple[float, float]]:
    return None if value is None else (value["lo"], value["hi"])
