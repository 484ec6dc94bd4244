"""The Python API beyond the command line's: models as dicts, values in effect, ground motions
from arrays, typed sweep tables, the package's layout and documentation."""

import copy
import inspect
import pickle
import re
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import flexrock

ROOT = Path(__file__).resolve().parents[2]
MODEL = ROOT / "models" / "ichinose1986.toml"
RECORD_MODEL = ROOT / "models" / "elcentro1940.toml"
AT2 = ROOT / "validation" / "records" / "elCentro.AT2"
STANDARD_GRAVITY = 9.80665


def same_results(a, b):
    for name in ["t", "q", "qdot", "s", "r", "floor_acc", "F", "energy_residual"]:
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert list(a.mode) == list(b.mode)
    assert a.events == b.events
    for key in ["max_q", "min_q", "n_uplift", "n_landing", "overturned", "final_time"]:
        assert a.summary[key] == b.summary[key], key


def read_at2(path):
    """An AT2 file read here, independently of the core: NPTS and DT from line 4, then values."""
    lines = Path(path).read_text().splitlines()
    header = lines[3].upper()
    npts = int(re.search(r"NPTS\s*=\s*(\d+)", header).group(1))
    dt = float(re.search(r"DT\s*=\s*([0-9.Ee+-]+)", header).group(1))
    values = [float(v) for line in lines[4:] for v in line.split()]
    assert len(values) == npts
    return dt, np.array(values)


# Layout and documentation.

def test_the_compiled_module_is_private_and_the_package_documented():
    assert flexrock._native.__name__ == "flexrock._native"
    assert flexrock.__doc__ and "from_dict" in flexrock.__doc__ and "to_xarray" in flexrock.__doc__
    for name in flexrock.__all__:
        obj = getattr(flexrock, name)
        if name.startswith("__"):
            continue
        doc = inspect.getdoc(obj) or ""
        assert len(doc.splitlines()) > 3, name
        for section in ["Parameters", "Returns", "Examples"]:
            if inspect.isfunction(obj) or obj in (flexrock.Model, flexrock.GroundMotion):
                assert section in doc, (name, section)
    assert (Path(flexrock.__file__).parent / "py.typed").is_file()
    assert (Path(flexrock.__file__).parent / "_native.pyi").is_file()


def test_no_command_line_flag_in_the_documentation():
    for name in flexrock.__all__:
        obj = getattr(flexrock, name)
        docs = [inspect.getdoc(obj) or ""]
        docs += [inspect.getdoc(m) or "" for _, m in inspect.getmembers(obj) if callable(m)]
        for doc in docs:
            assert not re.search(r"(?<![\w-])--[a-z]", doc), (name, doc)


# Model as a dict, values in effect, the file written back.

def tables(path):
    tomllib = pytest.importorskip("tomllib")
    return tomllib.loads(Path(path).read_text())


def test_a_model_from_a_dict_equals_the_file():
    same_results(flexrock.simulate(flexrock.Model.from_dict(tables(MODEL))),
                 flexrock.simulate(flexrock.Model.from_file(MODEL)))
    with pytest.raises(flexrock.FlexrockError, match="amplitud"):
        d = tables(MODEL)
        d["excitation"]["amplitud"] = 1.0
        flexrock.Model.from_dict(d)
    with pytest.raises(TypeError, match=r'^d\["body"\]\["height"\] = \[1, 2\]: .* not list'):
        d = tables(MODEL)
        d["body"]["height"] = [1, 2]
        flexrock.Model.from_dict(d)


def test_get_gives_the_value_in_effect():
    file = tables(MODEL)
    model = flexrock.Model.from_file(MODEL)
    assert model.get("excitation.amplitude") == file["excitation"]["amplitude"]
    model.set("excitation.amplitude", 3.25)
    assert model.get("excitation.amplitude") == 3.25
    # Omitted keys: the core's defaults (the book's model-file reference), else None.
    defaults = [("body.gravity", 9.81), ("body.depth", 1.0), ("body.damping_ratio", 0.05),
                ("body.self_weight", "paper"), ("body.constants", "exact"), ("solver.method", "exact"),
                ("solver.rtol", 1e-10), ("solver.atol", 1e-12), ("solver.output_dt", 0.005),
                ("simulation.q0", 0.0)]
    omitted = 0
    for key, default in defaults:
        section, name = key.split(".")
        given = file.get(section, {}).get(name)
        omitted += given is None
        assert model.get(key) == (default if given is None else given), key
    assert omitted >= 1
    assert model.get("body.mass") is None
    with pytest.raises(flexrock.FlexrockError) as error:
        model.get("excitation.amplitud")
    assert "excitation.amplitud" in str(error.value)
    assert "did you mean excitation.amplitude" in str(error.value)
    with pytest.raises(flexrock.FlexrockError, match="section.name"):
        model.get("amplitude")


@pytest.mark.parametrize("path", [MODEL, RECORD_MODEL, ROOT / "models" / "pulse-map.toml"])
def test_to_toml_and_to_dict_give_the_same_model_back(path, monkeypatch):
    monkeypatch.chdir(ROOT)
    model = flexrock.Model.from_file(path)
    if path == MODEL:
        model.set("excitation.amplitude", 4)
        model.set("solver.method", "tsit45")
    else:
        model.set("simulation.duration", 3.0)
    expected = flexrock.simulate(model)
    text = model.to_toml()
    assert "excitation" in text
    same_results(flexrock.simulate(flexrock.Model.from_toml(text)), expected)
    same_results(flexrock.simulate(flexrock.Model.from_dict(model.to_dict())), expected)
    d = model.to_dict()
    if path == MODEL:
        assert d["excitation"]["amplitude"] == 4 and d["solver"]["method"] == "tsit45"
    if path == RECORD_MODEL:
        # Record paths relative to the current directory, as from_toml and from_dict read them.
        assert (ROOT / d["excitation"]["path"]).resolve() == AT2.resolve()


# Ground motion from arrays.

def test_a_ground_motion_from_a_record_files_samples_is_that_file():
    dt, values = read_at2(AT2)
    file_model = flexrock.Model.from_file(RECORD_MODEL)
    gm = flexrock.GroundMotion(values, dt=dt, units="g")
    assert gm.dt == 0.02 and len(gm) == 1559 and gm.units == "g"
    assert np.array_equal(gm.acceleration, values * STANDARD_GRAVITY)
    model = file_model.with_ground_motion(gm)
    assert model.get("excitation.kind") == "record"
    model.set("excitation.tail", tables(RECORD_MODEL)["excitation"]["tail"])
    same_results(flexrock.simulate(model), flexrock.simulate(file_model))
    # The same samples as times and m/s^2.
    again = flexrock.GroundMotion(gm.acceleration, time=np.arange(len(values)) * dt, units="m/s2")
    assert again.dt == dt
    assert np.array_equal(again.acceleration, gm.acceleration)
    # The file's own motion is untouched.
    assert file_model.ground_motion is None and model.ground_motion.source == "arrays"


def test_read_record_reads_what_the_model_file_reads(tmp_path):
    gm = flexrock.read_record(AT2)
    dt, values = read_at2(AT2)
    assert (gm.dt, gm.units, gm.source) == (dt, "g", str(AT2))
    assert np.array_equal(gm.acceleration, values * STANDARD_GRAVITY)
    file_model = flexrock.Model.from_file(RECORD_MODEL)
    model = file_model.with_ground_motion(gm)
    model.set("excitation.tail", 5.0)
    same_results(flexrock.simulate(model), flexrock.simulate(file_model))
    csv = tmp_path / "one.csv"
    csv.write_text("0.0\n0.5\n-0.25\n")
    with pytest.raises(flexrock.FlexrockError, match="^units = None: required for CSV"):
        flexrock.read_record(csv, dt=0.01)
    one = flexrock.read_record(csv, dt=0.01, units="cm/s2")
    assert list(one.acceleration) == [0.0, 0.005, -0.0025] and one.dt == 0.01
    with pytest.raises(flexrock.FlexrockError, match="nonexistent"):
        flexrock.read_record("nonexistent.AT2")


def test_a_sine_ground_motion_gives_the_floor_acceleration_it_was_given():
    # Between samples the floor acceleration is linear: at the samples it is the samples.
    dt = 0.01
    t = np.arange(301) * dt
    a = 2.0 * np.sin(2 * np.pi * t)
    model = flexrock.Model.from_file(MODEL).with_ground_motion(
        flexrock.GroundMotion(a, dt=dt, units="m/s2"))
    result = flexrock.simulate(model, duration=3.0, output_dt=dt)
    assert np.allclose(result.floor_acc, np.interp(result.t, t, a), rtol=0, atol=1e-12)
    on_grid = np.abs(result.t / dt - np.round(result.t / dt)) < 1e-9
    assert on_grid.sum() == len(t)
    assert np.allclose(result.floor_acc[on_grid], a, rtol=0, atol=1e-12)


@pytest.mark.parametrize("kwargs, message", [
    (dict(acceleration=[0.0, 1.0, float("nan")], dt=0.01, units="g"), r"^acceleration\[2\] = NaN: "),
    (dict(acceleration=[0.0, 1.0], dt=-1.0, units="g"), r"^dt = -1: must be > 0"),
    (dict(acceleration=[0.0, 1.0], dt=1e-7, units="g"), r"^dt = 1e-7: .*1e-5 s"),
    (dict(acceleration=[0.0], dt=0.01, units="g"), r"^acceleration = 1 sample: .*at least 2"),
    (dict(acceleration=[0.0, 1.0], dt=0.01, units="m/s^2"), r'^units = "m/s\^2": must be "g", "m/s2"'),
    (dict(acceleration=[0.0, 1.0, 2.0], time=[0.0, 0.1, 0.3], units="g"), r"^time\[1\] = 0.1: .*uniformly"),
    (dict(acceleration=[0.0, 1.0], time=[0.5, 0.6], units="g"), r"^time\[0\] = 0.5: a record starts at t = 0"),
    (dict(acceleration=[0.0, 1.0], time=[0.0, 0.1, 0.2], units="g"), r"^time has 3 values and acceleration 2"),
    (dict(acceleration=[[0.0, 1.0]], dt=0.1, units="g"), r"^acceleration: must be 1-D"),
    (dict(acceleration=[0.0, 1.0], units="g"), r"either as dt .* or as time"),
])
def test_ground_motion_errors_name_the_argument(kwargs, message):
    with pytest.raises(flexrock.FlexrockError, match=message) as error:
        flexrock.GroundMotion(**kwargs)
    assert "--" not in str(error.value)


def test_a_ground_motion_beyond_the_floor_limit_is_refused_by_the_model():
    gm = flexrock.GroundMotion([0.0, 30.0, 0.0], dt=0.01, units="g")
    with pytest.raises(flexrock.FlexrockError, match="20 g"):
        flexrock.Model.from_file(MODEL).with_ground_motion(gm)
    model = flexrock.Model.from_file(MODEL).with_ground_motion(
        flexrock.GroundMotion([0.0, 1.0, 0.0], dt=0.01, units="g"))
    with pytest.raises(flexrock.FlexrockError, match=r"arrays.*to_csv\(PATH\).*record_path=PATH"):
        model.to_toml()


# Typed sweep tables.

TABLE = {
    "columns": ["point", "excitation.period", "excitation.path", "status", "overturned",
                "n_uplift", "t_overturn"],
    "kinds": ["int", "float", "str", "str", "bool", "int", "float"],
    "values": [
        [0, 1, 2, 3, 4, 5],
        [0.5, 0.5, 0.5, 1.0, 1.0, 1.0],
        ["a.AT2", "b.AT2", "c.AT2", "a.AT2", "b.AT2", "c.AT2"],
        ["ok", "ok", "ok", "ok", "ok", "failed"],
        [False, True, False, False, True, None],
        [0, 3, 1, 2, 4, None],
        [None, 1.5, None, None, 2.25, None],
    ],
    "axes": [("excitation.period", [0.5, 1.0]), ("excitation.path", ["a.AT2", "b.AT2", "c.AT2"])],
}


def test_a_sweep_result_types_its_columns():
    result = flexrock.SweepResult(TABLE)
    assert result.columns == TABLE["columns"]
    assert len(result) == 6 and result.shape == (2, 3)
    assert result["point"].dtype == np.int64 and list(result["point"]) == [0, 1, 2, 3, 4, 5]
    assert result["excitation.period"].dtype == np.float64
    assert result["status"].dtype == object and result["status"][5] == "failed"
    t = result["t_overturn"]
    assert t.dtype == np.float64 and np.isnan(t[0]) and t[1] == 1.5
    over = result["overturned"]
    assert isinstance(over, np.ma.MaskedArray) and over.dtype == np.bool_
    assert list(over.mask) == [False] * 5 + [True] and over[1] and not over[0]
    n = result["n_uplift"]
    assert isinstance(n, np.ma.MaskedArray) and n.dtype == np.int64 and n.sum() == 10
    full = flexrock.SweepResult({**TABLE, "values": TABLE["values"][:4] + [
        [False, True, False, False, True, True], [0, 3, 1, 2, 4, 5], TABLE["values"][6]]})
    assert not isinstance(full["overturned"], np.ma.MaskedArray)
    assert full["overturned"].dtype == np.bool_ and full["overturned"].sum() == 3
    with pytest.raises(KeyError, match="n_uplift"):
        result["n_uplif"]
    flat = result.to_dict()
    assert list(flat) == TABLE["columns"] and flat["point"].dtype == np.int64


def test_a_sweep_result_to_pandas_uses_nullable_dtypes():
    pd = pytest.importorskip("pandas")
    frame = flexrock.SweepResult(TABLE).to_pandas()
    assert list(frame.columns) == TABLE["columns"]
    assert str(frame["overturned"].dtype) == "boolean" and frame["overturned"].isna().sum() == 1
    assert str(frame["n_uplift"].dtype) == "Int64" and frame["n_uplift"].sum() == 10
    assert frame["point"].dtype == np.int64
    assert str(frame["status"].dtype) == "string"
    assert frame["t_overturn"].dtype == np.float64 and frame["t_overturn"].isna().sum() == 4
    assert isinstance(frame, pd.DataFrame)


def test_a_sweep_result_to_xarray_is_the_grid():
    pytest.importorskip("xarray")
    data = flexrock.SweepResult(TABLE).to_xarray()
    assert dict(data.sizes) == {"excitation.period": 2, "excitation.path": 3}
    assert list(data["excitation.period"].values) == [0.5, 1.0]
    assert list(data["excitation.path"].values) == ["a.AT2", "b.AT2", "c.AT2"]
    # Last axis fastest: point 4 is period 1.0, path b.AT2.
    cell = data.sel({"excitation.period": 1.0, "excitation.path": "b.AT2"})
    assert int(cell["point"]) == 4 and float(cell["t_overturn"]) == 2.25
    assert np.isnan(float(data["n_uplift"].sel({"excitation.period": 1.0, "excitation.path": "c.AT2"})))


def test_a_sweep_equals_the_command_lines_table_typed(tmp_path):
    from test_flexrock import read_csv, run_cli
    run_cli("sweep", MODEL, "--out", tmp_path, "--quiet", "--vary", "excitation.amplitude=2,4.5",
            "--vary", "excitation.period=0.5,1,1.5")
    rows = read_csv(tmp_path / "sweep.csv")
    got = flexrock.sweep(flexrock.Model.from_file(MODEL),
                         {"excitation.amplitude": [2, 4.5], "excitation.period": [0.5, 1.0, 1.5]})
    assert isinstance(got, flexrock.SweepResult)
    assert got.columns == list(rows[0]) and got.shape == (2, 3)
    assert got["overturned"].dtype == np.bool_
    assert list(got["overturned"]) == [r["overturned"] == "true" for r in rows]
    assert got["n_uplift"].dtype == np.int64
    assert list(got["n_uplift"]) == [int(r["n_uplift"]) for r in rows]
    assert list(got["max_abs_q_over_B"]) == [float(r["max_abs_q_over_B"]) for r in rows]


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(find_min=("excitation.amplitude", 2.0, 1.0)), r"^find_min = 2:1: LO must be below HI"),
        (dict(find_min=("excitation.amplitude", 1.0, float("nan"))), r"^find_min = 1:NaN: "),
        (dict(find_min=("excitation.amplitude", 1.0, 2.0), scan=1), r"^scan = 1: must lie in"),
        (dict(find_min=("excitation.amplitude", 1.0, 2.0), tol=-1.0), r"^tol = -1: must be a positive"),
        (dict(find_min=("excitation.amplitude", 1.0, 2.0), rigid_form="exact"),
         r"^rigid_form = exact: must be \"small-angle\""),
        (dict(rigid_form="full"), r"^rigid_form = full: chooses the rigid block of a minimum search"),
        (dict(find_min=("excitation.amplitude", 1.0, 2.0), rigid_overturning="never"),
         r"^rigid_overturning = never: must be \"reaches-limit\""),
        (dict(find_min=("excitation.amplitude", 1.0, 2.0), rigid_restitution=1.5),
         r"^rigid_restitution = 1.5: must lie strictly between 0 and 1"),
        (dict(find_min=("excitation.amplitude", 1.0, 2.0), rigid_restitution=1.0),
         r"^rigid_restitution = 1: must lie strictly between 0 and 1"),
        (dict(rigid_restitution=0.9), r"^rigid_restitution = 0.9: chooses the rigid block"),
    ],
)
def test_sweep_errors_name_the_argument(kwargs, message):
    model = flexrock.Model.from_file(ROOT / "models" / "sine-pulse.toml")
    with pytest.raises(flexrock.FlexrockError, match=message):
        flexrock.sweep(model, {"excitation.period": [0.8]}, **kwargs)


@pytest.mark.parametrize(
    "axes, message",
    [
        ({"excitation.amplitude": []}, r'^axes\["excitation.amplitude"\] = : an axis needs at least one value'),
        ({"excitation.amplitude": [float("nan")]}, r'^axes\["excitation.amplitude"\] = NaN: NaN is not a finite'),
        ({"excitation.amplitude": [1, 1.0]}, r"appears twice"),
        ({}, r"^axes = \(none\): a sweep needs at least one axis or a minimum search"),
    ],
)
def test_sweep_axes_are_checked_like_the_command_lines(axes, message):
    model = flexrock.Model.from_file(ROOT / "models" / "sine-pulse.toml")
    with pytest.raises(flexrock.FlexrockError, match=message):
        flexrock.sweep(model, axes)


# Errors of a model given as a dict name its place in the dict.

@pytest.mark.parametrize("change, error, message", [
    (lambda d: d.__setitem__("body", 5), TypeError,
     r'^d\["body"\] = 5: must be a dict of the keys of the model file\'s \[body\] table'),
    (lambda d: d["body"].__setitem__("height", "four"), flexrock.FlexrockError,
     r'^d\["body"\]\["height"\] = four: invalid type: string "four", expected f64$'),
    (lambda d: d["body"].__setitem__("height", -1.0), flexrock.FlexrockError,
     r'^d\["body"\]\["height"\] = -1: must be a finite number greater than 0$'),
    (lambda d: d["excitation"].__setitem__("amplitud", 1.0), flexrock.FlexrockError,
     r'^d\["excitation"\]: unknown field `amplitud`.*did you mean `amplitude`\?$'),
    (lambda d: d["body"].pop("height"), flexrock.FlexrockError,
     r'^d\["body"\]: missing field `height`$'),
    (lambda d: d["body"].__setitem__("density", 10**400), flexrock.FlexrockError,
     r'^d\["body"\]\["density"\] = an int of 401 digits: beyond the largest number'),
    (lambda d: d["body"].__setitem__(4, 1.0), TypeError,
     r'^d\["body"\]: every key must be a str, not 4$'),
])
def test_errors_of_a_dict_name_the_place_in_the_dict(change, error, message):
    d = tables(MODEL)
    change(d)
    with pytest.raises(error, match=message) as raised:
        flexrock.Model.from_dict(d)
    assert "(model text)" not in str(raised.value) and "BodySection" not in str(raised.value)


# Values: any Python number that a float holds; a str is not a list of its letters.

def test_an_int_beyond_64_bits_is_the_float_that_holds_it_and_beyond_floats_refused():
    model = flexrock.Model.from_file(MODEL)
    # The depth, to which q(t) is blind: 10**19 is beyond 64-bit ints, and a float exactly.
    model.set("body.depth", 10**19)
    same = flexrock.Model.from_file(MODEL)
    same.set("body.depth", 1e19)
    assert model.get("body.depth") == 1e19 and isinstance(model.get("body.depth"), float)
    same_results(flexrock.simulate(model), flexrock.simulate(same))
    with pytest.raises(flexrock.FlexrockError,
                       match=r"^body.depth = an int of 401 digits: beyond the largest number"):
        model.set("body.depth", 10**400)
    assert model.get("body.depth") == 1e19
    model.set("excitation.amplitude", np.float64(3.0))
    model.set("simulation.qdot0", np.int64(0))
    assert model.get("excitation.amplitude") == 3.0 and model.get("simulation.qdot0") == 0
    with pytest.raises(TypeError, match=r"^excitation.amplitude = \[3.0\]: .* not list"):
        model.set("excitation.amplitude", [3.0])
    with pytest.raises(TypeError, match=r"^excitation.amplitude = None: .* not NoneType"):
        model.set("excitation.amplitude", None)


@pytest.mark.parametrize("axes, message", [
    ({"excitation.amplitude": "12"},
     r'^axes\["excitation.amplitude"\] = \'12\': must be a sequence of values .* not a str; '
     r"for one value, give a list of one: \['12'\]"),
    ({"excitation.amplitude": 2.0},
     r'^axes\["excitation.amplitude"\] = 2.0: must be a sequence of values'),
    ({"excitation.amplitude": [1.0, [2.0]]},
     r'^axes\["excitation.amplitude"\]\[1\] = \[2.0\]: a model-file value must be'),
])
def test_an_axis_must_be_a_sequence_of_values(axes, message):
    model = flexrock.Model.from_file(ROOT / "models" / "sine-pulse.toml")
    with pytest.raises(TypeError, match=message):
        flexrock.sweep(model, axes)


# Several keys at once.

def test_update_sets_keys_that_only_make_sense_together(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    dt, values = read_at2(AT2)
    (tmp_path / "elcentro.csv").write_text("".join(f"{float(v)!r}\n" for v in values))
    file_model = flexrock.Model.from_file(RECORD_MODEL)
    switch = {"excitation.path": "elcentro.csv", "excitation.format": "csv",
              "excitation.units": "g", "excitation.dt": dt}
    # One key at a time, in either order, makes a model that cannot be read.
    for key in ["excitation.path", "excitation.format"]:
        model = flexrock.Model.from_file(RECORD_MODEL)
        with pytest.raises(flexrock.FlexrockError):
            model.set(key, switch[key])
    model = flexrock.Model.from_file(RECORD_MODEL)
    model.update(switch)
    assert model.get("excitation.path") == "elcentro.csv"
    assert model.settings[1:] == ["excitation.format=csv", "excitation.units=g", "excitation.dt=0.02"]
    same_results(flexrock.simulate(model), flexrock.simulate(file_model))
    # A bad key among them leaves the model as it was.
    with pytest.raises(flexrock.FlexrockError, match="excitation.scal"):
        model.update({"excitation.scale": 2.0, "excitation.scal": 2.0})
    assert model.get("excitation.scale") == 1.0 and len(model.settings) == 4
    with pytest.raises(TypeError, match="a dict of keys and values"):
        model.update([("excitation.scale", 2.0)])


# A model across threads, pickled, copied.

def test_set_while_another_thread_solves_the_model():
    model = flexrock.Model.from_file(MODEL)
    results = []
    runner = threading.Thread(target=lambda: results.append(flexrock.simulate(model, duration=200.0)))
    runner.start()
    amplitudes = [1.0 + 0.01 * k for k in range(50)]
    for a in amplitudes:
        model.set("excitation.amplitude", a)
        time.sleep(0.01)
    runner.join()
    assert model.get("excitation.amplitude") == amplitudes[-1]
    # The run solved the model as it stood when it started.
    same_results(results[0], flexrock.simulate(flexrock.Model.from_file(MODEL), duration=200.0))


def models_of_every_kind():
    from_file = flexrock.Model.from_file(RECORD_MODEL)
    from_file.update({"excitation.scale": 2, "solver.method": "bdf", "excitation.tail": 1.5})
    text = flexrock.Model.from_toml(MODEL.read_text())
    text.set("excitation.amplitude", 4)
    from_dict = flexrock.Model.from_dict(tables(MODEL))
    from_dict.set("solver.method", "exact")
    dt, values = read_at2(AT2)
    arrays = flexrock.Model.from_file(MODEL).with_ground_motion(
        flexrock.GroundMotion(values * 0.5, dt=dt, units="g", source="half El Centro"))
    arrays.update({"excitation.scale": 1.5, "excitation.tail": 2.0})
    return [from_file, text, from_dict, arrays]


def same_model(a, b):
    assert repr(a) == repr(b) and a.settings == b.settings and a.path == b.path
    for key in ["excitation.amplitude", "excitation.scale", "solver.method", "body.height"]:
        assert a.get(key) == b.get(key) and type(a.get(key)) is type(b.get(key)), key
    if a.ground_motion is None:
        assert b.ground_motion is None and a.to_toml() == b.to_toml()
    else:
        ga, gb = a.ground_motion, b.ground_motion
        assert (ga.dt, ga.units, ga.source, len(ga)) == (gb.dt, gb.units, gb.source, len(gb))
        assert np.array_equal(ga.acceleration, gb.acceleration)
    same_results(flexrock.simulate(a), flexrock.simulate(b))


def test_a_model_pickles_and_copies_to_the_same_model(tmp_path):
    for model in models_of_every_kind():
        same_model(pickle.loads(pickle.dumps(model)), model)
        for made in [copy.copy(model), copy.deepcopy(model)]:
            same_model(made, model)
            made.set("excitation.scale" if model.ground_motion else "body.damping_ratio", 0.02)
            assert made.settings != model.settings
    gm = flexrock.read_record(AT2)
    again = pickle.loads(pickle.dumps(gm))
    assert np.array_equal(again.acceleration, gm.acceleration) and again.dt == gm.dt
    assert (again.source, again.units) == (gm.source, gm.units)


def solve_q(model):
    return flexrock.simulate(model).q


def test_a_model_goes_to_another_process():
    import concurrent.futures
    import multiprocessing
    models = models_of_every_kind()
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=context) as pool:
        for model, q in zip(models, pool.map(solve_q, models)):
            assert np.array_equal(q, flexrock.simulate(model).q)


def test_a_model_whose_file_has_changed_is_refused_not_read_again(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(MODEL.read_text())
    model = flexrock.Model.from_file(path)
    pickled = pickle.dumps(model)
    path.write_text(MODEL.read_text().replace("amplitude = 5.0", "amplitude = 2.0"))
    for act in [lambda: model.set("excitation.amplitude", 3.0), lambda: pickle.loads(pickled),
                lambda: flexrock.sweep(model, {"excitation.period": [1.0]})]:
        with pytest.raises(flexrock.FlexrockError, match="has changed since the model was read"):
            act()


# A model whose ground motion was given as arrays: swept and saved.

def arrays_and_file_models():
    dt, values = read_at2(AT2)
    file_model = flexrock.Model.from_file(RECORD_MODEL)
    arrays = file_model.with_ground_motion(flexrock.GroundMotion(values, dt=dt, units="g"))
    arrays.set("excitation.tail", tables(RECORD_MODEL)["excitation"]["tail"])
    return arrays, file_model


def test_a_model_of_arrays_sweeps_as_its_record_file():
    arrays, file_model = arrays_and_file_models()
    axes = {"excitation.scale": [0.5, 1.0], "body.damping_ratio": [0.02, 0.05]}
    got, expected = flexrock.sweep(arrays, axes), flexrock.sweep(file_model, axes)
    assert got.columns == expected.columns and list(got["status"]) == ["ok"] * 4
    for name in got.columns:
        a, b = got[name], expected[name]
        if a.dtype == np.float64:
            assert np.array_equal(a, b, equal_nan=True), name
        else:
            assert list(a) == list(b), name
    with pytest.raises(flexrock.FlexrockError, match=r'^axes\["excitation.path"\]: .* given as arrays'):
        flexrock.sweep(arrays, {"excitation.path": [str(AT2)]})
    with pytest.raises(flexrock.FlexrockError, match=r"^excitation.units = m/s2: .* given as arrays"):
        arrays.set("excitation.units", "m/s2")


def test_a_model_of_arrays_is_saved_with_its_samples_in_a_record_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    arrays, file_model = arrays_and_file_models()
    arrays.set("excitation.scale", 0.75)
    arrays.ground_motion.to_csv("motion.csv")
    again = flexrock.read_record("motion.csv", dt=arrays.ground_motion.dt, units="g")
    assert np.array_equal(again.acceleration, arrays.ground_motion.acceleration)
    text = arrays.to_toml(record_path="motion.csv")
    same_results(flexrock.simulate(flexrock.Model.from_toml(text)), flexrock.simulate(arrays))
    d = arrays.to_dict(record_path="motion.csv")
    assert d["excitation"]["path"] == "motion.csv" and d["excitation"]["scale"] == 0.75
    same_results(flexrock.simulate(flexrock.Model.from_dict(d)), flexrock.simulate(arrays))
    # A file of other samples is not taken for this motion's.
    flexrock.GroundMotion([0.0, 0.1, 0.0], dt=0.02, units="g").to_csv("other.csv")
    with pytest.raises(flexrock.FlexrockError, match="^record_path = other.csv: does not hold"):
        arrays.to_toml(record_path="other.csv")
    with pytest.raises(flexrock.FlexrockError, match="^record_path = motion.csv: names the record"):
        file_model.to_toml(record_path="motion.csv")


def test_a_model_text_beyond_the_size_of_a_model_file_is_refused_before_it_is_read():
    text = MODEL.read_text() + "#" * (1024 * 1024)
    with pytest.raises(flexrock.FlexrockError, match=r"^Model.from_toml: the text has \d+ bytes, "
                                                     r"beyond the 1048576 bytes a model file"):
        flexrock.Model.from_toml(text)


def test_the_landing_restitution_and_the_damping_while_rocking_are_keys():
    model = flexrock.Model.from_file(MODEL)
    # The paper's model when left out.
    assert model.get("body.landing_restitution") == 1.0
    assert model.get("body.damping_while_rocking") is True
    model.set("body.landing_restitution", 0.8)
    model.set("body.damping_while_rocking", False)
    result = flexrock.simulate(model, method="exact")
    body, constants = result.summary["body"], result.summary["constants"]
    assert body["landing_restitution"] == 0.8
    assert body["damping_while_rocking"] is False
    landings = [e for e in result.events if e["kind"] == "landing"]
    assert landings
    # Every landing: q' -> e q'/zetaL.
    for e in landings:
        ratio = e["qdot_after"] / e["qdot_before"]
        assert abs(ratio - 0.8 / constants["zeta_landing"]) <= 1e-15 * ratio
    # No damping work while rocking: work_damping is flat between samples within a rocking mode.
    rocking = [i for i in range(1, len(result.t))
               if result.mode[i] == result.mode[i - 1] and result.mode[i].startswith("rock")]
    assert rocking
    assert all(result.work_damping[i] == result.work_damping[i - 1] for i in rocking)
    for value, rule in [(0.0, r"\(0, 1\]"), (1.5, r"\(0, 1\]")]:
        bad = flexrock.Model.from_file(MODEL)
        with pytest.raises(flexrock.FlexrockError, match=rf"body\.landing_restitution.*{rule}"):
            bad.set("body.landing_restitution", value)
            flexrock.simulate(bad)
    with pytest.raises(flexrock.FlexrockError, match=r"body\.damping_while_rocking.*boolean"):
        bad = flexrock.Model.from_file(MODEL)
        bad.set("body.damping_while_rocking", "no")
        flexrock.simulate(bad)
