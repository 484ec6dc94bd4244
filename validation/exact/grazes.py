#!/usr/bin/env python3
"""Knife-edge grazes: models whose q comes within a hair of a guard, their 40-digit solutions,
and how flexrock's exact method reports them.

    python3 validation/exact/grazes.py make [FAMILY...]     # grazes/cases/*.toml, grazes/margins.json
    python3 validation/exact/grazes.py reference [FAMILY...] # grazes/reference/<case>/ (mp_exact.py)
    python3 validation/exact/grazes.py check [FLEXROCK]     # grazes/results.md

Each family starts from a base model and a parameter that decides whether an event happens: the
amplitude (or a record's scale) at which q first touches s_n, the amplitude of a pulse or the
initial speed at which the body just overturns, and the initial speed at which a rocking body
just lands. The threshold is found at 40 digits: for an uplift from rest, where the motion is
linear in the amplitude, as s_n over the peak of the unit response; otherwise by bisection on
the outcome of mp_exact.py's solution, which reads the parameter as a double, so that the
threshold lies between two neighbouring doubles and the unshifted case is the one at which the
event happens. The cases are the doubles nearest the threshold moved by a few shares or ulps,
written with every digit of the double, so that flexrock and mp_exact.py solve the same model. margins.json holds, for each case, how far the hump of q goes beyond the guard
(negative short of it) in the 40-digit solution: s_n times the share for an uplift from rest,
otherwise the extremum nearest the guard or, where the event happens, v^2/(2|q''|) at it.

`check` runs `flexrock run` on every case and writes a table: the true margin, whether the run
warns of a graze, the rounding it reports, whether its sequence of events is the exact one, and
the largest ratio of a true error to the run's own estimate of it (events, both peaks and their
times; at most 1 where every estimate covers its error).
"""

from __future__ import annotations

import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib
from decimal import Decimal

import mpmath as mp
from mpmath import mpf

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mp_exact  # noqa: E402

ROOT = os.path.join(HERE, "grazes")
CASES = os.path.join(ROOT, "cases")
REFERENCE = os.path.join(ROOT, "reference")
MARGINS = os.path.join(ROOT, "margins.json")

PAPER_BODY = """[body]
height = 4.0
width = 0.7
depth = 1.0
density = 600.0
youngs_modulus = 5.0e6
damping_ratio = 0.05
"""
BINARY_BODY = """[body]
height = 4.0
width = 0.75
density = 600.0
youngs_modulus = 5000000.0
gravity = 9.8125
damping_ratio = 0.0625
"""
SOLVER = """
[solver]
method = "exact"
output_dt = 0.005
"""

# Each family: the model with {p} for the parameter, the guard whose event it decides, how the
# threshold is found ("linear": an uplift from rest; else a bracket (lo, hi) whose outcomes
# differ, with the outcome function), and the relative shifts of the parameter from it.
LINEAR_SHIFTS = [0, 1, -1, 1e-15, -1e-15, 1e-14, -1e-14, 1e-13, -1e-13, 1e-12, -1e-12, 1e-11]
BISECT_SHIFTS = [0, 1, -1, 1e-14, -1e-14, 1e-12, -1e-12, 1e-10, -1e-10, 1e-8, -1e-8]
FAMILIES = {
    # The paper's body under a 2 s sine (harmonic-2s+1ulp: the example of the exact method's page).
    "harmonic-2s": dict(
        model=PAPER_BODY + '\n[excitation]\nkind = "harmonic"\namplitude = {p}\nperiod = 2.0\n'
        "\n[simulation]\nduration = 6.0\n",
        guard="uplift", threshold="linear", small="0.01", shifts=LINEAR_SHIFTS),
    "harmonic-1.2s": dict(
        model=PAPER_BODY + '\n[excitation]\nkind = "harmonic"\namplitude = {p}\nperiod = 1.2\n'
        "\n[simulation]\nduration = 6.0\n",
        guard="uplift", threshold="linear", small="0.01", shifts=LINEAR_SHIFTS),
    "pulse-1s": dict(
        model=PAPER_BODY + '\n[excitation]\nkind = "sine-pulse"\namplitude = {p}\nperiod = 1.0\n'
        'cycles = 1\nshape = "antisymmetric"\n\n[simulation]\nduration = 5.0\n',
        guard="uplift", threshold="linear", small="0.01", shifts=LINEAR_SHIFTS),
    "elcentro": dict(
        model=PAPER_BODY + '\n[excitation]\nkind = "record"\npath = "../../../records/elCentro.AT2"\n'
        'format = "peer-at2"\nunits = "g"\nscale = {p}\nend = 12.0\n\n[simulation]\nduration = 15.0\n',
        guard="uplift", threshold="linear", small="0.01", shifts=LINEAR_SHIFTS),
    # A pulse that just overturns the body (or just fails to).
    "pulse-overturn": dict(
        model=PAPER_BODY + '\n[excitation]\nkind = "sine-pulse"\namplitude = {p}\nperiod = 0.8\n'
        'cycles = 1\nshape = "antisymmetric"\n\n[simulation]\nduration = 20.0\n',
        guard="overturn", threshold=("3.0", "4.0"), shifts=BISECT_SHIFTS),
    # Free rocking from 0.3 m at the speed that just carries the body over.
    "free-overturn": dict(
        model=PAPER_BODY + '\n[excitation]\nkind = "free"\n\n[simulation]\nduration = 20.0\n'
        "q0 = 0.3\nqdot0 = {p}\n",
        guard="overturn", threshold=("0.0", "2.0"), shifts=BISECT_SHIFTS),
    # A rocking body that comes back to s_n at the speed that just lands it, within 0.7 s (or
    # just does not, and turns back up to land later).
    "landing": dict(
        model=BINARY_BODY + '\n[excitation]\nkind = "sine-pulse"\namplitude = -3.0\nperiod = 4.0\n'
        'cycles = 1\nshape = "symmetric"\n\n[simulation]\nduration = 6.0\nq0 = 0.3\nqdot0 = {p}\n',
        guard="landing", threshold=("-0.8355", "-0.85"), before=0.7, shifts=BISECT_SHIFTS),
}


def exact_digits(x: float) -> str:
    """Every digit of the double x, so that its decimal is the double itself."""
    text = format(Decimal(x), "f")
    return text if "." in text else text + ".0"


def solve(text: str, dps: int = 40):
    """mp_exact's solution of a model given as text (paths relative to grazes/cases/): its
    constants, floor motion, solver, events, extrema and final mode."""
    mp.mp.dps = dps
    model = tomllib.loads(text)
    k = mp_exact.constants(model["body"])
    exc = mp_exact.Excitation(model["excitation"], CASES)
    sim = model["simulation"]
    solver = mp_exact.Solver(k, exc)
    q0, v0 = mp_exact.M(sim.get("q0", 0.0)), mp_exact.M(sim.get("qdot0", 0.0))
    events, extrema, mode, _, _ = solver.run(q0, v0, mp_exact.M(sim["duration"]))
    return k, exc, solver, events, extrema, mode


def happened(family: dict, events, mode) -> bool:
    if family["guard"] == "overturn":
        return mode == mp_exact.OVER
    first = events[0] if events else None
    return (first is not None and first["kind"] == family["guard"]
            and first["t"] < family.get("before", math.inf))


def threshold(name: str, family: dict) -> tuple[mpf, float]:
    """The parameter at which the family's event appears, to 40 digits, and the double the
    family's unshifted case is."""
    if family["threshold"] == "linear":
        k, _, _, events, extrema, _ = solve(family["model"].format(p=family["small"]))
        assert not events, f"{name}: the small response lifts off"
        peak = max(abs(q) for _, q, _ in extrema)
        p = mpf(family["small"]) * k["s_n"] / peak
        return p, float(p)
    lo, hi = (mpf(x) for x in family["threshold"])

    def outcome(p):
        _, _, _, events, _, mode = solve(family["model"].format(p=mp.nstr(p, 45)), 30)
        return happened(family, events, mode)

    assert outcome(lo) != outcome(hi), f"{name}: the bracket does not hold the threshold"
    low = outcome(lo)
    while abs(hi - lo) > mpf("1e-28") * abs(hi):
        mid = (lo + hi) / 2
        if outcome(mid) == low:
            lo = mid
        else:
            hi = mid
    # mp_exact.py reads the parameter as a double, as flexrock does: the bisection ends at the
    # midpoint of two neighbouring doubles, which rounds to either. The unshifted case is the
    # one at which the event happens.
    return (lo + hi) / 2, float(lo if low else hi)


def shifted(p: mpf | float, shift) -> float:
    """The double nearest p moved by `shift`: a relative share, or (an integer) that many doubles."""
    if isinstance(shift, int):
        x = float(p)
        for _ in range(abs(shift)):
            x = math.nextafter(x, math.inf if shift > 0 else -math.inf)
        return x
    return float(p * (1 + mpf(shift)))


def floor_acceleration(exc, t):
    for t0, t1, piece in exc.pieces:
        if t >= t0 and (t1 is None or t < t1):
            if piece[0] == "trig":
                _, a_s, a_c, w = piece
                return a_s * mp.sin(w * t) + a_c * mp.cos(w * t)
            if piece[0] == "poly":
                return mp.polyval(piece[1][::-1], t - t0) if piece[1] else mpf(0)
    raise ValueError("no piece")


def margin(family: dict, text: str) -> mpf:
    """How far the hump of q goes beyond the family's guard in the 40-digit solution, m."""
    k, exc, solver, events, extrema, _ = solve(text)
    kind = family["guard"]
    best, crossed = None, None
    for e in events:
        if e["kind"] == kind == "overturn":
            # A saddle passage, not a hump: no margin beyond.
            return None
        if e["kind"] == kind:
            mode = e["frm"]
            c, stiffness, beta, shift = solver.mode_coeffs(mode)
            v = e["qdot_before"]
            acc = -c * v - stiffness * (e["q"] - shift) - beta * floor_acceleration(exc, e["t"])
            best, crossed = v * v / (2 * abs(acc)), e["t"]
            break
    sources = {"uplift": [mp_exact.PRE], "landing": [mp_exact.RR, mp_exact.RL],
               "overturn": [mp_exact.RR, mp_exact.RL]}[kind]
    for t, q, mode in extrema:
        if mode not in sources or (crossed is not None and t >= crossed):
            continue
        for g_kind, _, level, sense in solver.guards(mode):
            if g_kind == kind and sense * (q - level) < 0:
                m = sense * (q - level)
                if best is None or abs(m) < abs(best):
                    best = m
    return best


def make(names):
    os.makedirs(CASES, exist_ok=True)
    margins = json.load(open(MARGINS)) if os.path.exists(MARGINS) else {}
    for name in names or FAMILIES:
        family = FAMILIES[name]
        p, first = threshold(name, family)
        print(f"{name}: threshold {mp.nstr(p, 30)}", flush=True)
        for shift in family["shifts"]:
            x = shifted(first, shift) if isinstance(shift, int) else shifted(p, shift)
            label = f"{shift:+d}ulp" if isinstance(shift, int) else f"{shift:+.0e}"
            case = f"{name}{'' if shift == 0 else label}"
            text = family["model"].format(p=exact_digits(x))
            header = (f"# Knife-edge graze ({name}): the parameter is the double nearest the "
                      f"threshold {mp.nstr(p, 25)}\n# moved by {label if shift else 'nothing'} "
                      f"(validation/exact/grazes.py make).\n")
            with open(os.path.join(CASES, case + ".toml"), "w") as fh:
                fh.write(header + text + SOLVER)
            if family["threshold"] == "linear":
                mp.mp.dps = 40
                s_n = mp_exact.constants(tomllib.loads(text)["body"])["s_n"]
                m = s_n * (mpf(exact_digits(x)) / p - 1)
            else:
                m = margin(family, text)
            margins[case] = dict(guard=family["guard"], margin=None if m is None else mp.nstr(m, 6))
            print(f"  {case}: margin {margins[case]['margin']} m", flush=True)
        with open(MARGINS, "w") as fh:
            json.dump(margins, fh, indent=1, sort_keys=True)
            fh.write("\n")


def reference(families):
    for case in sorted(os.listdir(CASES)):
        name = case.removesuffix(".toml")
        family = next(f for f in sorted(FAMILIES, key=len, reverse=True) if name.startswith(f))
        if case.endswith(".toml") and (not families or family in families):
            mp_exact.main([os.path.join(CASES, case), "--out", os.path.join(REFERENCE, name)])


def check(flexrock: str):
    margins = json.load(open(MARGINS))
    rows = []
    for case in sorted(margins):
        with tempfile.TemporaryDirectory() as out:
            subprocess.run([flexrock, "run", os.path.join(CASES, case + ".toml"), "--out", out,
                            "--timings-apart"], check=True, capture_output=True)
            summary = json.load(open(os.path.join(out, "summary.json")))
            events = list(csv.DictReader(open(os.path.join(out, "events.csv"))))
        ref_events = list(csv.DictReader(open(os.path.join(REFERENCE, case, "events.csv"))))
        peaks = json.load(open(os.path.join(REFERENCE, case, "peaks.json")))
        estimate = summary["error_estimate"]
        same = [(e["kind"], e["to"]) for e in events] == [(e["kind"], e["to"]) for e in ref_events]
        ratios = []
        for e, r, err in zip(events, ref_events, estimate["event_time"]):
            if (e["kind"], e["to"]) != (r["kind"], r["to"]):
                break
            ratios.append(abs(float(Decimal(e["t"]) - Decimal(r["t"]))) / err)
        if not same:
            # The first event the sequences differ at must be uncertain in the run's estimate.
            first = next((i for i, (e, r) in enumerate(zip(events, ref_events))
                          if (e["kind"], e["to"]) != (r["kind"], r["to"])),
                         min(len(events), len(ref_events)))
            t_first = min([float(x[first]["t"]) for x in (events, ref_events) if len(x) > first])
            covered = (estimate.get("uncertain_from") is not None
                       and estimate["uncertain_from"] <= t_first)
            ratios.append(0.0 if covered else float("inf"))
        for key in ["max_q", "t_max_q", "min_q", "t_min_q"]:
            true = abs(float(Decimal(str(summary[key])) - Decimal(str(peaks[key]))))
            ratios.append(true / estimate[key] if estimate[key] > 0 else float("inf") * (true > 0))
        graze = estimate["grazes"][0] if estimate.get("grazes") else None
        rows.append((case, margins[case]["margin"], graze is not None or estimate.get("uncertain_from")
                     is not None, graze["rounding"] if graze else None, same, max(ratios)))
    lines = ["| case | true margin (m) | warns | rounding (m) | sequence exact | largest error / estimate |",
             "|---|---|---|---|---|---|"]
    for case, m, warns, rounding, same, ratio in rows:
        lines.append(f"| {case} | {'crossed' if m is None else f'{float(m):.1e}'} | {'yes' if warns else 'no'} | "
                     f"{'-' if rounding is None else f'{rounding:.1e}'} | {'yes' if same else 'no'} | "
                     f"{ratio:.3g} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(ROOT, "results.md"), "w") as fh:
        fh.write(text)
    print(text)


def main(argv):
    if not argv or argv[0] not in ("make", "reference", "check"):
        print(__doc__, file=sys.stderr)
        return 2
    if argv[0] == "make":
        make(argv[1:])
    elif argv[0] == "reference":
        reference(argv[1:])
    else:
        check(argv[1] if len(argv) > 1 else "target/release/flexrock")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
