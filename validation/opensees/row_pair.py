#!/usr/bin/env python3
"""OpenSees model of two pounding columns, compared with flexrock's row (book/src/row.md).

Two beam-columns of beam_column.py (P-Delta, lumped masses with rotary inertia, a rigid base
plate on two no-tension toe springs, stiffness-proportional damping h on each column's own
first fixed-base mode), side by side on one floor:

* column 0 (left): the paper's body, H = 4 m, B = 0.7 m (models/ichinose1986.toml);
* column 1 (right): the same section and material, H = 3.2 m;
* their toes a clear gap g apart (the right toe of column 0 at x = B/2, the left toe of column 1
  at x = B/2 + g);
* a contact at the top of the shorter column: a zeroLength element in x between the node of
  column 0 at y = 3.2 m (the mesh of 80 elements on 4 m has one there) and the top node of
  column 1, with an ElasticPPGap material (compression only, gap g, stiffness k_c) and
  stiffness-proportional Rayleigh damping on that element alone (current tangent), so the
  dashpot c = beta_c k_c acts only while the gap is closed: a Kelvin-Voigt contact (linear
  spring and dashpot in parallel, active only in contact). For two masses on a Kelvin-Voigt
  contact released where its spring returns to zero, the coefficient of restitution is
  e = exp(-zeta pi / sqrt(1 - zeta^2)), zeta = c / (2 sqrt(k_c m_red)); zeta is set from
  flexrock's e, m_red from the two columns' effective masses at the contact (see contact_zeta).

Commands:

    row_pair.py run --out DIR [--flexrock BIN]     every case, the stiffness sweep, flexrock runs,
                                                   comparison tables, figures (row_results/)

flexrock runs the same rows from model files written to DIR/models/ with self_weight =
"consistent" on each column and restitution e.
"""

import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np
import openseespy.opensees as ops

import beam_column as bc

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = bc.REPO

TAG1 = 10000            # tag offset of column 1 (column 0 has the offsets of beam_column.py)
CONTACT_ELE = 50001
CONTACT_MAT = 50001
NEL_PER_M = 20          # 80 elements on the 4 m column, 64 on the 3.2 m one: dy = 0.05 m
RESTITUTION = 0.5       # flexrock's Newton coefficient (as models/row-pair.toml)
K_CONTACT = 1e8         # N/m: the stiffness of the reference runs (see the sweep)
DT = 0.001              # s: the step of the reference runs
OUT_DT = 0.01           # s: history output
MERGE = 0.02            # s: contact episodes closer than this are one impact (chatter)
Q_OVERTURN = 1.0        # m, as beam_column.py


def bodies():
    return bc.Body(), bc.Body(height=3.2)


def column_betaK(body, nel, pdelta=True):
    """betaK = 2 h / omega1 with omega1 the column's own fixed-base first mode after gravity."""
    bc.build(body, nel=nel, pdelta=pdelta)
    T1 = bc.fixed_base_period(1)[0]
    return 2 * body.h / (2 * math.pi / T1), T1


def u_shape(xi):
    return float(bc.U(xi))


def contact_mass(b0, b1, y_c):
    """Reduced mass of the contact points in flexrock's impact law before uplift
    (book/src/row.md section 3): each column's kinetic mass M int U^2 = M/4 seen through its slope
    U(y_c/H) at the contact: m_i / U_i^2."""
    m0 = b0.M / 4 / u_shape(y_c / b0.H) ** 2
    m1 = b1.M / 4 / u_shape(y_c / b1.H) ** 2
    return m0 * m1 / (m0 + m1)


def contact_zeta(e):
    """Damping ratio of a linear Kelvin-Voigt contact whose restitution is e."""
    if e <= 0:
        return 1.0
    le = -math.log(e)
    return le / math.sqrt(math.pi ** 2 + le ** 2)


def build_pair(b0, b1, gap, k_c, zeta, pdelta=True):
    n0 = int(round(b0.H * NEL_PER_M))
    n1 = int(round(b1.H * NEL_PER_M))
    beta0, T0 = column_betaK(b0, n0, pdelta)
    beta1, T1 = column_betaK(b1, n1, pdelta)
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    m0 = bc.build_column(b0, nel=n0, pdelta=pdelta)
    x1 = b0.B / 2 + gap + b1.B / 2
    m1 = bc.build_column(b1, nel=n1, pdelta=pdelta, tag0=TAG1, x0=x1)
    bc.gravity({**m0["weights"], **m1["weights"]})
    y_c = min(b0.H, b1.H)
    k = int(round(y_c / b0.H * n0))
    if abs(m0["ys"][k] - y_c) > 1e-9:
        raise RuntimeError("no node of column 0 at the contact height")
    node0 = m0["base"] + k
    node1 = m1["top"]
    m_red = contact_mass(b0, b1, y_c)
    c = 2 * zeta * math.sqrt(k_c * m_red)
    beta_c = c / k_c
    # compression only, closing at deformation u1 - u0 = -gap; yield force out of reach
    ops.uniaxialMaterial("ElasticPPGap", CONTACT_MAT, k_c, -1e15, -gap)
    ops.element("zeroLength", CONTACT_ELE, node0, node1, "-mat", CONTACT_MAT, "-dir", 1, "-doRayleigh", 1)
    ops.region(1, "-eleRange", m0["ele_first"], m0["ele_last"], "-rayleigh", 0.0, beta0, 0.0, 0.0)
    ops.region(2, "-eleRange", m1["ele_first"], m1["ele_last"], "-rayleigh", 0.0, beta1, 0.0, 0.0)
    ops.region(3, "-ele", CONTACT_ELE, "-rayleigh", 0.0, beta_c, 0.0, 0.0)
    return dict(m0=m0, m1=m1, node0=node0, node1=node1, y_c=y_c, gap=gap, k_c=k_c, zeta=zeta,
                m_red=m_red, c=c, beta_c=beta_c, T0=T0, T1=T1, beta0=beta0, beta1=beta1)


def run_pair(b0, b1, gap, acc_dt, acc, duration, dt=DT, k_c=K_CONTACT, e=RESTITUTION, pdelta=True):
    zeta = contact_zeta(e)
    mdl = build_pair(b0, b1, gap, k_c, zeta, pdelta)
    ops.timeSeries("Path", 3, "-dt", acc_dt, "-values", *map(float, acc))
    ops.pattern("UniformExcitation", 3, 1, "-accel", 3)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-9, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    nsteps = int(round(duration / dt))
    dec = max(1, int(round(OUT_DT / dt)))
    cols = (b0, b1), (mdl["m0"], mdl["m1"])

    def snap():
        st = [bc.state(b, m) for b, m in zip(*cols)]
        d = ops.nodeDisp(mdl["node1"], 1) - ops.nodeDisp(mdl["node0"], 1)
        w = ops.nodeVel(mdl["node0"], 1) - ops.nodeVel(mdl["node1"], 1)   # closing velocity
        f = -ops.eleResponse(CONTACT_ELE, "force")[0] if d < -gap else 0.0
        return st, gap + d, w, abs(f)

    t = 0.0
    st, gp, w, f = snap()
    rec = dict(t=[0.0], q0=[st[0][0]], q1=[st[1][0]], gap=[gp], w=[w], f=[f],
               ul0=[False], ur0=[False], ul1=[False], ur1=[False])
    hist = [(0.0, st[0][0], st[1][0], gp, f)]
    n_fail = 0
    overturned = None
    t0 = time.time()
    for k in range(nsteps):
        ok = ops.analyze(1, dt)
        if ok != 0:
            n_fail += 1
            if bc.substep(dt) != 0:
                print(f"row: no convergence at t = {t:.4f}", file=sys.stderr)
                break
        t = ops.getTime()
        st, gp, w, f = snap()
        for key, v in (("t", t), ("q0", st[0][0]), ("q1", st[1][0]), ("gap", gp), ("w", w), ("f", f),
                       ("ul0", st[0][3] > bc.UPLIFT_TOL), ("ur0", st[0][4] > bc.UPLIFT_TOL),
                       ("ul1", st[1][3] > bc.UPLIFT_TOL), ("ur1", st[1][4] > bc.UPLIFT_TOL)):
            rec[key].append(v)
        if (k + 1) % dec == 0:
            hist.append((t, st[0][0], st[1][0], gp, f))
        if max(abs(st[0][0]), abs(st[1][0])) > Q_OVERTURN:
            overturned = (0 if abs(st[0][0]) > Q_OVERTURN else 1, t)
            break
    rec = {k: np.array(v) for k, v in rec.items()}
    return dict(mdl=mdl, rec=rec, hist=np.array(hist), n_fail=n_fail, overturned=overturned,
                runtime=time.time() - t0, dt=dt, completed=t >= duration - 1e-9)


def contact_episodes(rec):
    """Runs of steps with the contact force > 0: start, end, closing velocity before (at the last
    step open), separating velocity after (at the first step open again), peak force."""
    t, f, w = rec["t"], rec["f"], rec["w"]
    on = f > 0
    eps = []
    i = 1
    n = len(t)
    while i < n:
        if on[i] and not on[i - 1]:
            j = i
            while j < n and on[j]:
                j += 1
            end = j if j < n else n - 1
            eps.append(dict(start=float(t[i]), end=float(t[end]), w_before=float(w[i - 1]),
                            w_after=float(-w[end]) if j < n else float("nan"),
                            peak_force=float(f[i:j].max())))
            i = j
        else:
            i += 1
    return eps


def merge_episodes(eps, gap=MERGE):
    """Episodes less than `gap` s apart are one impact (the stiff contact chatters)."""
    out = []
    for e in eps:
        if out and e["start"] - out[-1]["end"] < gap:
            out[-1]["end"] = e["end"]
            out[-1]["w_after"] = e["w_after"]
            out[-1]["n"] += 1
            out[-1]["peak_force"] = max(out[-1]["peak_force"], e["peak_force"])
        else:
            out.append(dict(e, n=1, w_after_first=e["w_after"]))
    return out


def os_summary(res):
    rec = res["rec"]
    eps = contact_episodes(rec)
    imp = merge_episodes(eps)
    out = dict(n_contact_episodes=len(eps), n_impacts=len(imp),
               t_first_contact=eps[0]["start"] if eps else float("nan"),
               overturned=res["overturned"] is not None,
               t_overturn=res["overturned"][1] if res["overturned"] else float("nan"))
    for i in (0, 1):
        q = rec[f"q{i}"]
        out[f"peak_q{i}"] = float(np.abs(q).max())
        out[f"peak_q{i}_pos"] = float(q.max())
        out[f"peak_q{i}_neg"] = float(q.min())
        el = bc.episodes(rec["t"], rec[f"ul{i}"], bc.MIN_EPISODE)
        er = bc.episodes(rec["t"], rec[f"ur{i}"], bc.MIN_EPISODE)
        out[f"n_uplifts{i}"] = len(el) + len(er)
    # apparent restitution of the contact points: their separating velocity right after the first
    # contact episode of an impact over the closing velocity before it
    e_app = [m["w_after_first"] / m["w_before"] for m in imp
             if m["w_before"] > 0 and not math.isnan(m["w_after_first"])]
    out["e_apparent_median"] = float(np.median(e_app)) if e_app else float("nan")
    return out, eps, imp


# --------------------------------------------------------------------------------------------
# flexrock
# --------------------------------------------------------------------------------------------

def column_toml(b):
    return (f"[[column]]\nheight = {b.H!r}\nwidth = {b.B!r}\ndepth = {b.D!r}\ndensity = {b.rho!r}\n"
            f"youngs_modulus = {b.E!r}\ndamping_ratio = {b.h!r}\ngravity = {b.g!r}\n"
            f"self_weight = \"consistent\"\n")


def flexrock_model(path, b0, b1, gap, excitation, duration, e=RESTITUTION):
    txt = ["# written by validation/opensees/row_pair.py: the OpenSees row's columns in flexrock",
           f"[row]\ngaps = [{gap!r}]\nrestitution = {e!r}\n", column_toml(b0), column_toml(b1)]
    if excitation["kind"] == "paper-sine":
        ex = excitation
        txt.append(f"[excitation]\nkind = \"paper-sine\"\namplitude = {float(ex['amplitude'])!r}\n"
                   f"period = {float(ex['period'])!r}\nramp = {float(ex['ramp'])!r}\n")
        txt.append(f"[simulation]\nduration = {duration!r}\n")
    else:
        rel = os.path.relpath(os.path.join(bc.RECORD_DIR, excitation["record"]), os.path.dirname(path))
        txt.append(f"[excitation]\nkind = \"record\"\npath = \"{rel}\"\nformat = \"peer-at2\"\nunits = \"g\"\n"
                   f"scale = {excitation['scale']!r}\ntail = {bc.RECORD_TAIL!r}\n")
    txt.append(f"[solver]\nmethod = \"exact\"\noutput_dt = {OUT_DT!r}\n")
    with open(path, "w") as f:
        f.write("\n".join(txt))


def run_flexrock(binary, model, out):
    if os.path.isdir(out):
        shutil.rmtree(out)
    p = subprocess.run([binary, "run", model, "--out", out], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"flexrock failed on {model}: {p.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        summ = json.load(f)
    hist = [np.genfromtxt(os.path.join(out, f"history-{i}.csv"), delimiter=",", names=True) for i in (0, 1)]
    imp = np.genfromtxt(os.path.join(out, "impacts.csv"), delimiter=",", names=True, ndmin=1)
    ev = []
    for i in (0, 1):
        with open(os.path.join(out, f"events-{i}.csv")) as f:
            ev.append(list(csv.DictReader(f)))
    # flexrock's histories are large (every column of the energy books); their q is kept in
    # history_<case>.csv and the rest is one `flexrock run` of models/<case>.toml away
    for i in (0, 1):
        for stem in ("history", "episodes"):
            os.remove(os.path.join(out, f"{stem}-{i}.csv"))
    return dict(summary=summ, hist=hist, impacts=imp, events=ev, stdout=p.stdout)


def fr_summary(fr):
    imp = fr["impacts"]
    n = int(imp.size) if imp.dtype.names else 0
    out = dict(n_impacts=n, t_first_contact=float(np.atleast_1d(imp["t"])[0]) if n else float("nan"),
               overturned=fr["summary"].get("overturned_column") is not None,
               t_overturn=fr["summary"].get("t_overturn") or float("nan"))
    for i in (0, 1):
        col = fr["summary"]["columns"][i]          # exact extremes, not the sampled history's
        out[f"peak_q{i}_pos"] = float(col["max_q"])
        out[f"peak_q{i}_neg"] = float(col["min_q"])
        out[f"peak_q{i}"] = max(abs(out[f"peak_q{i}_pos"]), abs(out[f"peak_q{i}_neg"]))
        out[f"n_uplifts{i}"] = sum(1 for e in fr["events"][i] if e.get("kind") == "uplift")
    return out


# --------------------------------------------------------------------------------------------
# Figure (plain SVG; PNG by rsvg-convert)
# --------------------------------------------------------------------------------------------

def svg_figure(path, title, t_os, q_os, t_fr, q_fr, contacts_os, contacts_fr, labels, extra=None):
    W, Hp, L, R, T, G = 900, 220, 70, 20, 40, 50
    n = len(q_os)
    Ht = T + n * Hp + (n - 1) * G + 70
    tmax = max(t_os[-1], t_fr[-1])
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{Ht}" viewBox="0 0 {W} {Ht}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{Ht}" fill="white"/>',
           f'<text x="{W / 2}" y="22" text-anchor="middle" font-size="14">{title}</text>']
    for p in range(n):
        y0 = T + p * (Hp + G)
        qa = max(np.abs(q_os[p]).max(), np.abs(q_fr[p]).max()) * 1.1
        qa = math.ceil(qa * 10) / 10
        X = lambda t: L + (W - L - R) * t / tmax
        Y = lambda q: y0 + Hp / 2 - (Hp / 2) * q / qa
        out.append(f'<rect x="{L}" y="{y0}" width="{W - L - R}" height="{Hp}" fill="none" stroke="black"/>')
        out.append(f'<line x1="{L}" x2="{W - R}" y1="{Y(0)}" y2="{Y(0)}" stroke="#bbb"/>')
        for v in (-qa, -qa / 2, qa / 2, qa):
            out.append(f'<text x="{L - 6}" y="{Y(v) + 4}" text-anchor="end">{v:g}</text>')
        out.append(f'<text x="{L - 6}" y="{Y(0) + 4}" text-anchor="end">0</text>')
        out.append(f'<text x="18" y="{y0 + Hp / 2}" transform="rotate(-90 18 {y0 + Hp / 2})" '
                   f'text-anchor="middle">q (m), {labels[p]}</text>')
        for tc in contacts_os:
            out.append(f'<line x1="{X(tc):.1f}" x2="{X(tc):.1f}" y1="{y0}" y2="{y0 + 8}" stroke="#1f77b4"/>')
        for tc in contacts_fr:
            out.append(f'<line x1="{X(tc):.1f}" x2="{X(tc):.1f}" y1="{y0 + Hp - 8}" y2="{y0 + Hp}" stroke="#d62728"/>')
        series = [(t_os, q_os[p], "#1f77b4", ""), (t_fr, q_fr[p], "#d62728", ' stroke-dasharray="5,3"')]
        if extra is not None:
            series.append((extra[0], extra[1][p], "#2ca02c", ' stroke-dasharray="1.5,2.5"'))
        for t, q, col, dash in series:
            pts = " ".join(f"{X(a):.1f},{Y(b):.1f}" for a, b in zip(t, q))
            out.append(f'<polyline points="{pts}" fill="none" stroke="{col}" stroke-width="1.3"{dash}/>')
        step = 1 if tmax <= 10 else 5
        for k in range(0, int(tmax) + 1, step):
            out.append(f'<text x="{X(k)}" y="{y0 + Hp + 15}" text-anchor="middle">{k}</text>')
    yb = Ht - 10
    out.append(f'<text x="{W / 2}" y="{Ht - 32}" text-anchor="middle">t (s)</text>')
    out.append(f'<line x1="{L}" x2="{L + 30}" y1="{yb - 4}" y2="{yb - 4}" stroke="#1f77b4" stroke-width="1.3"/>'
               f'<text x="{L + 36}" y="{yb}">OpenSees (ticks at top: contact episodes)</text>')
    out.append(f'<line x1="{L + 300}" x2="{L + 330}" y1="{yb - 4}" y2="{yb - 4}" stroke="#d62728" stroke-width="1.3" '
               f'stroke-dasharray="5,3"/><text x="{L + 336}" y="{yb}">flexrock, e = {RESTITUTION:g} (ticks at bottom: impacts)</text>')
    if extra is not None:
        out.append(f'<line x1="{L + 650}" x2="{L + 680}" y1="{yb - 4}" y2="{yb - 4}" stroke="#2ca02c" stroke-width="1.3" '
                   f'stroke-dasharray="1.5,2.5"/><text x="{L + 686}" y="{yb}">flexrock, e = 0</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    png = path[:-4] + ".png"
    subprocess.run(["rsvg-convert", "-o", png, path], check=True)


# --------------------------------------------------------------------------------------------
# Driver
# --------------------------------------------------------------------------------------------

SUM_COLS = ["case", "program", "gap", "k_contact", "e_contact", "dt", "t_first_contact", "n_impacts",
            "n_contact_episodes", "peak_q0", "peak_q0_pos", "peak_q0_neg", "peak_q1", "peak_q1_pos",
            "peak_q1_neg", "n_uplifts0", "n_uplifts1", "overturned", "t_overturn",
            "e_apparent_median", "completed", "t_end", "n_failed_steps", "runtime_s"]
CONTACT_COLS = ["impact", "start", "end", "duration", "closing_velocity", "separating_velocity", "peak_force"]
HIST_COLS = ["t", "q0_opensees", "q1_opensees", "gap_opensees", "contact_force_opensees", "q0_flexrock",
             "q1_flexrock", "q0_flexrock_e0", "q1_flexrock_e0"]


def cases(b0):
    ex = b0.excitation
    _, a = bc.paper_sine(float(ex["amplitude"]), float(ex["period"]), float(ex["ramp"]), b0.duration, 0.001)
    paper = dict(kind="paper-sine", amplitude=ex["amplitude"], period=ex["period"], ramp=ex["ramp"])
    yield "paper", paper, 0.05, 0.001, a, b0.duration
    rdt, vals = bc.read_at2(os.path.join(bc.RECORD_DIR, RECORD))
    acc = vals * bc.STANDARD_GRAVITY * RECORD_SCALE
    rec = dict(kind="record", record=RECORD, scale=RECORD_SCALE)
    yield RECORD_CASE, rec, RECORD_GAP, rdt, acc, len(vals) * rdt + bc.RECORD_TAIL
    yield "apart", paper, 5.0, 0.001, a, b0.duration


RECORD = "elCentro.AT2"
RECORD_SCALE = 2.0
RECORD_GAP = 0.05
RECORD_CASE = "elcentro-x2"
# (k_contact, dt, e of the contact dashpot); the reference run is (K_CONTACT, DT, RESTITUTION)
SWEEP = [(1e7, DT, RESTITUTION), (1e8, DT / 2, RESTITUTION), (1e9, DT, RESTITUTION),
         (1e9, DT / 2, RESTITUTION), (1e8, DT, 1.0), (1e8, DT, 0.0)]


def os_row(case, gap, k_c, e, dt, res, s):
    return [case, "opensees", gap, k_c, e, dt, s["t_first_contact"], s["n_impacts"], s["n_contact_episodes"],
            s["peak_q0"], s["peak_q0_pos"], s["peak_q0_neg"], s["peak_q1"], s["peak_q1_pos"], s["peak_q1_neg"],
            s["n_uplifts0"], s["n_uplifts1"], s["overturned"], s["t_overturn"], s["e_apparent_median"],
            res["completed"], float(res["rec"]["t"][-1]), res["n_fail"], res["runtime"]]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("what", choices=["run"])
    ap.add_argument("--out", default=os.path.join(HERE, "row_results"))
    ap.add_argument("--flexrock", default=os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(REPO, "target")),
                                                        "release", "flexrock"))
    ap.add_argument("--no-sweep", action="store_true")
    a = ap.parse_args(argv)
    out = a.out
    os.makedirs(os.path.join(out, "models"), exist_ok=True)
    b0, b1 = bodies()
    rows, meta = [], dict(cases={})
    for case, exc, gap, acc_dt, acc, dur in cases(b0):
        res = run_pair(b0, b1, gap, acc_dt, acc, dur)
        s, eps, imp = os_summary(res)
        rows.append(os_row(case, gap, K_CONTACT, RESTITUTION, DT, res, s))
        print(f"opensees {case}: " + ", ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}"
                                               for k, v in s.items()) + f", {res['runtime']:.1f} s", flush=True)
        model = os.path.join(out, "models", f"{case}.toml")
        flexrock_model(model, b0, b1, gap, exc, dur)
        t0 = time.time()
        fr = run_flexrock(a.flexrock, model, os.path.join(out, "flexrock", case))
        fs = fr_summary(fr)
        rows.append([case, "flexrock", gap, "", RESTITUTION, "", fs["t_first_contact"], fs["n_impacts"], "",
                     fs["peak_q0"], fs["peak_q0_pos"], fs["peak_q0_neg"], fs["peak_q1"], fs["peak_q1_pos"],
                     fs["peak_q1_neg"], fs["n_uplifts0"], fs["n_uplifts1"], fs["overturned"], fs["t_overturn"],
                     "", True, fr["summary"]["final_time"], "", time.time() - t0])
        print(f"flexrock {case}: " + ", ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}"
                                               for k, v in fs.items()), flush=True)
        # the same row with plastic impacts (e = 0): the OpenSees contact points hardly bounce
        model0 = os.path.join(out, "models", f"{case}-e0.toml")
        flexrock_model(model0, b0, b1, gap, exc, dur, e=0.0)
        t0 = time.time()
        fr0 = run_flexrock(a.flexrock, model0, os.path.join(out, "flexrock", f"{case}-e0"))
        f0 = fr_summary(fr0)
        rows.append([case, "flexrock_e0", gap, "", 0.0, "", f0["t_first_contact"], f0["n_impacts"], "",
                     f0["peak_q0"], f0["peak_q0_pos"], f0["peak_q0_neg"], f0["peak_q1"], f0["peak_q1_pos"],
                     f0["peak_q1_neg"], f0["n_uplifts0"], f0["n_uplifts1"], f0["overturned"], f0["t_overturn"],
                     "", True, fr0["summary"]["final_time"], "", time.time() - t0])
        print(f"flexrock e=0 {case}: " + ", ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}"
                                                   for k, v in f0.items()), flush=True)
        # contacts and histories
        crow = []
        idx = 0
        merged_starts = [m["start"] for m in imp]
        for e in eps:
            while idx + 1 < len(merged_starts) and e["start"] >= merged_starts[idx + 1]:
                idx += 1
            crow.append([idx, e["start"], e["end"], e["end"] - e["start"], e["w_before"], e["w_after"], e["peak_force"]])
        bc.write_csv(os.path.join(out, f"contacts_{case}.csv"), CONTACT_COLS, crow)
        h = res["hist"]
        fq = [np.interp(h[:, 0], fr["hist"][i]["t"], fr["hist"][i]["q"]) for i in (0, 1)]
        fq0 = [np.interp(h[:, 0], fr0["hist"][i]["t"], fr0["hist"][i]["q"]) for i in (0, 1)]
        bc.write_csv(os.path.join(out, f"history_{case}.csv"), HIST_COLS,
                     np.column_stack([h, fq[0], fq[1], fq0[0], fq0[1]]), digits=6)
        t_fr_imp = list(np.atleast_1d(fr["impacts"]["t"])) if fs["n_impacts"] else []
        svg_figure(os.path.join(out, f"row_{case}.svg"),
                   f"Two columns (H = 4 m left, 3.2 m right), gap {gap:g} m, {case}: q of each column",
                   h[:, 0], [h[:, 1], h[:, 2]], fr["hist"][0]["t"], [fr["hist"][0]["q"], fr["hist"][1]["q"]],
                   [m["start"] for m in imp], t_fr_imp, ["H = 4 m", "H = 3.2 m"],
                   extra=(fr0["hist"][0]["t"], [fr0["hist"][0]["q"], fr0["hist"][1]["q"]]))
        m = res["mdl"]
        meta["cases"][case] = dict(excitation=exc, gap_m=gap, duration_s=dur, dt_s=DT, runtime_s=res["runtime"],
                                   n_failed_steps=res["n_fail"], T_fixed_base_s=[m["T0"], m["T1"]],
                                   betaK_columns_s=[m["beta0"], m["beta1"]],
                                   flexrock_version=fr["summary"].get("flexrock_version"))
        if case == "apart":
            # each column alone, same mesh and step: the pair must reproduce it
            arow = []
            for i, (b, nel) in enumerate(((b0, 80), (b1, 64))):
                single = bc.dynamic(b, acc_dt, acc, dur, DT, nel=nel, out_dt=OUT_DT)
                d = float(np.abs(single["q"] - res["rec"][f"q{i}"]).max())
                arow.append([i, b.H, float(np.abs(single["q"]).max()), s[f"peak_q{i}"], d])
                print(f"apart: column {i} alone peak {np.abs(single['q']).max():.6f}, in the pair {s[f'peak_q{i}']:.6f}, "
                      f"max |dq| = {d:.3g} m", flush=True)
            bc.write_csv(os.path.join(out, "apart_vs_single.csv"),
                         ["column", "height", "peak_q_alone", "peak_q_in_pair", "max_abs_q_difference"], arow)
    c = res["mdl"]
    meta["contact"] = dict(element="zeroLength, dir 1, -doRayleigh 1", material="ElasticPPGap (compression only)",
                           k_contact_N_per_m=K_CONTACT, restitution_target=RESTITUTION,
                           zeta=c["zeta"], reduced_mass_kg=c["m_red"], dashpot_N_s_per_m=c["c"],
                           betaK_contact_s=c["beta_c"], merge_episodes_closer_than_s=MERGE,
                           contact_height_m=c["y_c"])
    meta.update(dt_s=DT, output_dt_s=OUT_DT, integrator="Newmark 0.5 0.25", nel=[80, 64],
                columns=[dict(height=b.H, width=b.B, density=b.rho, youngs_modulus=b.E, damping_ratio=b.h)
                         for b in (b0, b1)], q_overturn_m=Q_OVERTURN)
    bc.write_csv(os.path.join(out, "summary.csv"), SUM_COLS, rows)
    if not a.no_sweep:
        srows = [r for r in rows if r[0] == "paper" and r[1] == "opensees"]
        case, exc, gap, acc_dt, acc, dur = next(cases(b0))
        for k_c, dt, e in SWEEP:
            res = run_pair(b0, b1, gap, acc_dt, acc, dur, dt=dt, k_c=k_c, e=e)
            s, _, _ = os_summary(res)
            srows.append(os_row(case, gap, k_c, e, dt, res, s))
            print(f"sweep k={k_c:g} dt={dt:g} e={e:g} completed={res['completed']} t_end={res['rec']['t'][-1]:.4f}: " + ", ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}"
                                                             for k, v in s.items()), flush=True)
        bc.write_csv(os.path.join(out, "stiffness_sweep.csv"), SUM_COLS, srows)
        meta["sweep"] = [dict(k_contact_N_per_m=k, dt_s=d, e_contact=e, zeta=contact_zeta(e))
                         for k, d, e in [(K_CONTACT, DT, RESTITUTION)] + SWEEP]
    import scipy
    from importlib.metadata import version
    meta["versions"] = dict(python=sys.version.split()[0], openseespy=version("openseespy"),
                            numpy=np.__version__, scipy=scipy.__version__)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(meta, f, indent=1, sort_keys=True)
        f.write("\n")


if __name__ == "__main__":
    main()
