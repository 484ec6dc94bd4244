#!/usr/bin/env python3
"""flexrock's two self-weight variants against the OpenSees beam-column (validation/opensees/).

Runs the flexrock binary (env FLEXROCK_BIN, default target/release/flexrock) and writes
validation/self-weight/results/: pushover.csv/.md/.svg, dynamics.csv/.md, overlay figures,
spectrum.csv/.md/.svg, commands.txt (every command run) and timings.json.
"""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np
import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams["svg.hashsalt"] = "flexrock-self-weight"  # the same SVG from run to run
SVG_META = {"Date": None}

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
OPS = os.path.join(ROOT, "validation", "opensees", "results")
RES = os.path.join(HERE, "results")
BIN = os.environ.get("FLEXROCK_BIN", os.path.join(ROOT, "target", "release", "flexrock"))
PAPER = "models/ichinose1986.toml"
RECORD_MODEL = "models/elcentro1940.toml"  # reads ../validation/records/<name>, g, tail 5 s
PULSE = "models/pulse-map.toml"
E10 = "body.youngs_modulus=5e7"
VARIANTS = ("consistent", "paper")
RECORDS = ("elCentro", "ANLA196", "A-ELC180", "PBFEAS", "HEN-E")
FEM_MESH = ("--nx", "8", "--ny", "40")
MIN_EPISODE = 0.02  # s, as OpenSees' sustained uplift
COMMANDS = []
TMP = tempfile.mkdtemp(prefix="flexrock-sw-")


def sh(args):
    """Run flexrock from the repository root; log the command; return stdout."""
    cmd = [BIN] + list(args)
    COMMANDS.append(" ".join(["flexrock"] + list(args)).replace(TMP, "$TMP"))
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}")
    return p.stdout


def sets(variant, efac):
    s = ["--set", f"body.self_weight={variant}"]
    if efac == 10:
        s += ["--set", E10]
    return s


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def fnum(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def pct(x, ref):
    if not (np.isfinite(x) and np.isfinite(ref)) or ref == 0:
        return ""
    return f"{100.0 * (x - ref) / abs(ref):+.2f}"


def g(x, n=5):
    if isinstance(x, str):
        return x
    if x is None or not np.isfinite(x):
        return ""
    return f"{x:.{n}g}"


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow([g(v, 7) if isinstance(v, float) else v for v in r])


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in rows:
        out.append("| " + " | ".join(g(v) if isinstance(v, float) else str(v) for v in r) + " |")
    return "\n".join(out) + "\n"


def lsq_slope(x, y):
    return float(np.polyfit(x, y, 1)[0])


# ---------------------------------------------------------------- 1. pushover
def pushover():
    ops = {r["case"]: r for r in read_csv(os.path.join(OPS, "pushover_summary.csv"))}
    cont = {r["case"]: r for r in read_csv(os.path.join(OPS, "continuum_summary.csv"))}
    qty = ["K0 (N/m)", "K0/Ke", "q_uplift (m)", "V_uplift (N)", "post-uplift slope (N/m)",
           "q at V = 0 (m)", "T fixed base (s)"]
    rows, curves = [], {}
    for efac in (1, 10):
        case = f"E{efac}_pdelta"
        o, c = ops[case], cont[case]
        Ke_paper = fnum(o["Ke"])
        src = {}
        src["OpenSees"] = [fnum(o["K0"]), fnum(o["K0_over_Ke"]), fnum(o["q_uplift"]),
                           fnum(o["V_uplift"]), fnum(o["post_slope"]), fnum(o["q_zero_shear"]),
                           fnum(o["T_fixed_base_no_rotary"])]
        src["OpenSees (rotary inertia)"] = [np.nan] * 6 + [fnum(o["T_fixed_base"])]
        src["continuum"] = [fnum(c["K0"]), fnum(c["K0_over_Ke"]), fnum(c["q_uplift"]),
                            fnum(c["V_uplift"]), fnum(c["post_slope"]), fnum(c["q_zero_shear"]),
                            fnum(c["T_fixed_base"])]
        for v in VARIANTS:
            k = json.loads(sh(["props", PAPER, "--json"] + sets(v, efac)))["constants"]
            K, sn = k["generalised_stiffness"], k["uplift_displacement"]
            src[f"flexrock {v}"] = [K, K / Ke_paper, sn, K * sn, k["rocking_stiffness"],
                                    k["topple_displacement"], k["period"]]
            qq = np.linspace(0, 0.75, 751)
            F = np.where(qq <= sn, K * qq, K * sn + k["rocking_stiffness"] * (qq - sn))
            curves[(efac, f"flexrock {v}")] = (qq, F)
        # the FEM's rigid-plate pushover (8 x 40 QM6 mesh, P-Delta)
        d = os.path.join(TMP, f"pushover-E{efac}")
        sh(["fem", PAPER, "--pushover", *FEM_MESH, "--out", d] + (["--set", E10] if efac == 10 else []))
        pj = json.load(open(os.path.join(d, "pushover.json")))
        plate = [cv for cv in pj["curves"] if cv["base"] == "rigid-plate"][0]
        pr = [r for r in read_csv(os.path.join(d, "pushover.csv")) if r["base"] == "rigid-plate"]
        q = np.array([fnum(r["q"]) for r in pr])
        V = np.array([fnum(r["base_shear"]) for r in pr])
        qup = plate["heel_lift_q"]  # first q with the heel corner off the floor
        K0 = lsq_slope(q[q < qup / 2], V[q < qup / 2])
        Vup = float(np.interp(qup, q, V))
        sel = (q >= qup + 0.25 * (0.7 - qup)) & (q <= 0.7)
        slope, icpt = np.polyfit(q[sel], V[sel], 1)
        neg = np.nonzero(V[q > qup] <= 0)[0]
        qzero = float(np.interp(0, -V[q > qup], q[q > qup])) if len(neg) else -icpt / slope
        modes = sh(["fem", PAPER, "--modes", *FEM_MESH] + (["--set", E10] if efac == 10 else []))
        Tfem = float([ln.split() for ln in modes.splitlines() if ln.strip().startswith("1 ")][0][2])
        src["FEM rigid plate 8x40"] = [K0, K0 / Ke_paper, qup, Vup, float(slope), qzero, Tfem]
        curves[(efac, "FEM rigid plate 8x40")] = (q, V)
        po = read_csv(os.path.join(OPS, f"pushover_{case}.csv"))
        curves[(efac, "OpenSees")] = (np.array([fnum(r["q"]) for r in po]),
                                      np.array([fnum(r["base_shear"]) for r in po]))
        ref = src["OpenSees"]
        for name, vals in src.items():
            rows.append([f"E x {efac}", name] + [v for pair in zip(vals, [pct(x, r) for x, r in zip(vals, ref)]) for v in pair])
    header = ["body", "source"]
    for qn in qty:
        header += [qn, "% vs OpenSees"]
    write_csv(os.path.join(RES, "pushover.csv"), header, rows)
    with open(os.path.join(RES, "pushover.md"), "w") as f:
        f.write("Percent differences against OpenSees (P-Delta, no rotary inertia in T) in brackets. "
                "FEM rigid plate: q at V = 0 extrapolated from its post-uplift line where the curve "
                "(to q = B) does not reach zero.\n\n")
        h = ["body", "source"] + qty
        mrows = []
        for r in rows:
            cells = r[:2]
            for i in range(len(qty)):
                v, p = r[2 + 2 * i], r[3 + 2 * i]
                cells.append("" if not np.isfinite(v) else (g(v) + (f" ({p} %)" if p and r[1] != "OpenSees" else "")))
            mrows.append(cells)
        f.write(md_table(h, mrows))
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    styles = {"OpenSees": dict(color="k", lw=2.5), "flexrock consistent": dict(color="tab:red", ls="--"),
              "flexrock paper": dict(color="tab:blue", ls="-."), "FEM rigid plate 8x40": dict(color="tab:green", ls=":", lw=2)}
    for ax, efac in zip(axs, (1, 10)):
        for name, st in styles.items():
            x, y = curves[(efac, name)]
            ax.plot(x, y, label=name, **st)
        ax.axhline(0, color="0.7", lw=0.8)
        ax.set_xlim(0, 0.75)
        ax.set_xlabel("top displacement q (m)")
        ax.set_ylabel("base shear (N)")
        ax.set_title(f"pushover, E x {efac}")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(RES, "pushover.svg"), metadata=SVG_META)
    plt.close(fig)
    return rows


# ---------------------------------------------------------------- 2. dynamics
def episodes(events, t_end):
    """Uplift episodes (t_start, side, duration) from events.csv rows."""
    eps, cur = [], None
    for e in events:
        t = fnum(e["t"])
        if e["kind"] == "uplift":
            cur = (t, e["to"])
        elif cur is not None and e["from"] == cur[1]:
            eps.append((cur[0], cur[1], t - cur[0]))
            cur = None
    if cur is not None:
        eps.append((cur[0], cur[1], t_end - cur[0]))
    return eps


def flexrock_dyn(label, model, extra, variant, efac, keep):
    d = os.path.join(TMP, "run", f"{label}-E{efac}-{variant}")
    sh(["run", model, "--out", d] + extra + sets(variant, efac))
    s = json.load(open(os.path.join(d, "summary.json")))
    ev = read_csv(os.path.join(d, "events.csv"))
    eps = episodes(ev, s["final_time"])
    sus = [e for e in eps if e[2] >= MIN_EPISODE]
    first = lambda side: min([e[0] for e in sus if e[1] == side], default=float("nan"))
    out = dict(peak=max(s["max_q"], -s["min_q"]), pos=s["max_q"], neg=s["min_q"],
               t_rr=first("rock-right"), t_rl=first("rock-left"), n=len(sus), n_raw=s["n_uplift"],
               over=str(s["overturned"]).lower(), t_over=fnum(s["t_overturn"]), T=s["T"])
    if keep:
        h = read_csv(os.path.join(d, "history.csv"))
        out["hist"] = (np.array([fnum(r["t"]) for r in h]), np.array([fnum(r["q"]) for r in h]))
    return out


def fem_dyn(efac, Tdamp):
    d = os.path.join(TMP, f"fem-E{efac}")
    args = ["fem", PAPER, "--compare", *FEM_MESH, "--scheme", "average-acceleration", "--dt", "0.005",
            "--set", "fem.base=rigid-plate", "--set", f"fem.damping_period={Tdamp:.6f}",
            "--set", "body.self_weight=consistent", "--out", d]
    if efac == 10:
        args += ["--set", E10]
    sh(args)
    s = json.load(open(os.path.join(d, "fem_summary.json")))
    h = read_csv(os.path.join(d, "fem_history.csv"))
    t = np.array([fnum(r["t"]) for r in h])
    q = np.array([fnum(r["q"]) for r in h])
    # a toe counts as up when it is 1e-6 m above the floor, as in OpenSees: the base rotation
    # rocking/H times B exceeds 1e-6 m (rocking > 0: left corner up, flexrock's rock-right)
    r = np.array([fnum(x["rocking"]) for x in h])
    B, H = 0.7, 4.0
    sus = []
    for side, up in (("rock-right", r * B / H > 1e-6), ("rock-left", -r * B / H > 1e-6)):
        i = 0
        while i < len(t):
            if up[i]:
                j = i
                while j + 1 < len(t) and up[j + 1]:
                    j += 1
                if t[j] - t[i] + (t[1] - t[0]) >= MIN_EPISODE:
                    sus.append((t[i], side))
                i = j + 1
            else:
                i += 1
    first = lambda side: min([a for a, b in sus if b == side], default=float("nan"))
    ups = s["uplifts"]  # the FEM's own episodes (a corner free, rocking above 1 % of B)
    ov = s.get("overturned_at")
    return dict(peak=float(np.max(np.abs(q))), pos=float(q.max()), neg=float(q.min()),
                t_rr=first("rock-right"), t_rl=first("rock-left"), n=len(sus), n_raw=len(ups),
                over="true" if ov is not None else "false", t_over=fnum(ov), hist=(t, q))


def dynamics(fem_T):
    ops = read_csv(os.path.join(OPS, "dynamic_summary.csv"))
    # the finest dt of each OpenSees case (P-Delta runs)
    best = {}
    for r in ops:
        if r["pdelta"] != "true":
            continue
        key = (r["case"], r["record"].replace(".AT2", ""), int(float(r["scale"])))
        if key not in best or fnum(r["dt"]) < fnum(best[key]["dt"]):
            best[key] = r
    cases = [("paper-sine", 1)] + [(rec, sc) for sc in (1, 5) for rec in RECORDS]
    header = ["body", "excitation", "scale", "source", "peak abs q (m)", "% vs OpenSees", "peak q+ (m)", "peak q- (m)",
              "first rock-right t (s)", "first rock-left t (s)", "uplifts >= 0.02 s", "uplifts raw",
              "overturned", "t overturn (s)"]
    rows, hist = [], {}
    for efac in (1, 10):
        for rec, sc in cases:
            o = best[(f"E{efac}_pdelta", rec, sc)]
            ref = fnum(o["peak_q"])
            rows.append([f"E x {efac}", rec, sc, f"OpenSees dt={o['dt']}", ref, "", fnum(o["peak_q_pos"]),
                         fnum(o["peak_q_neg"]), fnum(o["t_first_uplift_left"]), fnum(o["t_first_uplift_right"]),
                         int(o["n_uplifts"]), "", o["overturned"], fnum(o["t_overturn"])])
            for v in VARIANTS:
                if rec == "paper-sine":
                    model, extra = PAPER, []
                else:
                    model = RECORD_MODEL
                    extra = ["--set", f"excitation.path=validation/records/{rec}.AT2",
                             "--set", f"excitation.scale={sc}"]
                keep = efac == 1 and (rec == "paper-sine" or (rec == "A-ELC180" and sc == 1))
                r = flexrock_dyn(rec, model, extra, v, efac, keep)
                if keep:
                    hist[(rec, v)] = r["hist"]
                rows.append([f"E x {efac}", rec, sc, f"flexrock {v}", r["peak"], pct(r["peak"], ref), r["pos"], r["neg"], r["t_rr"],
                             r["t_rl"], r["n"], r["n_raw"], r["over"], r["t_over"]])
            if rec == "paper-sine":
                r = fem_dyn(efac, fem_T[efac])
                if efac == 1:
                    hist[(rec, "fem")] = r["hist"]
                rows.append([f"E x {efac}", rec, sc, "FEM rigid plate 8x40", r["peak"], pct(r["peak"], ref), r["pos"], r["neg"],
                             r["t_rr"], r["t_rl"], r["n"], r["n_raw"], r["over"], r["t_over"]])
    write_csv(os.path.join(RES, "dynamics.csv"), header, rows)
    with open(os.path.join(RES, "dynamics.md"), "w") as f:
        f.write(md_table(header, rows))
    # overlays, and their decimated data (every 0.02 s)
    for rec, fname, title in (("paper-sine", "overlay-paper-wave", "paper's wave (E x 1)"),
                              ("A-ELC180", "overlay-A-ELC180-x1", "A-ELC180 x 1 (E x 1)")):
        ofile = "paper-sine" if rec == "paper-sine" else "A-ELC180_x1"
        oh = read_csv(os.path.join(OPS, f"history_E1_pdelta_{ofile}.csv"))
        series = {"OpenSees": (np.array([fnum(r["t"]) for r in oh]), np.array([fnum(r["q"]) for r in oh]))}
        for v in VARIANTS:
            series[f"flexrock {v}"] = hist[(rec, v)]
        if (rec, "fem") in hist:
            series["FEM rigid plate 8x40"] = hist[(rec, "fem")]
        tmax = min(s[0][-1] for s in series.values())
        tg = np.arange(0, tmax + 1e-9, 0.02)
        write_csv(os.path.join(RES, fname + ".csv"), ["t"] + list(series),
                  [[float(t)] + [float(np.interp(t, *s)) for s in series.values()] for t in tg])
        fig, ax = plt.subplots(figsize=(11, 4))
        st = [dict(color="k", lw=2.2), dict(color="tab:red", ls="--"), dict(color="tab:blue", ls="-."),
              dict(color="tab:green", ls=":", lw=2)]
        for (name, (t, q)), s in zip(series.items(), st):
            ax.plot(t, q, label=name, **s)
        if rec != "paper-sine":
            ax.set_xlim(7, 14)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("top displacement q (m)")
        ax.set_title(title)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(RES, fname + ".svg"), metadata=SVG_META)
        plt.close(fig)
    return rows


# ---------------------------------------------------------------- 3. spectrum
def spectrum():
    curves = {}
    rows = []
    for efac in (1, 10):
        for v in VARIANTS:
            d = os.path.join(TMP, f"spectrum-E{efac}-{v}")
            sh(["sweep", PULSE, "--out", d, "--vary", "excitation.period=log:0.3:3:13",
                "--find-min", "excitation.amplitude=0.5:40"] + sets(v, efac))
            sw = read_csv(os.path.join(d, "sweep.csv"))
            for r in sw:
                rows.append([f"E x {efac}", v, fnum(r["excitation.period"]), r["status"],
                             fnum(r["min_overturning"]), fnum(r["safe_below"]), r["overturning_bands"],
                             fnum(r["rigid_min_overturning"]), fnum(r["T"]), fnum(r["s_n"])])
            curves[(efac, v)] = ([fnum(r["excitation.period"]) for r in sw], [fnum(r["min_overturning"]) for r in sw],
                                 [fnum(r["rigid_min_overturning"]) for r in sw])
    header = ["body", "variant", "pulse period (s)", "status", "min overturning amplitude (m/s2)", "safe below (m/s2)",
              "overturning bands", "Housner rigid block (m/s2)", "T (s)", "s_n (m)"]
    write_csv(os.path.join(RES, "spectrum.csv"), header, rows)
    # side-by-side markdown: period, E1 cons, E1 paper, ratio, E10 cons, E10 paper, ratio, rigid
    per = curves[(1, "consistent")][0]
    md = []
    for i, tp in enumerate(per):
        a = [curves[(e, v)][1][i] for e in (1, 10) for v in VARIANTS]
        md.append([f"{tp:.3f}", a[0], a[1], f"{a[0] / a[1]:.3f}" if np.isfinite(a[0] / a[1]) else "",
                   a[2], a[3], f"{a[2] / a[3]:.3f}" if np.isfinite(a[2] / a[3]) else "", curves[(1, "paper")][2][i]])
    with open(os.path.join(RES, "spectrum.md"), "w") as f:
        f.write(md_table(["Tp (s)", "E: consistent", "E: paper", "ratio", "10E: consistent", "10E: paper", "ratio",
                          "Housner rigid"], md))
    fig, ax = plt.subplots(figsize=(8, 5))
    col = {1: "tab:red", 10: "tab:blue"}
    for (efac, v), (tp, a, rig) in curves.items():
        ax.plot(tp, a, marker="o" if v == "consistent" else "s", ls="-" if v == "consistent" else "--",
                color=col[efac], label=f"E x {efac}, {v}", mfc="none" if v == "paper" else None)
    ax.plot(curves[(1, "paper")][0], curves[(1, "paper")][2], color="0.4", ls=":", label="Housner rigid block")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("one-sine pulse period Tp (s)")
    ax.set_ylabel("minimum overturning amplitude (m/s$^2$)")
    ax.set_title("overturning spectrum, one-sine pulse (models/pulse-map.toml)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(RES, "spectrum.svg"), metadata=SVG_META)
    plt.close(fig)
    return md


def main():
    if not os.path.exists(BIN):
        sys.exit(f"no flexrock binary at {BIN}; build it (cargo build --release) or set FLEXROCK_BIN")
    if os.path.isdir(RES):
        shutil.rmtree(RES)
    os.makedirs(RES)
    times = {}
    t0 = time.time()
    po = pushover()
    times["pushover_s"] = time.time() - t0
    fem_T = {1: [r for r in po if r[0] == "E x 1" and r[1] == "FEM rigid plate 8x40"][0][14],
             10: [r for r in po if r[0] == "E x 10" and r[1] == "FEM rigid plate 8x40"][0][14]}
    t1 = time.time()
    dynamics(fem_T)
    times["dynamics_s"] = time.time() - t1
    t2 = time.time()
    spectrum()
    times["spectrum_s"] = time.time() - t2
    times["total_s"] = time.time() - t0
    with open(os.path.join(RES, "commands.txt"), "w") as f:
        f.write("# run from the repository root, in this order; outputs into a temporary directory\n")
        f.write("\n".join(COMMANDS) + "\n")
    with open(os.path.join(RES, "timings.json"), "w") as f:
        json.dump({k: round(v, 2) for k, v in times.items()}, f, indent=1)
    shutil.rmtree(TMP)
    print(json.dumps(times))


if __name__ == "__main__":
    main()
