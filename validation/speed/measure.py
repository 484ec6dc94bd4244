#!/usr/bin/env python3
"""Measures flexrock's speed goals as ratios, whole processes, in one run.

    validation/speed/measure.py [--rounds N] [--bin PATH] [--write]

Every figure is the CPU time (user + system, of the process and its threads, from getrusage of
the children) and the wall time of whole `flexrock` processes started from here: starting the
process, reading the model, solving, writing and syncing the files. Each round runs every case
once, one after the other, so that a machine whose speed drifts slows all of them alike; the
ratios are taken within each round and summarised by their median and range over the rounds.

The cases:
  1. the 100 x 100 overturning map of the overturning-spectrum tutorial (models/pulse-map.toml,
     10,000 one-sine pulses, by the exact method): CPU per cell (goal: at most 3 us);
  2. `flexrock run` on the paper's example (models/ichinose1986.toml, its history, events and
     summary) by the exact method against tsit45 at rtol = 1e-10 (goal: at most 1/4), each
     timed over RUNS processes in a row;
  3. peaks only, as a sweep's points run: a sweep of POINTS copies of the paper's example (the
     out-of-plane depth varied, which q(t) does not depend on) by the exact method against
     tsit45 at rtol = 1e-10 (goal: at most 1/10);
  and `flexrock --version`, the cost of a process that does nothing.

Nothing here is asserted by a test: timings depend on the machine and on what else it runs,
which the output states (cores, the sweeps' threads, the load average before and after).
With --write the table also goes to validation/speed/measured.md, which the book includes.
Builds nothing: build with `cargo build --release` first (or give --bin).
"""

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MAP_AXES = [
    "--vary", "excitation.period=lin:0.2:3:100",
    "--vary", "excitation.amplitude=lin:0.5:15:100",
]
MAP_CELLS = 100 * 100
RUNS = 20
POINTS = 1000
TSIT45 = ["solver.method=tsit45", "solver.rtol=1e-10", "solver.atol=1e-12"]


def timed(command, tmp):
    """Wall and CPU seconds of one process (its threads included)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"measure.py: {' '.join(map(str, command))} failed: {done.stderr.decode()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def repeated(make, n, tmp):
    """Wall and CPU seconds of n processes in a row, make(i) giving the i-th command."""
    wall = cpu = 0.0
    for i in range(n):
        w, c = timed(make(i), tmp)
        wall += w
        cpu += c
    return wall, cpu


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    return str(path)


def one_round(bin, tmp, r):
    sets = lambda keys: [a for k in keys for a in ("--set", k)]
    out = {}
    out["version"] = repeated(lambda i: [bin, "--version"], RUNS, tmp)
    out["map"] = timed(
        [bin, "sweep", "models/pulse-map.toml", "--out", fresh(tmp / f"map{r}")] + MAP_AXES, tmp
    )
    out["run exact"] = repeated(
        lambda i: [bin, "run", "models/ichinose1986.toml", "--out", fresh(tmp / f"exact{i}")],
        RUNS,
        tmp,
    )
    out["run tsit45"] = repeated(
        lambda i: [bin, "run", "models/ichinose1986.toml", "--out", fresh(tmp / f"tsit{i}")]
        + ["--method", "tsit45", "--rtol", "1e-10", "--atol", "1e-12"],
        RUNS,
        tmp,
    )
    points = ["--vary", f"body.depth=lin:1:2:{POINTS}"]
    out["peaks exact"] = timed(
        [bin, "sweep", "models/ichinose1986.toml", "--out", fresh(tmp / f"pe{r}")] + points, tmp
    )
    out["peaks tsit45"] = timed(
        [bin, "sweep", "models/ichinose1986.toml", "--out", fresh(tmp / f"pt{r}")]
        + points
        + sets(TSIT45),
        tmp,
    )
    return out


def summary(values, scale=1.0, digits=3):
    values = [v * scale for v in values]
    fmt = lambda v: f"{v:.{digits}g}"
    return f"{fmt(statistics.median(values))} ({fmt(min(values))} to {fmt(max(values))})"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--bin", default=str(ROOT / "target" / "release" / "flexrock"))
    parser.add_argument("--write", action="store_true")
    args = parser.parse_args()
    bin = os.path.abspath(args.bin)
    if not os.access(bin, os.X_OK):
        sys.exit(f"measure.py: no flexrock binary at {bin}: run `cargo build --release` first")
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
    ).stdout.strip()
    dirty = subprocess.run(
        ["git", "status", "--porcelain", "--", "src", "core", "Cargo.lock"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    ).stdout.strip()
    load_before = os.getloadavg()[0]
    rounds = []
    with tempfile.TemporaryDirectory(prefix="flexrock-speed-") as tmp:
        for r in range(args.rounds):
            rounds.append(one_round(bin, Path(tmp), r))
    load_after = os.getloadavg()[0]

    col = lambda key, i: [x[key][i] for x in rounds]
    ratio = lambda a, b, i: [x[a][i] / x[b][i] for x in rounds]
    rows = [
        ("100 x 100 pulse map, exact: CPU per cell", summary(col("map", 1), 1e6 / MAP_CELLS) + " us", "at most 3 us"),
        ("100 x 100 pulse map, exact: wall, whole map", summary(col("map", 0)) + " s", ""),
        (f"`flexrock run` paper's example, exact: CPU per run", summary(col("run exact", 1), 1e3 / RUNS) + " ms", ""),
        (f"`flexrock run` paper's example, tsit45 rtol 1e-10: CPU per run", summary(col("run tsit45", 1), 1e3 / RUNS) + " ms", ""),
        ("`flexrock run`, CPU exact / tsit45", summary(ratio("run exact", "run tsit45", 1), digits=2), "at most 0.25"),
        ("`flexrock run`, wall exact / tsit45", summary(ratio("run exact", "run tsit45", 0), digits=2), ""),
        (f"peaks only ({POINTS}-point sweep), exact: CPU per point", summary(col("peaks exact", 1), 1e6 / POINTS) + " us", ""),
        (f"peaks only ({POINTS}-point sweep), tsit45 rtol 1e-10: CPU per point", summary(col("peaks tsit45", 1), 1e6 / POINTS) + " us", ""),
        ("peaks only, CPU exact / tsit45", summary(ratio("peaks exact", "peaks tsit45", 1), digits=2), "at most 0.1"),
        ("`flexrock --version`: CPU per process", summary(col("version", 1), 1e3 / RUNS) + " ms", ""),
    ]
    text = [
        f"Measured by `validation/speed/measure.py --rounds {args.rounds}` at commit `{commit}`"
        + (" (with uncommitted changes)" if dirty else "")
        + f", on {os.cpu_count()} cores ({platform_name()}), the sweeps on all cores (their"
        + f" default threads), load average {load_before:.1f} before and {load_after:.1f} after."
        + " Medians over the rounds, the range in brackets; CPU is user + system time of the"
        + " whole process and its threads.",
        "",
        "| measured | value | goal |",
        "|---|---|---|",
    ] + [f"| {a} | {b} | {c} |" for a, b, c in rows]
    print("\n".join(text))
    if args.write:
        (ROOT / "validation" / "speed" / "measured.md").write_text("\n".join(text) + "\n")


def platform_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "processor unknown"


if __name__ == "__main__":
    main()
