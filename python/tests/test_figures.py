"""flexrock.figures: the command line's figures on matplotlib axes, with its conventions.

Skipped only where matplotlib (the [figures] extra) is not installed; CI installs it."""

from pathlib import Path

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import flexrock  # noqa: E402

ff = pytest.importorskip("flexrock.figures")

ROOT = Path(__file__).resolve().parents[2]
MODEL = ROOT / "models" / "ichinose1986.toml"
PULSE = ROOT / "models" / "pulse-map.toml"


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def test_the_module_is_reached_from_the_package_lazily():
    assert flexrock.figures is ff
    with pytest.raises(AttributeError):
        flexrock.no_such_thing


def test_motion_draws_four_labelled_panels_on_one_time_axis_with_one_legend():
    result = flexrock.simulate(flexrock.Model.from_file(MODEL))
    axes = ff.plot_motion(result)
    assert len(axes) == 4
    assert [a.get_title(loc="left") for a in axes] == ["(a)", "(b)", "(c)", "(d)"]
    # One time axis: shared, labelled on the bottom panel only.
    assert all(a.get_shared_x_axes().joined(axes[0], a) for a in axes)
    assert [a.get_xlabel() for a in axes] == ["", "", "", "t (s)"]
    fig = axes[0].figure
    assert len(fig.legends) == 1
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    n_uplift = sum(e["kind"] == "uplift" for e in result.events)
    assert labels.count(f"uplift ({n_uplift})") == 1
    assert any(lab.startswith("±sₙ") for lab in labels)
    # One column wide, in inches.
    assert fig.get_size_inches()[0] == pytest.approx(85 / 25.4)
    # The markers sit on the velocity at each event, as the events give it.
    uplift = [ln for ln in axes[3].lines if ln.get_label().startswith("uplift")][0]
    assert np.allclose(uplift.get_ydata(), [e["qdot_before"] for e in result.events if e["kind"] == "uplift"])


def test_motion_draws_onto_the_users_axes_and_refuses_a_wrong_count():
    result = flexrock.simulate(flexrock.Model.from_file(MODEL), duration=1.0)
    fig, mine = plt.subplots(4, 1)
    drawn = ff.plot_motion(result, axes=mine)
    assert list(drawn) == list(mine)
    with pytest.raises(ValueError, match="axes"):
        ff.plot_motion(result, axes=mine[:2])


def test_a_figure_saves_as_a_pdf_with_its_fonts_embedded_as_truetype(tmp_path):
    result = flexrock.simulate(flexrock.Model.from_file(MODEL), duration=1.0)
    axes = ff.plot_motion(result, width="page")
    path = tmp_path / "motion.pdf"
    with ff.style():
        axes[0].figure.savefig(path)
    pdf = path.read_bytes()
    assert pdf.startswith(b"%PDF")
    # Type 42: TrueType fonts embedded (FontFile2), not Type 3 bitmaps.
    assert b"FontFile2" in pdf and b"/Type3" not in pdf


def test_ida_median_and_fractiles_are_the_order_statistics_of_the_records():
    # Three records at scales 1 and 2. At 1: 0.1, 0.2, 0.3: the median 0.2, the 16 % fractile
    # 0.1 + 0.32 (0.2 - 0.1) = 0.132, the 84 % one 0.2 + 0.68 (0.3 - 0.2) = 0.268. At 2 the
    # third record overturned (above every value): the median 0.5 and the 16 % fractile
    # 0.4 + 0.32 (0.5 - 0.4) = 0.432 stand; the 84 % fractile lies between 0.5 and the
    # overturning, so it is not drawn.
    curves = [
        ff.IdaCurve("a", [1, 2], [0.1, 0.4], [False, False]),
        ff.IdaCurve("b", [1, 2], [0.2, 0.5], [False, False]),
        ff.IdaCurve("c", [1, 2], [0.3, 1.0], [False, True]),
    ]
    ax = ff.plot_ida(curves=curves, x_label="PGA (g)")
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert np.allclose(lines["median"].get_ydata(), [0.2, 0.5])
    assert np.allclose(lines["16 % and 84 % fractiles"].get_ydata(), [0.132, 0.432])
    assert ax.get_xlabel() == "PGA (g)"
    # The legend names the records by the labels given, and the overturning once.
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts[:3] == ["a", "b", "c"]
    assert texts.count("first overturning of a record") == 1
    # The overturned record's line ends at |q| = B; its cross stands above it.
    assert lines["c"].get_ydata()[-1] == 1.0


def test_spectrum_keeps_the_stand_up_mark_off_the_body_s_line():
    model = flexrock.Model.from_file(PULSE)
    sweep = flexrock.sweep(
        model,
        {"excitation.period": [0.2, 0.8, 1.2]},
        find_min=("excitation.amplitude", 0.5, 15.0),
    )
    axes = ff.plot_spectrum(sweep)
    ax = axes[0]
    lines = {ln.get_label(): ln for ln in ax.lines}
    stands = lines["stands (no overturning found)"]
    assert stands.get_linestyle() == "None"
    body = lines["elastic body (this model)"]
    # The body's line has no value at 0.2 s (it stands there): a gap, not a point at the top.
    x, y = np.asarray(body.get_xdata(), float), np.asarray(body.get_ydata(), float)
    assert np.isnan(y[np.argmin(x)])
    assert "Housner block, small-angle eq." in lines
    assert ax.get_xscale() == "log"
