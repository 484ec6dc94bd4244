#!/usr/bin/env python3
"""OpenSees beam-column cross-check of the Ichinose (1986) rocking body, with self-weight.

A 2-D model of the body per metre of depth (book/src/model.md sections 1, 7a, 7b):

* 80 elasticBeamColumn elements along the height H (E, A = B D, I = D B^3/12), geomTransf
  PDelta (default) or Linear (--no-pdelta, the self-weight left out of the bending);
* lumped masses m dy at the column nodes (m dy/2 at the top), horizontal, vertical and rotary
  (m dy B^2/12, the sections' rotary inertia); the base node carries no mass (its weight share
  m dy/2 is applied as a load);
* the self-weight as vertical nodal loads -m_i g in a gravity stage (10 load steps), then
  loadConst;
* a rigid base plate of width B: two elastic links (E x 1e4, section of the body) from the base
  node (x = 0) to two toe nodes at x = -B/2 (left) and x = +B/2 (right); each toe on a vertical zeroLength no-tension spring
  (ENT material, k_toe = 1e10 N/m) to a fixed ground node; the base node is fixed horizontally
  (no sliding; with a rigid plate in small-rotation kinematics this is the same as fixing
  both toes horizontally);
* damping (dynamics only): stiffness-proportional on the column elements only (region with
  -rayleigh 0 betaK 0 0, betaK = 2 h/omega1, omega1 the fixed-base first mode after the gravity
  stage, so the first mode has exactly the ratio h). The toe springs get no damping: a dashpot
  beside a 1e10 N/m spring would glue the toe to the floor.

Commands (see README.md):

    beam_column.py pushover  --out DIR [--e-factor F] [--no-pdelta]
    beam_column.py dynamic   --out DIR --excitation paper|RECORD.AT2 [--scale S] [--dt DT] ...
    beam_column.py all       --out DIR   (everything in results/)

Sign conventions: x to the right, y up, rotations counter-clockwise. q = horizontal
displacement of the top node relative to the base node. The rocking part is r = -theta_base H
(a clockwise base rotation, pivot on the right toe, moves the top to +x), s = q - r.
"Uplift left" means the left toe (x = -B/2) is off the floor (the body pivots on its right toe,
q > 0); "uplift right" the mirror.
"""

import argparse
import csv
import json
import math
import os
import sys
import time
import tomllib

import numpy as np
import openseespy.opensees as ops

LAM = 1.875104068711961
SIG = (math.cosh(LAM) + math.cos(LAM)) / (math.sinh(LAM) + math.sin(LAM))

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
MODEL_FILE = os.path.join(REPO, "models", "ichinose1986.toml")
RECORD_DIR = os.path.join(REPO, "validation", "records")

# Node and element numbering
BASE = 1                # column base node (x = 0, y = 0); column nodes 1 .. nel+1
TOE_L, TOE_R = 1001, 1002
GND_L, GND_R = 2001, 2002
SPR_L, SPR_R = 3001, 3002
MAT_ENT = 1
LINK_L, LINK_R = 4001, 4002
LINK_FACTOR = 1e4       # E of the base-plate links / E of the column
UPLIFT_TOL = 1e-6       # m: a toe is "up" when its vertical displacement exceeds this
                        # (static compression under self-weight is about 8e-7 m at k = 1e10)


def U(xi):
    """First mode of a uniform cantilever, U(1) = 1 (book/src/model.md section 2)."""
    return 0.5 * (np.cosh(LAM * xi) - np.cos(LAM * xi) - SIG * (np.sinh(LAM * xi) - np.sin(LAM * xi)))


class Body:
    def __init__(self, path=MODEL_FILE, e_factor=1.0, **overrides):
        """overrides: [body] keys of the model file replaced (e.g. height=3.2)."""
        with open(path, "rb") as f:
            doc = tomllib.load(f)
        b = dict(doc["body"], **overrides)
        self.H = float(b["height"])
        self.B = float(b["width"])
        self.D = float(b.get("depth", 1.0))
        self.rho = float(b["density"])
        self.E = float(b["youngs_modulus"]) * e_factor
        self.h = float(b.get("damping_ratio", 0.05))
        self.g = float(b.get("gravity", 9.81))
        self.excitation = doc["excitation"]
        self.duration = float(doc["simulation"]["duration"])
        self.A = self.B * self.D
        self.I = self.D * self.B ** 3 / 12.0
        self.EI = self.E * self.I
        self.m = self.rho * self.A              # kg per metre of height
        self.M = self.m * self.H
        self.Ke = LAM ** 3 * SIG * self.EI / self.H ** 3
        self.Me = self.M * SIG / LAM
        self.T_paper = 2 * math.pi / math.sqrt(self.Ke / self.Me)
        self.gamma_g = self.M * self.g * self.H ** 2 / self.EI
        # the paper's uplift displacement (eq. 8)
        self.s_n = self.B / (2 * self.EI * LAM ** 2 / (self.M * self.g * self.H ** 2) + 2 * SIG / LAM)
        # uplift with the weight left out of bending and of the moment balance (Linear transf)
        self.s_lin = self.B / (2 * self.EI * LAM ** 2 / (self.M * self.g * self.H ** 2))


def build(body, nel=80, pdelta=True, k_toe=1e10, rotary=True):
    """Build the model of one column and run the gravity stage. Returns a dict of model data."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    mdl = build_column(body, nel=nel, pdelta=pdelta, k_toe=k_toe, rotary=rotary)
    gravity(mdl["weights"])
    return mdl


def build_column(body, nel=80, pdelta=True, k_toe=1e10, rotary=True, tag0=0, x0=0.0):
    """Add one column to the current (2-D, 3 dof) model, with every node, element, material and
    transformation tag offset by tag0 and the column's axis at x = x0; no loads yet (gravity()
    applies the weights). Returns a dict of model data, tags included."""
    H, B, m = body.H, body.B, body.m
    dy = H / nel
    base = tag0 + BASE
    toe_l, toe_r = tag0 + TOE_L, tag0 + TOE_R
    gnd_l, gnd_r = tag0 + GND_L, tag0 + GND_R
    spr_l, spr_r = tag0 + SPR_L, tag0 + SPR_R
    mat = tag0 + MAT_ENT
    ys = np.linspace(0.0, H, nel + 1)
    for i, y in enumerate(ys):
        ops.node(base + i, x0, float(y))
    top = base + nel
    ops.node(toe_l, x0 - B / 2, 0.0)
    ops.node(toe_r, x0 + B / 2, 0.0)
    ops.node(gnd_l, x0 - B / 2, 0.0)
    ops.node(gnd_r, x0 + B / 2, 0.0)
    ops.fix(gnd_l, 1, 1, 1)
    ops.fix(gnd_r, 1, 1, 1)
    ops.fix(base, 1, 0, 0)                    # no sliding
    ops.uniaxialMaterial("ENT", mat, k_toe)
    ops.element("zeroLength", spr_l, gnd_l, toe_l, "-mat", mat, "-dir", 2)
    ops.element("zeroLength", spr_r, gnd_r, toe_r, "-mat", mat, "-dir", 2)
    ops.geomTransf("PDelta" if pdelta else "Linear", tag0 + 1)
    # the rigid base plate: two elastic links, 1e4 times the column's E (a rigidLink with the
    # Transformation handler made DisplacementControl fail to converge in OpenSees 3.7.1)
    ops.geomTransf("Linear", tag0 + 2)
    ops.element("elasticBeamColumn", tag0 + LINK_L, base, toe_l, body.A, body.E * LINK_FACTOR, body.I, tag0 + 2)
    ops.element("elasticBeamColumn", tag0 + LINK_R, base, toe_r, body.A, body.E * LINK_FACTOR, body.I, tag0 + 2)
    for e in range(nel):
        ops.element("elasticBeamColumn", tag0 + e + 1, base + e, base + e + 1, body.A, body.E, body.I, tag0 + 1)
    # lumped masses: m dy at interior nodes, m dy/2 at the top; the base node's share is only loaded
    weights = {}
    lateral = {}
    for i in range(nel + 1):
        node = base + i
        mi = m * dy * (0.5 if i in (0, nel) else 1.0)
        weights[node] = mi * body.g
        lateral[node] = mi * float(U(ys[i] / H))
        if i > 0:
            ops.mass(node, mi, mi, mi * B ** 2 / 12.0 if rotary else 0.0)
    return dict(nel=nel, top=top, ys=ys, weights=weights, lateral=lateral, pdelta=pdelta, k_toe=k_toe,
                base=base, toe_l=toe_l, toe_r=toe_r, spr_l=spr_l, spr_r=spr_r,
                ele_first=tag0 + 1, ele_last=tag0 + nel, H=H)


def gravity(weights, series=1, pattern=1):
    """The gravity stage: the nodal weights in 10 load steps, then loadConst (time reset to 0)."""
    ops.timeSeries("Linear", series)
    ops.pattern("Plain", pattern, series)
    for node, w in weights.items():
        ops.load(node, 0.0, -w, 0.0)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    ok = ops.analyze(10)
    if ok != 0:
        raise RuntimeError("gravity stage failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def fixed_base_period(nmodes=1):
    """Eigen analysis of the current (post-gravity) state; toes in contact = fixed base."""
    lam = ops.eigen("-fullGenLapack", nmodes)
    return [2 * math.pi / math.sqrt(v) for v in lam]


def state(body, mdl):
    """q, r, s, toe uplifts (vertical displacements of the toes, > 0 = up)."""
    base = mdl.get("base", BASE)
    q = ops.nodeDisp(mdl["top"], 1) - ops.nodeDisp(base, 1)
    theta = ops.nodeDisp(base, 3)
    r = -theta * body.H
    return q, r, q - r, ops.nodeDisp(mdl.get("toe_l", TOE_L), 2), ops.nodeDisp(mdl.get("toe_r", TOE_R), 2)


# --------------------------------------------------------------------------------------------
# Pushover
# --------------------------------------------------------------------------------------------

def pushover(body, pdelta=True, q_max=0.75, dq=2.5e-4, nel=80, k_toe=1e10):
    build(body, nel=nel, pdelta=pdelta, k_toe=k_toe, rotary=False)
    T1_norot = fixed_base_period(1)[0]
    mdl = build(body, nel=nel, pdelta=pdelta, k_toe=k_toe)
    T1 = fixed_base_period(1)[0]
    sum_lat = sum(mdl["lateral"].values())
    ops.timeSeries("Linear", 2)
    ops.pattern("Plain", 2, 2)
    for node, f in mdl["lateral"].items():
        if f != 0.0:
            ops.load(node, f, 0.0, 0.0)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-11, 100)
    ops.algorithm("Newton")
    ops.integrator("DisplacementControl", mdl["top"], 1, dq)
    ops.analysis("Static")
    rows = []
    q, r, s, ul, ur = state(body, mdl)
    rows.append((q, 0.0, ul, ur, s, r, ops.eleResponse(SPR_L, "force")[1], ops.eleResponse(SPR_R, "force")[1]))
    n = int(round(q_max / dq))
    for k in range(n):
        ok = ops.analyze(1)
        if ok != 0:
            for alg in (("ModifiedNewton", "-initial"), ("KrylovNewton",), ("NewtonLineSearch",)):
                ops.algorithm(*alg)
                ok = ops.analyze(1)
                ops.algorithm("Newton")
                if ok == 0:
                    break
        if ok != 0:
            print(f"pushover: no convergence at step {k}", file=sys.stderr)
            break
        lf = ops.getLoadFactor(2)
        q, r, s, ul, ur = state(body, mdl)
        # toe spring forces (ground -> toe element, local y = vertical; compression < 0)
        fl = ops.eleResponse(SPR_L, "force")[1]
        fr = ops.eleResponse(SPR_R, "force")[1]
        rows.append((q, lf * sum_lat, ul, ur, s, r, fl, fr))
    return np.array(rows), T1, T1_norot


def analyse_pushover(rows, body):
    q, V, ul, ur, s, r, fl, fr = rows.T
    # pre-uplift stiffness: secant over the first 20 % of the uplift displacement
    # uplift: the left toe's spring force reaches zero (linear interpolation)
    # spring "force" of the zeroLength: +/- convention checked below by the sign under gravity
    sgn = np.sign(fl[0])          # sign of a compressive force
    comp = sgn * fl               # > 0 while in contact
    k = int(np.argmax(comp <= 0.0))
    if k == 0:
        raise RuntimeError("no uplift found")
    # the contact force and the base shear are linear in q before uplift: extrapolate the last
    # two steps in contact to the zero of the contact force (exact up to round-off)
    a = comp[k - 1] / (comp[k - 2] - comp[k - 1])
    q_up = q[k - 1] + a * (q[k - 1] - q[k - 2])
    V_up = V[k - 1] + a * (V[k - 1] - V[k - 2])
    pre = (q > 0) & (q < 0.5 * q_up)
    K0 = np.polyfit(q[pre], V[pre], 1)[0]
    # post-uplift slope: least squares over q in [q_up + 0.25 (0.7 - q_up), 0.7] where V > 0
    lo = q_up + 0.25 * (0.7 - q_up)
    post = (q > lo) & (q < 0.7)
    slope, icpt = np.polyfit(q[post], V[post], 1)
    # zero base shear
    j = np.where((V[1:] <= 0.0) & (V[:-1] > 0.0))[0]
    if len(j):
        j = j[0]
        q0 = q[j] - V[j] * (q[j + 1] - q[j]) / (V[j + 1] - V[j])
        s_at_q0 = np.interp(q0, q, s)
    else:
        q0 = float("nan")
        s_at_q0 = float("nan")
    # base moment check at uplift: V_up * lever vs M g B/2 (not needed; reported: s at uplift)
    s_up = np.interp(q_up, q, s)
    return dict(K0=K0, K0_over_Ke=K0 / body.Ke, q_uplift=q_up, V_uplift=V_up, s_uplift=s_up,
                post_slope=slope, q_zero_shear=q0, s_at_zero_shear=s_at_q0,
                V_max=float(V.max()), q_end=float(q[-1]), V_end=float(V[-1]))


# --------------------------------------------------------------------------------------------
# Excitations
# --------------------------------------------------------------------------------------------

def paper_sine_coefficients(A, Tp, ramp):
    w = 2 * math.pi / Tp
    t = ramp
    Mx = np.array([[t, t ** 2, t ** 3],
                   [t ** 2 / 2, t ** 3 / 3, t ** 4 / 4],
                   [t ** 3 / 6, t ** 4 / 12, t ** 5 / 20]])
    rhs = np.array([A * math.sin(w * t), -A / w * math.cos(w * t), -A / w ** 2 * math.sin(w * t)])
    return np.linalg.solve(Mx, rhs)


def paper_sine(A, Tp, ramp, duration, dt):
    c1, c2, c3 = paper_sine_coefficients(A, Tp, ramp)
    t = np.arange(0.0, duration + 0.5 * dt, dt)
    a = np.where(t < ramp, t * (c1 + t * (c2 + t * c3)), A * np.sin(2 * math.pi * t / Tp))
    return t, a


def read_at2(path):
    """PEER AT2: four header lines, the fourth with NPTS and DT; then values (units g)."""
    with open(path) as f:
        lines = f.read().splitlines()
    hdr = lines[3].upper().replace(",", " ").replace("=", " ")
    tok = hdr.split()
    npts = dt = None
    for i, w in enumerate(tok):
        if w == "NPTS":
            npts = int(tok[i + 1])
        if w == "DT":
            dt = float(tok[i + 1])
    if npts is None or dt is None:      # older layout: "<npts> <dt> ..."
        nums = [x for x in tok if x.replace(".", "").replace("-", "").replace("E", "").isdigit()]
        npts, dt = int(float(nums[0])), float(nums[1])
    vals = []
    for ln in lines[4:]:
        # fixed-width 8F10.5 may have no spaces between fields of negative numbers: split by width too
        parts = ln.split()
        try:
            vals.extend(float(p) for p in parts)
        except ValueError:
            vals.extend(float(ln[i:i + 10]) for i in range(0, len(ln.rstrip()), 10))
    vals = np.array(vals[:npts])
    if len(vals) != npts:
        raise ValueError(f"{path}: {len(vals)} values, header says {npts}")
    return dt, vals


# --------------------------------------------------------------------------------------------
# Dynamics
# --------------------------------------------------------------------------------------------

def dynamic(body, acc_dt, acc, duration, dt, pdelta=True, nel=80, k_toe=1e10, q_over=1.0,
            out_dt=0.01, integrator=("Newmark", 0.5, 0.25), rotary=True):
    """acc in m/s^2, sampled at acc_dt from t = 0, linear in between, zero after the end."""
    mdl = build(body, nel=nel, pdelta=pdelta, k_toe=k_toe, rotary=rotary)
    T1 = fixed_base_period(1)[0]
    w1 = 2 * math.pi / T1
    betaK = 2 * body.h / w1
    ops.region(1, "-eleRange", 1, nel, "-rayleigh", 0.0, betaK, 0.0, 0.0)
    ops.timeSeries("Path", 3, "-dt", acc_dt, "-values", *map(float, acc))
    ops.pattern("UniformExcitation", 3, 1, "-accel", 3)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-9, 50)
    ops.algorithm("Newton")
    ops.integrator(*integrator)
    ops.analysis("Transient")
    nsteps = int(round(duration / dt))
    dec = max(1, int(round(out_dt / dt)))
    hist = []
    full_t, full_q, full_ul, full_ur = [0.0], [0.0], [False], [False]
    q, r, s, ul, ur = state(body, mdl)
    q_static = q
    hist.append((0.0, q, s, r, ul, ur, 0.0))
    overturned = False
    t_over = float("nan")
    n_fail = 0
    t = 0.0
    for k in range(nsteps):
        ok = ops.analyze(1, dt)
        if ok != 0:
            n_fail += 1
            ok = substep(dt)
            if ok != 0:
                print(f"dynamic: no convergence at t = {t:.4f}", file=sys.stderr)
                break
        t = ops.getTime()
        q, r, s, ul, ur = state(body, mdl)
        full_t.append(t)
        full_q.append(q)
        full_ul.append(ul > UPLIFT_TOL)
        full_ur.append(ur > UPLIFT_TOL)
        if (k + 1) % dec == 0:
            a = float(np.interp(t, np.arange(len(acc)) * acc_dt, acc, right=0.0))
            hist.append((t, q, s, r, ul, ur, a))
        if abs(q) > q_over:
            overturned = True
            t_over = t
            if (k + 1) % dec != 0:
                hist.append((t, q, s, r, ul, ur, float("nan")))
            break
    return dict(T1=T1, betaK=betaK, hist=np.array(hist), t=np.array(full_t), q=np.array(full_q),
                ul=np.array(full_ul), ur=np.array(full_ur), overturned=overturned, t_over=t_over,
                n_fail=n_fail, q_static=q_static, completed=(t >= duration - 1e-9) or overturned)


def substep(dt, n=10):
    """Retry a failed step as n substeps with more robust algorithms."""
    for alg in (("Newton",), ("KrylovNewton",), ("ModifiedNewton", "-initial")):
        ops.algorithm(*alg)
        ok = 0
        for _ in range(n):
            ok = ops.analyze(1, dt / n)
            if ok != 0:
                break
        ops.algorithm("Newton")
        if ok == 0:
            return 0
    return -1


def episodes(t, up, min_len):
    """Uplift episodes (runs of True) longer than min_len s: list of (start, end)."""
    eps = []
    start = None
    for i in range(len(t)):
        if up[i] and start is None:
            start = t[i]
        if not up[i] and start is not None:
            eps.append((start, t[i]))
            start = None
    if start is not None:
        eps.append((start, t[-1]))
    return [e for e in eps if e[1] - e[0] >= min_len]


def summarise(res, min_len=0.02):
    t, q = res["t"], res["q"]
    el = episodes(t, res["ul"], min_len)
    er = episodes(t, res["ur"], min_len)
    # first uplift = start of the first sustained episode; a one-step lift of 1e-6 m right after
    # an impact (chatter) depends on dt and is not counted
    first = lambda eps: float(eps[0][0]) if eps else float("nan")
    return dict(peak_q=float(np.abs(q).max()), peak_q_pos=float(q.max()), peak_q_neg=float(q.min()),
                t_peak=float(t[np.argmax(np.abs(q))]),
                t_first_uplift_right=first(er), t_first_uplift_left=first(el),
                n_uplifts=len(el) + len(er), n_uplifts_left=len(el), n_uplifts_right=len(er),
                overturned=res["overturned"], t_overturn=res["t_over"],
                n_failed_steps=res["n_fail"], completed=res["completed"])


# --------------------------------------------------------------------------------------------
# Driver: every output of results/
# --------------------------------------------------------------------------------------------

RECORDS = ["elCentro.AT2", "ANLA196.AT2", "A-ELC180.AT2", "PBFEAS.AT2", "HEN-E.AT2"]
RECORD_SCALES = (1.0, 5.0)  # 1.0 as models/elcentro1940.toml; 5.0 as core/tests/hardening.rs (0, 1, 5)
STANDARD_GRAVITY = 9.80665  # records in units of g, as flexrock reads them (core/src/base/units.rs)
RECORD_TAIL = 5.0       # s of free vibration after a record, as models/elcentro1940.toml
MIN_EPISODE = 0.02      # s: shorter uplift episodes are counted as chatter, not as uplifts
Q_OVERTURN = 1.0        # m: |q| beyond this = overturned (static zero-force point is 0.735 m)

PUSH_COLS = ["q", "base_shear", "uplift_left", "uplift_right", "s", "r",
             "toe_force_left", "toe_force_right"]
PUSH_SUMMARY_COLS = ["case", "e_factor", "pdelta", "gamma_g", "Ke", "K0", "K0_over_Ke",
                     "q_uplift", "V_uplift", "s_uplift", "post_slope", "q_zero_shear",
                     "s_at_zero_shear", "T_fixed_base", "T_fixed_base_no_rotary", "T_paper",
                     "s_n_paper", "runtime_s"]
DYN_COLS = ["case", "record", "scale", "dt", "pdelta", "peak_q", "peak_q_pos", "peak_q_neg",
            "t_peak", "t_first_uplift_right", "t_first_uplift_left", "n_uplifts",
            "n_uplifts_left", "n_uplifts_right", "overturned", "t_overturn", "completed",
            "n_failed_steps", "T_fixed_base", "betaK", "duration", "runtime_s"]
HIST_COLS = ["t", "q", "s", "r", "uplift_left", "uplift_right", "floor_acc"]


def fmt(x):
    if isinstance(x, (bool, np.bool_)):
        return "true" if x else "false"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        return "" if math.isnan(x) else f"{float(x):.7g}"
    return str(x)


def write_csv(path, cols, rows, digits=7):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(cols)
        for r in rows:
            w.writerow([f"{float(x):.{digits}g}" if digits != 7 and isinstance(x, (float, np.floating))
                        and not math.isnan(x) else fmt(x) for x in r])


def run_pushovers(out):
    rows = []
    for ef in (1.0, 10.0):
        for pd in (True, False):
            body = Body(e_factor=ef)
            case = f"E{int(ef)}_{'pdelta' if pd else 'linear'}"
            t0 = time.time()
            data, T1, T1n = pushover(body, pdelta=pd)
            rt = time.time() - t0
            res = analyse_pushover(data, body)
            write_csv(os.path.join(out, f"pushover_{case}.csv"), PUSH_COLS, data[::4])
            rows.append([case, ef, pd, body.gamma_g, body.Ke, res["K0"], res["K0_over_Ke"],
                         res["q_uplift"], res["V_uplift"], res["s_uplift"], res["post_slope"],
                         res["q_zero_shear"], res["s_at_zero_shear"], T1, T1n, body.T_paper,
                         body.s_n, rt])
            print(f"pushover {case}: " + ", ".join(f"{k}={v:.6g}" for k, v in res.items())
                  + f", T1={T1:.5f}, T1(no rotary)={T1n:.5f}, {rt:.1f} s", flush=True)
    write_csv(os.path.join(out, "pushover_summary.csv"), PUSH_SUMMARY_COLS, rows)


def excitations(body):
    ex = body.excitation
    dt_in = 0.001
    t, a = paper_sine(float(ex["amplitude"]), float(ex["period"]), float(ex["ramp"]), body.duration, dt_in)
    yield "paper-sine", 1.0, dt_in, a, body.duration, 0.005
    for scale in RECORD_SCALES:
        for rec in RECORDS:
            rdt, vals = read_at2(os.path.join(RECORD_DIR, rec))
            acc = vals * STANDARD_GRAVITY * scale
            yield rec, scale, rdt, acc, len(vals) * rdt + RECORD_TAIL, min(0.005, rdt / 4)


def run_dynamics(out, halve=True, linear=True, only=None):
    """E: P-Delta at dt and dt/2, Linear at dt. 10 E (the stiffer body of the pushover, where the
    self-weight matters little): P-Delta at dt and dt/2, histories of the paper's wave only."""
    rows = []
    for ef in (1.0, 10.0):
        body = Body(e_factor=ef)
        for name, scale, acc_dt, acc, dur, dt in excitations(body):
            if only and name not in only:
                continue
            variants = [(True, dt, True)]
            if halve:
                variants.append((True, dt / 2, False))
                if ef == 10.0 and name == "paper-sine":
                    # this run comes within 1 cm of the overturning criterion and its late part
                    # converges slowly in dt: three more halvings (6 s of motion, cheap)
                    variants.extend((True, dt / 2 ** k, False) for k in (2, 3, 4))
            if linear and ef == 1.0:
                variants.append((False, dt, True))
            rows.extend(dynamic_rows(out, body, ef, name, scale, acc_dt, acc, dur, variants))
    write_csv(os.path.join(out, "dynamic_summary.csv"), DYN_COLS, rows)


def dynamic_rows(out, body, ef, name, scale, acc_dt, acc, dur, variants):
    rows = []
    if True:
        for pd, step, write_hist in variants:
            case = f"E{int(ef)}_{'pdelta' if pd else 'linear'}"
            t0 = time.time()
            res = dynamic(body, acc_dt, acc, dur, step, pdelta=pd, q_over=Q_OVERTURN)
            rt = time.time() - t0
            sm = summarise(res, MIN_EPISODE)
            rows.append([case, name, scale, step, pd, sm["peak_q"], sm["peak_q_pos"], sm["peak_q_neg"],
                         sm["t_peak"], sm["t_first_uplift_right"], sm["t_first_uplift_left"],
                         sm["n_uplifts"], sm["n_uplifts_left"], sm["n_uplifts_right"],
                         sm["overturned"], sm["t_overturn"], sm["completed"], sm["n_failed_steps"],
                         res["T1"], res["betaK"], dur, rt])
            print(f"dynamic {case} {name} dt={step}: peak_q={sm['peak_q']:.5f} "
                  f"(+{sm['peak_q_pos']:.5f}/{sm['peak_q_neg']:.5f}) first uplift R/L="
                  f"{sm['t_first_uplift_right']:.3f}/{sm['t_first_uplift_left']:.3f} "
                  f"n={sm['n_uplifts']} overturned={sm['overturned']} fails={sm['n_failed_steps']} "
                  f"{rt:.1f} s", flush=True)
            # time histories: the P-Delta runs, and the Linear one of the paper's wave only (the
            # Linear record runs are in the summary; their histories would double the size)
            if write_hist and ((pd and ef == 1.0) or name == "paper-sine"):
                stem = name.replace(".AT2", "") + ("" if name == "paper-sine" else f"_x{scale:g}")
                write_csv(os.path.join(out, f"history_{case}_{stem}.csv"), HIST_COLS, res["hist"], digits=6)
    return rows


SENS_COLS = ["variant", "k_toe", "nel", "integrator", "rotary_inertia", "dt", "peak_q", "peak_q_pos",
             "peak_q_neg", "t_first_uplift_right", "t_first_uplift_left", "n_uplifts", "overturned",
             "n_failed_steps", "T_fixed_base", "runtime_s"]


def run_sensitivity(out):
    """The paper's wave on the P-Delta body: one modelling choice changed at a time."""
    body = Body()
    ex = body.excitation
    _, a = paper_sine(float(ex["amplitude"]), float(ex["period"]), float(ex["ramp"]), body.duration, 0.001)
    base = dict(k_toe=1e10, nel=80, integrator=("Newmark", 0.5, 0.25), rotary=True, dt=0.005)
    variants = [("reference", {}),
                ("k_toe=1e9", dict(k_toe=1e9)), ("k_toe=1e11", dict(k_toe=1e11)),
                ("k_toe=1e12", dict(k_toe=1e12)),
                ("nel=40", dict(nel=40)), ("nel=160", dict(nel=160)),
                ("HHT alpha=0.9", dict(integrator=("HHT", 0.9))),
                ("no rotary inertia", dict(rotary=False)),
                ("dt/2", dict(dt=0.0025)), ("dt/4", dict(dt=0.00125))]
    rows = []
    for name, change in variants:
        v = dict(base, **change)
        t0 = time.time()
        res = dynamic(body, 0.001, a, body.duration, v["dt"], nel=v["nel"], k_toe=v["k_toe"],
                      integrator=v["integrator"], rotary=v["rotary"], q_over=Q_OVERTURN)
        sm = summarise(res, MIN_EPISODE)
        rows.append([name, v["k_toe"], v["nel"], " ".join(map(str, v["integrator"])), v["rotary"], v["dt"],
                     sm["peak_q"], sm["peak_q_pos"], sm["peak_q_neg"], sm["t_first_uplift_right"],
                     sm["t_first_uplift_left"], sm["n_uplifts"], sm["overturned"], sm["n_failed_steps"],
                     res["T1"], time.time() - t0])
        print(f"sensitivity {name}: peak_q={sm['peak_q']:.5f} (+{sm['peak_q_pos']:.5f}/{sm['peak_q_neg']:.5f}) "
              f"first uplift R/L={sm['t_first_uplift_right']:.3f}/{sm['t_first_uplift_left']:.3f} "
              f"n={sm['n_uplifts']} T1={res['T1']:.4f}", flush=True)
    write_csv(os.path.join(out, "sensitivity_paper_sine.csv"), SENS_COLS, rows)


def versions(out):
    import scipy
    info = dict(python=sys.version.split()[0], openseespy=ops.version() if hasattr(ops, "version") else "",
                numpy=np.__version__, scipy=scipy.__version__)
    try:
        from importlib.metadata import version
        info["openseespy"] = version("openseespy")
    except Exception:
        pass
    with open(os.path.join(out, "versions.json"), "w") as f:
        json.dump(info, f, indent=1, sort_keys=True)
        f.write("\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("what", choices=["pushover", "dynamic", "sensitivity", "all"])
    ap.add_argument("--out", default=os.path.join(HERE, "results"))
    ap.add_argument("--only", nargs="*", help="dynamic: only these excitations (paper-sine, elCentro.AT2, ...)")
    ap.add_argument("--no-halve", action="store_true", help="dynamic: skip the dt/2 convergence runs")
    ap.add_argument("--no-linear", action="store_true", help="dynamic: skip the Linear-transf runs")
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    versions(a.out)
    if a.what in ("pushover", "all"):
        run_pushovers(a.out)
    if a.what in ("dynamic", "all"):
        run_dynamics(a.out, halve=not a.no_halve, linear=not a.no_linear, only=a.only)
    if a.what in ("sensitivity", "all"):
        run_sensitivity(a.out)


if __name__ == "__main__":
    main()
