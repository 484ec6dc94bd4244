#!/usr/bin/env python3
"""Compare a flexrock run with the exact multiprecision solution of the same model file.

    python3 compare.py RUN_DIR MP_DIR [--tol 1e-13] [--json FILE] [--quiet]

RUN_DIR is what `flexrock run MODEL --out RUN_DIR` wrote (events.csv, summary.json, episodes.csv);
MP_DIR is what `mp_exact.py MODEL --out MP_DIR` wrote (events.csv, peaks.json).

Reports, per event, |dt| (and |dq'| before the jump); per peak (the largest and the smallest q and
every rocking episode's largest |q|), |dq| and |dt|; whether the two event sequences (kind, from,
to) are identical; and the maxima.  Exit status 1 when the sequences differ or when the largest
event |dt|, peak |dq| or peak |dt| is above --tol; 0 otherwise; 2 on unreadable input.

Differences are taken in decimal arithmetic from the printed digits, so that they are not
limited by binary rounding of the 25-digit reference.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import sys
from decimal import Decimal, getcontext

getcontext().prec = 50


def D(x):
    if x is None or x == "":
        return None
    return Decimal(str(x))


def read_events(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def read_json_decimal(path):
    with open(path) as fh:
        return json.load(fh, parse_float=Decimal, parse_int=Decimal)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("mp_dir")
    ap.add_argument("--tol", type=float, default=1e-13)
    ap.add_argument("--json", default=None, help="write the maxima to this JSON file")
    ap.add_argument("--quiet", action="store_true", help="print only the summary line")
    args = ap.parse_args(argv)
    try:
        ev_run = read_events(os.path.join(args.run_dir, "events.csv"))
        ev_mp = read_events(os.path.join(args.mp_dir, "events.csv"))
        summ = read_json_decimal(os.path.join(args.run_dir, "summary.json"))
        peaks = read_json_decimal(os.path.join(args.mp_dir, "peaks.json"))
        ep_path = os.path.join(args.run_dir, "episodes.csv")
        ep_run = read_events(ep_path) if os.path.exists(ep_path) else []
    except (OSError, ValueError, KeyError) as e:
        print(f"compare.py: cannot read the inputs: {e}", file=sys.stderr)
        return 2

    seq_run = [(e["kind"], e["from"], e["to"]) for e in ev_run]
    seq_mp = [(e["kind"], e["from"], e["to"]) for e in ev_mp]
    same = seq_run == seq_mp
    out = []
    max_ev_dt = Decimal(0)
    max_ev_dqd = Decimal(0)
    n = min(len(ev_run), len(ev_mp))
    for i in range(n):
        a, b = ev_run[i], ev_mp[i]
        dt = abs(D(a["t"]) - D(b["t"]))
        dqd = abs(D(a["qdot_before"]) - D(b["qdot_before"]))
        tag = "" if seq_run[i] == seq_mp[i] else f"  DIFFERENT: {seq_run[i]} vs {seq_mp[i]}"
        out.append(f"  event {i:3d} {b['kind']:8s} {b['from']:>10s} -> {b['to']:<10s} "
                   f"t = {float(D(b['t'])):.15f}  |dt| = {float(dt):.2e}  |dqdot| = {float(dqd):.2e}{tag}")
        if seq_run[i] == seq_mp[i]:
            max_ev_dt = max(max_ev_dt, dt)
            max_ev_dqd = max(max_ev_dqd, dqd)
    if len(ev_run) != len(ev_mp):
        out.append(f"  event counts differ: run {len(ev_run)}, exact {len(ev_mp)}")

    max_pk_dq = Decimal(0)
    max_pk_dt = Decimal(0)
    pk = []
    for key, tkey in (("max_q", "t_max_q"), ("min_q", "t_min_q")):
        pk.append((key, D(summ[key]), D(summ[tkey]), D(peaks[key]), D(peaks[tkey])))
    eps_mp = peaks.get("episodes", [])
    if ep_run and len(ep_run) == len(eps_mp):
        for i, (a, b) in enumerate(zip(ep_run, eps_mp)):
            pk.append((f"episode {i} {b['side']}", D(a["peak_abs_q"]), D(a["t_peak"]),
                       D(b["peak_abs_q"]), D(b["t_peak"])))
    elif ep_run or eps_mp:
        out.append(f"  episode counts differ: run {len(ep_run)}, exact {len(eps_mp)}")
        same = False
    for name, qa, ta, qb, tb in pk:
        dq, dt = abs(qa - qb), abs(ta - tb)
        max_pk_dq, max_pk_dt = max(max_pk_dq, dq), max(max_pk_dt, dt)
        out.append(f"  peak {name:18s} q = {float(qb):+.15f} at t = {float(tb):.12f}  "
                   f"|dq| = {float(dq):.2e}  |dt| = {float(dt):.2e}")
    over_same = bool(summ.get("overturned")) == bool(peaks.get("overturned"))
    if not over_same:
        same = False
        out.append(f"  overturned: run {summ.get('overturned')}, exact {peaks.get('overturned')}")

    tol = Decimal(repr(args.tol))
    ok = same and max_ev_dt <= tol and max_pk_dq <= tol and max_pk_dt <= tol
    line = (f"{'OK ' if ok else 'BAD'} events {len(ev_run)}/{len(ev_mp)} sequences "
            f"{'identical' if same else 'DIFFER'}; max event |dt| = {float(max_ev_dt):.2e} s, "
            f"max event |dqdot| = {float(max_ev_dqd):.2e} m/s, max peak |dq| = {float(max_pk_dq):.2e} m, "
            f"max peak |dt| = {float(max_pk_dt):.2e} s (tol {args.tol:g})")
    if not args.quiet:
        print("\n".join(out))
    print(line)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(dict(identical=same, n_events_run=len(ev_run), n_events_exact=len(ev_mp),
                           max_event_dt=float(max_ev_dt), max_event_dqdot=float(max_ev_dqd),
                           max_peak_dq=float(max_pk_dq), max_peak_dt=float(max_pk_dt),
                           tol=args.tol, ok=ok), fh, indent=1)
            fh.write("\n")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
