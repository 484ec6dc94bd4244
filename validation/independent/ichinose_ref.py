#!/usr/bin/env python3
"""Independent reference implementation of the Ichinose (1986) SDOF rocking model.

T. Ichinose (1986), "Rocking motion of slender elastic body on rigid floor",
Bull. NZ Soc. Earthq. Eng. 19(1), 18-27, as restated in the project's model chapter
(book/src/model.md, sections 2-6).  Written from that restatement only (Python + numpy + scipy); it shares no
code with the Rust crate and is used to produce expected values for its tests.

Model (one state variable q = top displacement relative to the floor):

    Me q'' + c nu F'(q) q' + nu F(q) = -beta Me a(t),      c = gamma/E = 2 h / omega

    pre-uplift (|q| < s_n): nu = 1,   beta = beta1, F = Ke q,  F' = Ke
    rock-right (q >  s_n):  nu = nu2, beta = beta2, F =  Ke s_n (B - q)/(B - s_n)
    rock-left  (q < -s_n):  nu = nu2, beta = beta2, F = -Ke s_n (B + q)/(B - s_n)
                            F' = -Ke s_n/(B - s_n) in both rocking modes

  (F' < 0 while rocking, so the damping term feeds energy into q while rocking.
   That is the paper's model and it is implemented exactly as written.)

Hybrid automaton (book/src/model.md section 6):

    pre-uplift --q = +s_n rising--> rock-right   q' <- zetaU q'
    pre-uplift --q = -s_n falling-> rock-left    q' <- zetaU q'
    rock-right --q = +s_n falling-> pre-uplift   q' <- q'/zetaL
    rock-left  --q = -s_n rising--> pre-uplift   q' <- q'/zetaL
    rock-right --q = +B rising----> overturned   terminal
    rock-left  --q = -B falling---> overturned   terminal

Numerics
--------
* scipy.integrate.solve_ivp, DOP853 (primary) and Radau (cross-check, analytic
  Jacobian), rtol = 1e-12, atol = 1e-14, max_step = 0.01 s (a safety net so that
  no sign change of a guard can hide inside one step).
* Guards are directional, terminal event functions.  After a terminal event the
  state is reset (q set exactly to the guard value, q' multiplied by the jump
  factor) and the integration restarts in the new mode.  Because the guards are
  directional, a restart on a guard surface cannot re-trigger that guard.
* Peaks: a non-terminal event on q' (both directions) records every zero of q';
  max q / min q are taken over those, t = 0 and the final time (q' does not
  change sign at a reset since zetaU, zetaL > 0, so no other extrema exist).
* Event-time polishing: scipy locates an event on the step's dense-output
  interpolant.  Every event and peak time is then polished with Newton
  iterations in which the state at the trial time is obtained by a fresh
  integration (same method, same tolerances) from the last accepted step point
  before the event, so that event times and peak values carry the integrator's
  accuracy instead of the interpolant's (this matters for Radau, whose
  interpolant is only cubic).
* Integration is also stopped exactly at the end of the paper-sine ramp, at the
  end of a sine pulse and at every sample time (0, 0.25, 0.5, ... s), so that
  samples are step end points, not interpolated values.  On a segment that ends at
  a sine pulse's end the pulse formula is used up to and including that end (the
  left limit), so no step sees the cosine pulse's jump A -> 0.

Floor motions: paper-sine, harmonic, free (the cases below) and sine-pulse
(A sin(2 pi t/Tp) for shape "antisymmetric", A cos(2 pi t/Tp) for "symmetric",
for 0 <= t < cycles Tp, then 0), used by validation/sweep/compare.py.

Run from the repository root:

    python3 validation/independent/ichinose_ref.py          # everything
    python3 validation/independent/ichinose_ref.py --quick  # skip the LSODA timing

It writes tests/data/cases/<name>.toml and <name>.expected.json and prints the
quality checks (constants, ramp coefficients, DOP853 vs Radau, rigid limit,
grazing margins, LSODA timing) that are recorded in README.md beside this file.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

# --------------------------------------------------------------------------
# Section 2: exact constants
# --------------------------------------------------------------------------
LAM = 1.875104068711961
SIG = (math.cosh(LAM) + math.cos(LAM)) / (math.sinh(LAM) + math.sin(LAM))
BUCKLING_GAMMA_G = 7.837  # M g H^2/EI at which a uniform cantilever buckles under self-weight

PRE, RR, RL, OVER = "pre-uplift", "rock-right", "rock-left", "overturned"

RTOL_REF = 1e-12
ATOL_REF = 1e-14
MAX_STEP = 0.01
SAMPLE_DT = 0.25


def derived_constants(body: dict) -> dict:
    """All constants of book/src/model.md sections 2-5 and 7a for a body dict."""
    H = body["height"]
    B = body["width"]
    D = body.get("depth", 1.0)
    rho_v = body["density"]
    E = body["youngs_modulus"]
    h = body["damping_ratio"]
    g = body.get("gravity", 9.81)

    M = rho_v * H * B * D
    EI = E * D * B**3 / 12.0
    intU = SIG / LAM
    intU2 = 0.25
    Me = M * intU                       # rho H sig/L
    Ke = LAM**3 * SIG * EI / H**3
    omega = math.sqrt(Ke / Me)
    T = 2.0 * math.pi / omega
    c = 2.0 * h / omega                 # gamma/E
    beta1 = intU / intU2
    nu1 = 1.0
    gamma_g = M * g * H**2 / EI
    s_n = B / (2.0 * EI * LAM**2 / (M * g * H**2) + 2.0 * SIG / LAM)
    d = B - s_n
    intUV = (-s_n / 4.0 + B / LAM**2) / d
    intV = (-s_n * SIG / LAM + B / 2.0) / d
    intV2 = (s_n**2 / 4.0 - 2.0 * B * s_n / LAM**2 + B**2 / 3.0) / d**2
    nu2 = intUV / intV2
    beta2 = intV / intV2
    intUy = H**2 / LAM**2
    intVy = H**2 * (B / 3.0 - s_n / LAM**2) / d
    zetaU = (intUy + B**2 / 12.0) / (intVy + B**2 / 12.0 + (B**2 / 4.0) * B / d)
    zetaL = (intUy + B**2 / 12.0) / (intVy + B**2 / 12.0 - (B**2 / 4.0) * B / d)
    if s_n >= B:
        raise ValueError("s_n >= B: body unstable under its own weight")
    if zetaL >= 1.0:
        raise ValueError("zetaL >= 1: body too squat for the model")
    return dict(
        H=H, B=B, D=D, M=M, EI=EI, g=g, h=h,
        Me=Me, Ke=Ke, omega=omega, T=T, c=c, s_n=s_n,
        nu1=nu1, beta1=beta1, nu2=nu2, beta2=beta2, zetaU=zetaU, zetaL=zetaL,
        quasi_static_uplift_acc=omega**2 * s_n / beta1,
        gravity_parameter=gamma_g,
    )


# --------------------------------------------------------------------------
# Excitations
# --------------------------------------------------------------------------
def ramp_coefficients(A: float, Tp: float, tr: float) -> np.ndarray:
    """c1, c2, c3 of a = c1 t + c2 t^2 + c3 t^3 on [0, tr), floor at rest at t = 0,
    with a, floor velocity and floor displacement continuous at tr with the sine."""
    w = 2.0 * math.pi / Tp
    M = np.array([
        [tr, tr**2, tr**3],                       # a
        [tr**2 / 2, tr**3 / 3, tr**4 / 4],        # velocity = int a
        [tr**3 / 6, tr**4 / 12, tr**5 / 20],      # displacement = int int a
    ])
    rhs = np.array([
        A * math.sin(w * tr),
        -(A / w) * math.cos(w * tr),
        -(A / w**2) * math.sin(w * tr),
    ])
    return np.linalg.solve(M, rhs)


class Excitation:
    def __init__(self, exc: dict):
        self.kind = exc["kind"]
        self.breaks: list[float] = []
        if self.kind == "free":
            self.A, self.Tp = 0.0, 1.0
        else:
            self.A = float(exc["amplitude"])
            self.Tp = float(exc["period"])
        self.w = 2.0 * math.pi / self.Tp
        if self.kind == "paper-sine":
            self.ramp = float(exc["ramp"])
            self.coef = ramp_coefficients(self.A, self.Tp, self.ramp)
            self.breaks = [self.ramp]
        elif self.kind == "sine-pulse":
            # A sin(2 pi t/Tp) ("antisymmetric") or A cos(2 pi t/Tp) ("symmetric") for
            # 0 <= t < cycles Tp, then a = 0.  The pulse end is a break: a kink for the
            # sine, a jump (A -> 0) for the cosine.
            self.shape = exc.get("shape", "antisymmetric")
            if self.shape not in ("antisymmetric", "symmetric"):
                raise ValueError(self.shape)
            self.cycles = int(exc.get("cycles", 1))
            self.end = self.cycles * self.Tp
            self.breaks = [self.end]
        elif self.kind not in ("harmonic", "free"):
            raise ValueError(self.kind)

    def __call__(self, t: float) -> float:
        if self.kind == "free":
            return 0.0
        if self.kind == "paper-sine" and t < self.ramp:
            c1, c2, c3 = self.coef
            return t * (c1 + t * (c2 + t * c3))
        if self.kind == "sine-pulse":
            if t >= self.end:
                return 0.0
            return self._pulse(t)
        return self.A * math.sin(self.w * t)

    def _pulse(self, t: float) -> float:
        if self.shape == "symmetric":
            return self.A * math.cos(self.w * t)
        return self.A * math.sin(self.w * t)

    def piece(self, t0: float):
        """a(t) on the integration segment that starts at t0.  Segments never straddle a
        break (simulate stops at every break), so on a segment that starts before the
        pulse end the pulse formula holds on the closed segment, including its right end:
        the last stage of a step that ends exactly at the pulse end sees the left limit
        of the cosine pulse (A), not the rest value (0)."""
        if self.kind != "sine-pulse":
            return self
        if t0 < self.end:
            return self._pulse
        return lambda t: 0.0  # noqa: E731


# --------------------------------------------------------------------------
# The hybrid system
# --------------------------------------------------------------------------
class Rocker:
    def __init__(self, body: dict, exc: dict):
        self.k = derived_constants(body)
        self.a = Excitation(exc)

    def params(self, mode):
        k = self.k
        if mode == PRE:
            return 1.0, k["beta1"]
        return k["nu2"], k["beta2"]

    def force(self, mode, q):
        """F(q) and F'(q) of the given mode (continued past the mode's guards)."""
        k = self.k
        Ke, s_n, B = k["Ke"], k["s_n"], k["B"]
        if mode == PRE:
            return Ke * q, Ke
        slope = -Ke * s_n / (B - s_n)
        if mode == RR:
            return Ke * s_n * (B - q) / (B - s_n), slope
        return -Ke * s_n * (B + q) / (B - s_n), slope

    def rhs(self, mode, t0=0.0):
        """Right-hand side in a mode, on the integration segment that starts at t0."""
        k = self.k
        Me, c = k["Me"], k["c"]
        nu, beta = self.params(mode)
        a = self.a.piece(t0)

        def f(t, y):
            q, qd = y
            F, Fp = self.force(mode, q)
            qdd = (-beta * Me * a(t) - c * nu * Fp * qd - nu * F) / Me
            return np.array([qd, qdd])

        return f

    def jac(self, mode):
        k = self.k
        Me, c = k["Me"], k["c"]
        nu, _ = self.params(mode)
        _, Fp = self.force(mode, 0.0)
        J = np.array([[0.0, 1.0], [-nu * Fp / Me, -c * nu * Fp / Me]])
        return lambda t, y: J

    def guards(self, mode):
        """list of (name, function, direction, target mode, guard value)."""
        s_n, B = self.k["s_n"], self.k["B"]
        if mode == PRE:
            return [("uplift", lambda t, y: y[0] - s_n, +1, RR, s_n),
                    ("uplift", lambda t, y: y[0] + s_n, -1, RL, -s_n)]
        if mode == RR:
            return [("landing", lambda t, y: y[0] - s_n, -1, PRE, s_n),
                    ("overturn", lambda t, y: y[0] - B, +1, OVER, B)]
        return [("landing", lambda t, y: y[0] + s_n, +1, PRE, -s_n),
                ("overturn", lambda t, y: y[0] + B, -1, OVER, -B)]

    def reset(self, kind, qdot):
        if kind == "uplift":
            return self.k["zetaU"] * qdot
        if kind == "landing":
            return qdot / self.k["zetaL"]
        return qdot  # overturn: terminal, no jump


def initial_mode(k, q0):
    if q0 > k["s_n"]:
        return RR
    if q0 < -k["s_n"]:
        return RL
    return PRE


def _ivp(sys_, mode, t0, t1, y0, method, rtol, atol, max_step, events=None):
    kw = dict(method=method, rtol=rtol, atol=atol, max_step=max_step)
    if method in ("Radau", "BDF", "LSODA"):
        kw["jac"] = sys_.jac(mode)
    return solve_ivp(sys_.rhs(mode, t0), (t0, t1), y0, events=events, **kw)


def simulate(case: dict, method="DOP853", rtol=RTOL_REF, atol=ATOL_REF,
             max_step=MAX_STEP, polish=True, sample_dt=SAMPLE_DT, samples=True):
    """Integrate one case.  Returns a dict with events, peaks, samples, stats."""
    sys_ = Rocker(case["body"], case["excitation"])
    k = sys_.k
    sim = case["simulation"]
    T_end = float(sim["duration"])
    t = 0.0
    y = np.array([float(sim.get("q0", 0.0)), float(sim.get("qdot0", 0.0))])
    mode = initial_mode(k, y[0])

    stops = set(sys_.a.breaks)
    sample_times = []
    if samples:
        n = int(math.floor(T_end / sample_dt + 1e-9))
        sample_times = [i * sample_dt for i in range(n + 1)]
        stops.update(sample_times)
    stops = sorted(s for s in stops if 0.0 < s < T_end) + [T_end]

    events, peaks, samp = [], [], []
    if samples:
        samp.append([0.0, float(y[0]), float(y[1])])
    nfev = 0
    n_restarts = 0
    peak_fn = lambda t, y: y[1]  # noqa: E731
    peak_fn.terminal = False
    peak_fn.direction = 0

    def advance(mode_, t0, y0, t1):
        if t1 == t0:
            return np.array(y0, dtype=float)
        r = _ivp(sys_, mode_, t0, t1, y0, method, rtol, atol, max_step)
        return r.y[:, -1]

    def polish_root(mode_, tk, yk, te, ye, gfun, gdot):
        """Newton on g(t) = 0 with states from a fresh integration from (tk, yk)."""
        if not polish:
            return te, ye
        for _ in range(4):
            g = gfun(te, ye)
            gd = gdot(te, ye)
            if gd == 0.0:
                break
            dt = -g / gd
            te_new = te + dt
            if te_new < tk:
                te_new = tk
            ye = advance(mode_, tk, yk, te_new)
            if abs(te_new - te) <= 4e-16 * max(1.0, abs(te)):
                te = te_new
                break
            te = te_new
        return te, ye

    while t < T_end and mode != OVER:
        t_stop = next(s for s in stops if s > t + 1e-15)
        gl = sys_.guards(mode)
        evfuns = []
        for name, fn, direction, _, _ in gl:
            fn.terminal = True
            fn.direction = direction
            evfuns.append(fn)
        evfuns.append(peak_fn)
        sol = _ivp(sys_, mode, t, t_stop, y, method, rtol, atol, max_step, events=evfuns)
        n_restarts += 1
        if sol.status < 0:
            raise RuntimeError(sol.message)
        nfev += sol.nfev
        f = sys_.rhs(mode, t)
        step_t = sol.t
        step_y = sol.y

        def last_step_before(te):
            # step points only (the appended terminal-event point excluded)
            idx = np.searchsorted(step_t, te, side="left") - 1
            idx = max(idx, 0)
            return step_t[idx], step_y[:, idx]

        # peaks
        for te, ye in zip(sol.t_events[-1], sol.y_events[-1]):
            if te <= t:  # q' = 0 exactly at the segment start: recorded by caller
                continue
            tk, yk = last_step_before(te)
            te2, ye2 = polish_root(mode, tk, yk, te, ye,
                                   lambda tt, yy: yy[1], lambda tt, yy: f(tt, yy)[1])
            peaks.append((te2, float(ye2[0]), mode))

        hit = None
        for i, (name, fn, direction, target, gval) in enumerate(gl):
            if len(sol.t_events[i]):
                te = sol.t_events[i][0]
                if hit is None or te < hit[0]:
                    hit = (te, sol.y_events[i][0], i)
        if hit is None:
            t, y = float(sol.t[-1]), sol.y[:, -1].copy()
            if samples and any(abs(t - s) < 1e-12 for s in sample_times):
                samp.append([t, float(y[0]), float(y[1])])
            continue

        te, ye, i = hit
        name, fn, direction, target, gval = gl[i]
        tk, yk = last_step_before(te)
        te, ye = polish_root(mode, tk, yk, te, ye, fn, lambda tt, yy: yy[1])
        # discard peaks located after the (polished) event
        peaks = [p for p in peaks if p[0] <= te]
        qd_before = float(ye[1])
        qd_after = float(sys_.reset(name, qd_before))
        events.append(dict(t=float(te), kind=name, **{"from": mode}, to=target,
                           q=float(gval), qdot_before=qd_before, qdot_after=qd_after))
        t = float(te)
        y = np.array([gval, qd_after])
        mode = target

    t_final = t
    cand = [(0.0, float(sim.get("q0", 0.0)))] + [(p[0], p[1]) for p in peaks] + [(t_final, float(y[0]))]
    tmax, qmax = max(cand, key=lambda c: c[1])
    tmin, qmin = min(cand, key=lambda c: c[1])
    overturned = mode == OVER
    return dict(
        constants=k, events=events, peaks=peaks, samples=samp,
        max_q=qmax, t_max_q=tmax, min_q=qmin, t_min_q=tmin,
        overturned=overturned, t_overturn=(t_final if overturned else None),
        t_final=t_final, nfev=nfev, segments=n_restarts,
    )


# --------------------------------------------------------------------------
# Cases
# --------------------------------------------------------------------------
REF_BODY = dict(height=4.0, width=0.7, depth=1.0, density=600.0, youngs_modulus=5.0e6,
                damping_ratio=0.05, gravity=9.81, constants="exact")


def body(**over):
    b = dict(REF_BODY)
    b.update(over)
    return b


CASES = {
    # The paper's example, exactly as models/ichinose1986.toml.
    "ichinose1986": dict(
        comment="The paper's example (Ichinose 1986, sections 2.5 and 3): reference body, "
                "paper-sine A = 5 m/s^2, Tp = 1 s, cubic ramp on [0, 0.412) s.",
        body=body(),
        excitation=dict(kind="paper-sine", amplitude=5.0, period=1.0, ramp=0.412),
        simulation=dict(duration=6.0, q0=0.0, qdot0=0.0)),
    # Harmonic, reference body: repeated rocking on both toes.
    "harmonic-ref-a3-t1p2": dict(
        comment="Reference body, harmonic a = 3 sin(2 pi t/1.2) from t = 0: several uplifts "
                "and landings on both toes.",
        body=body(),
        excitation=dict(kind="harmonic", amplitude=3.0, period=1.2),
        simulation=dict(duration=8.0, q0=0.0, qdot0=0.0)),
    "harmonic-ref-a2p5-t1p5": dict(
        comment="Reference body, harmonic a = 2.5 sin(2 pi t/1.5) from t = 0 (period near the "
                "body's 1.55 s): a dozen uplifts and landings on both toes, no overturning.",
        body=body(),
        excitation=dict(kind="harmonic", amplitude=2.5, period=1.5),
        simulation=dict(duration=10.0, q0=0.0, qdot0=0.0)),
    # Free rocking.
    "free-right": dict(
        comment="Reference body, free rocking from q0 = 0.35 m > s_n (rock-right) with "
                "qdot0 = 0.1 m/s.",
        body=body(),
        excitation=dict(kind="free"),
        simulation=dict(duration=6.0, q0=0.35, qdot0=0.1)),
    "free-left": dict(
        comment="Reference body, free rocking from q0 = -0.3 m < -s_n (rock-left) with "
                "qdot0 = -0.15 m/s.",
        body=body(),
        excitation=dict(kind="free"),
        simulation=dict(duration=6.0, q0=-0.3, qdot0=-0.15)),
    # Other bodies.
    "body-b-undamped-paper-sine": dict(
        comment="A stiffer, lighter, undamped body (H = 3 m, B = 0.5 m, 450 kg/m^3, "
                "E = 8 MPa, h = 0) under the paper's sine.",
        body=body(height=3.0, width=0.5, density=450.0, youngs_modulus=8.0e6,
                  damping_ratio=0.0),
        excitation=dict(kind="paper-sine", amplitude=3.0, period=0.8, ramp=0.412),
        simulation=dict(duration=6.0, q0=0.0, qdot0=0.0)),
    "body-c-h2pct-harmonic": dict(
        comment="A taller, heavier body (H = 6 m, B = 1.0 m, 800 kg/m^3, E = 12 MPa, "
                "h = 0.02, g = 9.80665) under a harmonic floor motion.",
        body=body(height=6.0, width=1.0, density=800.0, youngs_modulus=1.2e7,
                  damping_ratio=0.02, gravity=9.80665),
        excitation=dict(kind="harmonic", amplitude=2.5, period=1.5),
        simulation=dict(duration=8.0, q0=0.0, qdot0=0.0)),
    # Overturning.
    "overturn-harmonic": dict(
        comment="Reference body, harmonic a = 2 sin(2 pi t/2.0): rocks on both toes (landings "
                "included), then overturns to the left (q reaches -B) at about 5.04 s.",
        body=body(),
        excitation=dict(kind="harmonic", amplitude=2.0, period=2.0),
        simulation=dict(duration=8.0, q0=0.0, qdot0=0.0)),
    "overturn-harmonic-fast": dict(
        comment="Reference body, harmonic a = 4 sin(2 pi t/2.0): overturns to the left on "
                "its first uplift (q reaches -B at about 0.744 s).",
        body=body(),
        excitation=dict(kind="harmonic", amplitude=4.0, period=2.0),
        simulation=dict(duration=8.0, q0=0.0, qdot0=0.0)),
    # Too weak to uplift.
    "harmonic-no-uplift": dict(
        comment="Reference body, harmonic a = 0.8 sin(2 pi t/1.0): too weak to uplift "
                "(quasi-static uplift acceleration about 1.6 m/s^2); linear damped oscillator.",
        body=body(),
        excitation=dict(kind="harmonic", amplitude=0.8, period=1.0),
        simulation=dict(duration=8.0, q0=0.0, qdot0=0.0)),
}

SOLVER_BLOCK = dict(method="bdf", rtol=1e-10, atol=1e-12, output_dt=0.005)


def fmt(v):
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, float):
        if v != 0.0 and abs(v) >= 1e5:
            mant, ex = f"{v:.12e}".split("e")
            mant = mant.rstrip("0")
            mant = mant + "0" if mant.endswith(".") else mant
            return f"{mant}e{int(ex)}"
        r = repr(v)
        return r if ("." in r or "e" in r or "inf" in r or "nan" in r) else r + ".0"
    return str(v)


UNITS = {
    "height": "m", "width": "m", "depth": "m", "density": "kg/m^3", "youngs_modulus": "Pa",
    "gravity": "m/s^2", "amplitude": "m/s^2", "period": "s", "ramp": "s", "duration": "s",
    "q0": "m", "qdot0": "m/s", "output_dt": "s",
}


def write_toml(path, name, case):
    lines = [f"# {name}: written by validation/independent/ichinose_ref.py",
             "# (do not edit by hand; rerun the script).  Expected values: "
             f"{name}.expected.json"]
    for chunk in _wrap(case["comment"], 86):
        lines.append(f"# {chunk}")
    for sect, d in (("body", case["body"]), ("excitation", case["excitation"]),
                    ("simulation", case["simulation"]), ("solver", SOLVER_BLOCK)):
        lines.append("")
        lines.append(f"[{sect}]")
        for key, val in d.items():
            s = f"{key} = {fmt(val)}"
            if key in UNITS:
                s = f"{s:<24}# {UNITS[key]}"
            lines.append(s)
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")


def _wrap(text, width):
    out, line = [], ""
    for w in text.split():
        if len(line) + len(w) + 1 > width:
            out.append(line)
            line = w
        else:
            line = (line + " " + w).strip()
    if line:
        out.append(line)
    return out


CONST_KEYS = ["Me", "Ke", "omega", "T", "s_n", "nu1", "beta1", "nu2", "beta2", "zetaU",
              "zetaL", "quasi_static_uplift_acc", "gravity_parameter"]


def compare(r1, r2):
    """max differences between two runs (same event sequence required)."""
    e1, e2 = r1["events"], r2["events"]
    same_seq = [(e["kind"], e["from"], e["to"]) for e in e1] == \
               [(e["kind"], e["from"], e["to"]) for e in e2]
    d = dict(same_event_sequence=same_seq, n_events=(len(e1), len(e2)))
    if same_seq and e1:
        d["event_t"] = max(abs(a["t"] - b["t"]) for a, b in zip(e1, e2))
        d["event_qdot"] = max(max(abs(a["qdot_before"] - b["qdot_before"]),
                                  abs(a["qdot_after"] - b["qdot_after"])) for a, b in zip(e1, e2))
    else:
        d["event_t"] = d["event_qdot"] = 0.0 if same_seq else float("nan")
    d["peak_q"] = max(abs(r1["max_q"] - r2["max_q"]), abs(r1["min_q"] - r2["min_q"]))
    d["peak_t"] = max(abs(r1["t_max_q"] - r2["t_max_q"]), abs(r1["t_min_q"] - r2["t_min_q"]))
    s1, s2 = np.array(r1["samples"]), np.array(r2["samples"])
    if s1.shape == s2.shape and len(s1):
        d["sample_q"] = float(np.max(np.abs(s1[:, 1] - s2[:, 1])))
        d["sample_qdot"] = float(np.max(np.abs(s1[:, 2] - s2[:, 2])))
    else:
        d["sample_q"] = d["sample_qdot"] = float("nan")
    return d


def grazing_margins(res):
    """Smallest distance of a peak of |q| from s_n and from B, and smallest |q'| at
    an uplift/landing (a grazing event has q' -> 0 there)."""
    k = res["constants"]
    s_n, B = k["s_n"], k["B"]
    m_sn = min((abs(abs(p[1]) - s_n), p[0]) for p in res["peaks"]) if res["peaks"] else (math.inf, None)
    m_B = min((abs(abs(p[1]) - B), p[0]) for p in res["peaks"]) if res["peaks"] else (math.inf, None)
    m_qd = min((abs(e["qdot_before"]) for e in res["events"]), default=math.inf)
    return dict(peak_to_sn=m_sn, peak_to_B=m_B, min_event_qdot=m_qd)


def expected_json(name, case, res, cross):
    k = res["constants"]
    return {
        "case": name,
        "constants": {key: k[key] for key in CONST_KEYS},
        "events": res["events"],
        "max_q": res["max_q"], "t_max_q": res["t_max_q"],
        "min_q": res["min_q"], "t_min_q": res["t_min_q"],
        "overturned": res["overturned"], "t_overturn": res["t_overturn"],
        "samples": res["samples"],
        "method": ("Independent Python reference (validation/independent/ichinose_ref.py): "
                   "scipy.integrate.solve_ivp DOP853, rtol=1e-12, atol=1e-14, max_step=0.01 s; "
                   "directional terminal event functions for uplift/landing/overturn with "
                   "restart and reset (q set to the guard value); non-terminal event q'=0 for "
                   "peaks; event and peak times polished by Newton on fresh integrations from "
                   "the last accepted step; integration stopped exactly at the ramp end and at "
                   "every sample time. Cross-checked against Radau at the same tolerances."),
        "rtol": RTOL_REF, "atol": ATOL_REF,
        "cross_check_radau": cross,
    }


# --------------------------------------------------------------------------
# Checks
# --------------------------------------------------------------------------
def check_reference_constants():
    k = derived_constants(REF_BODY)
    out = dict(
        Me_over_M=k["Me"] / k["M"], Ke_over_EI_H3=k["Ke"] * k["H"]**3 / k["EI"],
        T=k["T"], s_n=k["s_n"], beta1=k["beta1"], nu2=k["nu2"], beta2=k["beta2"],
        zetaU=k["zetaU"], zetaL=k["zetaL"], gamma_g=k["gravity_parameter"],
        gamma_g_over_buckling=k["gravity_parameter"] / BUCKLING_GAMMA_G,
        a_up=k["quasi_static_uplift_acc"])
    assert abs(SIG - 0.7340955137589) < 1e-12
    assert round(out["Me_over_M"], 4) == 0.3915
    assert round(out["Ke_over_EI_H3"], 4) == 4.8398
    assert round(out["T"], 4) == 1.5500
    assert round(out["s_n"], 5) == 0.15237
    assert abs(out["beta1"] - 1.565983512) < 1e-9
    assert abs(out["gamma_g"] - 1.845) < 1e-3
    return out


def check_ramp():
    c = ramp_coefficients(5.0, 1.0, 0.412)
    assert round(c[0], 3) == -133.694, c
    assert round(c[1], 2) == 1043.29, c
    assert round(c[2], 2) == -1707.09, c
    # continuity of a, v, d at the ramp end
    tr, A, w = 0.412, 5.0, 2 * math.pi
    a = c[0] * tr + c[1] * tr**2 + c[2] * tr**3
    v = c[0] * tr**2 / 2 + c[1] * tr**3 / 3 + c[2] * tr**4 / 4
    dd = c[0] * tr**3 / 6 + c[1] * tr**4 / 12 + c[2] * tr**5 / 20
    errs = (a - A * math.sin(w * tr), v + A / w * math.cos(w * tr), dd + A / w**2 * math.sin(w * tr))
    assert max(abs(e) for e in errs) < 1e-10
    return c, errs


def check_rigid_limit():
    """book/src/model.md section 7 (rigid limit): E x 1e5; zetaU/zetaL -> Housner; free
    rocking from B/2 reaches q = s_n at ~ acosh(2)/p, p = sqrt(3g/(2H))."""
    out = []
    H, B, g = REF_BODY["height"], REF_BODY["width"], REF_BODY["gravity"]
    housner = (2 * H**2 - B**2) / (2 * (H**2 + B**2))
    p = math.sqrt(3 * g / (2 * H))
    t_housner = math.acosh(1.0 / (1.0 - 0.5)) / p
    for h, fac in [(0.05, f) for f in (1e1, 1e2, 1e3, 1e4, 1e5)] + \
                  [(0.0, f) for f in (1e3, 1e4, 1e5)]:
        b = body(youngs_modulus=REF_BODY["youngs_modulus"] * fac, damping_ratio=h)
        k = derived_constants(b)
        case = dict(body=b, excitation=dict(kind="free"),
                    simulation=dict(duration=t_housner * 1.05, q0=B / 2, qdot0=0.0))
        res = simulate(case, samples=False, max_step=min(MAX_STEP, k["T"] / 20))
        land = [e for e in res["events"] if e["kind"] == "landing"]
        t_land = land[0]["t"] if land else float("nan")
        out.append(dict(h=h, E_factor=fac, s_n=k["s_n"], nu2=k["nu2"], beta2=k["beta2"],
                        zetaU=k["zetaU"], zetaL=k["zetaL"],
                        zetaU_over_zetaL=k["zetaU"] / k["zetaL"], housner=housner,
                        t_first_landing=t_land, t_housner=t_housner,
                        dt=t_land - t_housner))
    return out


def closed_form_pre_uplift(case, res):
    """book/src/model.md section 7: before uplift eq. 16 is
    q'' + 2 h w q' + w^2 q = -beta1 A sin(W t).
    Closed-form solution from rest (h < 1) compared with the samples and peaks."""
    k = derived_constants(case["body"])
    w, h, b1 = k["omega"], k["h"], k["beta1"]
    A, W = case["excitation"]["amplitude"], 2 * math.pi / case["excitation"]["period"]
    q0, v0 = case["simulation"]["q0"], case["simulation"]["qdot0"]
    # particular solution X sin(Wt) + Y cos(Wt)
    den = (w**2 - W**2) ** 2 + (2 * h * w * W) ** 2
    X = -b1 * A * (w**2 - W**2) / den
    Y = -b1 * A * (-2 * h * w * W) / den
    wd = w * math.sqrt(1 - h**2)
    C1 = q0 - Y                       # homogeneous: e^{-h w t}(C1 cos wd t + C2 sin wd t)
    C2 = (v0 - X * W + h * w * C1) / wd

    def q(t):
        return (math.exp(-h * w * t) * (C1 * math.cos(wd * t) + C2 * math.sin(wd * t))
                + X * math.sin(W * t) + Y * math.cos(W * t))

    def qd(t):
        e = math.exp(-h * w * t)
        return (e * (-h * w) * (C1 * math.cos(wd * t) + C2 * math.sin(wd * t))
                + e * wd * (-C1 * math.sin(wd * t) + C2 * math.cos(wd * t))
                + X * W * math.cos(W * t) - Y * W * math.sin(W * t))

    es = max(abs(s[1] - q(s[0])) for s in res["samples"])
    esd = max(abs(s[2] - qd(s[0])) for s in res["samples"])
    ep = max(abs(p[1] - q(p[0])) for p in res["peaks"])
    epd = max(abs(qd(p[0])) for p in res["peaks"])
    return dict(sample_q=es, sample_qdot=esd, peak_q=ep, qdot_at_peaks=epd)


def closed_form_free_rocking(body_, q0, v0):
    """Free rocking about the right toe (a = 0) is linear with constant coefficients:
    with y = q - B, y'' + a1 y' - p2 y = 0, a1 = c nu2 F'/Me (< 0: energy feeding),
    p2 = nu2 Ke s_n/(Me (B - s_n)).  Returns the first time q falls to s_n and q' then
    (closed form + brentq), for comparison with the integrator."""
    from scipy.optimize import brentq
    k = derived_constants(body_)
    B, s_n, d = k["B"], k["s_n"], k["B"] - k["s_n"]
    Fp = -k["Ke"] * s_n / d
    a1 = k["c"] * k["nu2"] * Fp / k["Me"]
    p2 = k["nu2"] * k["Ke"] * s_n / (k["Me"] * d)
    disc = math.sqrt(a1**2 + 4 * p2)
    r1, r2 = (-a1 + disc) / 2, (-a1 - disc) / 2
    y0 = q0 - B
    C1 = (v0 - r2 * y0) / (r1 - r2)
    C2 = y0 - C1
    y = lambda t: C1 * math.exp(r1 * t) + C2 * math.exp(r2 * t)  # noqa: E731
    yd = lambda t: C1 * r1 * math.exp(r1 * t) + C2 * r2 * math.exp(r2 * t)  # noqa: E731
    hi = 0.01
    while y(hi) + B > s_n:
        hi *= 1.5
    t_land = brentq(lambda t: y(t) + B - s_n, 0.0, hi, xtol=1e-15, rtol=1e-15)
    return t_land, yd(t_land)


def check_free_rocking_closed_form():
    rows = []
    for label, b, q0, v0 in [("reference body, h=0.05", body(), 0.35, 0.0),
                             ("reference body, h=0.05", body(), 0.35, 0.1),
                             ("reference body, h=0", body(damping_ratio=0.0), 0.5, -0.2),
                             ("body-c, h=0.02", CASES["body-c-h2pct-harmonic"]["body"], 0.6, 0.05)]:
        t_cf, v_cf = closed_form_free_rocking(b, q0, v0)
        case = dict(body=b, excitation=dict(kind="free"),
                    simulation=dict(duration=t_cf + 0.05, q0=q0, qdot0=v0))
        res = simulate(case, samples=False)
        e = res["events"][0]
        rows.append(dict(label=label, q0=q0, v0=v0, t_cf=t_cf, dt=e["t"] - t_cf,
                         dqd=e["qdot_before"] - v_cf))
    return rows


def time_lsoda(case, n=10):
    times = []
    res = None
    for _ in range(n):
        t0 = time.perf_counter()
        res = simulate(case, method="LSODA", rtol=1e-8, atol=1e-10, max_step=np.inf,
                       polish=False, samples=False)
        times.append(time.perf_counter() - t0)
    times2 = []
    for _ in range(n):
        t0 = time.perf_counter()
        simulate(case, method="LSODA", rtol=1e-8, atol=1e-10, max_step=MAX_STEP,
                 polish=False, samples=False)
        times2.append(time.perf_counter() - t0)
    return statistics.median(times), statistics.median(times2), res


# --------------------------------------------------------------------------
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="skip the LSODA timing")
    ap.add_argument("--root", default=None, help="project root (default: two levels up)")
    args = ap.parse_args(argv)
    root = args.root or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    outdir = os.path.join(root, "tests", "data", "cases")
    os.makedirs(outdir, exist_ok=True)

    print("== reference constants (book/src/model.md, section 2)")
    for kk, vv in check_reference_constants().items():
        print(f"  {kk:24s} {vv:.10g}")
    c, errs = check_ramp()
    print(f"== ramp coefficients c1..c3 = {c[0]:.6f} {c[1]:.6f} {c[2]:.6f}; "
          f"continuity errors a,v,d = {errs[0]:.1e} {errs[1]:.1e} {errs[2]:.1e}")

    print("== cases (DOP853 reference; Radau cross-check; DOP853 without polishing)")
    summary = {}
    for name, case in CASES.items():
        r = simulate(case, method="DOP853")
        rr = simulate(case, method="Radau")
        rn = simulate(case, method="DOP853", polish=False)
        rrn = simulate(case, method="Radau", polish=False)
        rinf = simulate(case, method="DOP853", max_step=np.inf)
        cross = compare(r, rr)
        cross_np = compare(r, rn)
        cross_rnp = compare(r, rrn)
        cross_inf = compare(r, rinf)
        gm = grazing_margins(r)
        cross_json = {kk: (list(vv) if isinstance(vv, tuple) else vv) for kk, vv in cross.items()}
        write_toml(os.path.join(outdir, f"{name}.toml"), name, case)
        with open(os.path.join(outdir, f"{name}.expected.json"), "w") as fh:
            json.dump(expected_json(name, case, r, cross_json), fh, indent=1)
            fh.write("\n")
        ne = {kk: sum(1 for e in r["events"] if e["kind"] == kk) for kk in ("uplift", "landing", "overturn")}
        sides = sorted({e["to"] for e in r["events"] if e["kind"] == "uplift"} |
                       ({initial_mode(r["constants"], case["simulation"]["q0"])} - {PRE}))
        summary[name] = dict(events=ne, cross=cross, cross_nopolish=cross_np,
                             cross_radau_nopolish=cross_rnp, cross_inf=cross_inf, graze=gm, res=r)
        print(f"  {name:28s} up={ne['uplift']:2d} land={ne['landing']:2d} over={ne['overturn']} "
              f"sides={','.join(s.replace('rock-', '') for s in sides) or '-'} "
              f"max_q={r['max_q']:+.6f}@{r['t_max_q']:.4f} min_q={r['min_q']:+.6f}@{r['t_min_q']:.4f}"
              + (f" t_over={r['t_overturn']:.6f}" if r["overturned"] else ""))
        print(f"      Radau: seq_same={cross['same_event_sequence']} dt_ev={cross['event_t']:.1e} "
              f"dqd_ev={cross['event_qdot']:.1e} dpeak_q={cross['peak_q']:.1e} "
              f"dpeak_t={cross['peak_t']:.1e} dsample_q={cross['sample_q']:.1e} "
              f"dsample_qd={cross['sample_qdot']:.1e}")
        print(f"      DOP853 no-polish: dt_ev={cross_np['event_t']:.1e} dpeak_q={cross_np['peak_q']:.1e} "
              f"dpeak_t={cross_np['peak_t']:.1e};  Radau no-polish: dt_ev={cross_rnp['event_t']:.1e} "
              f"dpeak_q={cross_rnp['peak_q']:.1e} dpeak_t={cross_rnp['peak_t']:.1e}")
        print(f"      DOP853 max_step=inf: seq_same={cross_inf['same_event_sequence']} "
              f"dt_ev={cross_inf['event_t']:.1e} dpeak_q={cross_inf['peak_q']:.1e} "
              f"dsample_q={cross_inf['sample_q']:.1e}")
        print(f"      grazing margins: |peak|q|-s_n|={gm['peak_to_sn'][0]:.3e} (t={gm['peak_to_sn'][1]}) "
              f"|peak|q|-B|={gm['peak_to_B'][0]:.3e} min|qdot| at event={gm['min_event_qdot']:.3e}")
        if gm["peak_to_sn"][0] < 1e-6 or gm["peak_to_B"][0] < 1e-6:
            print("      WARNING: near-grazing case, ill-conditioned")

    cf = closed_form_pre_uplift(CASES["harmonic-no-uplift"], summary["harmonic-no-uplift"]["res"])
    print("== closed form (linear damped oscillator) vs harmonic-no-uplift: "
          + " ".join(f"{kk}={vv:.1e}" for kk, vv in cf.items()))

    print("== closed-form free rocking (rock-right, a = 0) vs integrator, first landing")
    for row in check_free_rocking_closed_form():
        print(f"  {row['label']:24s} q0={row['q0']} v0={row['v0']}: t_cf={row['t_cf']:.12f} "
              f"dt={row['dt']:.1e} dqdot={row['dqd']:.1e}")

    print("== overall maxima over cases: DOP853 vs Radau | vs Radau unpolished | vs DOP853 "
          "unpolished | vs DOP853 max_step=inf")
    for key in ("event_t", "event_qdot", "peak_q", "peak_t", "sample_q", "sample_qdot"):
        vals = [max(s[c][key] for s in summary.values())
                for c in ("cross", "cross_radau_nopolish", "cross_nopolish", "cross_inf")]
        print(f"  {key:12s} " + " | ".join(f"{v:.2e}" for v in vals))

    print("== rigid limit (book/src/model.md, section 7)")
    H_ref, B_ref = REF_BODY["height"], REF_BODY["width"]
    for row in check_rigid_limit():
        print(f"  h={row['h']:.2f} E x {row['E_factor']:.0e}: s_n={row['s_n']:.3e} nu2={row['nu2']:.6f} "
              f"beta2={row['beta2']:.6f} zU/zL={row['zetaU_over_zetaL']:.8f} "
              f"(Housner {row['housner']:.8f}) t_land={row['t_first_landing']:.9f} "
              f"(Housner {row['t_housner']:.9f}, diff {row['dt']:.2e})")
    print(f"  3/L^2 = {3 / LAM**2:.6f}; at E x 1e5: zetaU = {row['zetaU']:.8f}, "
          f"zetaL = {row['zetaL']:.8f} (rigid limits (H^2/L^2 + B^2/12)/((H^2 + B^2)/3) = "
          f"{(H_ref**2 / LAM**2 + B_ref**2 / 12) / ((H_ref**2 + B_ref**2) / 3):.8f} and "
          f"(H^2/L^2 + B^2/12)/((H^2 - B^2/2)/3) = "
          f"{(H_ref**2 / LAM**2 + B_ref**2 / 12) / ((H_ref**2 - B_ref**2 / 2) / 3):.8f}); "
          "only the ratio zetaU/zetaL is Housner's restitution")

    if not args.quick:
        med, med2, res = time_lsoda(CASES["ichinose1986"])
        ref = summary["ichinose1986"]["res"]
        dtmax = max(abs(a["t"] - b["t"]) for a, b in zip(res["events"], ref["events"])) \
            if len(res["events"]) == len(ref["events"]) else float("nan")
        print(f"== LSODA (rtol 1e-8, atol 1e-10, events + restarts, no sample stops, no polish) "
              f"on ichinose1986, 6 s: median of 10 = {med * 1e3:.1f} ms (max_step=inf), "
              f"{med2 * 1e3:.1f} ms (max_step=0.01); {len(res['events'])} events, "
              f"max event-time diff vs reference {dtmax:.1e} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
