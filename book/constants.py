#!/usr/bin/env python3
"""Recompute every number quoted in book/src/model.md, with the Python standard library only.

This shares no code with the Rust crates: it starts from the formulas written in the chapter and
the reference body of its section 8 (H = 4 m, B = 0.7 m, D = 1 m, 600 kg/m^3, E = 5 MPa,
h = 0.05, g = 9.81 m/s^2). Compare its output with `flexrock props models/ichinose1986.toml`
(and with `--set body.self_weight=consistent` for the consistent variant).

    python3 book/constants.py
"""

import math

# The reference body (section 8 of the chapter).
H, B, D = 4.0, 0.7, 1.0
DENSITY, E, DAMPING, G = 600.0, 5.0e6, 0.05, 9.81
M = DENSITY * H * B * D
EI = E * D * B**3 / 12.0
BUCKLING = 7.837  # M g H^2/EI at which a uniform cantilever buckles under its own weight


def cantilever_root(k):
    """k-th root of cos L cosh L = -1, by bisection on cos L cosh L + 1 near (k - 1/2) pi."""
    f = lambda x: math.cos(x) * math.cosh(x) + 1.0
    centre = (k - 0.5) * math.pi
    lo, hi = centre - 0.5, centre + 0.5
    if f(lo) * f(hi) > 0:
        raise ValueError(f"no root bracketed for mode {k}")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


L = cantilever_root(1)
SIG = (math.cosh(L) + math.cos(L)) / (math.sinh(L) + math.sin(L))


def rocking_constants(int_u, int_u2, int_u_xi, ke, s_n, ds):
    """nu2, beta2, zetaU, zetaL for a rocking branch with ds/dq = ds (eqs. 11b-13, 19-22)."""
    dr = 1.0 - ds
    int_uv = ds * int_u2 + dr * int_u_xi
    int_v = ds * int_u + dr / 2.0
    int_v2 = ds * ds * int_u2 + 2.0 * ds * dr * int_u_xi + dr * dr / 3.0
    nu2, beta2 = int_uv / int_v2, int_v / int_v2
    num = H * H * int_u_xi + B * B / 12.0
    den = H * H * (ds * int_u_xi + dr / 3.0) + B * B / 12.0
    zeta_u = num / (den + B * B / 4.0 * dr)
    zeta_l = num / (den - B * B / 4.0 * dr)
    # Kinetic energy of the horizontal motion, M int (shape)^2 q'^2/2 (U before uplift, V while
    # rocking): the share kept at uplift and at landing (section 5).
    kept_u = zeta_u**2 * int_v2 / int_u2
    kept_l = int_u2 / (zeta_l**2 * int_v2)
    return nu2, beta2, zeta_u, zeta_l, kept_u, kept_l


def paper_variant(int_u, int_u2, int_u_xi, beta1, c_k, c_m, label):
    me = M * int_u
    ke = c_k * EI / H**3
    omega = math.sqrt(ke / me)
    s_n = B / (2.0 * EI * c_m / (M * G * H * H) + 2.0 * int_u)
    ds = -s_n / (B - s_n)
    nu2, beta2, zu, zl, ku, kl = rocking_constants(int_u, int_u2, int_u_xi, ke, s_n, ds)
    print(f"== paper's model, {label} constants")
    rows = [
        ("int U", int_u), ("int U^2", int_u2), ("int U xi", int_u_xi), ("beta1", beta1),
        ("Ke coefficient", c_k), ("Me (kg)", me), ("Ke (N/m)", ke), ("omega (rad/s)", omega),
        ("T (s)", 2 * math.pi / omega), ("gamma/E (s)", 2 * DAMPING / omega), ("s_n (m)", s_n),
        ("s_n/B", s_n / B), ("Ke s_n (N)", ke * s_n), ("dF/dq rocking (N/m)", ke * ds),
        ("ds/dq rocking", ds), ("nu2", nu2), ("beta2", beta2), ("zetaU", zu), ("zetaL", zl),
        ("zetaU/zetaL", zu / zl), ("kinetic energy kept at uplift", ku),
        ("kinetic energy kept at landing", kl), ("a_up = omega^2 s_n/beta1 (m/s^2)", omega**2 * s_n / beta1),
        ("rigid-limit uplift factor", c_k / (2 * int_u * c_m * beta1)),
    ]
    for name, value in rows:
        print(f"  {name:36s} {value:.9g}")


# --- the self-weight-consistent variant: a Ritz solve of the self-weighted cantilever mode ---

def gauss_rule(n):
    """Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n)."""
    rule = []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1.0)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-15:
                break
        rule.append((x, 2.0 / ((1.0 - x * x) * dp * dp)))
    return rule


def composite_points(panels=40, order=12):
    base = gauss_rule(order)
    pts = []
    for p in range(panels):
        a, b = p / panels, (p + 1) / panels
        for x, w in base:
            pts.append((a + (b - a) * (x + 1) / 2, w * (b - a) / 2))
    return pts


def mode_values(k, xi):
    """(phi, phi', phi'') of the k-th cantilever mode, phi(1) = +-1, derivatives in xi.

    cosh z - s sinh z and sinh z - s cosh z are written with 1 - s = (sin L - cos L - e^-L)/(sinh L
    + sin L), so that the large exponentials do not cancel.
    """
    lk = cantilever_root(k)
    den = math.sinh(lk) + math.sin(lk)
    one_minus_s = (math.sin(lk) - math.cos(lk) - math.exp(-lk)) / den
    s = 1.0 - one_minus_s
    z = lk * xi
    a = one_minus_s * math.exp(z)
    c_minus = 0.5 * (a + (1 + s) * math.exp(-z))  # cosh z - s sinh z
    s_minus = 0.5 * (a - (1 + s) * math.exp(-z))  # sinh z - s cosh z
    phi = 0.5 * (c_minus - math.cos(z) + s * math.sin(z))
    dphi = 0.5 * lk * (s_minus + math.sin(z) + s * math.cos(z))
    ddphi = 0.5 * lk * lk * (c_minus + math.cos(z) - s * math.sin(z))
    return phi, dphi, ddphi


def solve(matrix, rhs):
    """Gaussian elimination with partial pivoting."""
    n = len(rhs)
    a = [row[:] + [rhs[i]] for i, row in enumerate(matrix)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            for j in range(c, n + 1):
                a[r][j] -= f * a[c][j]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (a[r][n] - sum(a[r][j] * x[j] for j in range(r + 1, n))) / a[r][r]
    return x


def self_weighted_shape(gamma_g, modes=16):
    pts = composite_points()
    table = [[mode_values(k, xi) for k in range(1, modes + 1)] for xi, _ in pts]
    kmat = [[0.0] * modes for _ in range(modes)]
    mmat = [[0.0] * modes for _ in range(modes)]
    for (xi, w), vals in zip(pts, table):
        for i in range(modes):
            for j in range(modes):
                kmat[i][j] += w * (vals[i][2] * vals[j][2] - gamma_g * (1 - xi) * vals[i][1] * vals[j][1])
                mmat[i][j] += w * vals[i][0] * vals[j][0]
    # Lowest eigenpair of K a = Omega M a by inverse iteration (K is positive definite below
    # buckling).
    a = [1.0] + [0.0] * (modes - 1)
    omega_c = 0.0
    for _ in range(200):
        ma = [sum(mmat[i][j] * a[j] for j in range(modes)) for i in range(modes)]
        a_new = solve(kmat, ma)
        norm = math.sqrt(sum(v * v for v in a_new))
        a_new = [v / norm for v in a_new]
        ka = [sum(kmat[i][j] * a_new[j] for j in range(modes)) for i in range(modes)]
        ma = [sum(mmat[i][j] * a_new[j] for j in range(modes)) for i in range(modes)]
        rq = sum(x * y for x, y in zip(a_new, ka)) / sum(x * y for x, y in zip(a_new, ma))
        done = abs(rq - omega_c) < 1e-14 * rq
        a, omega_c = a_new, rq
        if done:
            break
    tip = sum(a[k] * mode_values(k + 1, 1.0)[0] for k in range(modes))
    a = [v / tip for v in a]
    i1 = i2 = ix = 0.0
    for (xi, w), vals in zip(pts, table):
        psi = sum(a[k] * vals[k][0] for k in range(modes))
        i1 += w * psi
        i2 += w * psi * psi
        ix += w * psi * xi
    return omega_c, i1, i2, ix


def consistent_variant():
    gamma_g = M * G * H * H / EI
    omega_c, i1, i2, ix = self_weighted_shape(gamma_g)
    me = M * i1
    ke = omega_c * i1 * EI / H**3
    omega = math.sqrt(ke / me)
    c_m = omega_c * ix
    s_n = B / (2.0 * c_m * EI / (M * G * H * H) + 2.0 * i1)
    kappa = 0.5 - ix * i1 / i2
    ds = -kappa / (B / (2 * s_n) - kappa)
    k_r = M * G * i1 * i1 / (i2 * H)
    dfdq = ke * ds - k_r * (1 - ds)
    q_topple = s_n - ke * s_n / dfdq
    nu2, beta2, zu, zl, ku, kl = rocking_constants(i1, i2, ix, ke, s_n, ds)
    print("== self-weight-consistent variant")
    rows = [
        ("gamma_g", gamma_g), ("Omega/L^4", omega_c / L**4), ("int psi", i1), ("int psi^2", i2),
        ("int psi xi", ix), ("beta1", i1 / i2), ("Me (kg)", me), ("Ke (N/m)", ke),
        ("omega (rad/s)", omega), ("T (s)", 2 * math.pi / omega), ("gamma/E (s)", 2 * DAMPING / omega),
        ("s_n (m)", s_n), ("Ke s_n (N)", ke * s_n), ("kappa", kappa), ("ds/dq rocking", ds),
        ("k_r (N/m)", k_r), ("dF/dq rocking (N/m)", dfdq), ("q_topple (m)", q_topple),
        ("s at q_topple (m)", s_n + ds * (q_topple - s_n)), ("nu2", nu2), ("beta2", beta2),
        ("zetaU", zu), ("zetaL", zl), ("kinetic energy kept at uplift", ku),
        ("kinetic energy kept at landing", kl),
        ("a_up = omega^2 s_n/beta1 (m/s^2)", omega**2 * s_n * i2 / i1),
    ]
    for name, value in rows:
        print(f"  {name:36s} {value:.9g}")


def ramp_coefficients(amp=5.0, period=1.0, t1=0.412):
    """c1, c2, c3 of a(t) = c1 t + c2 t^2 + c3 t^3 on [0, t1): a, v, d continuous at t1."""
    w = 2 * math.pi / period
    a1 = amp * math.sin(w * t1)
    v1 = -amp / w * math.cos(w * t1)
    d1 = -amp / w**2 * math.sin(w * t1)
    # a(t1), v(t1) = int a, d(t1) = int int a, with the floor at rest at t = 0.
    rows = [[t1, t1**2, t1**3], [t1**2 / 2, t1**3 / 3, t1**4 / 4], [t1**3 / 6, t1**4 / 12, t1**5 / 20]]
    return solve(rows, [a1, v1, d1])


def main():
    print("== body")
    gamma_g = M * G * H * H / EI
    for name, value in [("M (kg)", M), ("EI (N m^2)", EI), ("L", L), ("sigma", SIG),
                        ("gamma_g = M g H^2/EI", gamma_g), ("gamma_g/7.837", gamma_g / BUCKLING)]:
        print(f"  {name:36s} {value:.12g}")
    paper_variant(SIG / L, 0.25, 1 / L**2, 4 * SIG / L, L**3 * SIG, L * L, "exact")
    lp = 1.8751
    paper_variant(0.3915, 0.2503, 1 / lp**2, 1.564, 4.840, lp * lp, "paper's rounded")
    consistent_variant()
    print("== rigid limit (Housner)")
    p = math.sqrt(3 * G / (2 * H))
    print(f"  {'p = sqrt(3 g/(2 H)) (1/s)':36s} {p:.9g}")
    print(f"  {'alpha = B/H':36s} {B / H:.9g}")
    print(f"  {'(2H^2 - B^2)/(2(H^2 + B^2))':36s} {(2 * H * H - B * B) / (2 * (H * H + B * B)):.9g}")
    print(f"  {'3/L^2 (nu2 as s_n -> 0)':36s} {3 / L**2:.9g}")
    print(f"  {'L^3/(8 sigma)':36s} {L**3 / (8 * SIG):.9g}")
    print(f"  {'free rocking from B/2: (1/p) acosh 2':36s} {math.acosh(2.0) / p:.9g}")
    print("== ramp of the paper's excitation (A = 5 m/s^2, Tp = 1 s, 0.412 s)")
    for i, c in enumerate(ramp_coefficients(), start=1):
        print(f"  c{i} {c:.9g}")


if __name__ == "__main__":
    main()
