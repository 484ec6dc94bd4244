#!/usr/bin/env python3
"""flexrock sweep maps and spectra against the independent Python reference, cell by cell.

Run from the repository root:

    python3 validation/sweep/compare.py

The flexrock binary is $FLEXROCK, else target/release/flexrock.  The reference is
validation/independent/ichinose_ref.py (scipy DOP853, rtol 1e-12, atol 1e-14,
max_step 0.01 s, events polished), which knows nothing of flexrock; this script only
feeds both the same inputs (the values written in sweep.csv) and compares the outputs.

a. Maps: models/pulse-map.toml (reference body, one-sine pulse, 5 s tail) over
   excitation.period = lin:0.3:2:10 x excitation.amplitude = lin:1:8:10, once with the
   antisymmetric (sine) pulse and once with --set excitation.shape=symmetric (cosine).
   Compared per cell: overturned (must be equal), t_overturn, n_uplift, n_landing,
   max|q|/B.  Output: validation/sweep/map_comparison.csv.
b. Spectrum: --vary excitation.period=0.5,0.8,1.2,2 --find-min excitation.amplitude=0.5:15
   --scan 60 --tol 1e-4.  The reference checks that min_overturning overturns and
   safe_below does not, scans the same grid (0.5 + i 14.5/59) for the first overturning
   value, and bisects its own threshold to 1e-7 m/s^2.
   Output: validation/sweep/spectrum_comparison.csv.
"""

from __future__ import annotations

import csv
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from multiprocessing import Pool

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "independent"))

import numpy as np  # noqa: E402
import scipy  # noqa: E402

import ichinose_ref as ref  # noqa: E402

MODEL = "models/pulse-map.toml"
TAIL = 5.0
BODY = dict(height=4.0, width=0.7, depth=1.0, density=600.0, youngs_modulus=5.0e6,
            damping_ratio=0.05, gravity=9.81, constants="exact")
MAP_AXES = ["--vary", "excitation.period=lin:0.3:2:10",
            "--vary", "excitation.amplitude=lin:1:8:10"]
SPEC_PERIODS = "0.5,0.8,1.2,2"
SPEC_LO, SPEC_HI, SPEC_SCAN, SPEC_TOL = 0.5, 15.0, 60, 1e-4
# Tolerances for "agree" beyond the overturned flag (flexrock runs at rtol 1e-8)
TOL_T = 1e-5     # s
TOL_Q = 1e-5     # max|q|/B


def flexrock_bin():
    return os.environ.get("FLEXROCK", os.path.join("target", "release", "flexrock"))


# flexrock's side of the comparison, kept as it was read: validation/sweep/flexrock/<name>.csv is
# the sweep.csv of each command, and commands.txt the commands (OUT stands for their output
# directory), so that validation/check.sh can rerun them without the reference and compare.
FLEXROCK_SIDE = os.path.join(HERE, "flexrock")
SIDE_COMMANDS = []


def run_sweep(args, out):
    cmd = [flexrock_bin(), "sweep", MODEL, "--out", out] + args
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    name = os.path.basename(out)
    os.makedirs(FLEXROCK_SIDE, exist_ok=True)
    shutil.copyfile(os.path.join(out, "sweep.csv"), os.path.join(FLEXROCK_SIDE, name + ".csv"))
    SIDE_COMMANDS.append(" ".join(["flexrock", "sweep", MODEL, "--out", "OUT/" + name] + args))
    with open(os.path.join(out, "sweep.csv"), newline="") as fh:
        return cmd, list(csv.DictReader(fh))


def reference(shape, period, amplitude):
    """One reference run of the pulse-map model; summary quantities."""
    case = dict(body=BODY,
                excitation=dict(kind="sine-pulse", amplitude=amplitude, period=period,
                                cycles=1, shape=shape),
                simulation=dict(duration=period + TAIL, q0=0.0, qdot0=0.0))
    r = ref.simulate(case, samples=False)
    B, s_n = BODY["width"], r["constants"]["s_n"]
    ev = r["events"]
    gm = ref.grazing_margins(r)
    # peaks of |q| strictly inside a rocking excursion that stayed below B
    return dict(
        overturned=r["overturned"], t_overturn=r["t_overturn"],
        n_uplift=sum(e["kind"] == "uplift" for e in ev),
        n_landing=sum(e["kind"] == "landing" for e in ev),
        max_q_over_B=max(abs(r["max_q"]), abs(r["min_q"])) / B,
        peak_to_B=gm["peak_to_B"][0] / B, peak_to_sn=gm["peak_to_sn"][0] / s_n,
        min_event_qdot=gm["min_event_qdot"])


def closed_form_pulse_check():
    """The reference's sine-pulse implementation against the closed form of the linear
    damped oscillator (no uplift: A below the uplift acceleration), during the pulse and in
    the free vibration after it, for both shapes.  Max differences of the samples
    (t = 0, 0.25, ...: stop points of the reference) in q (m) and q' (m/s)."""
    out = {}
    for shape, Tp, A in (("antisymmetric", 0.3, 1.0), ("symmetric", 0.3, 1.0),
                         ("antisymmetric", 2.0, 0.4), ("symmetric", 1.1, 0.4)):
        case = dict(body=BODY, excitation=dict(kind="sine-pulse", amplitude=A, period=Tp,
                                               cycles=1, shape=shape),
                    simulation=dict(duration=Tp + TAIL, q0=0.0, qdot0=0.0))
        r = ref.simulate(case, samples=True)
        assert not r["events"], "closed-form check needs a run without uplift"
        k = r["constants"]
        w, h, b1 = k["omega"], k["h"], k["beta1"]
        W = 2 * math.pi / Tp
        phi = math.pi / 2 if shape == "symmetric" else 0.0
        # q'' + 2 h w q' + w^2 q = -b1 A sin(W t + phi) on [0, Tp); particular X sin + Y cos
        den = (w**2 - W**2) ** 2 + (2 * h * w * W) ** 2
        X = -b1 * A * (w**2 - W**2) / den
        Y = -b1 * A * (-2 * h * w * W) / den
        wd = w * math.sqrt(1 - h**2)

        def free(C1, C2, tau):  # e^{-h w tau}(C1 cos wd tau + C2 sin wd tau) and derivative
            e, c, s_ = math.exp(-h * w * tau), math.cos(wd * tau), math.sin(wd * tau)
            return (e * (C1 * c + C2 * s_),
                    e * (-h * w * (C1 * c + C2 * s_) + wd * (-C1 * s_ + C2 * c)))

        C1 = -(Y * math.cos(phi) + X * math.sin(phi))
        C2 = (-(X * W * math.cos(phi) - Y * W * math.sin(phi)) + h * w * C1) / wd

        def state(t):
            t_ = min(t, Tp)
            hq, hv = free(C1, C2, t_)
            q = hq + X * math.sin(W * t_ + phi) + Y * math.cos(W * t_ + phi)
            v = hv + X * W * math.cos(W * t_ + phi) - Y * W * math.sin(W * t_ + phi)
            if t <= Tp:
                return q, v
            return free(q, (v + h * w * q) / wd, t - Tp)

        eq = max(abs(sq - state(st)[0]) for st, sq, _ in r["samples"])
        ev = max(abs(sv - state(st)[1]) for st, _, sv in r["samples"])
        out[f"{shape} Tp={Tp:g} A={A:g}"] = (eq, ev)
    return out


def _ref_job(args):
    return reference(*args)


def fbool(s):
    return s.strip().lower() == "true"


def ffloat(s):
    return float(s) if s.strip() != "" else None


def threshold_near(shape, period, amp, pool, width=0.02):
    """For a cell whose flags disagree: the reference's overturning threshold within
    amp +- width (bisection to 1e-9 m/s^2), or None if the flag does not change there."""
    lo, hi = amp - width, amp + width
    flo, fhi = pool.map(_ref_job, [(shape, period, lo), (shape, period, hi)])
    if flo["overturned"] == fhi["overturned"]:
        return None
    olo = flo["overturned"]
    while hi - lo > 1e-9:
        mid = 0.5 * (lo + hi)
        if reference(shape, period, mid)["overturned"] == olo:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def compare_maps(pool, tmp):
    rows = []
    cmds = []
    for shape, extra in (("antisymmetric", []),
                         ("symmetric", ["--set", "excitation.shape=symmetric"])):
        cmd, fr = run_sweep(MAP_AXES + extra + ["--quiet"], os.path.join(tmp, f"map-{shape}"))
        cmds.append(cmd)
        jobs = [(shape, float(r["excitation.period"]), float(r["excitation.amplitude"]))
                for r in fr]
        refs = pool.map(_ref_job, jobs)
        for r, (_, Tp, A), q in zip(fr, jobs, refs):
            assert r["status"] == "ok", r
            f_over = fbool(r["overturned"])
            f_t = ffloat(r["t_overturn"])
            row = dict(
                shape=shape, point=int(r["point"]), period=r["excitation.period"],
                amplitude=r["excitation.amplitude"],
                flexrock_overturned=f_over, ref_overturned=q["overturned"],
                flexrock_t_overturn=f_t, ref_t_overturn=q["t_overturn"],
                d_t_overturn=(f_t - q["t_overturn"]) if (f_over and q["overturned"]) else None,
                flexrock_n_uplift=int(r["n_uplift"]), ref_n_uplift=q["n_uplift"],
                flexrock_n_landing=int(r["n_landing"]), ref_n_landing=q["n_landing"],
                flexrock_max_q_over_B=float(r["max_abs_q_over_B"]),
                ref_max_q_over_B=q["max_q_over_B"],
                d_max_q_over_B=float(r["max_abs_q_over_B"]) - q["max_q_over_B"],
                ref_peak_to_B_over_B=q["peak_to_B"], ref_peak_to_sn_over_sn=q["peak_to_sn"],
                ref_min_event_qdot=q["min_event_qdot"],
                ref_threshold_nearby=None)
            row["same_overturned"] = f_over == q["overturned"]
            row["same_events"] = (row["flexrock_n_uplift"] == q["n_uplift"]
                                  and row["flexrock_n_landing"] == q["n_landing"])
            row["agree"] = (row["same_overturned"] and row["same_events"]
                            and abs(row["d_max_q_over_B"]) <= TOL_Q
                            and (row["d_t_overturn"] is None or abs(row["d_t_overturn"]) <= TOL_T))
            rows.append(row)
    for row in rows:
        if not row["same_overturned"]:
            row["ref_threshold_nearby"] = threshold_near(
                row["shape"], float(row["period"]), float(row["amplitude"]), pool)
    return cmds, rows


def compare_spectrum(pool, tmp):
    args = ["--vary", f"excitation.period={SPEC_PERIODS}",
            "--find-min", f"excitation.amplitude={SPEC_LO:g}:{SPEC_HI:g}",
            "--scan", str(SPEC_SCAN), "--tol", f"{SPEC_TOL:g}", "--quiet"]
    cmd, fr = run_sweep(args, os.path.join(tmp, "spectrum"))
    grid = [SPEC_LO + i * (SPEC_HI - SPEC_LO) / (SPEC_SCAN - 1) for i in range(SPEC_SCAN)]
    rows = []
    for r in fr:
        Tp = float(r["excitation.period"])
        mo, sb = ffloat(r["min_overturning"]), ffloat(r["safe_below"])
        scan = pool.map(_ref_job, [("antisymmetric", Tp, A) for A in grid])
        flags = [s["overturned"] for s in scan]
        first = next((A for A, f in zip(grid, flags) if f), None)
        bands = []  # runs of consecutive overturning scan values, [lo, hi]
        for j, (A, f) in enumerate(zip(grid, flags)):
            if f and (j == 0 or not flags[j - 1]):
                bands.append([A, A])
            elif f:
                bands[-1][1] = A
        ref_bands = ";".join(f"{b[0]:.15g}-{b[1]:.15g}" for b in bands)
        fr_first = float(r["overturning_bands"].split("-")[0]) if r["overturning_bands"] else None
        at_mo, at_sb = pool.map(_ref_job, [("antisymmetric", Tp, mo), ("antisymmetric", Tp, sb)])
        # the reference's own threshold: bisection between the scan value before the first
        # overturning one and that one, to 1e-7 m/s^2
        thr = None
        if first is not None and first > SPEC_LO:
            i = grid.index(first)
            lo, hi = grid[i - 1], grid[i]
            while hi - lo > 1e-7:
                mid = 0.5 * (lo + hi)
                if reference("antisymmetric", Tp, mid)["overturned"]:
                    hi = mid
                else:
                    lo = mid
            thr = hi
        rows.append(dict(
            period=r["excitation.period"],
            flexrock_min_overturning=mo, flexrock_safe_below=sb,
            ref_overturns_at_min_overturning=at_mo["overturned"],
            ref_stands_at_safe_below=not at_sb["overturned"],
            ref_max_q_over_B_at_safe_below=at_sb["max_q_over_B"],
            flexrock_first_scan_overturning=fr_first, ref_first_scan_overturning=first,
            same_first_scan=(fr_first is not None and first is not None
                             and abs(fr_first - first) < 1e-9),
            flexrock_overturning_bands=r["overturning_bands"], ref_overturning_bands=ref_bands,
            ref_threshold=thr,
            d_threshold=(mo - thr) if (thr is not None and mo is not None) else None,
            ref_threshold_in_bracket=(thr is not None and sb is not None and mo is not None
                                      and sb < thr <= mo),
            flexrock_t_overturn=ffloat(r["t_overturn"]),
            ref_t_overturn_at_min_overturning=at_mo["t_overturn"]))
    return cmd, rows


def write_csv(path, rows):
    keys = list(rows[0].keys())
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(keys)
        for r in rows:
            w.writerow(["" if r[k] is None else (f"{r[k]:.15g}" if isinstance(r[k], float) else r[k])
                        for k in keys])


def main():
    t0 = time.time()
    print(f"Python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}; "
          f"flexrock {flexrock_bin()}")
    print("== reference sine pulse vs closed form (linear oscillator, no uplift), "
          "max sample differences q (m), q' (m/s):")
    for key, (eq, ev) in closed_form_pulse_check().items():
        print(f"  {key:28s} {eq:.1e} {ev:.1e}")
    with tempfile.TemporaryDirectory() as tmp, Pool() as pool:
        cmds, rows = compare_maps(pool, tmp)
        t_map = time.time() - t0
        scmd, srows = compare_spectrum(pool, tmp)
    t_all = time.time() - t0
    with open(os.path.join(FLEXROCK_SIDE, "commands.txt"), "w") as fh:
        fh.write("".join(c + "\n" for c in SIDE_COMMANDS))
    write_csv(os.path.join(HERE, "map_comparison.csv"), rows)
    write_csv(os.path.join(HERE, "spectrum_comparison.csv"), srows)

    print("== maps: " + " | ".join(" ".join(c[1:]) for c in cmds))
    for shape in ("antisymmetric", "symmetric", None):
        rs = [r for r in rows if shape is None or r["shape"] == shape]
        n = len(rs)
        same_o = sum(r["same_overturned"] for r in rs)
        same_e = sum(r["same_events"] for r in rs)
        both = [r for r in rs if r["d_t_overturn"] is not None]
        dt = max((abs(r["d_t_overturn"]) for r in both), default=0.0)
        dq = max(abs(r["d_max_q_over_B"]) for r in rs if r["same_overturned"])
        agree = sum(r["agree"] for r in rs)
        print(f"  {shape or 'all':14s} cells {n}: overturned flag equal in {same_o}/{n} "
              f"({sum(r['ref_overturned'] for r in rs)} overturn in the reference, "
              f"{sum(r['flexrock_overturned'] for r in rs)} in flexrock); "
              f"uplift and landing counts equal in {same_e}/{n}; "
              f"max |d t_overturn| = {dt:.2e} s over {len(both)} cells; "
              f"max |d max|q|/B| = {dq:.2e}; all within tolerances in {agree}/{n}")
    bad = [r for r in rows if not r["agree"]]
    if bad:
        print("  cells that differ:")
    for r in bad:
        thr = r["ref_threshold_nearby"]
        print(f"    {r['shape']} Tp={r['period']} A={r['amplitude']}: overturned "
              f"{r['flexrock_overturned']}/{r['ref_overturned']} (flexrock/ref), uplifts "
              f"{r['flexrock_n_uplift']}/{r['ref_n_uplift']}, landings "
              f"{r['flexrock_n_landing']}/{r['ref_n_landing']}, max|q|/B "
              f"{r['flexrock_max_q_over_B']:.6f}/{r['ref_max_q_over_B']:.6f}; ref margins: "
              f"peak to B {r['ref_peak_to_B_over_B']:.2e} B, peak to s_n "
              f"{r['ref_peak_to_sn_over_sn']:.2e} s_n, min |q'| at events "
              f"{r['ref_min_event_qdot']:.2e} m/s"
              + (f"; ref threshold at A = {thr:.9f} ({thr - float(r['amplitude']):+.2e})"
                 if thr is not None else ""))
    worst = sorted(rows, key=lambda r: -abs(r["d_max_q_over_B"]) if r["same_overturned"] else 0)[:3]
    print("  worst max|q|/B differences: " + "; ".join(
        f"{r['shape']} Tp={r['period']} A={r['amplitude']}: {r['d_max_q_over_B']:+.2e}" for r in worst))
    both = sorted((r for r in rows if r["d_t_overturn"] is not None),
                  key=lambda r: -abs(r["d_t_overturn"]))[:3]
    print("  worst t_overturn differences: " + "; ".join(
        f"{r['shape']} Tp={r['period']} A={r['amplitude']}: {r['d_t_overturn']:+.2e} s" for r in both))
    near = sorted(rows, key=lambda r: r["ref_peak_to_B_over_B"])[:3]
    print("  closest grazes of q = B among all cells (reference peak of |q| from B, over B): " + "; ".join(
        f"{r['shape']} Tp={r['period']} A={r['amplitude']}: {r['ref_peak_to_B_over_B']:.2e}" for r in near))
    near = sorted(rows, key=lambda r: r["ref_peak_to_sn_over_sn"])[:3]
    print("  closest grazes of q = s_n: " + "; ".join(
        f"{r['shape']} Tp={r['period']} A={r['amplitude']}: {r['ref_peak_to_sn_over_sn']:.2e}" for r in near))

    print("== spectrum: " + " ".join(scmd[1:]))
    for r in srows:
        print(f"  Tp={r['period']}: flexrock [{r['flexrock_safe_below']:.9f}, "
              f"{r['flexrock_min_overturning']:.9f}]; ref overturns at min_overturning: "
              f"{r['ref_overturns_at_min_overturning']}, stands at safe_below: "
              f"{r['ref_stands_at_safe_below']}; first overturning scan value flexrock "
              f"{r['flexrock_first_scan_overturning']} ref {r['ref_first_scan_overturning']} "
              f"(same: {r['same_first_scan']}); bands flexrock {r['flexrock_overturning_bands']} "
              f"ref {r['ref_overturning_bands']}; ref threshold {r['ref_threshold']:.9f}, "
              f"flexrock min_overturning - ref = {r['d_threshold']:+.2e} (inside flexrock's "
              f"bracket: {r['ref_threshold_in_bracket']}); t_overturn at min_overturning "
              f"flexrock {r['flexrock_t_overturn']:.6f} ref "
              f"{r['ref_t_overturn_at_min_overturning']:.6f} s")
    ok = sum(r["ref_overturns_at_min_overturning"] and r["ref_stands_at_safe_below"]
             and r["same_first_scan"] and r["ref_threshold_in_bracket"] for r in srows)
    print(f"  brackets confirmed by the reference: {ok}/{len(srows)}")
    print(f"== wrote validation/sweep/map_comparison.csv ({len(rows)} rows), "
          f"validation/sweep/spectrum_comparison.csv ({len(srows)} rows); "
          f"took {t_all:.0f} s (maps {t_map:.0f} s) on {os.cpu_count()} cores")
    n_ok = sum(r["same_overturned"] for r in rows)
    return 0 if (n_ok == len(rows) and ok == len(srows)) else 1


if __name__ == "__main__":
    sys.exit(main())
