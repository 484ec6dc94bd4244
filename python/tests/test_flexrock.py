"""The Python bindings against the command line: the same numbers to the last digit.

The flexrock binary is found by FLEXROCK_BIN, else target/release/flexrock, else built with
`cargo run --release --bin flexrock --` from the repository root.
"""

import csv
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import flexrock

ROOT = Path(__file__).resolve().parents[2]
MODEL = ROOT / "models" / "ichinose1986.toml"


def cli():
    if os.environ.get("FLEXROCK_BIN"):
        return [os.environ["FLEXROCK_BIN"]]
    binary = ROOT / "target" / "release" / "flexrock"
    if binary.is_file():
        return [str(binary)]
    if shutil.which("cargo"):
        return ["cargo", "run", "--quiet", "--release", "--bin", "flexrock", "--"]
    pytest.skip("no flexrock binary: set FLEXROCK_BIN")


def run_cli(*args):
    subprocess.run(cli() + [str(a) for a in args], cwd=ROOT, check=True, capture_output=True)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def same_as_cli(result, out):
    history = read_csv(out / "history.csv")
    assert len(history) == len(result.t)
    for name in history[0]:
        column = getattr(result, name)
        for i, row in enumerate(history):
            if name == "mode":
                assert column[i] == row[name]
            else:
                assert column[i] == float(row[name]), (name, i)
    events = read_csv(out / "events.csv")
    assert len(events) == len(result.events)
    for mine, theirs in zip(result.events, events):
        for key, text in theirs.items():
            value = mine[key]
            assert (str(value) if isinstance(value, (str, int)) else value) == (
                text if isinstance(value, (str, int)) else float(text)
            ), key
    episodes = read_csv(out / "episodes.csv")
    assert len(episodes) == len(result.episodes)
    for mine, theirs in zip(result.episodes, episodes):
        for key, text in theirs.items():
            value = mine[key]
            if value is None:
                assert text == "", key
            elif isinstance(value, (str, int)):
                assert str(value) == text, key
            else:
                assert value == float(text), key
    summary = json.loads((out / "summary.json").read_text())
    for key in ["max_q", "t_max_q", "min_q", "t_min_q", "n_uplift", "n_landing", "overturned",
                "t_overturn", "max_energy_residual", "final_time", "final_mode", "T", "s_n",
                "constants", "body", "inputs", "warnings"]:
        assert result.summary[key] == summary[key], key
    for key in ["steps", "rhs_evaluations", "method"]:
        assert result.summary["statistics"][key] == summary["statistics"][key], key


def test_simulate_equals_the_command_line(tmp_path):
    run_cli("run", MODEL, "--out", tmp_path)
    result = flexrock.simulate(flexrock.Model.from_file(MODEL))
    same_as_cli(result, tmp_path)
    assert result.summary["n_uplift"] > 0
    assert result.q.dtype == np.float64


def test_method_and_tolerances_as_the_flags(tmp_path):
    run_cli("run", MODEL, "--out", tmp_path, "--method", "tsit45", "--rtol", "1e-8", "--atol", "1e-12")
    model = flexrock.Model.from_file(MODEL)
    same_as_cli(flexrock.simulate(model, method="tsit45", rtol=1e-8, atol=1e-12), tmp_path)


def test_the_exact_method_equals_the_command_line_and_estimates_its_error(tmp_path):
    run_cli("run", MODEL, "--out", tmp_path, "--method", "exact")
    result = flexrock.simulate(flexrock.Model.from_file(MODEL), method="exact")
    same_as_cli(result, tmp_path)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert result.summary["error_estimate"] == summary["error_estimate"]
    estimate = result.summary["error_estimate"]
    assert len(estimate["event_time"]) == len(result.events) > 0
    assert all(0 < e < 1e-9 for e in estimate["event_time"])
    assert result.summary["solver"] == {"method": "exact", "output_dt": 0.005}
    with pytest.raises(flexrock.FlexrockError, match="rtol"):
        flexrock.simulate(flexrock.Model.from_file(MODEL), method="exact", rtol=1e-8)


def test_set_is_editing_the_file(tmp_path):
    text = MODEL.read_text()
    model = flexrock.Model.from_toml(text)
    model.set("excitation.amplitude", 4.0)
    model.set("solver.method", "tsit45")
    run_cli("run", MODEL, "--out", tmp_path / "out", "--set", "excitation.amplitude=4.0",
            "--set", "solver.method=tsit45")
    result = flexrock.simulate(model)
    same_as_cli(result, tmp_path / "out")
    base = flexrock.simulate(flexrock.Model.from_file(MODEL))
    assert base.summary["max_q"] != result.summary["max_q"]
    assert model.settings == ["excitation.amplitude=4", "solver.method=tsit45"]


def test_a_set_method_meets_the_rules_of_the_same_method_in_the_file():
    bdf = MODEL.read_text().replace('method = "exact"', 'method = "bdf"\nrtol = 1e-10', 1)
    model = flexrock.Model.from_toml(bdf)
    with pytest.raises(flexrock.FlexrockError, match="solver.rtol") as set_error:
        model.set("solver.method", "exact")
    with pytest.raises(flexrock.FlexrockError, match="solver.rtol") as file_error:
        flexrock.Model.from_toml(bdf.replace('method = "bdf"', 'method = "exact"'))
    assert str(set_error.value).endswith(str(file_error.value).split(": ", 1)[-1])
    assert model.get("solver.method") == "bdf"


def test_bad_keys_and_values_raise_with_the_key():
    model = flexrock.Model.from_file(MODEL)
    with pytest.raises(flexrock.FlexrockError, match="excitation.period"):
        model.set("excitation.period", -1.0)
    with pytest.raises(flexrock.FlexrockError, match="nonsense"):
        model.set("excitation.nonsense", 1.0)
    with pytest.raises(flexrock.FlexrockError, match="solver.rtol"):
        model.set("solver.rtol", 5.0)
    with pytest.raises(ValueError):
        flexrock.Model.from_toml("[body]\nheight = 1\n")
    with pytest.raises(flexrock.FlexrockError):
        flexrock.simulate(model, method="nonsense")
    # A refused value leaves the model as it was.
    assert model.settings == []


def test_props_are_the_json_of_props():
    props = flexrock.props(flexrock.Model.from_file(MODEL))
    assert props["constants"]["period"] > 0
    assert props["body"]["height"] > 0


def same_table(got, rows):
    """A typed sweep table equals sweep.csv's text, field by field."""
    assert got.columns == list(rows[0])
    assert len(got) == len(rows)
    for name in got.columns:
        column = got[name]
        for i, row in enumerate(rows):
            text = row[name]
            value = column[i]
            if text == "":
                assert value is None or value is np.ma.masked or np.isnan(value), name
            elif column.dtype == np.bool_:
                assert bool(value) == (text == "true"), name
            elif column.dtype == object:
                assert value == text, name
            else:
                assert value == float(text), name


def test_sweep_equals_the_command_line(tmp_path):
    run_cli("sweep", MODEL, "--out", tmp_path, "--quiet", "--vary", "excitation.amplitude=2,4.5",
            "--vary", "excitation.period=0.5,1,1.5")
    rows = read_csv(tmp_path / "sweep.csv")
    got = flexrock.sweep(flexrock.Model.from_file(MODEL),
                         {"excitation.amplitude": [2, 4.5], "excitation.period": [0.5, 1.0, 1.5]})
    same_table(got, rows)


def test_sweep_of_a_model_text_with_a_minimum_search(tmp_path):
    run_cli("sweep", MODEL, "--out", tmp_path, "--quiet", "--vary", "excitation.period=0.5,1",
            "--find-min", "excitation.amplitude=1:20", "--scan", "8")
    rows = read_csv(tmp_path / "sweep.csv")
    got = flexrock.sweep(flexrock.Model.from_toml(MODEL.read_text()),
                         {"excitation.period": [0.5, 1.0]},
                         find_min=("excitation.amplitude", 1.0, 20.0), scan=8)
    same_table(got, rows)


def test_sweep_with_the_full_rigid_equation_equals_the_command_line(tmp_path):
    # rigid_form="full" is --rigid-form full: the same table, with its rigid_form column.
    pulse = ROOT / "models" / "pulse-map.toml"
    run_cli("sweep", pulse, "--out", tmp_path, "--quiet", "--vary", "excitation.period=0.8",
            "--find-min", "excitation.amplitude=1.8:8", "--rigid-form", "full")
    rows = read_csv(tmp_path / "sweep.csv")
    got = flexrock.sweep(flexrock.Model.from_file(pulse), {"excitation.period": [0.8]},
                         find_min=("excitation.amplitude", 1.8, 8.0), rigid_form="full")
    same_table(got, rows)
    assert rows[0]["rigid_form"] == "full"
    # The reference block overturns from 3.033 m/s^2 by the full equation (2.998 small-angle).
    assert abs(float(rows[0]["rigid_min_overturning"]) / 3.033 - 1) < 2e-3


def test_sweep_with_a_papers_rigid_block_equals_the_command_line(tmp_path):
    # rigid_overturning and rigid_restitution are the flags of the same names: Zhang and Makris'
    # block at omega_p/p = 5 overturns from between 3.00 and 3.01 g tan(alpha) (their paper).
    model = ROOT / "models" / "zhang-makris.toml"
    run_cli("sweep", model, "--out", tmp_path, "--quiet", "--find-min",
            "excitation.amplitude=2:20", "--scan", "200", "--rigid-overturning", "cannot-return",
            "--rigid-restitution", "0.9")
    rows = read_csv(tmp_path / "sweep.csv")
    got = flexrock.sweep(flexrock.Model.from_file(model), {},
                         find_min=("excitation.amplitude", 2.0, 20.0), scan=200,
                         rigid_overturning="cannot-return", rigid_restitution=0.9)
    same_table(got, rows)
    assert rows[0]["rigid_overturning"] == "cannot-return"
    assert float(rows[0]["rigid_restitution"]) == 0.9
    beta = float(rows[0]["rigid_amplitude_over_g_tan_alpha"])
    assert 3.00 * 0.996 <= beta <= 3.01 * 1.004


def test_to_pandas():
    pandas = pytest.importorskip("pandas")
    frame = flexrock.simulate(flexrock.Model.from_file(MODEL)).to_pandas()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns)[:5] == ["t", "q", "qdot", "s", "r"]


def test_the_consistent_variant_is_one_key_away(tmp_path):
    # The self-weight-consistent variant from Python equals the command line's, and its
    # constants are those of props --json for the same setting.
    run_cli("run", MODEL, "--out", tmp_path, "--set", "body.self_weight=consistent")
    model = flexrock.Model.from_file(MODEL)
    model.set("body.self_weight", "consistent")
    result = flexrock.simulate(model)
    same_as_cli(result, tmp_path)
    props = flexrock.props(model)
    assert props["constants"]["self_weight"] == "consistent"
    # An elastic beam-column with P-Delta lifts off at 0.1895 m (validation/opensees).
    assert abs(props["constants"]["uplift_displacement"] - 0.1895) < 0.003
    paper = flexrock.props(flexrock.Model.from_file(MODEL))
    assert paper["constants"]["uplift_displacement"] < 0.16
    with pytest.raises(flexrock.FlexrockError, match="body.self_weight"):
        model.set("body.self_weight", "both")


def test_sweep_of_a_model_text_reads_its_record_from_the_current_directory(monkeypatch):
    # A model given as text reads a relative record path from the current directory, in a
    # sweep as in simulate; the rows equal those of the same model read from its file.
    record_model = ROOT / "models" / "elcentro1940.toml"
    monkeypatch.chdir(record_model.parent)
    axes = {"excitation.scale": [0.5, 1.0]}
    from_text = flexrock.sweep(flexrock.Model.from_toml(record_model.read_text()), axes)
    from_file = flexrock.sweep(flexrock.Model.from_file(record_model), axes)
    assert list(from_text["status"]) == ["ok", "ok"]
    for name in ["max_abs_q_over_B", "n_uplift", "steps"]:
        assert np.array_equal(from_text[name], from_file[name]), name


def test_a_record_path_set_in_python_is_relative_to_the_current_directory(tmp_path, monkeypatch):
    # One rule for relative paths: a path typed in Python, like one on the command line, is
    # relative to the current directory, not to the model file (whose directory has no such file).
    shutil.copy(ROOT / "validation" / "records" / "elCentro.AT2", tmp_path / "here.AT2")
    model = flexrock.Model.from_file(ROOT / "models" / "elcentro1940.toml")
    monkeypatch.chdir(tmp_path)
    model.set("excitation.path", "here.AT2")
    model.set("excitation.end", 1.0)
    assert flexrock.simulate(model).summary["n_uplift"] >= 0
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    with pytest.raises(flexrock.FlexrockError, match=str(elsewhere / "here.AT2")):
        model.set("excitation.path", "here.AT2")


def test_run_settings_as_arguments_named_in_their_errors(tmp_path):
    # duration and output_dt as arguments, equal to the same keys on the command line; an error
    # about an argument names the argument and its key, never a command-line flag.
    run_cli("run", MODEL, "--out", tmp_path, "--duration", "3", "--set", "solver.output_dt=0.01")
    model = flexrock.Model.from_file(MODEL)
    result = flexrock.simulate(model, duration=3.0, output_dt=0.01)
    same_as_cli(result, tmp_path)
    assert result.t[-1] == 3.0
    for argument, key, value in [("rtol", "solver.rtol", -1.0), ("duration", "simulation.duration", -3.0),
                                 ("output_dt", "solver.output_dt", 0.0)]:
        with pytest.raises(flexrock.FlexrockError) as error:
            flexrock.simulate(model, **{argument: value})
        message = str(error.value)
        assert message.startswith(f"{argument} (sets {key}) = "), message
        assert "--" not in message, message
    with pytest.raises(flexrock.FlexrockError) as error:
        model.set("excitation.amplitud", 1.0)
    assert "--set" not in str(error.value) and "excitation.amplitud" in str(error.value)


def test_compare_equals_the_command_line(tmp_path):
    run_cli("compare", MODEL, "--dt", "0.005", "--out", tmp_path)
    theirs = json.loads((tmp_path / "compare.json").read_text())
    mine = flexrock.compare(flexrock.Model.from_file(MODEL), dt=0.005)
    assert mine["comparison"] == theirs["comparison"]
    history = read_csv(tmp_path / "compare_history.csv")
    assert len(mine["grid"]) == len(history)
    for row, theirs_row in zip(mine["grid"], history):
        for key, text in theirs_row.items():
            assert row[key] == float(text), key


def test_converge_equals_the_command_line(tmp_path):
    run_cli("converge", MODEL, "--dt", "0.01,0.005", "--rtol", "1e-6,1e-8", "--out", tmp_path)
    rows = read_csv(tmp_path / "convergence.csv")
    study = flexrock.converge(flexrock.Model.from_file(MODEL), dts=[0.01, 0.005], rtols=[1e-6, 1e-8])
    assert len(study["cases"]) == len(rows)
    for case, row in zip(study["cases"], rows):
        assert case["method"] == row["method"] and case["status"] == row["status"]
        for key in ("max_q_error", "max_event_time_error", "peak_error", "steps", "rhs_evaluations"):
            assert case[key] == float(row[key]), key
    with pytest.raises(flexrock.FlexrockError, match=r"^rtols \(sets"):
        flexrock.converge(flexrock.Model.from_file(MODEL), dts=[0.01], rtols=[5.0])


def test_fem_check_equals_the_command_line(tmp_path):
    run_cli("fem", MODEL, "--nx", "2", "--ny", "8", "--dt", "0.005", "--out", tmp_path)
    history = read_csv(tmp_path / "fem_history.csv")
    fem = flexrock.fem_check(flexrock.Model.from_file(MODEL), nx=2, ny=8, dt=0.005)
    assert len(fem["history"]) == len(history)
    for row, theirs in zip(fem["history"][::50], history[::50]):
        for key in ("t", "q", "flexural", "rocking"):
            assert row[key] == float(theirs[key]), key
    assert fem["peaks"]["max_q"] == max(float(r["q"]) for r in history)
    with pytest.raises(flexrock.FlexrockError, match=r"^nx \(sets fem.nx\) = 0"):
        flexrock.fem_check(flexrock.Model.from_file(MODEL), nx=0)


def test_a_convergence_study_without_cases_is_refused():
    with pytest.raises(flexrock.FlexrockError, match="needs at least one Newmark step"):
        flexrock.converge(flexrock.Model.from_file(MODEL), dts=[], rtols=[])
