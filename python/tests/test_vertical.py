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
