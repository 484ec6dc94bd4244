"""flexrock: a slender elastic body rocking on a rigid floor (Ichinose 1986), in Python.

The package runs the same solver as the ``flexrock`` command line, in your process, and returns
numpy arrays; its numbers equal the command line's to the last digit. A model is a model file
(TOML) or a dict of its tables; a ground motion may be a model-file excitation, a record file
or numpy arrays; a sweep's table goes to numpy, pandas or xarray.

Examples
--------
>>> import numpy as np
>>> import flexrock
>>> model = flexrock.Model.from_file("models/ichinose1986.toml")    # or Model.from_dict({...})
>>> model.set("excitation.amplitude", 3.0)                          # m/s^2
>>> result = flexrock.simulate(model)                               # numpy arrays: result.t, .q
>>> gm = flexrock.GroundMotion(0.5 * np.sin(np.linspace(0, 20, 1001)), dt=0.01, units="g")
>>> shaken = flexrock.simulate(model.with_ground_motion(gm))
>>> grid = flexrock.sweep(model, {"excitation.period": [0.5, 1.0], "excitation.amplitude": [2, 4]})
>>> frame = grid.to_pandas()                                        # one row per point
>>> data = grid.to_xarray()                                         # one dimension per axis

Errors are `FlexrockError` (a ValueError) whose message names the model key or the Python
argument, the value and the rule.
"""

from __future__ import annotations

from typing import Mapping, Optional, Sequence, Tuple, Union

from . import _native
from ._native import FlexrockError, GroundMotion, Model, Result, __version__
from ._sweep import SweepResult

__all__ = [
    "FlexrockError",
    "GroundMotion",
    "Model",
    "Result",
    "SweepResult",
    "__version__",
    "props",
    "read_record",
    "simulate",
    "sweep",
]

Value = Union[bool, int, float, str]


def props(model: Model) -> dict:
    """The body as understood and its derived constants.

    Parameters
    ----------
    model : Model
        The model.

    Returns
    -------
    dict
        The JSON of ``flexrock props --json``: ``body``, ``constants`` (period, s_n, ...).

    Examples
    --------
    >>> flexrock.props(flexrock.Model.from_file("models/ichinose1986.toml"))["constants"]["period"]
    1.55...
    """
    return _native.props(model)


def simulate(
    model: Model,
    method: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    duration: Optional[float] = None,
    output_dt: Optional[float] = None,
) -> Result:
    """Solves a model: the time history, the events, the rocking episodes and the summary.

    Parameters
    ----------
    model : Model
        The model (with its settings, and its ground motion if given as arrays).
    method : str, optional
        The solver, for this run (replaces the model's ``solver.method``): "bdf", "tsit45",
        "newmark", ...
    rtol, atol : float, optional
        Tolerances of an adaptive solver (``solver.rtol``, ``solver.atol``, m).
    duration : float, optional
        Simulated time, s (``simulation.duration``).
    output_dt : float, optional
        Spacing of the sampled history, s (``solver.output_dt``).

    Returns
    -------
    Result
        numpy arrays ``t``, ``q``, ``qdot``, ``s``, ``r``, ``mode``, ``floor_acc``, ``F`` and the
        energy books (the columns of history.csv); ``events``, ``episodes`` (lists of dicts) and
        ``summary`` (the dict of summary.json); ``to_pandas()``.

    Raises
    ------
    FlexrockError
        On a bad argument (the message names it and the key it sets:
        ``rtol (sets solver.rtol) = -1: ...``) or a model that cannot be solved.

    Examples
    --------
    >>> result = flexrock.simulate(model, method="tsit45", rtol=1e-8)
    >>> result.summary["n_uplift"]
    """
    return _native.simulate(
        model, method=method, rtol=rtol, atol=atol, duration=duration, output_dt=output_dt
    )


def read_record(
    path,
    format: Optional[str] = None,
    dt: Optional[float] = None,
    units: Optional[str] = None,
) -> GroundMotion:
    """Reads a ground-motion record file into a `GroundMotion`.

    Parameters
    ----------
    path : str or os.PathLike
        The record file, relative to the current directory.
    format : {"peer-at2", "csv"}, optional
        The file's layout; by default from the extension (.AT2, .csv).
    dt : float, optional
        Sampling interval, s: required for a one-column CSV file; otherwise it must agree with
        the file's.
    units : {"g", "m/s2", "cm/s2"}, optional
        The units of the file's values; "g" by default for AT2 files, required for CSV.

    Returns
    -------
    GroundMotion
        ``dt``, ``acceleration`` (m/s^2, numpy), ``units`` and ``source`` (the path).

    Raises
    ------
    FlexrockError
        A file that cannot be read or breaks the rules of its format (the message names the
        file and line), or a bad ``format`` or ``units``.

    Examples
    --------
    >>> gm = flexrock.read_record("validation/records/elCentro.AT2")
    >>> gm.dt, len(gm), gm.units
    (0.02, 1559, 'g')
    """
    return _native.read_record(path, format=format, dt=dt, units=units)


def sweep(
    model: Model,
    axes: Mapping[str, Sequence[Value]],
    find_min: Optional[Tuple[str, float, float]] = None,
    scan: Optional[int] = None,
    tol: Optional[float] = None,
) -> SweepResult:
    """A parametric study: every combination of the axes' values, on every core.

    Parameters
    ----------
    model : Model
        The model (its settings apply at every point). A model with a ground motion given as
        arrays cannot be swept yet: write the samples to a record file.
    axes : mapping of str to sequence
        Model-file keys and their values, e.g. ``{"excitation.period": [0.5, 1.0]}``; the last
        axis varies fastest.
    find_min : (key, lo, hi), optional
        At each point, search [lo, hi] for the smallest value of ``key`` that overturns the body
        (column ``min_overturning``; NaN where nothing in the interval overturns).
    scan : int, optional
        Values scanned before the bisection of ``find_min``.
    tol : float, optional
        Tolerance of the bisection of ``find_min``, in the key's unit.

    Returns
    -------
    SweepResult
        Typed columns by name (``result["overturned"]`` is a bool array), ``shape`` (the axes'
        lengths), ``to_pandas()``, ``to_xarray()`` and ``to_dict()``.

    Raises
    ------
    FlexrockError
        A bad key or value (the message names it).

    Examples
    --------
    >>> grid = flexrock.sweep(model, {"excitation.period": [0.5, 1.0],
    ...                               "excitation.amplitude": [2.0, 4.0]})
    >>> grid.to_xarray()["max_abs_q_over_B"].sel({"excitation.period": 1.0})
    """
    if model.ground_motion is not None:
        raise FlexrockError(
            "sweep: the model's ground motion was given as arrays; a sweep reads its record from "
            "a file: write the samples to a CSV record file and set excitation.path to it"
        )
    table = _native.sweep(model, dict(axes), find_min=find_min, scan=scan, tol=tol)
    if isinstance(table, dict) and "columns" in table and "kinds" in table:
        return SweepResult(table)
    return SweepResult(_table_of_flat_columns(table, axes))


def _table_of_flat_columns(flat, axes) -> dict:
    """The sweep table of the compiled sweep's former flat dict of columns (numbers as float64
    arrays, text as lists of str), until the compiled sweep returns the typed table itself."""
    import numpy as np

    ints = {"point", "n_uplift", "n_landing", "steps", "rhs_evaluations"}
    columns, kinds, values = [], [], []
    for name, column in flat.items():
        if isinstance(column, list):
            if all(v in ("true", "false", "") for v in column) and any(column):
                kinds.append("bool")
                values.append([None if v == "" else v == "true" for v in column])
            else:
                kinds.append("str")
                values.append([None if v == "" else v for v in column])
        else:
            array = np.asarray(column)
            if name in ints or array.dtype.kind in "iu":
                kinds.append("int")
                values.append([None if np.isnan(v) else int(v) for v in array.astype(float)])
            else:
                kinds.append("float")
                values.append([None if np.isnan(v) else float(v) for v in array])
        columns.append(name)
    typed_axes = []
    for key, vals in axes.items():
        vals = list(vals)
        numeric = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in vals)
        typed_axes.append((key, [float(v) for v in vals] if numeric else [str(v) for v in vals]))
    return {"columns": columns, "kinds": kinds, "values": values, "axes": typed_axes}
