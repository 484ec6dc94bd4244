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


def _study(capacities, theta, beta, im="pga", unit="g"):
    """A FragilityResult of the given capacities ((value, censored) pairs) and fit."""
    records = [
        {
            "path": f"r{i}.AT2",
            "label": f"record {i}",
            "im_unscaled": 0.3,
            "min_overturning_scale": None if c else v / 0.3,
            "capacity": {"value": v, "kind": "censored" if c else "observed"},
            "overturning_bands": "",
            "n_bands": 1,
        }
        for i, (v, c) in enumerate(capacities)
    ]
    fit = {
        "state": "overturning", "theta": theta, "beta": beta, "beta_unbiased": None,
        "method": "censored-mle", "theta_interval": None, "beta_interval": None,
        "fractile_16": theta * np.exp(-beta), "fractile_84": theta * np.exp(beta),
        "observed": sum(not c for _, c in capacities),
        "censored": sum(c for _, c in capacities),
    }
    return flexrock.FragilityResult(
        {"fits": [fit], "im": im, "im_unit": unit, "sa_period_s": None, "warnings": [],
         "records": records}
    )


STUDY = [(0.21, False), (0.28, False), (0.33, False), (0.6, True), (0.41, False), (0.52, False)]


def test_fragility_draws_the_lognormal_curve_on_the_users_axes():
    theta, beta = 0.36, 0.35
    fig, mine = plt.subplots()
    ax = ff.plot_fragility(_study(STUDY, theta, beta), ax=mine)
    assert ax is mine
    lines = {ln.get_label(): ln for ln in ax.lines}
    curve = lines["overturning: θ = 0.36 g, β = 0.35"]
    x, y = np.asarray(curve.get_xdata(), float), np.asarray(curve.get_ydata(), float)
    # At the median the curve is 1/2; at theta exp(beta) it is Phi(1) = 0.841345 (the normal
    # table); at theta exp(-beta), Phi(-1) = 0.158655.
    assert np.interp(theta, x, y) == pytest.approx(0.5, abs=1e-4)
    assert np.interp(theta * np.exp(beta), x, y) == pytest.approx(0.841345, abs=1e-4)
    assert np.interp(theta * np.exp(-beta), x, y) == pytest.approx(0.158655, abs=1e-4)
    assert y[x <= 0].tolist() == [0.0] * int(np.sum(x <= 0))
    assert ax.get_xlabel() == "PGA (g)"
    assert ax.get_ylabel() == "P(overturning | IM)"
    assert ax.get_ylim() == (0.0, 1.0)
    # The observed fractions: the i-th smallest observed capacity at i/n, n counting the
    # censored record, which is drawn only as a mark along the top.
    records = lines["records, i/n (n = 6)"]
    assert np.allclose(records.get_xdata(), [0.21, 0.28, 0.33, 0.41, 0.52])
    assert np.allclose(records.get_ydata(), np.arange(1, 6) / 6)
    assert "censored (1), capacity above" in lines
    # One legend, outside the data (to the right of the user's axes).
    legend = ax.get_legend()
    assert legend is not None and legend.get_bbox_to_anchor().x0 > ax.bbox.x1


def test_fragility_of_the_fits_of_capacities_and_of_stripes():
    scipy_stats = pytest.importorskip("scipy.stats")
    fit = flexrock.fit_capacities([0.3, 0.5, 0.8, 1.2])
    ax = ff.plot_fragility(fit, capacity=[0.3, 0.5, 0.8, 1.2], x_label="PGA (g)")
    curve = [ln for ln in ax.lines if ln.get_label().startswith("damage state")][0]
    x, y = np.asarray(curve.get_xdata(), float), np.asarray(curve.get_ydata(), float)
    assert np.allclose(y[x > 0], scipy_stats.lognorm.cdf(x[x > 0], s=fit["beta"], scale=fit["theta"]))
    assert ax.get_xlabel() == "PGA (g)"
    # A figure of its own: one figure legend above the panel.
    assert len(ax.figure.legends) == 1 and ax.get_legend() is None
    levels, n, z = [0.1, 0.2, 0.4], [20, 20, 20], [2, 9, 17]
    stripes = flexrock.fit_stripes(levels, records=n, damaged=z)
    ax = ff.plot_fragility(stripes, stripes=(levels, n, z), log=True)
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert np.allclose(lines["observed fraction damaged"].get_ydata(), [0.1, 0.45, 0.85])
    assert ax.get_xscale() == "log"
    assert ax.get_xlabel() == "IM"


def test_fragility_and_capacities_refuse_a_result_without_a_fit():
    with pytest.raises(ValueError, match=r"plot_fragility: dict holds no fit \(theta and beta\)"):
        ff.plot_fragility({"observed": 3})
    with pytest.raises(ValueError, match=r"beta = nan: a lognormal curve needs a finite theta > 0"):
        ff.plot_fragility({"theta": 0.3, "beta": float("nan")})
    with pytest.raises(ValueError, match=r"theta = -0.3"):
        ff.plot_fragility({"theta": -0.3, "beta": 0.4})
    with pytest.raises(ValueError, match="plot_capacities: dict holds no records' capacities"):
        ff.plot_capacities({"theta": 0.3, "beta": 0.4})


def test_capacities_name_each_record_and_mark_the_median_and_fractiles():
    theta, beta = 0.36, 0.35
    fig, mine = plt.subplots()
    ax = ff.plot_capacities(_study(STUDY, theta, beta), ax=mine)
    assert [t.get_text() for t in ax.get_yticklabels()] == [f"record {i}" for i in range(6)]
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert np.allclose(lines["median θ = 0.36 g"].get_xdata(), theta)
    fractiles = [ln for ln in ax.lines if ln.get_linestyle() == "--"]
    assert sorted(ln.get_xdata()[0] for ln in fractiles) == pytest.approx(
        [theta * np.exp(-beta), theta * np.exp(beta)])
    assert np.allclose(lines["censored (capacity above)"].get_xdata(), [0.6])
    assert ax.get_xlabel() == "PGA (g)"


def test_row_draws_the_floor_the_columns_and_the_gaps_with_the_impacts():
    row = flexrock.simulate_row(ROOT / "models" / "row-pair.toml", duration=1.0)
    axes = ff.plot_row(row)
    assert [a.get_ylabel() for a in axes] == ["a (m/s²)", "q (m)", "clear gap (mm)"]
    assert [a.get_xlabel() for a in axes] == ["", "", "t (s)"]
    assert [a.get_title(loc="left") for a in axes] == ["(a)", "(b)", "(c)"]
    gap = [ln for ln in axes[2].lines if ln.get_label().startswith("contact 0")][0]
    assert np.allclose(gap.get_ydata(), 1e3 * np.asarray(row.contacts["gap"], float))
    labels = [t.get_text() for t in axes[0].figure.legends[0].get_texts()]
    assert f"impact ({len(row.impacts)})" in labels
    fig, mine = plt.subplots(3, 1)
    assert list(ff.plot_row(row, axes=mine)) == list(mine)


def test_a_figure_legend_stays_inside_a_column_wide_figure():
    row = flexrock.simulate_row(ROOT / "models" / "row-pair.toml", duration=1.0)
    fig = ff.plot_row(row)[0].figure
    fig.canvas.draw()
    box = fig.legends[0].get_window_extent()
    assert box.x0 >= 0 and box.x1 <= fig.bbox.x1


def test_every_plot_is_listed_by_the_kind_of_result_it_draws():
    assert ff.PLOTS["fragility"] == (ff.plot_fragility, ff.plot_capacities)
    assert ff.PLOTS["row"] == (ff.plot_row,)
    listed = {f for plots in ff.PLOTS.values() for f in plots}
    assert {getattr(ff, n) for n in ff.__all__ if n.startswith("plot_")} == listed


def test_a_figure_made_here_saves_its_pdf_fonts_as_truetype_outside_the_style(tmp_path):
    # As the book shows it: savefig on the figure, with matplotlib's own settings in effect.
    ax = ff.plot_fragility(_study(STUDY, 0.36, 0.35))
    path = tmp_path / "fragility.pdf"
    ax.figure.savefig(path)
    pdf = path.read_bytes()
    assert b"FontFile2" in pdf and b"/Type3" not in pdf
