#!/usr/bin/env python3
"""Arbitrary-precision Maugis-Dugdale oracle for the extended lambda domain.

Independent of the Rust solver: equations (1)-(3) of docs/PHYSICS.md section 2, parametrised by
mu = sqrt(m^2 - 1), evaluated in mpmath with 120 working digits (the slope of the load at the
pull-off is a difference of terms larger by lambda^-3, at most 1e60 over the range here, so
more than 50 digits survive everywhere), roots by bisection to the last working digit.

For every lambda it writes the load-controlled pull-off, the displacement-controlled jump-out
(its interior minimum above lambda_D, the A -> 0 end at or below it) and states on the
load-stable branch at given loads (near the pull-off and at given contact radii), each with A,
Pbar, Dbar and m - 1, rounded to 17 significant digits. lambda and the states' Pbar are written
as the IEEE doubles the Rust test parses (the rows are exact for those doubles).

Usage: python3 tests/reference/md_oracle.py [LOG10_LO LOG10_HI STEPS_PER_DECADE] > tests/data/md_extended.csv
"""

import sys

from mpmath import mp, mpf, atan, sqrt, log, exp, pi, nstr

mp.dps = 120

LAMBDA_D = mpf("0.937947457210712")


def curve(lam, mu):
    """Curve point at mu: (A, Pbar, Dbar, m - 1, dPbar/dmu, dDbar/dmu)."""
    at = atan(mu)
    mu2 = mu * mu
    m = sqrt(1 + mu2)
    m1 = mu2 / (1 + m)
    f1 = (mu2 - 1) * at + mu
    f2 = mu * at - m1
    alpha = lam / 2 * f1
    beta = mpf(4) / 3 * lam * lam * f2
    a = 2 / (beta + sqrt(beta * beta + 4 * alpha))
    g = mu + m * m * at
    load = a**3 - lam * a * a * g
    approach = a * a - mpf(4) / 3 * lam * a * mu
    # Slopes along the curve (implicit differentiation of equation (1)).
    df1 = 2 * mu * at + 2 * mu2 / (1 + mu2)
    df2 = at - mu * mu2 / ((1 + m) * (1 + mu2))
    dalpha = lam / 2 * df1
    dbeta = mpf(4) / 3 * lam * lam * df2
    da = -(dalpha * a * a + dbeta * a) / (2 * alpha * a + beta)
    dg = 2 + 2 * mu * at
    dload = da * (3 * a * a - 2 * lam * a * g) - lam * a * a * dg
    dapproach = da * (2 * a - mpf(4) / 3 * lam * mu) - mpf(4) / 3 * lam * a
    return a, load, approach, m1, dload, dapproach


def bisect(f, lo, hi):
    """Root of f on [lo, hi] (f(lo) < 0 < f(hi)), to the working precision."""
    flo = f(lo)
    fhi = f(hi)
    assert flo < 0 < fhi, (flo, fhi)
    for _ in range(mp.prec + 20):
        mid = (lo + hi) / 2
        if mid == lo or mid == hi:
            break
        if f(mid) < 0:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def minimum(lam, which, x_est):
    """x = ln(mu) of the minimum of Pbar (which=4) or Dbar (which=5) near x_est."""
    slope = lambda x: curve(lam, exp(x))[which]
    lo, hi = x_est - 3, x_est + 3
    while slope(lo) >= 0:
        lo -= 3
    while slope(hi) <= 0:
        hi += 3
    return bisect(slope, lo, hi)


def mu_at_radius(lam, a):
    """x = ln(mu) at which the contact radius is a (A falls strictly with mu)."""
    return bisect(lambda x: a - curve(lam, exp(x))[0], mpf(-400), mpf(400))


def zero_radius_end(lam):
    qa = pi * lam / 4
    qb = 2 * (pi - 2) * lam * lam / 3
    c = 2 / (qb + sqrt(qb * qb + 4 * qa))
    return -(pi * lam / 2) * c * c, -(mpf(4) / 3) * lam * c


def s(x):
    return nstr(x, 17, min_fixed=-4, max_fixed=6, strip_zeros=False) if x != 0 else "0"


def rows(lam_f):
    lam = mpf(lam_f)
    x_est = log(mpf("1.1447") / lam + mpf("0.54") * lam ** mpf("-1.5"))
    xc = minimum(lam, 4, x_est)
    a_c, p_c, d_c, m1_c, _, _ = curve(lam, exp(xc))
    out = [(lam_f, "pulloff_load", repr(float(a_c)), s(p_c), s(d_c), s(m1_c))]
    if lam > LAMBDA_D:
        xd = minimum(lam, 5, log(mpf("1.65") / lam) if lam > 1 else xc + 2)
        a_d, p_d, d_d, m1_d, _, _ = curve(lam, exp(xd))
        out.append((lam_f, "pulloff_displacement", repr(float(a_d)), s(p_d), s(d_d), s(m1_d)))
    else:
        p_e, d_e = zero_radius_end(lam)
        out.append((lam_f, "pulloff_displacement", "0", s(p_e), s(d_e), "inf"))
    # States on the load-stable branch, each at a load that is an exact double (what a caller
    # can give): 1e-10, 1e-6 and 1e-3 of max(1, |Pbar_c|) above the pull-off, and the loads of
    # contact radii 1.1 and 2 times the pull-off's and 0.5 .. 9000 (Pbar ~ 7e11).
    loads = [float(p_c + g * max(1, abs(p_c))) for g in (mpf("1e-10"), mpf("1e-6"), mpf("1e-3"))]
    for a_f in (float(a_c) * 1.1, float(a_c) * 2, 0.5, 1.0, 3.0, 30.0, 1e3, 9e3):
        if a_f > float(a_c) * 1.05:
            loads.append(float(curve(lam, exp(mu_at_radius(lam, mpf(a_f))))[1]))
    for p_f in sorted(set(loads)):
        if not mpf(p_f) > p_c:
            continue
        # The stable branch is mu < mu_c, where Pbar falls strictly with mu.
        x = bisect(lambda x: p_f - curve(lam, exp(x))[1], xc - 400, xc)
        a, p, d, m1, _, _ = curve(lam, exp(x))
        assert abs(p - p_f) < mpf(10) ** -80 * max(1, abs(p_f)), (lam_f, p_f, p)
        out.append((lam_f, "state", s(a), repr(p_f), s(d), s(m1)))
    return out


def main():
    lo, hi, per = (-12, 12, 2) if len(sys.argv) < 4 else (int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]))
    print("# Maugis-Dugdale states from tests/reference/md_oracle.py (mpmath, 120 digits, rounded to 17)")
    print("# kind: pulloff_load (minimum of Pbar), pulloff_displacement (minimum of Dbar; A = 0 at the")
    print("# A -> 0 end for lambda <= lambda_D), state (load-stable branch at the load Pbar, an exact double)")
    print("lambda,kind,A,Pbar,Dbar,m_minus_1")
    for k in range(lo * per, hi * per + 1):
        lam_f = float(mpf(10) ** (mpf(k) / per))
        for r in rows(lam_f):
            print(",".join([repr(r[0])] + list(r[1:])))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
