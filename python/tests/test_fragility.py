"""`flexrock fragility`'s fit, made again with scipy from the command's own per-record outputs."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

scipy_stats = pytest.importorskip("scipy.stats")
scipy_optimize = pytest.importorskip("scipy.optimize")

ROOT = Path(__file__).resolve().parents[2]
FLEXROCK = os.environ.get("FLEXROCK_BIN", str(ROOT / "target" / "release" / "flexrock"))


def run_fragility(out, *extra, bootstrap="0"):
    subprocess.run(
        [FLEXROCK, "fragility", str(ROOT / "models" / "elcentro1940.toml"),
         "--records", str(ROOT / "validation" / "records" / "records.list"),
         "--out", str(out), "--quiet", "--bootstrap", bootstrap, *extra],
        check=True, capture_output=True,
    )
    return json.loads((out / "fragility.json").read_text())


def test_the_censored_fit_is_scipys_maximum_likelihood(tmp_path):
    # Two of the five records never overturn up to scale 20: censored capacities.
    summary = run_fragility(tmp_path / "out", "--scale", "0.1:20", "--scan", "40")
    caps = summary["records"]
    observed = np.log([c["capacity"]["value"] for c in caps if c["capacity"]["kind"] == "observed"])
    censored = np.log([c["capacity"]["value"] for c in caps if c["capacity"]["kind"] == "censored"])
    assert len(censored) == 2 and len(observed) == 3

    def minus_log_likelihood(p):
        mu, beta = p[0], np.exp(p[1])
        return -(np.sum(scipy_stats.norm.logpdf(observed, mu, beta))
                 + np.sum(scipy_stats.norm.logsf(censored, mu, beta)))

    start = [observed.mean(), np.log(observed.std())]
    best = scipy_optimize.minimize(minus_log_likelihood, start, method="Nelder-Mead",
                                   options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 20000})
    fit = summary["fits"][0]
    assert fit["method"] == "censored-mle"
    assert fit["theta"] == pytest.approx(np.exp(best.x[0]), rel=1e-6)
    assert fit["beta"] == pytest.approx(np.exp(best.x[1]), rel=1e-6)


def test_the_uncensored_fit_is_scipys_lognormal_fit(tmp_path):
    # Sa at the body's period: capacities from the per-record table, fitted by scipy's own
    # maximum likelihood lognormal (location fixed at 0).
    summary = run_fragility(tmp_path / "out", "--scale", "0.1:20", "--scan", "40", "--im", "sa")
    observed = [c["capacity"]["value"] for c in summary["records"]
                if c["capacity"]["kind"] == "observed"]
    shape, _, scale = scipy_stats.lognorm.fit(observed, floc=0)
    # The same three records, refitted alone by the command, give scipy's numbers.
    kept = [c["path"] for c in summary["records"] if c["capacity"]["kind"] == "observed"]
    listing = tmp_path / "kept.list"
    listing.write_text("".join(f"{p}\n" for p in kept))
    out = tmp_path / "kept"
    subprocess.run(
        [FLEXROCK, "fragility", str(ROOT / "models" / "elcentro1940.toml"), "--records",
         str(listing), "--out", str(out), "--quiet", "--bootstrap", "0", "--scale", "0.1:20",
         "--scan", "40", "--im", "sa"],
        check=True, capture_output=True,
    )
    fit = json.loads((out / "fragility.json").read_text())["fits"][0]
    assert fit["method"] == "moments"
    assert fit["theta"] == pytest.approx(scale, rel=1e-6)
    assert fit["beta"] == pytest.approx(shape, rel=1e-6)


# The Python API: flexrock.fragility, flexrock.fit_capacities and flexrock.fit_stripes.

flexrock = pytest.importorskip("flexrock")
SUITE = ROOT / "validation" / "records" / "records.list"


def scipy_censored_fit(observed, censored):
    """theta and beta maximising the censored lognormal likelihood, by scipy."""
    observed, censored = np.log(observed), np.log(censored)

    def minus_log_likelihood(p):
        mu, beta = p[0], np.exp(p[1])
        return -(np.sum(scipy_stats.norm.logpdf(observed, mu, beta))
                 + np.sum(scipy_stats.norm.logsf(censored, mu, beta)))

    start = [observed.mean(), np.log(observed.std())]
    best = scipy_optimize.minimize(minus_log_likelihood, start, method="Nelder-Mead",
                                   options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 20000})
    return np.exp(best.x[0]), np.exp(best.x[1])


def test_fit_capacities_uncensored_is_the_closed_form():
    c = np.array([0.31, 0.52, 0.47, 0.9, 1.4, 0.66])
    fit = flexrock.fit_capacities(c)
    ln = np.log(c)
    assert fit["method"] == "moments" and fit["censored"] == 0 and fit["observed"] == 6
    assert fit["theta"] == pytest.approx(np.exp(ln.mean()), rel=1e-13)
    # The maximum likelihood beta: divisor n; beta_unbiased: divisor n - 1.
    assert fit["beta"] == pytest.approx(ln.std(ddof=0), rel=1e-13)
    assert fit["beta_unbiased"] == pytest.approx(ln.std(ddof=1), rel=1e-13)
    # scipy's own maximum likelihood lognormal (location fixed at 0) agrees.
    shape, _, scale = scipy_stats.lognorm.fit(c, floc=0)
    assert fit["theta"] == pytest.approx(scale, rel=1e-6)
    assert fit["beta"] == pytest.approx(shape, rel=1e-6)


def test_fit_capacities_censored_is_scipys_maximum_likelihood():
    c = np.array([0.31, 0.52, 0.47, 0.9, 1.4, 2.0, 2.0])
    censored = np.array([False, False, False, False, False, True, True])
    fit = flexrock.fit_capacities(c, censored)
    theta, beta = scipy_censored_fit(c[~censored], c[censored])
    assert fit["method"] == "censored-mle" and fit["censored"] == 2
    assert fit["beta_unbiased"] is None
    assert fit["theta"] == pytest.approx(theta, rel=1e-6)
    assert fit["beta"] == pytest.approx(beta, rel=1e-6)


def test_fit_stripes_is_scipys_binomial_maximum_likelihood():
    levels = np.array([0.1, 0.2, 0.3, 0.5, 0.8])
    records = np.array([20, 20, 20, 20, 18])
    damaged = np.array([1, 4, 9, 14, 17])
    fit = flexrock.fit_stripes(levels, records, damaged)

    def minus_log_likelihood(p):
        u = (np.log(levels) - p[0]) / np.exp(p[1])
        return -np.sum(damaged * scipy_stats.norm.logcdf(u)
                       + (records - damaged) * scipy_stats.norm.logcdf(-u))

    best = scipy_optimize.minimize(minus_log_likelihood, [np.log(0.3), np.log(0.5)],
                                   method="Nelder-Mead",
                                   options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 20000})
    assert fit["method"] == "stripes-mle"
    assert fit["theta"] == pytest.approx(np.exp(best.x[0]), rel=1e-6)
    assert fit["beta"] == pytest.approx(np.exp(best.x[1]), rel=1e-6)


def test_fits_refuse_bad_arrays_by_name():
    with pytest.raises(flexrock.FlexrockError, match="censored: has 1 values for 2"):
        flexrock.fit_capacities([0.3, 0.5], [True])
    with pytest.raises(flexrock.FlexrockError, match=r"capacity = -0.5: must be a positive"):
        flexrock.fit_capacities([0.3, -0.5])
    with pytest.raises(flexrock.FlexrockError, match=r"damaged\[1\] = 5: must be at most"):
        flexrock.fit_stripes([0.1, 0.2], [4, 4], [1, 5])
    with pytest.raises(flexrock.FlexrockError, match="no record reached the damage state"):
        flexrock.fit_stripes([0.1, 0.2], [4, 4], [0, 0])
    with pytest.raises(TypeError):
        flexrock.fit_stripes([0.1, 0.2], [4.5, 4], [1, 2])


def test_the_study_in_python_is_the_commands(tmp_path):
    summary = run_fragility(tmp_path / "out", "--scale", "0.1:20", "--scan", "40",
                            "--seed", "7", bootstrap="200")
    model = flexrock.Model.from_file(ROOT / "models" / "elcentro1940.toml")
    study = flexrock.fragility(model, SUITE, scale=(0.1, 20), scan=40, bootstrap=200, seed=7)
    fit = summary["fits"][0]
    assert (study.theta, study.beta, study.method) == (fit["theta"], fit["beta"], fit["method"])
    assert study.theta_interval == (fit["theta_interval"]["lo"], fit["theta_interval"]["hi"])
    assert study.beta_interval == (fit["beta_interval"]["lo"], fit["beta_interval"]["hi"])
    assert [r["capacity"] for r in study.summary["records"]] == \
        [r["capacity"] for r in summary["records"]]
    assert study.warnings == summary["warnings"]
    # The fit is scipy's censored maximum likelihood of the capacities the study returns.
    capacity, censored = study["capacity"], study["censored"]
    assert capacity.dtype == np.float64 and censored.dtype == np.bool_
    assert censored.sum() == 2
    theta, beta = scipy_censored_fit(capacity[~censored], capacity[censored])
    assert study.theta == pytest.approx(theta, rel=1e-6)
    assert study.beta == pytest.approx(beta, rel=1e-6)
    # The same fit from the arrays.
    again = flexrock.fit_capacities(capacity, censored)
    assert (again["theta"], again["beta"]) == (study.theta, study.beta)
    # Records named from their files' headers (the PEER AT2 title line), else by file name.
    labels = list(study["label"])
    assert "BORREGO MOUNTAIN" in labels[1] and "EL CENTRO ARRAY #9" in labels[1]
    assert "CHI-CHI" in labels[4] and "HEN" in labels[4]
    assert all(labels)


def test_the_study_to_pandas(tmp_path):
    pd = pytest.importorskip("pandas")
    model = flexrock.Model.from_file(ROOT / "models" / "elcentro1940.toml")
    study = flexrock.fragility(model, SUITE, scale=(0.1, 20), scan=40, bootstrap=0)
    frame = study.to_pandas()
    assert isinstance(frame, pd.DataFrame) and len(frame) == 5
    assert list(frame.columns) == study.columns
    assert frame["censored"].dtype == bool and frame["capacity"].dtype == np.float64
    assert frame["label"].dtype == "string"
    # A censored record has no overturning scale: NaN.
    assert frame.loc[frame["censored"], "min_overturning_scale"].isna().all()
    assert study.theta_interval is None and study.beta_interval is None


def test_the_study_refuses_bad_arguments_by_name(tmp_path):
    model = flexrock.Model.from_file(ROOT / "models" / "elcentro1940.toml")
    with pytest.raises(flexrock.FlexrockError, match="im = pgx: must be one of"):
        flexrock.fragility(model, SUITE, im="pgx")
    with pytest.raises(flexrock.FlexrockError, match="scale = 0:20: LO must be above 0"):
        flexrock.fragility(model, SUITE, scale=(0, 20))
    with pytest.raises(flexrock.FlexrockError, match="bootstrap = 1: must be 0"):
        flexrock.fragility(model, SUITE, bootstrap=1)
    with pytest.raises(flexrock.FlexrockError, match="period = 0.5: is the period of Sa"):
        flexrock.fragility(model, SUITE, period=0.5)
    with pytest.raises(flexrock.FlexrockError, match="records = .*no such file"):
        flexrock.fragility(model, tmp_path / "missing")
