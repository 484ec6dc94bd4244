"""The rigid block under vertical floor motion from Python: flexrock.rigid_block."""

import math

import pytest

import flexrock


def model(vertical=None):
    d = {
        "body": {"height": 2.0, "width": 0.4, "mass": 1000.0, "period": 0.05},
        "excitation": {"kind": "sine-pulse", "amplitude": 4.0, "period": 0.5, "tail": 2.0},
    }
    if vertical is not None:
        d["excitation"]["vertical"] = vertical
    return flexrock.Model.from_dict(d)


def test_the_first_uplift_is_where_the_horizontal_beats_the_raised_gravity():
    r = flexrock.rigid_block(model({"ratio": 0.5}), form="full")
    # 4 sin(w t) = (g B/H)(1 + 2 sin(w t)/g): sin(w t) = 1.962/3.6, w = 4 pi.
    expected = math.asin(1.962 / 3.6) / (4 * math.pi)
    assert r["first_uplift_s"] == pytest.approx(expected, abs=1e-12)
    assert r["block"]["equation"] == "full"
    assert r["vertical_excitation"] == {"kind": "ratio", "ratio": 0.5}
    assert r["events"][0]["event"] == "uplift" and r["events"][0]["to"] == "rock-left"
    # Without vertical motion the block lifts off earlier, at g B/H.
    plain = flexrock.rigid_block(model(), form="full")
    assert plain["first_uplift_s"] == pytest.approx(math.asin(1.962 / 4) / (4 * math.pi), abs=1e-12)
    assert plain["vertical_excitation"] is None


def test_a_floor_falling_faster_than_gravity_is_refused():
    with pytest.raises(flexrock.FlexrockError, match=r'\["vertical"\].*faster than gravity'):
        model({"ratio": 3.0})


def test_the_elastic_body_and_bad_arguments_are_refused_by_name():
    m = model({"ratio": 0.5})
    with pytest.raises(flexrock.FlexrockError, match="excitation.vertical"):
        flexrock.simulate(m)
    with pytest.raises(flexrock.FlexrockError, match="form"):
        flexrock.rigid_block(m, form="ful")
    with pytest.raises(flexrock.FlexrockError, match="restitution"):
        flexrock.rigid_block(m, restitution=1.5)


def test_the_smallest_overturning_pulse_of_the_reference_block():
    # The reference block's smallest overturning 0.8 s one-sine pulse: 2.998 (small angle) and
    # 3.033 m/s^2 (full), computed independently (core/tests/rigid_forms.rs).
    m = flexrock.Model.from_dict({
        "body": {"height": 4.0, "width": 0.7, "mass": 1000.0, "period": 0.05},
        "excitation": {"kind": "sine-pulse", "amplitude": 3.0, "period": 0.8, "tail": 5.0},
    })
    for form, expected in [("small-angle", 2.998), ("full", 3.033)]:
        found = flexrock.rigid_block(
            m, form=form, find_min=("excitation.amplitude", 2.0, 4.0), tol=1e-4)["find_min"]
        assert found["min_overturning"] == pytest.approx(expected, abs=1e-3)
        assert found["n_bands"] == 1 and found["key"] == "excitation.amplitude"
    assert flexrock.rigid_block(m)["find_min"] is None
    with pytest.raises(flexrock.FlexrockError, match="find_min"):
        flexrock.rigid_block(m, find_min=("excitation.amplitude", 4.0, 2.0))
    with pytest.raises(flexrock.FlexrockError, match="scan and tol"):
        flexrock.rigid_block(m, scan=10)
