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
>>> study = flexrock.fragility(model, "records/")                   # fragility over a suite

Errors are `FlexrockError` (a ValueError) whose message names the model key or the Python
argument, the value and the rule.
"""

from __future__ import annotations

from typing import Mapping, Optional, Sequence, Tuple, Union

from . import _native
from ._native import FlexrockError, GroundMotion, Model, Result, RowResult, __version__
from ._fragility import FragilityResult
from ._records import Records
from ._sweep import SweepResult


def __getattr__(name: str):
    # flexrock.figures needs matplotlib (the [figures] extra): imported on first use only.
    if name == "figures":
        import importlib

        return importlib.import_module(".figures", __name__)
    raise AttributeError(f"module 'flexrock' has no attribute {name!r}")

__all__ = [
    "FlexrockError",
    "FragilityResult",
    "GroundMotion",
    "Model",
    "Records",
    "Result",
    "RowResult",
    "SweepResult",
    "__version__",
    "compare",
    "converge",
    "fem_check",
    "fit_capacities",
    "fit_stripes",
    "fragility",
    "intensity_measures",
    "props",
    "read_record",
    "response_spectrum",
    "rigid_block",
    "simulate",
    "simulate_row",
    "sweep",
]

Value = Union[bool, int, float, str]

FlexrockError.__doc__ = """An error of flexrock: a bad model key, value, argument or file.

A `ValueError`. The message names the model-file key (``excitation.amplitude``) or the Python
argument (``acceleration[17]``, ``rtol (sets solver.rtol)``), the value and the rule it breaks,
and where there is one, the closest known name (``did you mean ...``).

Examples
--------
>>> try:
...     model.set("excitation.amplitud", 3.0)
... except flexrock.FlexrockError as e:
...     print(e)
"""

Model.__doc__ = """A model: a model file (or its text, or a dict of its tables) and the keys set on it.

Build one with `Model.from_file`, `Model.from_toml` or `Model.from_dict`; every constructor and
`set` validates the model by the rules of the model file.

Parameters
----------
(none: use the static constructors)
    ``Model.from_file(path)``: a model file; its record paths are relative to its directory.
    ``Model.from_toml(text)``: the text of a model file; record paths relative to the current
    directory. ``Model.from_dict(d)``: the file's tables as a nested dict,
    ``{"body": {...}, "excitation": {...}, "solver": {...}}``; record paths relative to the
    current directory.

Methods
-------
set(key, value)
    Sets a model-file key (``"excitation.amplitude"``, ``"solver.method"``); a record path is
    relative to the current directory. Raises FlexrockError naming the key on a bad key or value
    (TypeError for a value that is not a bool, a number or a str), and leaves the model as it
    was. An int beyond 64 bits is the nearest float; one beyond the largest float is refused.
update(settings)
    Sets several keys at once, ``{"excitation.path": ..., "excitation.units": ...}``, checked
    together (keys that only make sense together, such as a record file and its units); on an
    error the model stays as it was.
get(key)
    The value in effect: set with `set`, else the file's, else the default the core uses where it
    has one, else None. An unknown key raises FlexrockError naming it ("did you mean ...").
to_dict(record_path=None), to_toml(record_path=None)
    The model file with the settings applied (record paths relative to the current directory):
    ``Model.from_dict(m.to_dict())`` and ``Model.from_toml(m.to_toml())`` solve to the same
    numbers, bit for bit. For a model with a ground motion from arrays, ``record_path`` names
    the CSV record file ``m.ground_motion.to_csv(record_path)`` wrote (checked to hold exactly
    its samples).
with_ground_motion(ground_motion)
    A new model whose ``[excitation]`` is the `GroundMotion` (``kind = "record"``); the
    model's other tables and settings stay, its ``excitation.*`` settings are dropped. The record
    keys ``excitation.scale``, ``start``, ``end`` and ``tail`` may then be set as for a record
    file; ``simulation.duration``, when the model gives one, still applies (else the record's
    length plus the tail).
copy.copy, copy.deepcopy, pickle
    A model of its own with the same file, text, settings and ground motion. A pickled model
    carries its file's name and text: unpickled, it reads the file again and refuses one whose
    text has changed (as ``set`` does), so ``multiprocessing`` sends a model to other processes.
    The functions solve a model as it stands when they start: another thread may set keys on
    it meanwhile.

Returns
-------
Model
    The constructors return a validated model; ``with_ground_motion`` a new one.

Raises
------
FlexrockError
    A model that breaks a rule of the model file (the message names the key, or its place in
    a dict: ``d["body"]["height"] = -1: ...``).
TypeError
    A value that is not a bool, a number or a str; a dict's section that is not a dict.

Examples
--------
>>> model = flexrock.Model.from_dict({
...     "body": {"height": 4.0, "width": 0.7, "density": 600.0, "youngs_modulus": 5e6},
...     "excitation": {"kind": "paper-sine", "amplitude": 2.5, "period": 1.0, "ramp": 1.0},
...     "simulation": {"duration": 6.0}})
>>> model.set("excitation.amplitude", 3.0)
>>> model.get("excitation.amplitude"), model.get("body.gravity")
(3.0, 9.81)
>>> text = model.to_toml()
"""

GroundMotion.__doc__ = """A floor acceleration record sampled at a uniform interval, from arrays.

Checked by the rules and limits of a record file; a model solved under it
(`Model.with_ground_motion`) uses the core's recorded motion, linear between samples, so its
numbers equal those of a record file with the same samples.

Parameters
----------
acceleration : array_like of float, 1-D
    The samples, first at t = 0, in `units`: finite, at least 2.
dt : float, optional
    Sampling interval, s: at least 1e-5 s. Give `dt` or `time`.
time : array_like of float, optional (keyword)
    The sample times, s: from 0, uniformly spaced to 1e-6 relative (as a CSV record's time
    column); dt is their mean step.
units : {"g", "m/s2", "cm/s2"} (keyword, required)
    The units of `acceleration`, as ``excitation.units`` names them (g is standard gravity,
    9.80665 m/s^2).
source : str, optional (keyword)
    A name for tables and messages (default "arrays").

Returns
-------
GroundMotion
    Attributes ``dt`` (s), ``acceleration`` (m/s^2, numpy), ``time`` (s, numpy), ``units``,
    ``source``, ``duration`` (s), and ``len()``; ``to_csv(path)`` writes the samples, as given,
    to a one-column CSV record file (``read_record(path, dt=gm.dt, units=gm.units)`` reads them
    back exactly). A GroundMotion pickles with its samples.

Raises
------
FlexrockError
    A value that breaks a rule, named by its argument: ``acceleration[17] = NaN: ...``,
    ``dt = -1: must be > 0 s``, ``time[3] = 0.035: the times must be uniformly spaced ...``.
    More samples than a record may hold (33554432) are refused from the array's shape, before
    any is copied. A peak beyond 20 g is refused when a model takes the motion.

Examples
--------
>>> t = np.arange(0, 10, 0.01)
>>> gm = flexrock.GroundMotion(0.3 * np.sin(2 * np.pi * t), dt=0.01, units="g")
>>> shaken = flexrock.simulate(model.with_ground_motion(gm))
"""

Result.__doc__ = """The solution of `simulate`.

Attributes
----------
t, q, qdot, s, r, floor_acc, F, energy_residual, work_input, work_damping : numpy.ndarray
    The columns of history.csv (s, m, m/s, m, m, m/s^2, N, J, J, J).
mode : numpy.ndarray of str
    The mode at each sample.
events : list of dict
    The event log (events.csv's columns).
episodes : list of dict
    The rocking episodes (episodes.csv's columns; None where empty).
summary : dict
    The keys of summary.json.

Methods
-------
to_pandas()
    The history as a pandas DataFrame (ImportError without pandas).

Examples
--------
>>> result = flexrock.simulate(model)
>>> result.q.max(), result.summary["n_uplift"]
"""

RowResult.__doc__ = """The solution of `simulate_row`: a row of columns that strike each other.

Attributes
----------
columns : list of Result
    Each column's solution, left to right (counted from 0): its history as numpy arrays, its
    events (impacts among them, kind "impact") and episodes; its ``summary`` is the column's
    entry of the row's summary.
impacts : list of dict
    One dict per contact struck, with impacts.csv's columns (``t`` in s, ``impulse`` in N s,
    velocities in m/s, ``instant_energy_lost`` in J).
contacts : Records
    Every contact at every sampled instant, with contacts.csv's columns (``force`` and
    ``friction_force`` None under the impact law): a sequence of dicts kept as numpy columns.
summary : dict
    The keys of the row's summary.json.

Examples
--------
>>> row = flexrock.simulate_row("models/row-pair.toml")
>>> len(row.columns), len(row.impacts), row.impacts[0]["impulse"]
"""


def simulate_row(path, duration: Optional[float] = None) -> RowResult:
    """Solves a row of columns from its model file, by the exact method.

    A row model file has a ``[row]`` table (``gaps``, ``restitution``), one ``[[column]]`` table
    per column (the keys of ``[body]`` and ``q0``, ``qdot0``), and the ``[excitation]`` all
    columns stand on (the book's chapter "A row of columns").

    Parameters
    ----------
    path : str or path-like
        The row model file; its record paths are relative to its directory.
    duration : float, optional
        Simulated time, s (replaces ``simulation.duration``).

    Returns
    -------
    RowResult
        ``columns`` (a `Result` per column), ``impacts`` (list of dicts) and ``summary``.

    Raises
    ------
    FlexrockError
        On a bad file or argument (the message names the key, e.g. ``column[1].width``, or
        ``duration (sets simulation.duration)``), or a row that cannot be solved.

    Examples
    --------
    >>> row = flexrock.simulate_row("models/row-pair.toml")
    >>> [c.summary["n_impact"] for c in row.columns]
    """
    return _native.simulate_row(path, duration)


def rigid_block(
    model: Model,
    form: Optional[str] = None,
    overturning: Optional[str] = None,
    restitution: Optional[float] = None,
    find_min: Optional[Tuple[str, float, float]] = None,
    scan: Optional[int] = None,
    tol: Optional[float] = None,
) -> dict:
    """Housner's rigid block of the model's body, alone on the model's floor.

    The block has the body's height, width and gravity; the floor moves as the model's
    ``[excitation]`` says, horizontally and, with ``[excitation.vertical]``, vertically (gravity
    is then g + a_v(t) in the block's equation, its uplift acceleration and its pull towards the
    floor). A vertical motion that reaches -g is refused.

    Parameters
    ----------
    model : Model
        The model: its body's geometry and gravity, its floor motions and duration.
    form : str, optional
        ``"small-angle"`` (the default) or ``"full"`` (Housner's equation).
    overturning : str, optional
        ``"reaches-limit"`` (the default) or ``"cannot-return"``.
    restitution : float, optional
        The block's own coefficient of restitution, in (0, 1); Housner's by default.
    find_min : (key, lo, hi), optional
        Also search the smallest value of a model-file key in [lo, hi] that overturns the block
        (a scan, then bisection of the first transition, as `sweep`'s ``find_min``); each value
        a fresh model. The result goes under ``find_min`` (``min_overturning``, ``safe_below``,
        ``bands``...).
    scan : int, optional
        Values scanned before the bisection (100).
    tol : float, optional
        Width of the final bracket, in the key's unit (1e-4 of hi - lo).

    Returns
    -------
    dict
        The command line's rigid summary.json (``first_uplift_s``, ``overturned``,
        ``t_overturn_s``, ``max_abs_q_m``, the block's numbers under ``block``...), with the events
        (``t_s``, ``event``, ``q_m``, ``qdot_before_m_s``, ``qdot_after_m_s``, ``to``) under
        ``events``.

    Examples
    --------
    >>> m = flexrock.Model.from_file("models/pulse-map.toml")
    >>> m.set("excitation.vertical.ratio", 0.5)
    >>> flexrock.rigid_block(m, form="full")["overturned"]
    False
    """
    return _native.rigid_block(model, form, overturning, restitution, find_min, scan, tol)


def props(model: Model) -> dict:
    """The body as understood and its derived constants.

    Parameters
    ----------
    model : Model
        The model.

    Returns
    -------
    dict
        The JSON the command line's props command writes: ``body``, ``constants`` (period, s_n, ...).

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
        The solver, for this run (replaces the model's ``solver.method``): "exact" (the
        closed-form solution, the default of a model that names no method and no tolerance;
        ``summary["error_estimate"]`` then holds its own error on each event time and peak),
        "bdf", "esdirk34", "tr-bdf2", "tsit45" or "newmark".
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
    KeyboardInterrupt
        On Ctrl-C, at once; the run itself finishes in the background and is thrown away.

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
    format : {"peer-at2", "csv", "text", "cosmos", "esm"}, optional
        The file's layout; by default from the extension (.AT2, .csv, .txt, .dat, .V1, .V2,
        .ASC) and the first line.
    dt : float, optional
        Sampling interval, s: required for a one-column CSV or text file; otherwise it must
        agree with the file's.
    units : {"g", "m/s2", "cm/s2"}, optional
        The units of the file's values, for a file that does not say them (a CSV file without
        a unit column); one that contradicts the file's header is refused.

    Returns
    -------
    GroundMotion
        ``dt``, ``acceleration`` (m/s^2, numpy), ``units``, ``source`` (the path),
        ``metadata`` (a dict: ``format``, ``units``, ``event``, ``date``, ``station``,
        ``component``, ``magnitude``, ``distance_km``, None where the file gives none) and
        ``label`` (event, station and component, for a legend).

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
    rigid_form: Optional[str] = None,
    rigid_overturning: Optional[str] = None,
    rigid_restitution: Optional[float] = None,
) -> SweepResult:
    """A parametric study: every combination of the axes' values, on every core.

    Parameters
    ----------
    model : Model
        The model (its settings, and its ground motion if given as arrays, apply at every
        point).
    axes : mapping of str to sequence
        Model-file keys and their values, e.g. ``{"excitation.period": [0.5, 1.0]}`` (a list,
        a tuple or a numpy array; a str is refused, not taken as its letters); the last axis
        varies fastest.
    find_min : (key, lo, hi), optional
        At each point, search [lo, hi] for the smallest value of ``key`` that overturns the body
        (column ``min_overturning``; NaN where nothing in the interval overturns).
    scan : int, optional
        Values scanned before the bisection of ``find_min``.
    tol : float, optional
        Tolerance of the bisection of ``find_min``, in the key's unit.
    rigid_form : {"small-angle", "full"}, optional
        The equation of Housner's rigid block searched beside the body by ``find_min``: the
        small-angle one (the default) or the full one, which adds a ``rigid_form`` column.
    rigid_overturning : {"reaches-limit", "cannot-return"}, optional
        When that block counts as overturned: when its tilt reaches its limit (the default), or
        only once it cannot come back, the rule of the rocking literature's minimum overturning
        accelerations; ``"cannot-return"`` adds a ``rigid_overturning`` column.
    rigid_restitution : float, optional
        That block's own coefficient of restitution (strictly between 0 and 1) instead of
        Housner's; adds a
        ``rigid_restitution`` column.

    Returns
    -------
    SweepResult
        Typed columns by name (``result["overturned"]`` is a bool array), ``shape`` (the axes'
        lengths), ``to_pandas()``, ``to_xarray()`` and ``to_dict()``.

    Raises
    ------
    FlexrockError
        A bad key or value (the message names it), or a table beyond the 256 MiB a sweep in
        Python may hold (about 1.3 million points of a single body's sweep over two axes),
        refused before any point is computed; the command line's sweep writes its table to
        disk instead.
    TypeError
        An axis that is not a sequence of values, or a value that is not a bool, a number or
        a str.
    MemoryError
        A table the process has no memory for.
    KeyboardInterrupt
        On Ctrl-C, at once: no further point is started.

    Examples
    --------
    >>> grid = flexrock.sweep(model, {"excitation.period": [0.5, 1.0],
    ...                               "excitation.amplitude": [2.0, 4.0]})
    >>> grid.to_xarray()["max_abs_q_over_B"].sel({"excitation.period": 1.0})
    """
    return SweepResult(
        _native.sweep(
            model,
            dict(axes),
            find_min=find_min,
            scan=scan,
            tol=tol,
            rigid_form=rigid_form,
            rigid_overturning=rigid_overturning,
            rigid_restitution=rigid_restitution,
        )
    )


def fragility(
    model: Model,
    records,
    im: str = "pga",
    period: Optional[float] = None,
    scale: Tuple[float, float] = (0.1, 5.0),
    scan: Optional[int] = None,
    tol: Optional[float] = None,
    bootstrap: int = 1000,
    seed: int = 1,
) -> FragilityResult:
    """A fragility function of overturning over a suite of records, as ``flexrock fragility``.

    Incremental dynamic analysis: for each record, the smallest ``excitation.scale`` in
    ``scale`` that overturns the body (the sweep's minimum search), expressed in the intensity
    measure ``im``; a lognormal fit of these capacities (a record that does not overturn up to
    the top of the range is censored there and enters by its likelihood) and bootstrap
    intervals over records. The numbers equal the command's with the same arguments; nothing
    is written to disk.

    Parameters
    ----------
    model : Model
        A model with a record excitation (``kind = "record"``); its settings apply to every
        record.
    records : str or path
        The suite: a directory of record files, a list file (one path a line) or a file
        pattern such as ``"suite/*.AT2"`` (relative to the current directory).
    im : {"pga", "pgv", "pgd", "arias", "cav", "sa"}
        The intensity measure: pga (g), pgv (m/s), pgd (m), arias (m/s), cav (m/s), sa
        (Sa(T, 5 %), g).
    period : float, optional
        The period T of Sa, s (``im="sa"`` only) [default: the body's pre-uplift period].
    scale : (lo, hi)
        The range of ``excitation.scale`` searched, lo above 0.
    scan : int, optional
        Scales scanned before the bisection [default: 100].
    tol : float, optional
        Width of the final bracket, in scale [default: (hi - lo)/1e4].
    bootstrap : int
        Resamples over records for the 5-95 % intervals (0: none; 1 is refused).
    seed : int
        Seed of the bootstrap's generator (SplitMix64).

    Returns
    -------
    FragilityResult
        ``theta``, ``beta``, their intervals, each record's capacity (``result["capacity"]``,
        ``result["censored"]``, ``result["label"]``), ``to_pandas()``, and the whole summary.

    Raises
    ------
    FlexrockError
        A bad argument (named), a record that is not a record, a record whose search failed,
        or capacities that fix no fit (fewer than 2 observed, or all equal).
    KeyboardInterrupt
        On Ctrl-C, at once: no further record is started.

    Examples
    --------
    >>> model = flexrock.Model.from_file("models/elcentro1940.toml")
    >>> study = flexrock.fragility(model, "validation/records/records.list", scale=(0.1, 20))
    >>> study.theta, study.beta, study.to_pandas()[["label", "capacity", "censored"]]
    """
    import os

    return FragilityResult.from_json(
        _native.fragility(
            model, os.fspath(records), im, period, (float(scale[0]), float(scale[1])), scan,
            tol, bootstrap, seed,
        )
    )


def fit_capacities(capacity, censored=None) -> dict:
    """The lognormal fit of capacities, by the code ``flexrock fragility`` uses.

    Without a censored capacity, ln theta is the mean of ln c and beta the standard deviation
    of ln c with the divisor n (the maximum likelihood estimate; ``beta_unbiased`` has the
    divisor n - 1). With any, theta and beta maximise the likelihood with censoring: a censored
    capacity lies above its value and enters as 1 - Phi(z).

    Parameters
    ----------
    capacity : sequence of float
        Each record's capacity (the intensity at which it reached the damage state), > 0.
    censored : sequence of bool, optional
        True where the record did not reach it up to ``capacity`` [default: none censored].

    Returns
    -------
    dict
        ``{"theta", "beta", "beta_unbiased" (None with censoring), "method" ("moments" or
        "censored-mle"), "observed", "censored"}``.

    Raises
    ------
    FlexrockError
        A capacity that is not a positive number, fewer than 2 observed capacities, or
        observed capacities all equal.

    Examples
    --------
    >>> flexrock.fit_capacities([0.3, 0.5, 0.8, 1.2], censored=[False, False, False, True])
    """
    import numpy as np

    values = np.asarray(capacity, dtype=np.float64).ravel()
    flags = (np.zeros(values.shape, dtype=bool) if censored is None
             else np.asarray(censored, dtype=bool).ravel())
    return _native.fit_capacities(values.tolist(), flags.tolist())


def fit_stripes(levels, records, damaged) -> dict:
    """The lognormal fit of counts at intensity levels (multiple-stripe analysis), by the
    maximum of the binomial likelihood (Baker 2015), the core's code.

    Parameters
    ----------
    levels : sequence of float
        The intensity levels, > 0.
    records : sequence of int
        Records run at each level.
    damaged : sequence of int
        Of them, those that reached the damage state.

    Returns
    -------
    dict
        ``{"theta", "beta", "method": "stripes-mle"}``.

    Raises
    ------
    FlexrockError
        Counts that fix no finite maximum: no record damaged, all damaged, or the damaged
        levels all above the undamaged ones with nothing between.

    Examples
    --------
    >>> flexrock.fit_stripes([0.1, 0.2, 0.4], records=[20, 20, 20], damaged=[2, 9, 17])
    """
    import numpy as np

    return _native.fit_stripes(
        np.asarray(levels, dtype=np.float64).ravel().tolist(),
        np.asarray(records).ravel().tolist(),
        np.asarray(damaged).ravel().tolist(),
    )


def compare(
    model: Model,
    dt: Optional[float] = None,
    variant: Optional[str] = None,
    reference_rtol: Optional[float] = None,
) -> dict:
    """The model solved by the paper's Newmark method and by the exact solution, compared.

    The same computation as ``flexrock compare``: events matched one to one (a missed or an
    extra event is reported, never paired with a neighbour), peaks, and the differences of q on
    the output grid.

    Parameters
    ----------
    model : Model
        The model; its ``solver.dt`` (if its method is Newmark) is the default step.
    dt : float, optional
        Newmark's time step, s.
    variant : {"compensate", "substep"}, optional
        How Newmark treats a step that crosses an event.
    reference_rtol : float, optional
        Relative tolerance of an adaptive reference (the model's adaptive method, BDF when it
        names another). Default None: the reference is the exact solution, so the
        differences are Newmark's true errors.

    Returns
    -------
    dict
        ``reference`` and ``newmark`` (the two solvers, as labels), ``comparison`` (matched
        events with their time differences, peaks, grid differences) and ``grid`` (a
        `Records` of rows: t, q of both, their difference).

    Raises
    ------
    FlexrockError
        A bad argument (the message names it, e.g. ``dt (sets solver.dt) = -1``).

    Examples
    --------
    >>> c = flexrock.compare(model, dt=0.005)
    >>> c["comparison"]["events"]["max_abs_time_difference"]
    """
    return _native.compare(model, dt=dt, variant=variant, reference_rtol=reference_rtol)


def converge(
    model: Model,
    dts: Optional[Sequence[float]] = None,
    rtols: Optional[Sequence[float]] = None,
    reference_rtol: Optional[float] = None,
) -> dict:
    """A convergence study: Newmark's steps and the adaptive tolerances against one reference.

    The same computation as ``flexrock converge``: each case's errors in event times, peaks and
    q on the grid, its work (steps, right-hand-side evaluations), and the fitted slopes (Newmark's
    order against dt; each adaptive method's error against work).

    Parameters
    ----------
    model : Model
        The model.
    dts : sequence of float, optional
        Newmark steps, s (default: the command line's list).
    rtols : sequence of float, optional
        Tolerances of the adaptive methods (default: 1e-3 to 1e-11).
    reference_rtol : float, optional
        Relative tolerance of an adaptive reference (the model's adaptive method, BDF when it
        names another); it must be below every tolerance of ``rtols``. Default None: the
        reference is the exact solution, so the errors are true errors.

    Returns
    -------
    dict
        ``reference`` (its solver), ``output_dt``, ``cases`` (one dict per case, with the
        columns of convergence.csv; None where a failed case has no measurement) and
        ``slopes``.

    Raises
    ------
    FlexrockError
        A bad argument (the message names it).

    Examples
    --------
    >>> study = flexrock.converge(model, dts=[0.01, 0.005], rtols=[1e-6, 1e-8])
    >>> [s["slope"] for s in study["slopes"]]
    """
    return _native.converge(
        model,
        dts=None if dts is None else list(dts),
        rtols=None if rtols is None else list(rtols),
        reference_rtol=reference_rtol,
    )


def fem_check(
    model: Model,
    nx: Optional[int] = None,
    ny: Optional[int] = None,
    dt: Optional[float] = None,
    scheme: Optional[str] = None,
) -> dict:
    """The plane-stress finite element model of the body, compared with the one-mode model.

    The same computation as ``flexrock fem``: the body meshed with ``nx`` x ``ny`` elements on a
    floor it may lift off, under the model's floor motion, from rest.

    Parameters
    ----------
    model : Model
        The model (its ``[fem]`` keys are the defaults of the arguments below).
    nx, ny : int, optional
        Elements across the width and up the height.
    dt : float, optional
        Time step, s.
    scheme : str, optional
        The time-stepping scheme, as the model file's ``fem.scheme`` names it.

    Returns
    -------
    dict
        ``comparison`` (quantities of both models side by side, uplift times), ``peaks``,
        ``uplifts`` (the finite element run's uplift episodes), ``history`` (a `Records` of
        the rows of fem_history.csv) and ``warnings``.

    Raises
    ------
    FlexrockError
        A bad argument (the message names it), or a mesh beyond the size limits.

    Examples
    --------
    >>> fem = flexrock.fem_check(model, nx=4, ny=16)
    >>> fem["peaks"]["max_q"]
    """
    return _native.fem_check(model, nx=nx, ny=ny, dt=dt, scheme=scheme)


def intensity_measures(motion, period: Optional[float] = None, damping: float = 0.05) -> dict:
    """A ground motion's intensity measures, computed exactly.

    The motion is the samples, linear between them, as flexrock applies it: PGA; PGV and PGD
    from the exact integrals from rest (peaks between samples included); the Arias intensity
    pi/(2 g) * integral of a^2 dt (g = 9.80665 m/s^2); CAV, integral of |a| dt; and Sa, the
    pseudo-acceleration omega^2 max |u| of the damped oscillator, u solved exactly (peak
    between samples included). No baseline correction and no filtering.

    Parameters
    ----------
    motion : GroundMotion or Model
        A GroundMotion, or a Model whose excitation is a record (its motion scaled and trimmed
        as the model applies it).
    period : float, optional
        The period of Sa, s; by default the body's pre-uplift period T for a Model, none (no
        Sa) for a GroundMotion.
    damping : float
        The damping ratio of Sa's oscillator (default 5 %).

    Returns
    -------
    dict
        ``pga`` (m/s^2), ``pga_g``, ``t_pga`` (s), ``pgv`` (m/s), ``t_pgv``, ``pgd`` (m),
        ``t_pgd``, ``arias`` (m/s), ``cav`` (m/s); with a period also ``sa`` (m/s^2), ``sa_g``,
        ``sd`` (m), ``t_sa`` (s), ``sa_at_samples`` (m/s^2, the peak over the samples alone),
        ``period`` and ``damping``.

    Examples
    --------
    >>> gm = flexrock.read_record("validation/records/elCentro.AT2")
    >>> flexrock.intensity_measures(gm, period=1.0)["sa_g"]
    """
    return _native.intensity_measures(motion, period=period, damping=damping)


def response_spectrum(motion, periods=None, damping: float = 0.05) -> dict:
    """The pseudo-acceleration response spectrum of a ground motion (see `intensity_measures`).

    Parameters
    ----------
    motion : GroundMotion or Model
        As for `intensity_measures`.
    periods : sequence of float, optional
        Periods, s (default: 0.01 s to 10 s, 20 a decade on a logarithmic scale).
    damping : float
        The damping ratio of the oscillators (default 5 %).

    Returns
    -------
    dict of numpy.ndarray
        ``period`` (s), ``sa`` (m/s^2), ``sd`` (m), ``t_peak`` (s), ``sa_at_samples`` (m/s^2).

    Examples
    --------
    >>> spectrum = flexrock.response_spectrum(flexrock.read_record("validation/records/elCentro.AT2"))
    >>> spectrum["sa"].max() / 9.80665
    """
    return _native.response_spectrum(motion, periods=periods, damping=damping)
