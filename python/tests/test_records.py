"""Records through Python: their metadata, their intensity measures (the command line's
numbers), and ground motions from arrays running for their own length."""

import csv
import io
import os
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexrock

ROOT = Path(__file__).resolve().parents[2]
MODEL = ROOT / "models" / "ichinose1986.toml"
RECORD_MODEL = ROOT / "models" / "elcentro1940.toml"
FIXTURES = ROOT / "tests" / "data" / "records"
FLEXROCK = os.environ.get("FLEXROCK_BIN", str(ROOT / "target" / "release" / "flexrock"))


def test_a_ground_motion_from_arrays_runs_for_its_own_length():
    # The model file's duration (6 s) was its sine's: a 20 s record runs 20 s.
    t = np.arange(0, 2001) * 0.01
    gm = flexrock.GroundMotion(0.05 * np.sin(2 * np.pi * t), dt=0.01, units="g")
    model = flexrock.Model.from_file(MODEL).with_ground_motion(gm)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = flexrock.simulate(model)
    assert result.t[-1] == pytest.approx(20.0, abs=1e-12)
    # A duration given cuts the record, and says so.
    with pytest.warns(UserWarning, match=r"the run lasts 6 s .* the record lasts 20 s: its last 14 s"):
        result = flexrock.simulate(model, duration=6.0)
    assert result.t[-1] == pytest.approx(6.0, abs=1e-12)
    assert "the record lasts 20 s" in result.summary["warnings"][0]


def test_read_record_honours_the_units_the_file_says_and_gives_its_metadata():
    for name, units in [("nga-g.AT2", "g"), ("nga-cmss.AT2", "cm/s2"), ("cosmos-cmss.V2", "cm/s2"),
                        ("esm-cmss.ASC", "cm/s2")]:
        gm = flexrock.read_record(FIXTURES / name)
        assert gm.units == units
        assert gm.acceleration.max() == pytest.approx(0.5 * (9.80665 if units == "g" else 1.0))
    gm = flexrock.read_record(FIXTURES / "esm-cmss.ASC")
    assert gm.metadata == {
        "format": "esm", "units": "cm/s2", "event": "L'AQUILA MAINSHOCK (SYNTHETIC)",
        "date": "2009-04-06", "station": "IT.AQV", "component": "HNE", "magnitude": 6.1,
        "distance_km": 4.9}
    assert gm.label == "L'AQUILA MAINSHOCK (SYNTHETIC), IT.AQV, HNE"
    with pytest.raises(flexrock.FlexrockError, match=r'^units = "g": contradicts the record file'):
        flexrock.read_record(FIXTURES / "nga-cmss.AT2", units="g")
    with pytest.raises(flexrock.FlexrockError, match="holds a velocity time series"):
        flexrock.read_record(FIXTURES / "nga-velocity.VT2")


def test_intensity_measures_are_the_command_lines():
    record = ROOT / "validation" / "records" / "PBFEAS.AT2"
    out = subprocess.run([FLEXROCK, "record", "intensity", str(record), "--period", "0.4"],
                         capture_output=True, text=True, check=True).stdout
    row = next(csv.DictReader(io.StringIO(out)))
    m = flexrock.intensity_measures(flexrock.read_record(record), period=0.4)
    for key, column in [("pga_g", "pga_g"), ("pgv", "pgv_m_s"), ("pgd", "pgd_m"),
                        ("arias", "arias_m_s"), ("cav", "cav_m_s"), ("sa_g", "sa_g")]:
        assert m[key] == float(row[column]), key
    spectrum = flexrock.response_spectrum(flexrock.read_record(record), periods=[0.4, 2.0])
    assert spectrum["sa"][0] == m["sa"]
    assert list(spectrum["period"]) == [0.4, 2.0]
    # A model's record as it applies it, Sa at its body's pre-uplift period T by default.
    model = flexrock.Model.from_file(RECORD_MODEL)
    model.set("excitation.scale", 2.0)
    scaled = flexrock.intensity_measures(model)
    assert scaled["period"] == flexrock.props(model)["constants"]["period"]
    alone = flexrock.intensity_measures(flexrock.read_record(ROOT / "validation" / "records" / "elCentro.AT2"),
                                        period=scaled["period"])
    assert scaled["pga"] == pytest.approx(2 * alone["pga"], rel=1e-15)
    assert scaled["sa"] == pytest.approx(2 * alone["sa"], rel=1e-12)
    with pytest.raises(flexrock.FlexrockError, match="not a record"):
        flexrock.intensity_measures(flexrock.Model.from_file(MODEL))
    with pytest.raises(flexrock.FlexrockError, match=r"^period = 0: must lie in"):
        flexrock.intensity_measures(model, period=0.0)


def test_a_sweep_over_records_has_their_columns():
    model = flexrock.Model.from_file(RECORD_MODEL)
    table = flexrock.sweep(model, {"excitation.scale": [1.0, 2.0]})
    frame = table.to_pandas()
    assert list(frame.columns[-12:]) == [
        "event", "date", "station", "component", "magnitude", "distance_km", "pga_g", "pgv_m_s",
        "pgd_m", "arias_m_s", "cav_m_s", "sa_g"]
    assert frame["pga_g"].tolist() == pytest.approx([0.31882, 2 * 0.31882], rel=1e-15)
