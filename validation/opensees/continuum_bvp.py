#!/usr/bin/env python3
"""Continuum check of the OpenSees pushover: the beam-column with self-weight as a boundary-value
problem (scipy solve_bvp), for the paper's body and for E x 10, with and without the weight in
the bending. Shares nothing with beam_column.py except the model file it reads.

Euler-Bernoulli column on [0, H], lateral displacement u(y) relative to the base node (which does
not slide), compression N(y) = m g (H - y), lateral loads p(y) = lam m U(y/H). Moments about the
section y of everything above it (small rotations, the weight displaced by u(eta) - u(y)):

    EI u''(y) = int_y^H p(eta) (eta - y) d eta + m g int_y^H (u(eta) - u(y)) d eta

and its derivative, which is the system solved here (first order in u, u', u''):

    EI u'''(y) = -V(y) - N(y) u'(y),      V(y) = lam m H int_{y/H}^1 U(xi) d xi

Boundary conditions: u(0) = 0, u''(H) = 0, and
  * before uplift (the base plate flat on both toes, a fixed base):   u'(0) = 0
  * rocking about the right toe (the left toe's reaction zero):       EI u''(0) = M g B/2
    (the only base reaction is M g at x = +B/2, so the base moment about the base node is M g B/2;
     the base rotation theta = u'(0) is then free; r = theta H, s = q - r).
Uplift is where the pre-uplift solution reaches EI u''(0) = M g B/2. Everything is linear in lam
in each phase, so two solves per phase give the whole branch; the rocking branch is checked at a
third point. Without the weight in the bending, N = 0 in both.

The fixed-base period after gravity: (EI u'')'' + (N u')' = omega^2 m u, u(0) = u'(0) = 0,
u''(H) = 0, EI u'''(H) = 0, u(H) = 1 (omega^2 an unknown parameter of solve_bvp; solved in
dimensionless form). No rotary inertia (Euler-Bernoulli).
"""

import argparse
import csv
import math
import os
import tomllib

import numpy as np
from scipy.integrate import solve_bvp

LAM = 1.875104068711961
SIG = (math.cosh(LAM) + math.cos(LAM)) / (math.sinh(LAM) + math.sin(LAM))
HERE = os.path.dirname(os.path.abspath(__file__))
MODEL_FILE = os.path.normpath(os.path.join(HERE, "..", "..", "models", "ichinose1986.toml"))


def U(xi):
    return 0.5 * (np.cosh(LAM * xi) - np.cos(LAM * xi) - SIG * (np.sinh(LAM * xi) - np.sin(LAM * xi)))


def intU0(xi):
    """int_0^xi U."""
    return 0.5 * ((np.sinh(LAM * xi) - np.sin(LAM * xi))
                  - SIG * (np.cosh(LAM * xi) + np.cos(LAM * xi) - 2.0)) / LAM


def body(e_factor):
    with open(MODEL_FILE, "rb") as f:
        b = tomllib.load(f)["body"]
    H, B, D, rho = b["height"], b["width"], b.get("depth", 1.0), b["density"]
    E = b["youngs_modulus"] * e_factor
    g = b.get("gravity", 9.81)
    EI = E * D * B ** 3 / 12
    m = rho * B * D
    return dict(H=H, B=B, m=m, M=m * H, EI=EI, g=g, Ke=LAM ** 3 * SIG * EI / H ** 3)


def solve_static(bd, lam, weight, rocking):
    H, m, g, EI, M, B = bd["H"], bd["m"], bd["g"], bd["EI"], bd["M"], bd["B"]
    tot = intU0(1.0)
    wg = m * g if weight else 0.0

    def f(y, z):
        V = lam * m * H * (tot - intU0(y / H))
        N = wg * (H - y)
        return np.vstack([z[1], z[2], (-V - N * z[1]) / EI])

    def bc(za, zb):
        third = za[2] - M * g * B / (2 * EI) if rocking else za[1]
        return np.array([za[0], zb[2], third])

    y = np.linspace(0.0, H, 401)
    sol = solve_bvp(f, bc, y, np.zeros((3, y.size)), tol=1e-10, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(sol.message)
    q = float(sol.sol(H)[0])
    theta = float(sol.sol(0.0)[1])
    curv0 = float(sol.sol(0.0)[2])
    return dict(q=q, r=theta * H, s=q - theta * H, base_moment=EI * curv0, V=lam * M * tot)


def period(bd, weight):
    """Dimensionless: xi = y/H, gamma = M g H^2/EI, Omega = omega^2 m H^4/EI;
    u'''' + gamma ((1 - xi) u')' = Omega u, with w = u''' + gamma (1 - xi) u' (the shear)."""
    H, m, g, EI = bd["H"], bd["m"], bd["g"], bd["EI"]
    gam = bd["M"] * g * H ** 2 / EI if weight else 0.0

    def f(x, z, p):
        return np.vstack([z[1], z[2], z[3] - gam * (1 - x) * z[1], p[0] * z[0]])

    def bc(za, zb, p):
        return np.array([za[0], za[1], zb[2], zb[3], zb[0] - 1.0])

    x = np.linspace(0.0, 1.0, 201)
    L = LAM
    d1 = 0.5 * L * (np.sinh(L * x) + np.sin(L * x) - SIG * (np.cosh(L * x) - np.cos(L * x)))
    d2 = 0.5 * L ** 2 * (np.cosh(L * x) + np.cos(L * x) - SIG * (np.sinh(L * x) + np.sin(L * x)))
    d3 = 0.5 * L ** 3 * (np.sinh(L * x) - np.sin(L * x) - SIG * (np.cosh(L * x) - np.cos(L * x)))
    z0 = np.vstack([U(x), d1, d2, d3 + gam * (1 - x) * d1])
    sol = solve_bvp(f, bc, x, z0, p=[L ** 4], tol=1e-9, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(sol.message)
    omega2 = sol.p[0] * EI / (m * H ** 4)
    return 2 * math.pi / math.sqrt(omega2)


def pushover(e_factor, weight):
    bd = body(e_factor)
    M, g, B = bd["M"], bd["g"], bd["B"]
    # pre-uplift: linear in lam
    a = solve_static(bd, 1.0, weight, rocking=False)
    K0 = a["V"] / a["q"]
    lam_up = M * g * B / 2 / a["base_moment"]
    q_up, V_up = lam_up * a["q"], lam_up * a["V"]
    if weight:
        # rocking branch: affine in lam; two solves and a check at a third
        r1 = solve_static(bd, lam_up, weight, rocking=True)
        r0 = solve_static(bd, 0.0, weight, rocking=True)
        slope = (r1["V"] - r0["V"]) / (r1["q"] - r0["q"])
        rh = solve_static(bd, lam_up / 2, weight, rocking=True)
        affine_err = abs(rh["q"] - (r0["q"] + r1["q"]) / 2)
    else:
        # without the weight in the bending nothing resists the base rotation once the base moment
        # is M g B/2: the rocking branch is a plateau V = V_uplift at any q (the BVP is singular)
        r1 = dict(q=float("nan"))
        r0 = dict(q=float("nan"), s=float("nan"))
        slope, affine_err = 0.0, float("nan")
    return dict(case=f"E{int(e_factor)}_{'pdelta' if weight else 'linear'}", e_factor=e_factor,
                weight_in_bending=weight, K0=K0, K0_over_Ke=K0 / bd["Ke"], q_uplift=q_up, V_uplift=V_up,
                rocking_q_at_uplift=r1["q"], post_slope=slope,
                q_zero_shear=r0["q"], s_at_zero_shear=r0["s"],
                T_fixed_base=period(bd, weight), affine_check=affine_err)


COLS = ["case", "e_factor", "weight_in_bending", "K0", "K0_over_Ke", "q_uplift", "V_uplift",
        "rocking_q_at_uplift", "post_slope", "q_zero_shear", "s_at_zero_shear", "T_fixed_base",
        "affine_check"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(HERE, "results"))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for ef in (1.0, 10.0):
        for w in (True, False):
            r = pushover(ef, w)
            rows.append(r)
            print("continuum " + ", ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}"
                                           for k, v in r.items()), flush=True)
    with open(os.path.join(a.out, "continuum_summary.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(COLS)
        for r in rows:
            w.writerow([("true" if r[c] else "false") if isinstance(r[c], bool) else
                        (f"{r[c]:.7g}" if isinstance(r[c], float) else r[c]) for c in COLS])


if __name__ == "__main__":
    main()
