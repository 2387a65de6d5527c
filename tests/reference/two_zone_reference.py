#!/usr/bin/env python3
"""Independent numerical reference for the two-zone (solid + meniscus) Dugdale contact.

Usage:
    python3 tests/reference/two_zone_reference.py > tests/data/two_zone_reference.csv
    python3 tests/reference/two_zone_reference.py --validate [--points FILE]

Needs Python 3.8+ and mpmath (tested with mpmath 1.3.0); nothing else.

Problem (axisymmetric, frictionless, elastic half-space with reduced modulus E*, K = 4E*/3).
A sphere of radius R (profile r^2/(2R)) is pressed on a flat to a contact of radius a: gap 0
inside, pressure p(r) (compressive positive) bounded at r = a. Outside the contact a tensile
traction s1 acts where the gap g(r) < h1 and s2 where g(r) < h2; the gap grows with r, so each
zone is the annulus a < r < c_i with g(c_i) = h_i. Given (K, R, s1, h1, s2, h2, a) the script
finds the load P (compressive positive), the approach delta and c1, c2.

Method A (the solver). Every axisymmetric pressure on r < c is a superposition of flat-punch
distributions (Sneddon): p(r) = int_r^c F(s) / sqrt(s^2 - r^2) ds. A punch of radius s with
density F(s) ds carries the load 2 pi s F(s) ds and displaces the surface by pi F(s) ds / E*
inside s and by (2/E*) F(s) ds arcsin(s/r) outside. Hence

    delta = (pi/E*) int_0^c F ds,     P = 2 pi int_0^c s F ds,
    g(r)  = r^2/(2R) - (2/E*) int_0^r F(s) arccos(s/r) ds.

The contact condition g = 0 on r < a fixes F = 2 E* s / (pi R) there (an Abel equation; a punch
of radius a could be added, and the bounded pressure at r = a is what excludes it). Outside, the
Abel inverse of the known traction gives F = -(2 s_i / pi) s / sqrt(c_i^2 - s^2) on a < s < c_i
for each zone. The integrals are evaluated by tanh-sinh quadrature (mpmath.quad) split at every
kink (a, c1, c2, r), the zone densities with s = c_i sin(theta) so the integrands are smooth; no
closed form of the resulting integrals is used. c1, c2 solve g(c1) = h1, g(c2) = h2 by nested
bracketed root searches (for each c2 the c1 that closes zone 1, then c2), which need no
derivative; with h1 = h2 both zones end at one radius (the gap is monotonic, which every row
checks) and a single search finds it. Run at 34 and 50 digits.

Method B (the check). The surface displacement is recomputed from the pressure itself with the
Boussinesq ring-load kernel, u(r) = (4/(pi E*)) int_0^c p(s) s/(r+s) K(k) ds,
k = 2 sqrt(r s)/(r+s) (complete elliptic integral K by the AGM of 1 and k' = |r-s|/(r+s)),
with the pressure inside the contact from the Abel sum above. It checks the contact condition
(g = 0 at points of 0 <= r <= a) and solves the two gap conditions for c1, c2 again by Newton
on this kernel; P is the quadrature of 2 pi r p(r) and delta = u(0). B shares with A only the
form of the pressure, which its contact residual verifies.

est_rel_error (per row) is the largest of |A34 - A50| and |A50 - B| over load, approach, c1 and
c2, each divided by |value| (for the load by max(|P|, pi (s1 h1 + s2 h2) R), the adhesive load
scale, so that a load near zero is judged by an absolute error), together with B's contact
residual divided by the approach, floored at 1e-16.

--validate compares method A with the single-zone Maugis-Dugdale equations (1)-(3) of
docs/PHYSICS.md (s2 = 0 and s1 = 0), with MD at the summed stress (h1 = h2) and with the
swapped zones; --points FILE also compares with a reference table of (lambda, Pbar) states
(columns lambda, Pbar, A, Dbar, m as in the 50-digit MD tables).
"""

import sys
import time

import mpmath as mp

# ---------------------------------------------------------------- method A


class Problem:
    """Parameters and the solved state; all arithmetic in mpmath at the current precision."""

    def __init__(self, K, R, s1, h1, s2, h2, a):
        self.K, self.R = mp.mpf(K), mp.mpf(R)
        self.E = 3 * self.K / 4
        self.s = [mp.mpf(s1), mp.mpf(s2)]
        self.h = [mp.mpf(h1), mp.mpf(h2)]
        self.a = mp.mpf(a)


def breaks(lo, hi, points):
    """[lo, ..., hi] with the points strictly inside, sorted."""
    inner = sorted(set(p for p in points if lo < p < hi))
    return [lo] + inner + [hi]


def zone_arccos_integral(pb, c, sigma, r):
    """int_a^min(r,c) F_zone(s) arccos(s/r) ds with s = c sin(theta)."""
    a = pb.a
    top = min(r, c)
    if top <= a or sigma == 0:
        return mp.mpf(0)
    t0 = mp.asin(a / c)
    t1 = mp.pi / 2 if top == c else mp.asin(top / c)
    f = lambda t: mp.sin(t) * mp.acos(min(mp.mpf(1), c * mp.sin(t) / r))
    return -(2 * sigma / mp.pi) * c * mp.quad(f, [t0, t1])


def gap_A(pb, r, c):
    """g(r) for r >= a with zone radii c = [c1, c2]."""
    r = mp.mpf(r)
    a = pb.a
    hertz_coef = 2 * pb.E / (mp.pi * pb.R)
    # Hertz density up to a (r >= a): int_0^a s arccos(s/r) ds.
    hz = hertz_coef * mp.quad(lambda s: s * mp.acos(s / r), [0, a])
    zones = sum(zone_arccos_integral(pb, c[i], pb.s[i], r) for i in range(2))
    return r * r / (2 * pb.R) - (2 / pb.E) * (hz + zones)


def load_approach_A(pb, c):
    a = pb.a
    hc = 2 * pb.E / (mp.pi * pb.R)
    int_f = hc * mp.quad(lambda s: s, [0, a])
    int_sf = hc * mp.quad(lambda s: s * s, [0, a])
    for i in range(2):
        ci, si = c[i], pb.s[i]
        if si == 0:
            continue
        t0 = mp.asin(a / ci)
        k = -(2 * si / mp.pi) * ci
        int_f += k * mp.quad(mp.sin, [t0, mp.pi / 2])
        int_sf += k * ci * mp.quad(lambda t: mp.sin(t) ** 2, [t0, mp.pi / 2])
    return 2 * mp.pi * int_sf, (mp.pi / pb.E) * int_f


def bracket_root(f, lo, flo, step, rtol, maxit=400):
    """Root of f on (lo, inf) with f(lo) = flo < 0: expand, then Illinois with a bisection guard."""
    hi = lo + step
    fhi = f(hi)
    while fhi < 0:
        lo, flo = hi, fhi
        step *= 2
        hi = lo + step
        fhi = f(hi)
    side = 0
    for _ in range(maxit):
        if hi - lo <= rtol * abs(hi):
            break
        x = (lo * fhi - hi * flo) / (fhi - flo)
        if not (lo < x < hi) or (hi - lo) < 0:
            x = (lo + hi) / 2
        fx = f(x)
        if fx == 0:
            return x
        if fx < 0:
            lo, flo = x, fx
            if side == -1:
                fhi /= 2
            side = -1
        else:
            hi, fhi = x, fx
            if side == 1:
                flo /= 2
            side = 1
    else:
        raise RuntimeError("root search did not converge")
    return (lo * fhi - hi * flo) / (fhi - flo)


def solve_A(pb, dps):
    """c1, c2, P, delta by method A at dps digits."""
    with mp.workdps(dps):
        # the quadratures are good to about 10^-(0.75 dps) near the root; stop above that noise
        rtol = mp.mpf(10) ** (-int(dps * 0.65))
        a = pb.a
        step0 = lambda h: a / 4 + mp.sqrt(2 * pb.R * h)

        last = []

        def c1_of(c2):
            f = lambda c1: gap_A(pb, c1, [c1, c2]) - pb.h[0]
            lo, flo, step = a, -pb.h[0], step0(pb.h[0])
            if last:
                # warm start: c1 moves little between outer iterations
                x = last[-1]
                lo = max(a, x * (1 - mp.mpf("1e-4")))
                flo = f(lo) if lo > a else -pb.h[0]
                if flo >= 0:
                    lo, flo = a, -pb.h[0]
                else:
                    step = x * mp.mpf("2e-4")
            c1 = bracket_root(f, lo, flo, step, rtol)
            last.append(c1)
            return c1

        def outer(c2):
            return gap_A(pb, c2, [c1_of(c2), c2]) - pb.h[1]

        if pb.h[0] == pb.h[1]:
            # equal ranges: the gap grows with r, so both zones end at the same radius
            c2 = bracket_root(
                lambda c: gap_A(pb, c, [c, c]) - pb.h[0], a, -pb.h[0], step0(pb.h[0]), rtol
            )
            c1 = c2
        else:
            c2 = bracket_root(outer, a, -pb.h[1], step0(pb.h[1]), rtol)
            c1 = c1_of(c2)
        c = [c1, c2]
        P, d = load_approach_A(pb, c)
        return {"c1": c1, "c2": c2, "load": P, "approach": d}


def monotone_gap_A(pb, sol, n=40):
    """True when the gap grows strictly on a < r < 1.2 max(c) (sampled), i.e. zones are annuli."""
    c = [sol["c1"], sol["c2"]]
    top = max(c) * mp.mpf("1.2")
    prev = mp.mpf(0)
    for j in range(1, n + 1):
        r = pb.a + (top - pb.a) * j / n
        g = gap_A(pb, r, c)
        if not g > prev:
            return False
        prev = g
    return True


# ---------------------------------------------------------------- method B


def pressure_B(pb, c, s):
    """Pressure (compressive positive) at s from the Abel sum of punches (elementary integrals)."""
    a = pb.a
    if s < a:
        p = (2 * pb.E / (mp.pi * pb.R)) * mp.sqrt(a * a - s * s)
        for i in range(2):
            if pb.s[i] != 0:
                # int_a^c t / (sqrt(c^2-t^2) sqrt(t^2-s^2)) dt = arccos(sqrt((a^2-s^2)/(c^2-s^2)))
                p -= (2 * pb.s[i] / mp.pi) * mp.acos(mp.sqrt((a * a - s * s) / (c[i] ** 2 - s * s)))
        return p
    return -sum(pb.s[i] for i in range(2) if s < c[i])


def ellipk_k(kp):
    """K(k) from the complementary modulus k' = sqrt(1-k^2), exact near k = 1."""
    return mp.pi / (2 * mp.agm(1, kp))


def displacement_B(pb, c, r):
    """u(r) from the ring-load kernel, split at every kink of the pressure and at r."""
    r = mp.mpf(r)
    top = max(c)
    pts = breaks(mp.mpf(0), top, [pb.a, c[0], c[1], r])
    if r == 0:
        return (2 / pb.E) * mp.quad(lambda s: pressure_B(pb, c, s), pts)

    def f(s):
        if s == 0:
            return mp.mpf(0)
        kp = abs(r - s) / (r + s)
        if kp == 0:
            return mp.mpf(0)  # integrable log singularity at an interval end
        return pressure_B(pb, c, s) * s / (r + s) * ellipk_k(kp)

    return (4 / (mp.pi * pb.E)) * mp.quad(f, pts)


def check_B(pb, solA, dps):
    """Contact residual, and c1, c2, P, delta re-solved with the Boussinesq kernel."""
    with mp.workdps(dps):
        # start away from A's radii so that B's own Newton iteration finds them
        shift = mp.mpf("1e-3") if pb.h[0] == pb.h[1] else -mp.mpf("1e-3")
        c = [mp.mpf(solA["c1"]) * (1 + mp.mpf("1e-3")), mp.mpf(solA["c2"]) * (1 + shift)]
        R = pb.R

        def gaps(c):
            d = displacement_B(pb, c, 0)
            return [
                c[i] ** 2 / (2 * R) - d + displacement_B(pb, c, c[i]) - pb.h[i] for i in range(2)
            ]

        tol = mp.mpf(10) ** (-(dps - 8))
        equal = pb.h[0] == pb.h[1]
        for _ in range(12):
            res = gaps(c)
            if equal:
                # one radius: secant-free Newton on the common c (the 2x2 Jacobian is
                # log-singular at c1 = c2)
                eps = c[0] * mp.mpf(10) ** (-(dps // 2))
                r2 = gaps([c[0] + eps, c[1] + eps])
                dc = -res[0] * eps / (r2[0] - res[0])
                c = [c[0] + dc, c[1] + dc]
                step = abs(dc) / c[0]
            else:
                eps = [ci * mp.mpf(10) ** (-(dps // 2)) for ci in c]
                g1 = gaps([c[0] + eps[0], c[1]])
                g2 = gaps([c[0], c[1] + eps[1]])
                J = mp.matrix(
                    [
                        [(g1[0] - res[0]) / eps[0], (g2[0] - res[0]) / eps[1]],
                        [(g1[1] - res[1]) / eps[0], (g2[1] - res[1]) / eps[1]],
                    ]
                )
                dc = mp.lu_solve(J, mp.matrix([-res[0], -res[1]]))
                c = [c[0] + dc[0], c[1] + dc[1]]
                step = max(abs(dc[0]) / c[0], abs(dc[1]) / c[1])
            if step < tol:
                break
        else:
            raise RuntimeError("method B: Newton did not converge")
        d = displacement_B(pb, c, 0)
        pts = breaks(mp.mpf(0), max(c), [pb.a, c[0], c[1]])
        P = 2 * mp.pi * mp.quad(lambda s: s * pressure_B(pb, c, s), pts)
        # contact condition: g = r^2/(2R) - delta + u(r) = 0 on 0 <= r <= a
        contact = max(
            abs(pb.a**2 * x * x / (2 * R) - d + displacement_B(pb, c, pb.a * x))
            for x in [mp.mpf(v) for v in ("0.3", "0.6", "0.9", "1")]
        )
        return {"c1": c[0], "c2": c[1], "load": P, "approach": d, "contact": contact}


# ---------------------------------------------------------------- rows and output


def solid_params(lam, K=1, R=1):
    """s1, h1 of a solid with Maugis lambda and w = 1/pi (K = R = 1: the MD units are 1)."""
    w = mp.mpf(1) / mp.pi
    s = mp.mpf(lam) / 2 * mp.cbrt(mp.pi * w * mp.mpf(K) ** 2 / R)
    return s, w / s


# (lambda of the solid alone, s2/s1, h2/h1, a) with K = R = 1 and w1 = 1/pi.
STATES = [
    # single zone (s2 = 0): validation rows, c2 is still where the gap reaches h2
    (0.1, 0, 3, 0.5),
    (1, 0, 0.2, 1.0),
    (5, 0, 10, 1.5),
    # no solid adhesion (s1 = 0): the meniscus alone, MD with lambda = 1 for zone 2
    ("meniscus only", 1, 3, 0.6),
    # two zones
    (0.1, 0.1, 10, 0.3),
    (0.1, 1, 3, 1.0),
    (0.1, 5, 0.2, 0.2),
    (0.1, 1, 1, 2.0),
    (0.3, 5, 3, 0.5),
    (0.3, 0.1, 0.2, 1.5),
    (0.5, 1, 10, 0.8),
    (0.5, 5, 1, 1.2),
    (1, 0.1, 3, 0.4),
    (1, 1, 0.2, 0.9),
    (1, 5, 10, 2.5),
    (1, 1, 1, 0.3),
    (2, 5, 0.2, 1.0),
    (2, 0.1, 1, 1.1),
    (2, 1, 3, 3.0),
    (3, 1, 10, 0.6),
    (3, 0.1, 0.2, 2.0),
    (5, 1, 0.2, 1.2),
    (5, 5, 3, 0.7),
    (5, 0.1, 10, 4.0),
    (5, 1, 1, 0.5),
]


def fmt(x):
    return mp.nstr(x, 17, min_fixed=0, max_fixed=0, strip_zeros=False)


def fmt_in(x):
    return repr(float(x))


def row_problem(lam, q, r, a):
    with mp.workdps(60):
        if lam == "meniscus only":
            # zone 2 is an MD zone of lambda q (w2 = 1/pi); zone 1 has no stress, range h2 * r
            s2, h2 = solid_params(q)
            return [float(v) for v in (1, 1, 0, h2 * r, s2, h2, a)]
        s1, h1 = solid_params(lam)
        # inputs are rounded to doubles once; every method then uses these exact doubles
        vals = [float(v) for v in (1, 1, s1, h1, s1 * q, h1 * r, a)]
    return vals


def compute_row(vals):
    pb_lo = Problem(*vals)
    a34 = solve_A(pb_lo, 34)
    a50 = solve_A(Problem(*vals), 50)
    with mp.workdps(50):
        mono = monotone_gap_A(Problem(*vals), a50)
    b = check_B(Problem(*vals), a50, 26)
    with mp.workdps(50):
        pb = Problem(*vals)
        scale = {
            "load": max(abs(a50["load"]), mp.pi * (pb.s[0] * pb.h[0] + pb.s[1] * pb.h[1]) * pb.R),
            "approach": abs(a50["approach"]),
            "c1": a50["c1"],
            "c2": a50["c2"],
        }
        err = mp.mpf("1e-16")
        detail = {}
        for key in scale:
            ea = abs(a34[key] - a50[key]) / scale[key]
            eb = abs(b[key] - a50[key]) / scale[key]
            detail[key] = (ea, eb)
            err = max(err, ea, eb)
        contact = b["contact"] / abs(a50["approach"])
        err = max(err, contact)
    return a50, err, detail, contact, mono


HEADER = """\
# Two-zone Dugdale contact (solid + meniscus): independent numerical reference.
# Generated by tests/reference/two_zone_reference.py (mpmath only); do not edit by hand.
# Problem: axisymmetric frictionless contact of a sphere of radius R (profile r^2/(2R)) on a
#   flat, elastic half-space with reduced modulus E*, K = 4 E*/3. Contact radius a: gap 0 inside,
#   pressure bounded (no singularity) at r = a. Outside: tensile traction s1 where the gap < h1
#   and s2 where the gap < h2; zone i is the annulus a < r < c_i with gap(c_i) = h_i.
# Units: any consistent set (here K = 1, R = 1; the solid has w1 = s1*h1 = 1/pi, so its Maugis
#   lambda = 2 s1 (R/(pi w1 K^2))^(1/3) = 2 s1 and radii, loads, approaches are also in the
#   Johnson-Greenwood units of the solid alone, to the rounding of the inputs: A = a,
#   Pbar = load, Dbar = approach). The row with s1 = 0 has no solid adhesion: zone 2 alone is an
#   MD zone with w2 = s2*h2 = 1/pi, and its c1 is where the gap reaches h1.
# Inputs k,r,s1,h1,s2,h2,a are exact IEEE doubles (parse them as doubles); outputs are rounded
#   to 17 significant digits.
# Signs: load compressive positive (tensile negative); approach positive when the bodies are
#   pressed together (Hertz: approach = a^2/R); s1, s2 > 0 are tensile stresses; c1, c2 >= a.
#   A row with s2 = 0 is the single-zone Maugis-Dugdale contact; its c2 is still the radius where
#   the gap reaches h2. c1 < c2 when h1 < h2.
# Method A: flat-punch (Abel) superposition, p(r) = int_r^c F(s)/sqrt(s^2-r^2) ds, with F fixed
#   by the contact condition inside a and by the known tractions outside; load, approach and the
#   gap g(r) = r^2/(2R) - (2/E*) int_0^r F(s) arccos(s/r) ds by tanh-sinh quadrature; c1, c2 by
#   nested bracketed root searches; at 34 and 50 digits. Every row checks that the gap grows
#   monotonically outside the contact (so each zone is an annulus).
# Method B: the same state re-solved with the Boussinesq ring-load kernel (complete elliptic
#   integral K), load by quadrature of the pressure, contact residual checked inside a.
# est_rel_error: max of |A34-A50| and |A50-B| over load, approach, c1, c2, each relative to the
#   value (the load relative to max(|load|, pi (s1 h1 + s2 h2) R)), and B's contact residual
#   relative to the approach; floored at 1e-16. Values are those of A at 50 digits.
# Validation (--validate): s2 = 0 and s1 = 0 against Maugis-Dugdale equations (1)-(3), h1 = h2
#   against MD with s1 + s2, and the swapped zones; max relative difference {validation}."""


def md_state(lam, A):
    """Single-zone MD (docs/PHYSICS.md section 2) at given lambda, A: m, Pbar, Dbar."""
    lam, A = mp.mpf(lam), mp.mpf(A)

    def eq1(mu):
        m = mp.sqrt(1 + mu * mu)
        asec = mp.atan(mu)
        return (lam * A**2 / 2) * ((m * m - 2) * asec + mu) + (4 * lam**2 * A / 3) * (
            mu * asec - m + 1
        ) - 1

    lo, hi = mp.mpf("1e-30"), mp.mpf(1)
    while eq1(hi) < 0:
        hi *= 2
    mu = mp.findroot(eq1, (lo, hi), solver="anderson")
    m = mp.sqrt(1 + mu * mu)
    P = A**3 - lam * A**2 * (mu + m * m * mp.atan(mu))
    D = A**2 - mp.mpf(4) / 3 * lam * A * mu
    return m, P, D


def validate(points_file=None):
    worst = mp.mpf(0)
    out = []
    with mp.workdps(40):
        # 1. single zone against MD, both as zone 1 and as zone 2
        for lam in ["0.1", "0.3", "1", "2", "5"]:
            for A in ["0.2", "0.7", "1.5", "3"]:
                s, h = solid_params(lam)
                m, P, D = md_state(lam, A)
                for which in (0, 1):
                    args = [1, 1, s, h, 0, 2 * h, A] if which == 0 else [1, 1, 0, 3 * h, s, h, A]
                    sol = solve_A(Problem(*args), 30)
                    ci = sol["c1"] if which == 0 else sol["c2"]
                    e = max(
                        abs(ci / mp.mpf(A) - m) / m,
                        abs(sol["load"] - P) / max(abs(P), 1),
                        abs(sol["approach"] - D) / max(abs(D), 1),
                    )
                    worst = max(worst, e)
                    out.append(f"single zone {which + 1} lambda={lam} A={A}: {mp.nstr(e, 3)}")
        # 2. equal ranges: MD with the summed stress; 3. swapped zones
        for lam, q, A in [("0.1", "1", "0.5"), ("1", "5", "1.2"), ("5", "0.1", "0.8")]:
            s, h = solid_params(lam)
            q = mp.mpf(q)
            stot = s * (1 + q)
            w = stot * h
            lam_tot = 2 * stot * mp.cbrt(1 / (mp.pi * w))
            unit_r = mp.cbrt(mp.pi * w)  # (pi w R^2/K)^(1/3)
            unit_p = mp.pi * w
            unit_d = mp.cbrt(mp.pi**2 * w**2)
            A_tot = mp.mpf(A) / unit_r
            m, P, D = md_state(lam_tot, A_tot)
            sol = solve_A(Problem(1, 1, s, h, s * q, h, A), 30)
            e = max(
                abs(sol["c1"] / mp.mpf(A) - m) / m,
                abs(sol["c2"] / mp.mpf(A) - m) / m,
                abs(sol["load"] / unit_p - P) / max(abs(P), 1),
                abs(sol["approach"] / unit_d - D) / max(abs(D), 1),
            )
            worst = max(worst, e)
            out.append(f"equal ranges lambda={lam} s2/s1={q} a={A}: {mp.nstr(e, 3)}")
            for r in ("0.2", "3"):
                x = solve_A(Problem(1, 1, s, h, s * q, h * mp.mpf(r), A), 30)
                y = solve_A(Problem(1, 1, s * q, h * mp.mpf(r), s, h, A), 30)
                e = max(
                    abs(x["c1"] - y["c2"]) / x["c1"],
                    abs(x["c2"] - y["c1"]) / x["c2"],
                    abs(x["load"] - y["load"]) / max(abs(x["load"]), 1),
                    abs(x["approach"] - y["approach"]) / max(abs(x["approach"]), 1),
                )
                worst = max(worst, e)
                out.append(f"swapped lambda={lam} s2/s1={q} h2/h1={r} a={A}: {mp.nstr(e, 3)}")
        if points_file:
            import csv

            pw = mp.mpf(0)
            n = 0
            with open(points_file) as fh:
                rows = list(csv.DictReader(fh))
            for row in rows[:: max(1, len(rows) // 12)]:
                lam = mp.mpf(float(row["lambda"]))
                A = mp.mpf(row["A"])
                if A < mp.mpf("0.02") or A > 20:
                    continue
                s, h = solid_params(lam)
                sol = solve_A(Problem(1, 1, s, h, 0, h, A), 30)
                e = max(
                    abs(sol["c1"] / A - mp.mpf(row["m"])) / mp.mpf(row["m"]),
                    abs(sol["load"] - mp.mpf(row["Pbar"])) / max(abs(mp.mpf(row["Pbar"])), 1),
                    abs(sol["approach"] - mp.mpf(row["Dbar"])) / max(abs(mp.mpf(row["Dbar"])), 1),
                )
                pw = max(pw, e)
                n += 1
                out.append(f"table lambda={mp.nstr(lam, 6)} A={mp.nstr(A, 6)}: {mp.nstr(e, 3)}")
            out.append(f"max over {n} table states: {mp.nstr(pw, 3)}")
            worst = max(worst, pw)
    return worst, out


def main(argv):
    if "--validate" in argv:
        pf = argv[argv.index("--points") + 1] if "--points" in argv else None
        t0 = time.time()
        worst, lines = validate(pf)
        print("\n".join(lines))
        print(f"max relative difference: {mp.nstr(worst, 3)} ({time.time() - t0:.1f} s)")
        return 0
    t0 = time.time()
    with mp.workdps(40):
        worst, _ = validate()
    rows = []
    for lam, q, r, a in STATES:
        vals = row_problem(lam, q, r, a)
        sol, err, detail, contact, mono = compute_row(vals)
        if not mono:  # zones would not be annuli: the problem as posed does not apply
            raise SystemExit(f"state {vals}: the gap is not monotonic outside the contact")
        rows.append((vals, sol, err))
        print(
            f"lambda={lam} s2/s1={q} h2/h1={r} a={a}: est {mp.nstr(err, 3)} "
            f"(A34-A50, A-B: "
            + ", ".join(f"{k} {mp.nstr(v[0], 2)}/{mp.nstr(v[1], 2)}" for k, v in detail.items())
            + f"; contact {mp.nstr(contact, 2)}) {time.time() - t0:.0f} s",
            file=sys.stderr,
        )
    print(HEADER.format(validation=mp.nstr(worst, 2)))
    print("k,r,s1,h1,s2,h2,a,load,approach,c1,c2,est_rel_error")
    for vals, sol, err in rows:
        with mp.workdps(50):
            line = [fmt_in(v) for v in vals] + [
                fmt(sol["load"]),
                fmt(sol["approach"]),
                fmt(sol["c1"]),
                fmt(sol["c2"]),
                mp.nstr(err, 2, min_fixed=0, max_fixed=0),
            ]
        print(",".join(line))
    print(f"total {time.time() - t0:.0f} s", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
