#!/usr/bin/env python3
"""Exact multiprecision solution of the Ichinose (1986) rocking model for one flexrock model file.

Within each mode of the hybrid automaton (book/src/model.md, section 6) the equation of motion
(eq. 16)

    Me q'' + (gamma/E) nu F' q' + nu F(q) = -beta Me a(t)

is linear with constant coefficients, because F is linear in q on each branch.  With x = q - q_eq
(q_eq = 0 before uplift, +-q_topple while rocking) it reads

    x'' + C x' + K x = -beta a(t),     C = (gamma/E) nu F'/Me,   K = nu F'/Me.

On every piece of the floor motion where a(t) is a polynomial (the paper-sine's cubic ramp, a
record's linear pieces, zero), a sine or a cosine, the solution is a closed form: the homogeneous
solution (two real exponentials while rocking, a damped sine before uplift) plus a particular
solution (a polynomial, or the steady-state sine).  A Ricker wavelet is handled by Duhamel's
integral, whose inner integrals have a closed form through the error function of a complex
argument.  The closed form is re-anchored at every breakpoint of a(t) and at every event.

Events are the first crossings of the guards q = +-s_n and q = +-q_topple in the guard's direction.
On each piece the extrema of q are located first (roots of q', bracketed on a grid of at most
T/64 with a check of q'' that splits an interval holding two roots of q'), so that q is monotone
between consecutive points; a guard crossing is then bracketed by a sign change on one of these
monotone pieces and refined by bisection and Newton's method to 1e-30 s or better.  A grazing
approach (q peaks just short of s_n, or just past it) is therefore decided by the sign of
q - s_n at the located extremum, computed to 40 significant digits.

Every constant is computed from the model file's raw numbers with mpmath at 40 digits; nothing is
read from flexrock's output.

Usage:  python3 mp_exact.py MODEL.toml --out DIR [--dps 40] [--name NAME]
Writes DIR/events.csv, DIR/peaks.json and prints a one-line summary.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
import tomllib

import mpmath as mp
from mpmath import mpf

PRE, RR, RL, OVER = "pre-uplift", "rock-right", "rock-left", "overturned"
STANDARD_GRAVITY = "9.80665"
GL_POINTS = 40  # AT2 records in g are converted with standard gravity


def M(x) -> mpf:
    """An mpf from a TOML number: through its shortest decimal repr, i.e. the decimal written."""
    if isinstance(x, bool):
        raise TypeError(x)
    if isinstance(x, int):
        return mpf(x)
    return mpf(repr(float(x)))


# --------------------------------------------------------------------------------------------
# Constants (book/src/model.md sections 2-5 and 7b)
# --------------------------------------------------------------------------------------------
def cantilever_root(i: int) -> mpf:
    """i-th root (i = 1, 2, ...) of cos L cosh L = -1."""
    guess = (2 * i - 1) * mp.pi / 2
    if i == 1:
        guess = mpf("1.875")
    return mp.findroot(lambda L: mp.cos(L) * mp.cosh(L) + 1, guess)


def cantilever_mode(L: mpf):
    """phi(xi) = [cosh - cos - sig (sinh - sin)](L xi)/2 and its first derivative."""
    sig = (mp.cosh(L) + mp.cos(L)) / (mp.sinh(L) + mp.sin(L))

    def phi(x):
        z = L * x
        return (mp.cosh(z) - mp.cos(z) - sig * (mp.sinh(z) - mp.sin(z))) / 2

    def dphi(x):
        z = L * x
        return L * (mp.sinh(z) + mp.sin(z) - sig * (mp.cosh(z) - mp.cos(z))) / 2

    return sig, phi, dphi


def self_weighted_shape(gamma_g: mpf, nmodes: int):
    """Ritz solve of  int psi''^2 - gamma_g int (1 - xi) psi'^2 = Omega int psi^2  over the first
    nmodes cantilever modes (book/src/model.md 7b).  Returns Omega, int psi, int psi^2,
    int psi xi, psi scaled to psi(1) = 1."""
    with mp.workdps(mp.mp.dps + 20):
        Ls = [cantilever_root(i) for i in range(1, nmodes + 1)]
        modes = [cantilever_mode(L) for L in Ls]
        # Gauss-Legendre, 40 points on each eighth of [0, 1]: exact to the working precision for
        # these entire integrands (checked against 60 points in the README)
        X, Wt = mp.gauss_quadrature(GL_POINTS, "legendre")
        xs, ws = [], []
        for s in range(8):
            lo = mpf(s) / 8
            for x, w in zip(X, Wt):
                xs.append(lo + (x + 1) / 16)
                ws.append(w / 16)
        ph = [[m[1](x) for x in xs] for m in modes]
        dph = [[m[2](x) for x in xs] for m in modes]
        G = mp.matrix(nmodes, nmodes)
        for i in range(nmodes):
            for j in range(i, nmodes):
                G[i, j] = G[j, i] = mp.fsum(w * (1 - x) * a * b
                                            for w, x, a, b in zip(ws, xs, dph[i], dph[j]))
        A = mp.matrix(nmodes, nmodes)
        for i in range(nmodes):
            for j in range(nmodes):
                # the modes are orthogonal: int phi_i phi_j = delta/4, int phi_i'' phi_j'' = L^4 delta/4
                A[i, j] = 4 * ((Ls[i] ** 4 / 4 if i == j else 0) - gamma_g * G[i, j])
        E, Q = mp.eigsy(A)
        k = min(range(nmodes), key=lambda m: E[m])
        Omega = E[k]
        a = [Q[i, k] for i in range(nmodes)]
        tip = sum(a[i] * modes[i][1](mpf(1)) for i in range(nmodes))
        a = [ai / tip for ai in a]
        I1 = sum(a[i] * mp.fsum(w * p for w, p in zip(ws, ph[i])) for i in range(nmodes))
        I2 = sum(ai * ai for ai in a) / 4
        Ix = sum(a[i] * mp.fsum(w * x * p for w, x, p in zip(ws, xs, ph[i])) for i in range(nmodes))
        return +Omega, +I1, +I2, +Ix


def constants(body: dict, consistent_modes: int = 12) -> dict:
    H = M(body["height"])
    B = M(body["width"])
    D = M(body.get("depth", 1.0))
    g = M(body.get("gravity", 9.81))
    h = M(body.get("damping_ratio", 0.05))
    which = body.get("constants", "exact")
    variant = body.get("self_weight", "paper")
    if which == "paper" and variant == "consistent":
        raise ValueError("constants = 'paper' cannot be combined with self_weight = 'consistent'")
    if "density" in body:
        Mt = M(body["density"]) * H * B * D
    else:
        Mt = M(body["mass"])
    if which == "exact":
        L = mp.findroot(lambda L: mp.cos(L) * mp.cosh(L) + 1, mpf("1.875"))
        sig = (mp.cosh(L) + mp.cos(L)) / (mp.sinh(L) + mp.sin(L))
        intU, intU2, intUx = sig / L, mpf(1) / 4, 1 / L**2
        beta1 = intU / intU2
        ke_coef = L**3 * sig          # Ke = ke_coef EI/H^3  (= L^4 int U)
        mb_coef = L**2                # U''(0)
    elif which == "paper":
        L = mpf("1.8751")
        intU, intU2, intUx = mpf("0.3915"), mpf("0.2503"), 1 / L**2
        beta1 = mpf("1.564")
        ke_coef = mpf("4.840")
        mb_coef = L**2
    else:
        raise ValueError(f"body.constants = {which!r}: expected 'exact' or 'paper'")
    Me = Mt * intU

    if "youngs_modulus" in body:
        EI = M(body["youngs_modulus"]) * D * B**3 / 12
    elif "flexural_rigidity" in body:
        EI = M(body["flexural_rigidity"])
    else:
        if variant == "consistent":
            raise ValueError("body.period with self_weight = 'consistent' is not supported here")
        T = M(body["period"])
        EI = (2 * mp.pi / T) ** 2 * Me * H**3 / ke_coef
    gamma_g = Mt * g * H**2 / EI

    if variant == "paper":
        Ke = ke_coef * EI / H**3
        s_n = B / (2 * EI * mb_coef / (Mt * g * H**2) + 2 * intU)
        d = B - s_n
        sp, rp = -s_n / d, B / d       # ds/dq, dr/dq while rocking
        Fp = Ke * sp
        q_top = B
        I1, I2, Ix = intU, intU2, intUx
        Omega = None
    elif variant == "consistent":
        Omega, I1, I2, Ix = self_weighted_shape(gamma_g, consistent_modes)
        Me = Mt * I1
        Ke = Omega * I1 * EI / H**3
        beta1 = I1 / I2
        c_M = Omega * Ix
        s_n = B / (2 * c_M * EI / (Mt * g * H**2) + 2 * I1)
        kappa = mpf(1) / 2 - Ix * I1 / I2
        k_r = Mt * g * I1**2 / (H * I2)
        sp = -kappa / (B / (2 * s_n) - kappa)
        rp = 1 - sp
        Fp = Ke * sp - k_r * rp
        q_top = s_n - Ke * s_n / Fp
    else:
        raise ValueError(f"body.self_weight = {variant!r}: expected 'paper' or 'consistent'")

    omega = mp.sqrt(Ke / Me)
    c = 2 * h / omega
    intpV = sp * I2 + rp * Ix
    intV = sp * I1 + rp / 2
    intV2 = sp**2 * I2 + 2 * sp * rp * Ix + rp**2 / 3
    nu2 = intpV / intV2
    beta2 = intV / intV2
    num = H**2 * Ix + B**2 / 12
    den0 = H**2 * (sp * Ix + rp / 3) + B**2 / 12
    zetaU = num / (den0 + (B**2 / 4) * rp)
    zetaL = num / (den0 - (B**2 / 4) * rp)
    if s_n >= B:
        raise ValueError("s_n >= B: the body lifts off under its own weight")
    if zetaL >= 1:
        raise ValueError("zetaL >= 1: the body is too squat for the model")
    return dict(H=H, B=B, D=D, M=Mt, EI=EI, g=g, h=h, Me=Me, Ke=Ke, omega=omega,
                T=2 * mp.pi / omega, c=c, s_n=s_n, beta1=beta1, nu2=nu2, beta2=beta2,
                zetaU=zetaU, zetaL=zetaL, F_slope_rocking=Fp, q_topple=q_top,
                gamma_g=gamma_g, constants=which, self_weight=variant,
                Omega=Omega)


# --------------------------------------------------------------------------------------------
# Floor motion as pieces: (t_start, t_end, piece); piece = ("poly", [a0, a1, ...]) in the local
# time tau = t - t_start, ("trig", As, Ac, W): As sin(W t) + Ac cos(W t) in global t, or
# ("ricker", A, Tp, tc).
# --------------------------------------------------------------------------------------------
def ramp_coefficients(A, Tp, tr):
    w = 2 * mp.pi / Tp
    Mx = mp.matrix([[tr, tr**2, tr**3],
                    [tr**2 / 2, tr**3 / 3, tr**4 / 4],
                    [tr**3 / 6, tr**4 / 12, tr**5 / 20]])
    rhs = mp.matrix([A * mp.sin(w * tr), -(A / w) * mp.cos(w * tr), -(A / w**2) * mp.sin(w * tr)])
    c = mp.lu_solve(Mx, rhs)
    return [c[0], c[1], c[2]]


def read_at2(path):
    with open(path) as fh:
        lines = fh.read().splitlines()
    head = lines[3]
    import re
    mN = re.search(r"NPTS\s*=\s*([0-9]+)", head, re.I)
    mD = re.search(r"DT\s*=\s*([0-9.eE+-]+)", head, re.I)
    if not (mN and mD):
        raise ValueError(f"{path}: no NPTS/DT on header line 4")
    n, dt = int(mN.group(1)), mpf(mD.group(1))
    vals = []
    for ln in lines[4:]:
        vals.extend(mpf(tok) for tok in ln.split())
    if len(vals) < n:
        raise ValueError(f"{path}: {len(vals)} values, NPTS = {n}")
    return dt, vals[:n]


def read_csv_record(path, dt_key):
    ts, vs = [], []
    with open(path) as fh:
        for ln in fh:
            ln = ln.strip()
            if not ln or ln.startswith("#"):
                continue
            toks = [t for t in ln.replace(",", " ").split()]
            try:
                nums = [mpf(t) for t in toks]
            except (ValueError, TypeError):
                continue  # header row
            if len(nums) == 2:
                ts.append(nums[0])
                vs.append(nums[1])
            else:
                vs.append(nums[0])
    if ts:
        dt = (ts[-1] - ts[0]) / (len(ts) - 1)
    else:
        dt = M(dt_key)
    return dt, vs


class Excitation:
    def __init__(self, exc: dict, model_dir: str):
        self.kind = kind = exc["kind"]
        self.pieces = []          # list of (t0, t1, piece); t1 = None means to infinity
        self.natural_duration = None
        if kind == "free":
            self.pieces = [(mpf(0), None, ("poly", []))]
        elif kind == "harmonic":
            A, Tp = M(exc["amplitude"]), M(exc["period"])
            self.pieces = [(mpf(0), None, ("trig", A, mpf(0), 2 * mp.pi / Tp))]
        elif kind == "paper-sine":
            A, Tp, tr = M(exc["amplitude"]), M(exc["period"]), M(exc["ramp"])
            self.ramp = ramp_coefficients(A, Tp, tr)
            self.pieces = [(mpf(0), tr, ("poly", [mpf(0)] + self.ramp)),
                           (tr, None, ("trig", A, mpf(0), 2 * mp.pi / Tp))]
        elif kind == "sine-pulse":
            A, Tp = M(exc["amplitude"]), M(exc["period"])
            cycles = M(exc.get("cycles", 1))
            shape = exc.get("shape", "antisymmetric")
            end = cycles * Tp
            W = 2 * mp.pi / Tp
            if shape == "antisymmetric":
                p = ("trig", A, mpf(0), W)
            elif shape == "symmetric":
                p = ("trig", mpf(0), A, W)
            else:
                raise ValueError(f"excitation.shape = {shape!r}")
            self.pieces = [(mpf(0), end, p), (end, None, ("poly", []))]
            if "tail" in exc:
                self.natural_duration = end + M(exc["tail"])
        elif kind == "ricker":
            A, Tp, tc = M(exc["amplitude"]), M(exc["period"]), M(exc["center"])
            self.pieces = [(mpf(0), None, ("ricker", A, Tp, tc))]
        elif kind == "record":
            path = os.path.join(model_dir, exc["path"])
            fmt = exc.get("format")
            if fmt is None:
                fmt = "peer-at2" if path.lower().endswith(".at2") else "csv"
            units = exc.get("units", "g" if fmt == "peer-at2" else None)
            if fmt == "peer-at2":
                dt, vals = read_at2(path)
            else:
                dt, vals = read_csv_record(path, exc.get("dt"))
            f = {"g": mpf(STANDARD_GRAVITY), "m/s2": mpf(1), "cm/s2": mpf(1) / 100}[units]
            scale = M(exc.get("scale", 1.0))
            # start and end keep the whole samples inside [start, end]; start becomes t = 0.
            # Only a start on a sample time is supported (then the first kept sample is at t = 0).
            start = M(exc.get("start", 0.0))
            end = M(exc["end"]) if "end" in exc else (len(vals) - 1) * dt
            eps = dt * mpf("1e-9")
            i0 = int(mp.ceil(start / dt - mpf("1e-9")))
            if abs(i0 * dt - start) > eps:
                raise ValueError("excitation.start between two samples is not supported here")
            i1 = int(mp.floor(end / dt + mpf("1e-9")))
            vals = vals[i0:i1 + 1]
            a = [v * f * scale for v in vals]
            n = len(a)
            for k in range(n - 1):
                t0, t1 = k * dt, (k + 1) * dt
                self.pieces.append((t0, t1, ("poly", [a[k], (a[k + 1] - a[k]) / dt])))
            self.pieces.append(((n - 1) * dt, None, ("poly", [])))
            self.natural_duration = (n - 1) * dt + M(exc.get("tail", 0.0))
            self.record_dt = dt
        else:
            raise ValueError(f"excitation.kind = {kind!r} not supported")


# --------------------------------------------------------------------------------------------
# One closed-form segment: x'' + C x' + K x = -beta a(t) on [t0, t1], x = q - shift
# --------------------------------------------------------------------------------------------
class Segment:
    def __init__(self, C, K, beta, shift, piece, piece_t0, t0, q0, v0):
        self.C, self.K, self.beta, self.shift, self.t0 = C, K, beta, shift, t0
        self.piece_t0 = piece_t0      # the origin of a polynomial piece's local time
        self.piece = piece
        kind = piece[0]
        disc = C * C - 4 * K
        self.real = disc > 0
        if self.real:
            sq = mp.sqrt(disc)
            self.r1, self.r2 = (-C + sq) / 2, (-C - sq) / 2
        else:
            self.al = C / 2
            self.wd = mp.sqrt(-disc) / 2
            if self.wd == 0:
                raise ValueError("critically damped mode: not supported")
        self.poly = None
        self.trig = None
        self.ricker = None
        if kind == "poly":
            p = [-beta * ck for ck in piece[1]]
            n = len(p)
            a = [mpf(0)] * (n + 2)
            for k in range(n - 1, -1, -1):
                a[k] = (p[k] - C * (k + 1) * a[k + 1] - (k + 2) * (k + 1) * a[k + 2]) / K
            self.poly = a[:n]
        elif kind == "trig":
            _, As, Ac, W = piece
            Fs, Fc = -beta * As, -beta * Ac
            det = (K - W * W) ** 2 + (C * W) ** 2
            if det == 0:
                raise ValueError("undamped resonance: not supported")
            # [[K - W^2, -C W], [C W, K - W^2]] [X, Y] = [Fs, Fc]
            X = ((K - W * W) * Fs + C * W * Fc) / det
            Y = ((K - W * W) * Fc - C * W * Fs) / det
            self.trig = (X, Y, W)
        elif kind == "ricker":
            self.ricker = piece[1:]
            if self.real:
                self.rts = [mpf(self.r1), mpf(self.r2)]
            else:
                self.rts = [mp.mpc(-self.al, self.wd), mp.mpc(-self.al, -self.wd)]
            _, _, Tp, tc = piece
            self.sig = Tp / mp.pi
            self.G0 = [self._ricker_G(r, (t0 - tc) / self.sig) for r in self.rts]
        xp0, vp0 = self._part(t0, 0), self._part(t0, 1)
        X0, V0 = (q0 - shift) - xp0, v0 - vp0
        if self.real:
            self.A = (V0 - self.r2 * X0) / (self.r1 - self.r2)
            self.B = X0 - self.A
        else:
            self.P = X0
            self.Q = (V0 + self.al * X0) / self.wd

    # ---- particular part (zero-state from t0 for the Ricker wavelet)
    def _ricker_G(self, r, x):
        b = r * self.sig
        J0 = mp.exp(b * b / 4) * mp.sqrt(mp.pi) / 2 * mp.erf(x + b / 2)
        return mp.exp(-b * x) * x * mp.exp(-x * x) + b * (-mp.exp(-b * x - x * x) / 2 - b / 2 * J0)

    def _part(self, t, n):
        if self.poly is not None:
            tau = t - self.piece_t0
            a = self.poly
            for _ in range(n):
                a = [k * a[k] for k in range(1, len(a))]
            return mp.polyval(a[::-1], tau) if a else mpf(0)
        if self.trig is not None:
            X, Y, W = self.trig
            s, c = mp.sin(W * t), mp.cos(W * t)
            v = [X * s + Y * c, W * (X * c - Y * s), -W * W * (X * s + Y * c)][n]
            return v
        # Ricker: y(t) = int_t0^t h(t - s) f(s) ds, h = (e^{r1 u} - e^{r2 u})/(r1 - r2),
        # f = -beta A (1 - 2 x^2) e^{-x^2}, x = (s - tc)/sig.  I_r(t) = int e^{-r s} f ds
        # = -beta A sig e^{-r tc} [G(x(t)) - G(x(t0))];  y = sum_r +-e^{r t} I_r/(r1 - r2).
        A, Tp, tc = self.ricker
        x = (t - self.t0 + self.t0 - tc) / self.sig
        r1, r2 = self.rts
        Is = []
        for r, G0 in zip(self.rts, self.G0):
            Is.append(-self.beta * A * self.sig * (self._ricker_G(r, x) - G0))
        # e^{r t} e^{-r tc} = e^{r sig x}
        terms = [mp.exp(r * self.sig * x) * I for r, I in zip(self.rts, Is)]
        y = (terms[0] - terms[1]) / (r1 - r2)
        if n == 0:
            val = y
        else:
            yd = (r1 * terms[0] - r2 * terms[1]) / (r1 - r2)   # the boundary term h(0) f = 0
            if n == 1:
                val = yd
            else:
                xx = (t - tc) / self.sig
                f = -self.beta * A * (1 - 2 * xx * xx) * mp.exp(-xx * xx)
                val = (r1 * r1 * terms[0] - r2 * r2 * terms[1]) / (r1 - r2) + f
        return mp.re(val)

    def _hom(self, t, n):
        tau = t - self.t0
        if self.real:
            e1, e2 = mp.exp(self.r1 * tau), mp.exp(self.r2 * tau)
            return self.A * self.r1**n * e1 + self.B * self.r2**n * e2
        P, Q = self.P, self.Q
        for _ in range(n):
            P, Q = -self.al * P + self.wd * Q, -self.al * Q - self.wd * P
        return mp.exp(-self.al * tau) * (P * mp.cos(self.wd * tau) + Q * mp.sin(self.wd * tau))

    def q(self, t):
        return self.shift + self._hom(t, 0) + self._part(t, 0)

    def qd(self, t):
        return self._hom(t, 1) + self._part(t, 1)

    def qdd(self, t):
        return self._hom(t, 2) + self._part(t, 2)


# --------------------------------------------------------------------------------------------
# Root finding on a bracket where the function is monotone
# --------------------------------------------------------------------------------------------
def refine(f, df, a, b, fa, fb, tol):
    """Root of f in [a, b] with fa <= 0 <= fb or fa >= 0 >= fb; bisection then Newton."""
    if fa == 0:
        return a
    if fb == 0:
        return b
    stop = mpf("1e-12") if df is not None else tol
    while b - a > stop:
        m = (a + b) / 2
        fm = f(m)
        if fm == 0:
            return m
        if (fm < 0) == (fa < 0):
            a, fa = m, fm
        else:
            b, fb = m, fm
    if df is None:
        return (a + b) / 2
    t = (a + b) / 2
    for _ in range(60):
        d = df(t)
        if d == 0:
            break
        tn = t - f(t) / d
        if tn < a or tn > b:      # keep it in the bracket
            tn = (a + b) / 2
        ft = f(tn)
        if ft == 0:
            return tn
        if (ft < 0) == (fa < 0):
            a, fa = tn, ft
        else:
            b, fb = tn, ft
        if abs(tn - t) < tol:
            return tn
        t = tn
    return t


# --------------------------------------------------------------------------------------------
# The hybrid automaton
# --------------------------------------------------------------------------------------------
class Solver:
    def __init__(self, k: dict, exc: Excitation, tol=mpf("1e-32")):
        self.k, self.exc, self.tol = k, exc, tol
        self.grid_max = min([k["T"] / 64] + self._exc_scales())

    def _exc_scales(self):
        out = []
        for _, _, p in self.exc.pieces:
            if p[0] == "trig":
                out.append(2 * mp.pi / p[3] / 64)
            if p[0] == "ricker":
                out.append(p[2] / 64)
        k = self.k
        Fp = k["F_slope_rocking"]
        rate = mp.sqrt(abs(k["nu2"] * Fp / k["Me"]))
        out.append(1 / rate / 16)
        return out

    def mode_coeffs(self, mode):
        k = self.k
        if mode == PRE:
            nu, beta, Fp, shift = mpf(1), k["beta1"], k["Ke"], mpf(0)
        else:
            nu, beta, Fp = k["nu2"], k["beta2"], k["F_slope_rocking"]
            shift = k["q_topple"] if mode == RR else -k["q_topple"]
        C = k["c"] * nu * Fp / k["Me"]
        K = nu * Fp / k["Me"]
        return C, K, beta, shift

    def guards(self, mode):
        """(kind, target, level, sense): the guard fires when sense*(q - level) reaches 0 from below."""
        s_n, qt = self.k["s_n"], self.k["q_topple"]
        if mode == PRE:
            return [("uplift", RR, s_n, 1), ("uplift", RL, -s_n, -1)]
        if mode == RR:
            return [("landing", PRE, s_n, -1), ("overturn", OVER, qt, 1)]
        return [("landing", PRE, -s_n, 1), ("overturn", OVER, -qt, -1)]

    def critical_points(self, seg, a, b):
        """Roots of q' in (a, b], sorted."""
        out = []
        n = max(1, int(mp.ceil((b - a) / self.grid_max)))
        h = (b - a) / n
        pts = [a + i * h for i in range(n)] + [b]
        dq = [seg.qd(t) for t in pts]
        ddq = [seg.qdd(t) for t in pts]
        for i in range(n):
            lo, hi = pts[i], pts[i + 1]
            subs = [(lo, dq[i]), (hi, dq[i + 1])]
            if ddq[i] * ddq[i + 1] < 0:     # q' has an extremum inside: q' may cross twice
                m = refine(seg.qdd, None, lo, hi, ddq[i], ddq[i + 1], mpf("1e-20"))
                subs = [(lo, dq[i]), (m, seg.qd(m)), (hi, dq[i + 1])]
            for (t_a, f_a), (t_b, f_b) in zip(subs, subs[1:]):
                if f_b == 0:
                    out.append(t_b)
                elif f_a != 0 and (f_a < 0) != (f_b < 0):
                    out.append(refine(seg.qd, seg.qdd, t_a, t_b, f_a, f_b, self.tol))
        return sorted(t for t in out if a < t <= b)

    def run(self, q0, v0, t_end):
        k = self.k
        t = mpf(0)
        q, v = q0, v0
        mode = RR if q0 > k["s_n"] else RL if q0 < -k["s_n"] else PRE
        events = []
        extrema = [(t, q, mode)]          # (t, q, mode) of every extremum candidate
        pieces = self.exc.pieces
        pi = 0
        n_segments = 0
        while mode != OVER and t < t_end:
            while pieces[pi][1] is not None and pieces[pi][1] <= t:
                pi += 1
            p_end = pieces[pi][1]
            t1 = t_end if p_end is None else min(p_end, t_end)
            C, K, beta, shift = self.mode_coeffs(mode)
            seg = Segment(C, K, beta, shift, pieces[pi][2], pieces[pi][0], t, q, v)
            n_segments += 1
            crit = self.critical_points(seg, t, t1)
            pts = [t] + crit + ([t1] if not crit or crit[-1] != t1 else [])
            qs = [seg.q(s) for s in pts]
            hit = None
            for j in range(len(pts) - 1):
                for kind, target, level, sense in self.guards(mode):
                    ga, gb = sense * (qs[j] - level), sense * (qs[j + 1] - level)
                    if gb >= 0 and ga < 0:
                        te = refine(lambda s: sense * (seg.q(s) - level),
                                    lambda s: sense * seg.qd(s), pts[j], pts[j + 1], ga, gb, self.tol)
                        if hit is None or te < hit[0]:
                            hit = (te, kind, target, level)
                if hit is not None:
                    break
            if hit is None:
                for s, qq in zip(pts[1:-1], qs[1:-1]):
                    extrema.append((s, qq, mode))
                q, v, t = qs[-1], seg.qd(t1), t1
                if t >= t_end:
                    extrema.append((t, q, mode))
                continue
            te, kind, target, level = hit
            for s, qq in zip(pts[1:-1], qs[1:-1]):
                if s < te:
                    extrema.append((s, qq, mode))
            vb = seg.qd(te)
            va = vb * k["zetaU"] if kind == "uplift" else vb / k["zetaL"] if kind == "landing" else vb
            events.append(dict(t=te, kind=kind, frm=mode, to=target, q=level, qdot_before=vb,
                               qdot_after=va))
            extrema.append((te, level, mode))
            mode, t, q, v = target, te, level, va
        return events, extrema, mode, t, n_segments


def episodes_of(events, extrema, mode0, t_final, final_mode):
    """Rocking episodes with their peak |q| (from the extremum candidates)."""
    eps = []
    cur = None
    if mode0 in (RR, RL):
        cur = dict(side="right" if mode0 == RR else "left", t_start=mpf(0))
    for e in events:
        if e["kind"] == "uplift":
            cur = dict(side="right" if e["to"] == RR else "left", t_start=e["t"])
        elif cur is not None:
            cur.update(t_end=e["t"], ended_by=e["kind"])
            eps.append(cur)
            cur = None
    if cur is not None:
        cur.update(t_end=None, ended_by="run-end")
        eps.append(cur)
    for ep in eps:
        hi = ep["t_end"] if ep["t_end"] is not None else t_final
        cands = [(abs(qq), s) for s, qq, _ in extrema if ep["t_start"] <= s <= hi]
        best = max(cands, key=lambda c: c[0])
        ep["peak_abs_q"], ep["t_peak"] = best
    return eps


# --------------------------------------------------------------------------------------------
# Output
# --------------------------------------------------------------------------------------------
def num(x, digits=25):
    if x is None:
        return "null"
    s = mp.nstr(mpf(x), digits, strip_zeros=False, min_fixed=-mp.inf, max_fixed=mp.inf)
    if "e" not in s and "." not in s:
        s += ".0"
    return s


def to_json(obj, indent=0):
    pad = "  " * (indent + 1)
    if isinstance(obj, dict):
        items = [f'{pad}{json.dumps(k)}: {to_json(v, indent + 1)}' for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if isinstance(obj, list):
        if not obj:
            return "[]"
        items = [pad + to_json(v, indent + 1) for v in obj]
        return "[\n" + ",\n".join(items) + "\n" + "  " * indent + "]"
    if isinstance(obj, mpf):
        return num(obj)
    if obj is None or isinstance(obj, (bool, int, str)):
        return json.dumps(obj)
    if isinstance(obj, float):
        return repr(obj)
    raise TypeError(type(obj))


def solve_file(path, dps=40, consistent_modes=12):
    mp.mp.dps = dps
    with open(path, "rb") as fh:
        model = tomllib.load(fh)
    k = constants(model["body"], consistent_modes)
    exc = Excitation(model["excitation"], os.path.dirname(os.path.abspath(path)))
    sim = model.get("simulation", {})
    if "duration" in sim:
        t_end = M(sim["duration"])
    elif exc.natural_duration is not None:
        t_end = exc.natural_duration
    else:
        raise ValueError("simulation.duration is required for this excitation")
    q0, v0 = M(sim.get("q0", 0.0)), M(sim.get("qdot0", 0.0))
    solver = Solver(k, exc)
    events, extrema, final_mode, t_final, nseg = solver.run(q0, v0, t_end)
    mode0 = RR if q0 > k["s_n"] else RL if q0 < -k["s_n"] else PRE
    eps = episodes_of(events, extrema, mode0, t_final, final_mode)
    tmax, qmax, _ = max(extrema, key=lambda e: e[1])
    tmin, qmin, _ = min(extrema, key=lambda e: e[1])
    over = final_mode == OVER
    return dict(constants=k, events=events, episodes=eps, max_q=qmax, t_max_q=tmax, min_q=qmin,
                t_min_q=tmin, overturned=over, t_overturn=t_final if over else None,
                final_time=t_final, final_mode=final_mode, duration=t_end, segments=nseg)


def write_outputs(res, out, name, dps, elapsed):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "events.csv"), "w") as fh:
        fh.write("index,t,kind,from,to,q,qdot_before,qdot_after\n")
        for i, e in enumerate(res["events"]):
            fh.write(f"{i},{num(e['t'])},{e['kind']},{e['frm']},{e['to']},{num(e['q'])},"
                     f"{num(e['qdot_before'])},{num(e['qdot_after'])}\n")
    k = res["constants"]
    ck = ["Me", "Ke", "omega", "T", "c", "s_n", "beta1", "nu2", "beta2", "zetaU", "zetaL",
          "F_slope_rocking", "q_topple", "gamma_g"]
    doc = {
        "case": name,
        "method": "closed form per mode and per piece of a(t), mpmath",
        "dps": dps,
        "self_weight": k["self_weight"],
        "constants_set": k["constants"],
        "duration": res["duration"],
        "final_time": res["final_time"],
        "final_mode": res["final_mode"],
        "n_uplift": sum(1 for e in res["events"] if e["kind"] == "uplift"),
        "n_landing": sum(1 for e in res["events"] if e["kind"] == "landing"),
        "overturned": res["overturned"],
        "t_overturn": res["t_overturn"],
        "max_q": res["max_q"], "t_max_q": res["t_max_q"],
        "min_q": res["min_q"], "t_min_q": res["t_min_q"],
        "episodes": [dict(index=i, side=ep["side"], t_start=ep["t_start"], t_end=ep["t_end"],
                          ended_by=ep["ended_by"], peak_abs_q=ep["peak_abs_q"], t_peak=ep["t_peak"])
                     for i, ep in enumerate(res["episodes"])],
        "constants": {c: k[c] for c in ck},
    }
    with open(os.path.join(out, "peaks.json"), "w") as fh:
        fh.write(to_json(doc) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("model")
    ap.add_argument("--out", required=True)
    ap.add_argument("--dps", type=int, default=40)
    ap.add_argument("--name", default=None)
    ap.add_argument("--consistent-modes", type=int, default=12,
                    help="cantilever modes of the Ritz solve of the consistent variant (12)")
    args = ap.parse_args(argv)
    name = args.name or os.path.splitext(os.path.basename(args.model))[0]
    t0 = time.perf_counter()
    res = solve_file(args.model, args.dps, args.consistent_modes)
    el = time.perf_counter() - t0
    write_outputs(res, args.out, name, args.dps, el)
    nu = sum(1 for e in res["events"] if e["kind"] == "uplift")
    nl = sum(1 for e in res["events"] if e["kind"] == "landing")
    print(f"{name}: {len(res['events'])} events ({nu} uplift, {nl} landing"
          + (f", overturn at t = {mp.nstr(res['t_overturn'], 17)} s" if res["overturned"] else "")
          + f"), max q = {mp.nstr(res['max_q'], 12)} m at {mp.nstr(res['t_max_q'], 12)} s, "
          f"min q = {mp.nstr(res['min_q'], 12)} m at {mp.nstr(res['t_min_q'], 12)} s; "
          f"{res['segments']} segments, {el:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
