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


def run_fragility(out, *extra):
    subprocess.run(
        [FLEXROCK, "fragility", str(ROOT / "models" / "elcentro1940.toml"),
         "--records", str(ROOT / "validation" / "records" / "records.list"),
         "--out", str(out), "--quiet", "--bootstrap", "0", *extra],
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
