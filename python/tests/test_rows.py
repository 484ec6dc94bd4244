"""Rows of columns from Python: the same numbers as the core's run of each column alone when the
gaps never close, the impacts as events of both columns, and errors that name the key."""

from pathlib import Path

import numpy as np
import pytest

import flexrock

ROOT = Path(__file__).resolve().parents[2]
PAIR = ROOT / "models" / "row-pair.toml"

BODIES = [
    {"height": 4.0, "width": 0.7, "density": 600.0, "youngs_modulus": 5.0e6, "damping_ratio": 0.05},
    {"height": 3.0, "width": 0.8, "density": 500.0, "youngs_modulus": 2.0e7, "damping_ratio": 0.03},
]
EXCITATION = {"kind": "paper-sine", "amplitude": 4.0, "period": 1.0, "ramp": 0.412}


def toml_table(d):
    return "".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in d.items())


def test_far_apart_columns_are_their_own_runs(tmp_path):
    text = "[row]\ngaps = [30.0]\nrestitution = 0.5\n\n"
    for body in BODIES:
        text += "[[column]]\n" + toml_table(body) + "\n"
    text += "[excitation]\n" + toml_table(EXCITATION) + "\n[simulation]\nduration = 6.0\n"
    path = tmp_path / "row.toml"
    path.write_text(text)
    row = flexrock.simulate_row(path)
    assert row.impacts == [] and row.summary["n_impacts"] == 0
    for column, body in zip(row.columns, BODIES):
        alone = flexrock.simulate(
            flexrock.Model.from_dict(
                {"body": body, "excitation": EXCITATION, "simulation": {"duration": 6.0}}
            ),
            method="exact",
        )
        for name in ["t", "q", "qdot", "s", "r", "floor_acc", "F", "energy_residual"]:
            assert np.array_equal(getattr(column, name), getattr(alone, name)), name
        assert column.events == alone.events
        assert len(alone.events) > 2


def test_a_pair_strikes_and_every_impact_is_an_event_of_both_columns():
    row = flexrock.simulate_row(PAIR)
    assert len(row.columns) == 2 and len(row.impacts) == row.summary["n_impacts"] > 0
    for impact in row.impacts:
        assert impact["impulse"] > 0
        # Newton's law: the contact points leave at the restitution times their closing speed.
        assert impact["separating_velocity"] == pytest.approx(
            0.5 * impact["closing_velocity"], rel=1e-12
        )
        for column in row.columns:
            assert any(e["kind"] == "impact" and e["t"] == impact["t"] for e in column.events)
    assert [c.summary["n_impact"] for c in row.columns] == [len(row.impacts)] * 2
    assert "RowResult(2 columns" in repr(row)


def test_row_errors_name_the_key_or_the_argument(tmp_path):
    with pytest.raises(flexrock.FlexrockError, match=r"duration \(sets simulation.duration\) = -1"):
        flexrock.simulate_row(PAIR, duration=-1.0)
    bad = tmp_path / "bad.toml"
    bad.write_text(PAIR.read_text().replace("restitution = 0.5", "restitution = 2.0"))
    with pytest.raises(flexrock.FlexrockError, match=r"row.restitution = 2"):
        flexrock.simulate_row(bad)


FRICTION = PAIR.parent / "row-friction.toml"


def test_a_row_gives_every_contact_at_every_sample_and_friction_within_mu_p():
    row = flexrock.simulate_row(FRICTION)
    assert row.contacts and set(row.contacts[0]) == {
        "t", "contact", "state", "gap", "closing_velocity", "sliding_velocity", "force",
        "friction_force",
    }
    states = {c["state"] for c in row.contacts}
    assert {"sliding", "sticking"} <= states
    for c in row.contacts:
        assert abs(c["friction_force"]) <= 0.5 * max(c["force"], 0.0) * (1 + 1e-9) + 1e-9
    # The impact law's contacts have gaps and no forces (its forces are impulses).
    pair = flexrock.simulate_row(PAIR)
    assert all(c["force"] is None and c["gap"] > -1e-9 for c in pair.contacts)
