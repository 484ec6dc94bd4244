#!/usr/bin/env python3
"""Intensity measures of the shipped records, computed independently of flexrock.

Written from the definitions only (book: Reference, "Records"), without reading flexrock's
code: the record is its samples a_k at t_k = k dt, linear between them.

- PGA = max |a_k|.
- v and d from rest, integrated in closed form on each interval (v quadratic, d cubic); PGV and
  PGD the largest |v|, |d| over the whole curve: at the samples, where a = 0 inside an interval
  (for v) and where v = 0 inside one (for d).
- Arias intensity pi / (2 g) * sum of h (a0^2 + a0 a1 + a1^2) / 3, g = 9.80665 m/s^2; CAV the
  sum of the exact integrals of |a| (split where a changes sign).
- Sa(T, zeta) = omega^2 max |u|, u'' + 2 zeta omega u' + omega^2 u = -a(t) from rest, solved in
  closed form on each interval (a damped sine plus a straight line: the Nigam-Jennings
  solution, not flexrock's series and recurrence). Its largest |u| between samples: u' is
  evaluated at 32 points of each interval, every sign change is bisected to the last bit, and
  u there is compared with the samples'. sa_at_samples is the largest |u| over the samples.

Writes tests/data/records/intensity_reference.csv, which tests/records.rs compares with
`flexrock record intensity` and `flexrock record spectrum` (1e-9 relative for PGA, PGV, PGD,
Arias, CAV and Sa over the samples; 1e-6 for Sa). Plain Python floats, no package needed:

    python3 validation/intensity/reference.py      # from the repository root, ~1 min
"""

import math
import re
from pathlib import Path

G = 9.80665
ROOT = Path(__file__).resolve().parents[2]
RECORDS = ["elCentro.AT2", "ANLA196.AT2", "A-ELC180.AT2", "PBFEAS.AT2", "HEN-E.AT2"]
PERIODS = [0.05, 0.2, 1.0, 1.55, 3.0]
DAMPINGS = [0.05, 0.02]
SUBDIVISIONS = 32


def read_at2(path):
    """Values (in g, as every shipped file's line 3 says) and dt of a PEER AT2 file."""
    lines = path.read_text().splitlines()
    assert re.search(r"UNITS OF G|\(g\)", lines[2], re.I), lines[2]
    npts = int(re.search(r"NPTS\s*=\s*(\d+)", lines[3], re.I).group(1))
    dt = float(re.search(r"DT\s*=\s*([0-9.Ee+-]+)", lines[3], re.I).group(1))
    values = [float(w) for line in lines[4:] for w in line.split()]
    assert len(values) == npts
    return values, dt


def ground(a, h):
    """PGA, PGV, PGD, Arias intensity and CAV of samples a (m/s^2) at interval h."""
    pga = max(abs(x) for x in a)
    v = d = 0.0
    pgv = pgd = arias = cav = 0.0
    for a0, a1 in zip(a, a[1:]):
        s = (a1 - a0) / h
        vel = lambda t: v + a0 * t + 0.5 * s * t * t
        disp = lambda t: d + v * t + 0.5 * a0 * t * t + s * t ** 3 / 6.0
        cands_v = [h]
        if a0 * a1 < 0:
            cands_v.append(-a0 / s)
        cands_d = [h]
        # v(t) = 0: 0.5 s t^2 + a0 t + v = 0
        if s == 0:
            if a0 != 0:
                cands_d.append(-v / a0)
        else:
            disc = a0 * a0 - 2.0 * s * v
            if disc >= 0:
                r = math.sqrt(disc)
                cands_d += [(-a0 + r) / s, (-a0 - r) / s]
        pgv = max([pgv] + [abs(vel(t)) for t in cands_v if 0 < t <= h])
        pgd = max([pgd] + [abs(disp(t)) for t in cands_d if 0 < t <= h])
        v, d = vel(h), disp(h)
        arias += h * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0
        if a0 * a1 >= 0:
            cav += 0.5 * h * (abs(a0) + abs(a1))
        else:
            cav += 0.5 * h * (a0 * a0 + a1 * a1) / (abs(a0) + abs(a1))
    return pga, pgv, pgd, math.pi / (2.0 * G) * arias, cav


def spectral(a, h, period, zeta):
    """Sa (between samples included) and Sa over the samples, m/s^2."""
    w = 2.0 * math.pi / period
    wd = w * math.sqrt(1.0 - zeta * zeta)
    u = du = 0.0
    peak = at_samples = 0.0
    for a0, a1 in zip(a, a[1:]):
        f0, f1 = -a0, -(a1 - a0) / h
        c1 = f1 / (w * w)
        c0 = (f0 - 2.0 * zeta * w * c1) / (w * w)
        x0, x1 = u - c0, du - c1
        b = (x1 + zeta * w * x0) / wd

        def state(t):
            e = math.exp(-zeta * w * t)
            c, s = math.cos(wd * t), math.sin(wd * t)
            hom = e * (x0 * c + b * s)
            return c0 + c1 * t + hom, c1 + e * (wd * (b * c - x0 * s)) - zeta * w * hom

        grid = [h * j / SUBDIVISIONS for j in range(SUBDIVISIONS + 1)]
        values = [state(t) for t in grid]
        for (ta, (ua, va)), (tb, (ub, vb)) in zip(zip(grid, values), zip(grid[1:], values[1:])):
            peak = max(peak, abs(ub))
            if va * vb < 0:
                lo, hi = ta, tb
                for _ in range(200):
                    mid = 0.5 * (lo + hi)
                    if mid in (lo, hi):
                        break
                    if (state(mid)[1] > 0) == (va > 0):
                        lo = mid
                    else:
                        hi = mid
                peak = max(peak, abs(state(lo)[0]), abs(state(hi)[0]))
        u, du = values[-1]
        at_samples = max(at_samples, abs(u))
    return w * w * peak, w * w * at_samples


def main():
    rows = ["record,period,damping,pga,pgv,pgd,arias,cav,sa,sa_at_samples"]
    for name in RECORDS:
        values, dt = read_at2(ROOT / "validation" / "records" / name)
        a = [x * G for x in values]
        pga, pgv, pgd, arias, cav = ground(a, dt)
        for zeta in DAMPINGS:
            for period in PERIODS:
                sa, sa_samples = spectral(a, dt, period, zeta)
                rows.append(
                    f"{name},{period!r},{zeta!r},{pga!r},{pgv!r},{pgd!r},{arias!r},{cav!r},"
                    f"{sa!r},{sa_samples!r}"
                )
                print(rows[-1], flush=True)
    out = ROOT / "tests" / "data" / "records" / "intensity_reference.csv"
    out.write_text("\n".join(rows) + "\n")
    print(f"wrote {out.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
