//! The least-squares problem of one model on one curve (Levenberg-Marquardt), its Jacobian,
//! and a fit's parameters, standard errors and pull-off.

use super::*;
use crate::law::follow as path;
use crate::law::{ContactLaw, Law, TwoZones};

/// Physical parameters of a model.
#[derive(Clone, Copy, Debug)]
pub struct Params {
    /// The reduced modulus E* (Pa).
    pub e_star: f64,
    /// The work of adhesion w (J/m^2).
    pub w: f64,
    /// The Maugis parameter (used by Maugis-Dugdale only).
    pub lambda: f64,
    /// The contact point: the base height where the base displacement is zero (m).
    pub zc: f64,
    /// The force offset added to the model's force (N).
    pub f0: f64,
}

/// The unit conversions of one parameter set: force and approach units and kbar (a sphere's
/// Johnson-Greenwood units, a tip's of docs/PHYSICS.md section 12).
#[derive(Clone, Copy, Debug)]
pub struct Units {
    /// The force unit `pi w l^2 / d` (N): the sphere's `pi w R`.
    pub force: f64,
    /// The approach unit d (m): the sphere's `(pi^2 w^2 R / K^2)^(1/3)`, `K = 4 E*/3`.
    pub approach: f64,
    /// The radius unit l (m): the sphere's `(pi w R^2 / K)^(1/3)`.
    pub radius: f64,
    /// The spring constant in these units: `k` times the approach unit over the force unit.
    pub kbar: f64,
}

/// The Johnson-Greenwood units of `p` with the tip radius `radius` (m) and the spring constant
/// `spring` (N/m) ([`Geometry::units`] of the sphere).
pub fn units(p: &Params, radius: f64, spring: f64) -> Units {
    Geometry::Sphere(radius).units(p.e_star, p.w, spring)
}

/// lambda from the Lennard-Jones range z0 (Dugdale stress matched to it).
pub fn lambda_from_z0(e_star: f64, w: f64, radius: f64, z0: f64) -> f64 {
    let k = 4.0 / 3.0 * e_star;
    2.0 * (LJ_STRESS * w / z0) * (radius / (PI * w * k * k)).cbrt()
}

/// The Lennard-Jones range z0 whose matched Dugdale stress gives lambda.
pub fn z0_from_lambda(e_star: f64, w: f64, radius: f64, lambda: f64) -> f64 {
    let k = 4.0 / 3.0 * e_star;
    2.0 * LJ_STRESS * w * (radius / (PI * w * k * k)).cbrt() / lambda
}

/// Model forces (N), contact radii (m), the states and the path they lie on.
pub type Evaluated = (Vec<f64>, Vec<f64>, Vec<PathState>, DrivenPath);

/// The model force (N, without offset) and contact radius (m) at each height, and the state,
/// on the tip `tip` (a radius is a sphere's).
pub fn model_forces(
    model: Model,
    p: &Params,
    tip: impl Into<Geometry>,
    spring: f64,
    height: &[f64],
    dir: &[Direction],
    side: Option<&[Side]>,
) -> Option<Evaluated> {
    model_forces_from(model, p, tip.into(), spring, height, dir, side, None)
}

/// [`model_forces`], each point's search started from its state in `hints` (nearby parameters).
#[allow(clippy::too_many_arguments)]
pub fn model_forces_from(
    model: Model,
    p: &Params,
    tip: Geometry,
    spring: f64,
    height: &[f64],
    dir: &[Direction],
    side: Option<&[Side]>,
    hints: Option<&[PathState]>,
) -> Option<Evaluated> {
    let u = tip.units(p.e_star, p.w, spring);
    if model.has_lambda() && !tip.admits_lambda(p.lambda) {
        return None;
    }
    forces_on(
        tip.law(model, p.lambda, &u),
        &u,
        p.zc,
        height,
        dir,
        side,
        hints,
    )
}

/// [`model_forces_from`] of any law in its units `u`, with the contact point `zc` (m).
pub(super) fn forces_on(
    law: ContactLaw,
    u: &Units,
    zc: f64,
    height: &[f64],
    dir: &[Direction],
    side: Option<&[Side]>,
    hints: Option<&[PathState]>,
) -> Option<Evaluated> {
    if !(u.kbar > 0.0 && u.kbar.is_finite() && u.approach > 0.0) {
        return None;
    }
    let deltas: Vec<f64> = height.iter().map(|h| (zc - h) / u.approach).collect();
    let top = deltas.iter().cloned().fold(1.0, f64::max);
    let path = DrivenPath::of(law, u.kbar, top);
    let states: Vec<PathState> = deltas
        .iter()
        .zip(dir)
        .enumerate()
        .map(|(i, (&d, &dir))| {
            path.at_side_from(
                d,
                dir,
                side.map_or(Side::Any, |s| s[i]),
                hints.map(|h| &h[i]),
            )
        })
        .collect();
    let f = states.iter().map(|s| s.load * u.force).collect();
    let a = states.iter().map(|s| s.a * u.radius).collect();
    Some((f, a, states, path))
}

/// The law of `model` at the parameters `p` and its units, on the tip `tip` (a radius is a
/// sphere's) with the spring constant: the model at its lambda in the units of its w, or (the
/// two-zone law with a `meniscus`, its stress in Pa and range in m, on a sphere) the solid's
/// zone with the meniscus in the units of their total w.
pub fn law_units(
    model: Model,
    p: &Params,
    tip: impl Into<Geometry>,
    spring: f64,
    meniscus: Option<(f64, f64)>,
) -> (ContactLaw, Units) {
    let tip = tip.into();
    match (meniscus, tip) {
        (Some(m), Geometry::Sphere(radius)) if model == Model::SolidAndMeniscus => {
            let (law, w) = TwoZones::of_sphere_in_meniscus(p.e_star, p.w, p.lambda, radius, m);
            (
                ContactLaw::SolidAndMeniscus(law),
                tip.units(p.e_star, w, spring),
            )
        }
        _ => {
            let u = tip.units(p.e_star, p.w, spring);
            (tip.law(model, p.lambda, &u), u)
        }
    }
}

/// [`model_forces`] of a fit with the options it was made with (the two-zone law takes its
/// meniscus from their humidity).
pub fn fitted_forces(
    m: &ModelFit,
    opt: &FitOptions,
    height: &[f64],
    dir: &[Direction],
    side: Option<&[Side]>,
) -> Option<Evaluated> {
    let p = m.params();
    if m.model != Model::SolidAndMeniscus {
        return model_forces(m.model, &p, opt.geometry(), opt.spring, height, dir, side);
    }
    let (law, u) = law_units(
        m.model,
        &p,
        opt.geometry(),
        opt.spring,
        meniscus(m.model, opt),
    );
    forces_on(law, &u, p.zc, height, dir, side, None)
}

/// The meniscus (stress in Pa, range in m) a model's law takes from the options: the humidity's
/// for the two-zone law, none for the others.
fn meniscus(model: Model, opt: &FitOptions) -> Option<(f64, f64)> {
    (model == Model::SolidAndMeniscus)
        .then(|| opt.humidity.as_ref()?.stress_and_range())
        .flatten()
}

/// The least-squares problem of one model on one prepared curve.
pub(super) struct Problem<'a> {
    pub(super) model: Model,
    /// The two-zone law's meniscus: its stress (Pa) and range (m).
    pub(super) meniscus: Option<(f64, f64)>,
    pub(super) data: &'a Prepared,
    pub(super) tip: Geometry,
    pub(super) spring: f64,
    pub(super) z0: Option<f64>,
    /// Maugis-Dugdale at a fixed lambda (the profile that picks the start).
    pub(super) fixed_lambda: Option<f64>,
    /// Hertz has no w: its units use this one (it cancels).
    pub(super) w_ref: f64,
    pub(super) z_scale: f64,
    pub(super) f_scale: f64,
    pub(super) x: DVector<f64>,
    /// The states at the current parameters (the Jacobian keeps each point on its piece).
    pub(super) states: RefCell<Option<Vec<PathState>>>,
    /// Where each point's search starts at the next parameters: the last states evaluated, or
    /// after a Jacobian its base states moved along their slides (`slides`).
    pub(super) hints: RefCell<Option<Vec<PathState>>>,
    /// The states where the Jacobian was last taken, with each state's slide `dt/dx`: the next
    /// trial's hints move along it (Newton then starts second-order close).
    pub(super) slides: RefCell<Option<Slides>>,
    pub(super) jacobians: RefCell<usize>,
    /// The watch on a fit at fixed lambda that crawls (None elsewhere): see [`Crawl`].
    pub(super) crawl: RefCell<Option<Crawl>>,
}

/// A Maugis-Dugdale fit at fixed lambda (a profile point, an interval's crossing) is stopped
/// where it crawls: where the misfit's steps (the jump crossing points) keep
/// Levenberg-Marquardt's trust region small, it can spend its whole budget gaining a tenth of
/// chi^2 per hundred evaluations (the brain tissue of bench/jpk_curves.py: 0.4 s of its 0.47). A profile point places Delta chi^2 against levels
/// of 1 to 9, so the fit ends once a window of [`CRAWL_WINDOW`] evaluations per parameter gains
/// less than [`CRAWL_CHI2`] in chi^2, at the best parameters met. (Its s^2 is the point's own,
/// `RSS / (m - n)`: far from the minimum the cut is looser than the profile's chi^2, whose s^2
/// is the free fit's, by the ratio of their RSS.) Free fits are not watched: a free fit's slow
/// valley can still carry w by a few half-widths of its interval; nor the humid fit's shape
/// points, which keep only converged fits.
pub(super) struct Crawl {
    /// Evaluations of the residuals so far.
    evaluations: usize,
    /// The best RSS met (the residuals' squared norm) and its parameters.
    best: f64,
    best_x: DVector<f64>,
    /// The best RSS at the start of the current window (the first window's: the start's).
    window_start: f64,
    /// Set when a window gained too little: the residuals then refuse, ending the fit.
    stalled: bool,
}

/// The window of [`Crawl`], in evaluations per parameter (the budget is 150 of them).
const CRAWL_WINDOW: usize = 20;
/// The least gain in chi^2 over a window of [`Crawl`] for a fit to go on.
const CRAWL_CHI2: f64 = 0.2;

impl Crawl {
    /// A watch from the start `x`.
    fn new(x: &DVector<f64>) -> Crawl {
        Crawl {
            evaluations: 0,
            best: f64::INFINITY,
            best_x: x.clone(),
            window_start: f64::INFINITY,
            stalled: false,
        }
    }

    /// The stop of a fit that ended crawling.
    fn stop_text() -> String {
        format!("stopped crawling: less than {CRAWL_CHI2} in chi^2 gained over the last {CRAWL_WINDOW} evaluations per parameter (as at the iteration limit)")
    }
}

impl Problem<'_> {
    /// Ends the watch; where the fit crawled, puts it at the best parameters met (their states
    /// located afresh, not from the last trial's) and says so.
    fn end_crawl(&mut self) -> bool {
        let Some(c) = self.crawl.take().filter(|c| c.stalled) else {
            return false;
        };
        self.set_params(&c.best_x);
        *self.hints.borrow_mut() = None;
        true
    }

    /// Counts an evaluation of the residuals `r` at the current parameters; false where the
    /// fit crawls and is to end.
    fn watch(&self, r: &DVector<f64>) -> bool {
        let mut guard = self.crawl.borrow_mut();
        let Some(c) = guard.as_mut() else {
            return true;
        };
        let rss = r.norm_squared();
        if rss < c.best {
            c.best = rss;
            c.best_x.copy_from(&self.x);
        }
        c.evaluations += 1;
        if c.evaluations == 1 {
            c.window_start = rss;
        }
        let window = CRAWL_WINDOW * (self.n() + 1);
        if c.evaluations % window == 0 {
            let m = self.data.count as f64;
            let s2 = (c.best + self.data.within / (self.f_scale * self.f_scale))
                / (m - self.n() as f64).max(1.0);
            if c.window_start - c.best < CRAWL_CHI2 * s2 {
                c.stalled = true;
                return false;
            }
            c.window_start = c.best;
        }
        true
    }
}

/// A Jacobian's base: its internal parameters, its states and how far each state's parameter t
/// slides per unit of each internal parameter at fixed base displacement.
pub(super) struct Slides {
    x: DVector<f64>,
    states: Vec<PathState>,
    dt_dx: DMatrix<f64>,
}

impl Slides {
    /// The base states with t moved to first order to the parameters `x` (held and free
    /// points as they were).
    fn hints(&self, x: &DVector<f64>) -> Vec<PathState> {
        let dx = x - &self.x;
        self.states
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let mut h = *s;
                let t = s.t + (self.dt_dx.row(i) * &dx)[0];
                if t.is_finite() && !s.clamped && s.piece != Piece::Free {
                    h.t = t;
                }
                h
            })
            .collect()
    }
}

impl Problem<'_> {
    pub(super) fn has_w(&self) -> bool {
        self.model.adhesive()
    }
    pub(super) fn has_lambda(&self) -> bool {
        self.model.has_lambda() && self.z0.is_none() && self.fixed_lambda.is_none()
    }
    /// The law and its units at p ([`law_units`]).
    pub(super) fn law_units(&self, p: &Params) -> (ContactLaw, Units) {
        law_units(self.model, p, self.tip, self.spring, self.meniscus)
    }

    pub(super) fn n(&self) -> usize {
        2 + self.has_w() as usize + 1 + self.has_lambda() as usize
    }

    pub(super) fn params(&self, x: &DVector<f64>) -> Params {
        let mut i = 0;
        let mut next = || {
            i += 1;
            x[i - 1]
        };
        let e_star = next().exp();
        let w = if self.has_w() {
            next().exp()
        } else {
            self.w_ref
        };
        let lambda = if self.has_lambda() {
            next().exp()
        } else if let Some(l) = self.fixed_lambda {
            l
        } else if let (true, Some(z0)) = (self.model.has_lambda(), self.z0) {
            self.tip.lambda_from_z0(e_star, w, z0)
        } else {
            1.0
        };
        let zc = next() * self.z_scale;
        let f0 = next() * self.f_scale;
        Params {
            e_star,
            w,
            lambda,
            zc,
            f0,
        }
    }

    pub(super) fn internal(&self, p: &Params) -> DVector<f64> {
        let mut v = vec![p.e_star.ln()];
        if self.has_w() {
            v.push(p.w.ln());
        }
        if self.has_lambda() {
            v.push(p.lambda.ln());
        }
        v.push(p.zc / self.z_scale);
        v.push(p.f0 / self.f_scale);
        DVector::from_vec(v)
    }

    /// Residuals at parameters x; with `near`, each point stays on the piece it had.
    pub(super) fn eval(
        &self,
        x: &DVector<f64>,
        near: Option<&[PathState]>,
    ) -> Option<(DVector<f64>, Vec<PathState>)> {
        let (p, law, u) = self.checked(x)?;
        let d = self.data;
        let states: Vec<PathState> = match near {
            Some(base) => self.states_near(&p, law, &u, base, 0..base.len()),
            None => {
                let hints = self.hints.borrow();
                forces_on(
                    law,
                    &u,
                    p.zc,
                    &d.height,
                    &d.dir,
                    Some(&d.side),
                    hints.as_deref(),
                )?
                .2
            }
        };
        let r = DVector::from_iterator(
            states.len(),
            states
                .iter()
                .enumerate()
                .map(|(i, s)| self.residual(&p, &u, i, s) * d.weight[i].sqrt()),
        );
        r.iter().all(|v| v.is_finite()).then_some((r, states))
    }

    /// The parameters, the law and its units at x; None where they leave the models' domain.
    fn checked(&self, x: &DVector<f64>) -> Option<(Params, ContactLaw, Units)> {
        let p = self.params(x);
        let (law, u) = self.law_units(&p);
        if !(u.kbar > 0.0 && u.kbar.is_finite() && u.approach > 0.0 && u.force > 0.0) {
            return None;
        }
        if self.model.has_lambda() && !self.tip.admits_lambda(p.lambda) {
            return None;
        }
        // A force offset beyond the largest force measured (the baseline, read on the far
        // approach, is the zero of force up to a drift): there a Dugdale zone longer than the
        // curve pulls nearly alike at every point and its adhesion trades against the offset
        // along a valley whose misfit falls without end (w, z0 and f0 growing together).
        if self.model.has_lambda() && self.z0.is_none() && !(p.f0.abs() <= self.f_scale) {
            return None;
        }
        Some((p, law, u))
    }

    /// The states of the points `rows` at (p, u), each on the piece its `base` state had: Newton
    /// steps from it, or where those fail (a point at a fold, or at the A = 0 end of DMT) and for
    /// held points, located on the path itself.
    fn states_near(
        &self,
        p: &Params,
        law: ContactLaw,
        u: &Units,
        base: &[PathState],
        rows: impl Iterator<Item = usize>,
    ) -> Vec<PathState> {
        let d = self.data;
        let top = d
            .height
            .iter()
            .map(|h| (p.zc - h) / u.approach)
            .fold(1.0, f64::max);
        let mut full: Option<DrivenPath> = None;
        rows.map(|i| {
            let s = &base[i];
            let delta = (p.zc - d.height[i]) / u.approach;
            (!s.clamped)
                .then(|| path::near(&law, u.kbar, delta, s.piece, s.t))
                .flatten()
                .unwrap_or_else(|| {
                    full.get_or_insert_with(|| DrivenPath::of(law, u.kbar, top))
                        .at_side(delta, d.dir[i], d.side[i])
                })
        })
        .collect()
    }

    /// Point i's residual in state s: its distance to the fold before a jump, else its force's.
    fn residual(&self, p: &Params, u: &Units, i: usize, s: &PathState) -> f64 {
        self.fold_residual(p, u, i, s)
            .unwrap_or_else(|| (s.load * u.force + p.f0 - self.data.force[i]) / self.f_scale)
    }

    /// A point before a measured jump: its distance to the model's curve near its state (in
    /// the plane of load and FOLD_SCALE kbar Delta, so that away from the fold, where the slope
    /// dP/dDelta is at most about kbar, it is the force residual within 0.5%).
    pub(super) fn fold_residual(
        &self,
        p: &Params,
        u: &Units,
        i: usize,
        s: &PathState,
    ) -> Option<f64> {
        self.nearest_fold(p, u, i, s)
            .map(|(r, ..)| r * u.force / self.f_scale)
    }

    /// Point `i` before a jump seen from the curve: its signed distance (normalised), the
    /// parameter of the nearest state, and its Delta and load. None off a jump, on the free
    /// piece, or where the search for the nearest state fails.
    fn nearest_fold(
        &self,
        p: &Params,
        u: &Units,
        i: usize,
        s: &PathState,
    ) -> Option<(f64, f64, f64, f64)> {
        if !self.data.at_jump[i] || s.piece == Piece::Free {
            return None;
        }
        let delta = (p.zc - self.data.height[i]) / u.approach;
        let load = (self.data.force[i] - p.f0) / u.force;
        let (r, t) = path::fold_distance(
            self.law_units(p).0,
            u.kbar,
            FOLD_SCALE * u.kbar,
            s.piece,
            s.t,
            delta,
            load,
        )?;
        Some((r, t, delta, load))
    }

    /// The rows of the points before a jump, whose residual is the signed distance `r = e.n`
    /// from the measured point to the curve's nearest state (see [`path::fold_distance`]), times
    /// the force unit over `f_scale` (the sphere's `pi w R`). The nearest state is stationary (`e.T = 0`, so `e` lies along the
    /// unit normal `n`): as a parameter moves, `dr = n . de` at that state's fixed t, the moves
    /// of t and of `n` dropping out. In the plane (load, 10 kbar Delta) `e` is
    /// `(P - L, 10 (kbar (D - Delta) + P))` with the measured load `L = (F - f0) / force unit`.
    pub(super) fn fold_rows(&self, j: &mut DMatrix<f64>, base: &[PathState]) {
        let p = self.params(&self.x);
        let (law, u) = self.law_units(&p);
        for (i, s) in base.iter().enumerate() {
            let Some((r, t, delta, load)) = self.nearest_fold(&p, &u, i, s) else {
                // Not before a jump, or no nearest state: the residual is the force's, and so
                // is its analytic row.
                continue;
            };
            let q = law.state(s.piece, t);
            let (tp, td) = (q.dload, FOLD_SCALE * (u.kbar * q.dapproach + q.dload));
            let norm = tp.hypot(td);
            let (np, nd) = (td / norm, -tp / norm);
            let kb = u.kbar;
            let (ep, ed) = (
                q.load - load,
                FOLD_SCALE * (kb * (q.approach - delta) + q.load),
            );
            if !(norm > 0.0) || (ep * tp + ed * td).abs() > 1e-6 * norm * ep.hypot(ed) {
                // Not a regular nearest state: the closed forms' curves have a cusp at A = 0
                // (DMT's jump), where the tangent vanishes and e is not along the normal.
                self.fold_row_by_differences(j, i, s);
                continue;
            }
            // de = (dP - dL, 10 (dkbar (D - Delta) - kbar dDelta + dP)) per column.
            let de = |dp: f64, dl: f64, dkbar: f64, ddelta: f64| {
                np * (dp - dl) + nd * FOLD_SCALE * (dkbar * (q.approach - delta) - kb * ddelta + dp)
            };
            let to_res = u.force / self.f_scale;
            let mut k = 0;
            if self.tip.is_sphere() {
                // kbar ~ w^(-1/3) E*^(-2/3), Delta ~ w^(-2/3) E*^(2/3), L ~ 1/w.
                j[(i, k)] = de(0.0, 0.0, -2.0 / 3.0 * kb, 2.0 / 3.0 * delta) * to_res;
                k += 1;
                if self.has_w() {
                    // The factor pi w R of the residual moves with w too.
                    j[(i, k)] = (de(0.0, -load, -kb / 3.0, -2.0 / 3.0 * delta) + r) * to_res;
                    k += 1;
                }
            } else {
                // A tip's units move as its log slopes say: L = (F - f0) / force, Delta =
                // (zc - h) / d, and the residual's factor `force` with them.
                let slopes = self.tip.log_slopes();
                let cols = if self.has_w() { 2 } else { 1 };
                for &(fs, ds, ks) in &slopes[..cols] {
                    j[(i, k)] = (de(0.0, -fs * load, ks * kb, -ds * delta) + fs * r) * to_res;
                    k += 1;
                }
            }
            if self.has_lambda() {
                let (pl, dl) = law.state_dlambda(s.piece, t);
                let dp = p.lambda * pl;
                j[(i, k)] = (np * dp + nd * FOLD_SCALE * (kb * p.lambda * dl + dp)) * to_res;
                k += 1;
            }
            j[(i, k)] = de(0.0, 0.0, 0.0, self.z_scale / u.approach) * to_res;
            j[(i, k + 1)] = de(0.0, -self.f_scale / u.force, 0.0, 0.0) * to_res;
        }
    }

    /// Row `i` of a point before a jump by central differences of its distance.
    fn fold_row_by_differences(&self, j: &mut DMatrix<f64>, i: usize, s: &PathState) {
        for k in 0..self.n() {
            let h = 1e-6 * self.x[k].abs().max(1.0);
            let at = |dx: f64| {
                let mut x = self.x.clone();
                x[k] += dx;
                let p = self.params(&x);
                let u = self.law_units(&p).1;
                self.fold_residual(&p, &u, i, s)
            };
            if let (Some(a), Some(b)) = (at(h), at(-h)) {
                j[(i, k)] = (a - b) / (2.0 * h);
            }
        }
    }
}

/// The weight of Delta against the load in the distance of a point before a jump, in units of
/// kbar (the largest slope of a stable stretch away from its fold).
pub(super) const FOLD_SCALE: f64 = 10.0;

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.x.copy_from(x);
        *self.states.borrow_mut() = None;
    }

    fn params(&self) -> DVector<f64> {
        self.x.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        if let Some(h) = self.slides.borrow().as_ref().map(|b| b.hints(&self.x)) {
            *self.hints.borrow_mut() = Some(h);
        }
        // Outside the domain: a large residual, so the step is refused and shortened (a None
        // would end the whole minimisation).
        match self.eval(&self.x, None) {
            Some((r, s)) => {
                *self.hints.borrow_mut() = Some(s.clone());
                *self.states.borrow_mut() = Some(s);
                self.watch(&r).then_some(r)
            }
            None => Some(DVector::from_element(self.data.force.len(), 1e6)),
        }
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let mut j = self.unweighted_jacobian()?;
        // A bin's row counts as its points: its residual is scaled by the root of its count.
        for (i, w) in self.data.weight.iter().enumerate() {
            if *w != 1.0 {
                j.row_mut(i).scale_mut(w.sqrt());
            }
        }
        Some(j)
    }
}

impl Problem<'_> {
    /// The Jacobian of the residuals, each point's row before its weight.
    fn unweighted_jacobian(&self) -> Option<DMatrix<f64>> {
        *self.jacobians.borrow_mut() += 1;
        let base = match self.states.borrow().clone() {
            Some(s) => s,
            None => self.eval(&self.x, None)?.1,
        };
        if (self.model.has_lambda() && self.z0.is_some())
            || !self.model.scales()
            || !self.tip.scales()
        {
            // lambda (or the law's path) moves with E* and w: every column by differences.
            return self.numeric_jacobian(&base, &(0..self.n()).collect::<Vec<_>>());
        }
        let (mut j, dt_dx) = self.analytic_jacobian(&base);
        let held = |s: &PathState| s.clamped && s.piece != Piece::Free;
        let rows: Vec<usize> = (0..base.len()).filter(|&i| held(&base[i])).collect();
        if self.has_lambda() && !rows.is_empty() {
            // A held point sits at the end of its stretch, which moves with lambda: its row of
            // lambda's column by differences (of its rows alone: most Jacobians of a free fit
            // have held points, and the other rows would double the fit's evaluations).
            let k = 1 + self.has_w() as usize;
            let c = self.numeric_rows(&base, &rows, k)?;
            for (&i, v) in rows.iter().zip(c) {
                j[(i, k)] = v;
            }
        }
        self.fold_rows(&mut j, &base);
        *self.slides.borrow_mut() = Some(Slides {
            x: self.x.clone(),
            states: base,
            dt_dx,
        });
        Some(j)
    }
    /// The Jacobian from the state's slopes. With u = (ln E*, ln w), the force is
    /// `F = Fs P(Delta, kbar)` with `Delta = (z_c - h) / Ds` and `kbar = k Ds / Fs`, the units
    /// moving with E* and w as [`Geometry::log_slopes`] says (the sphere's `Fs ~ w`,
    /// `Ds ~ w^(2/3) E*^(-2/3)`, `kbar ~ w^(-1/3) E*^(-2/3)`); along the branch `dP/dDelta = P'/g` and
    /// `dP/dkbar = P' P / (kbar^2 g)`, with `g = dDelta/dt = D' + P'/kbar`. Points on the free
    /// piece, or held at the end of their stretch (where the data put them past the model's
    /// jump), move with the offset only: for held points an approximation, which the iteration
    /// tolerates and which a converged fit rarely needs. Lambda's column is the state's slide
    /// along its piece as lambda moves ([`Problem::dload_dlambda`]); held points take theirs
    /// from differences (their stretch's end moves with lambda). Also returns each state's
    /// slide `dt/dx` along its piece (zero for free and held points), from the same slopes.
    pub(super) fn analytic_jacobian(&self, base: &[PathState]) -> (DMatrix<f64>, DMatrix<f64>) {
        let p = self.params(&self.x);
        let (law, u) = self.law_units(&p);
        let (m, n) = (base.len(), self.n());
        let mut j = DMatrix::zeros(m, n);
        let mut dt = DMatrix::zeros(m, n);
        for (i, s) in base.iter().enumerate() {
            // 1/g = dt/dDelta at fixed kbar, the state's slide along its piece; the state's
            // slopes at s.t, as stored with it (`Law::state`'s there, or theirs one Newton step
            // below 1e-8 away, where `path::near` stopped).
            let g = s.dapproach + s.dload / u.kbar;
            let slides = !(s.piece == Piece::Free || s.clamped) && g.abs() > 0.0;
            let (dp_dd, dp_dk) = if slides {
                (s.dload / g, s.dload * s.load / (u.kbar * u.kbar * g))
            } else {
                (0.0, 0.0)
            };
            let inv_g = if slides { 1.0 / g } else { 0.0 };
            let delta = (p.zc - self.data.height[i]) / u.approach;
            // A parameter that scales the force by dln_fs, the approach unit by dln_ds and kbar
            // by dln_k moves Delta by -Delta dln_ds and the spring's share P / kbar by
            // -(P / kbar) dln_k.
            let mut col = |k: usize, dln_fs: f64, dln_ds: f64, dln_k: f64| {
                dt[(i, k)] = (-delta * dln_ds + s.load / u.kbar * dln_k) * inv_g;
                j[(i, k)] = u.force
                    * (s.load * dln_fs - dp_dd * delta * dln_ds + dp_dk * u.kbar * dln_k)
                    / self.f_scale;
            };
            let mut k = 0;
            let [(fe, de, ke), (fw, dw, kw)] = self.tip.log_slopes();
            col(k, fe, de, ke);
            k += 1;
            if self.has_w() {
                col(k, fw, dw, kw);
                k += 1;
            }
            if self.has_lambda() {
                let (dp, slide) = self.dload_dlambda(&law, &u, s);
                j[(i, k)] = u.force * p.lambda * dp / self.f_scale;
                dt[(i, k)] = p.lambda * slide;
                k += 1;
            }
            j[(i, k)] = u.force * dp_dd * (self.z_scale / u.approach) / self.f_scale;
            dt[(i, k)] = (self.z_scale / u.approach) * inv_g;
            j[(i, k + 1)] = 1.0;
        }
        (j, dt)
    }

    /// dPbar/dlambda at the point's Delta (fixed) and kbar, and the state's slide along its
    /// piece, `dt/dlambda = -(D_lambda + P_lambda / kbar) / g`. Zero on the free piece and for
    /// held points (their rows are taken by differences).
    fn dload_dlambda(&self, law: &ContactLaw, u: &Units, s: &PathState) -> (f64, f64) {
        if s.piece == Piece::Free || s.clamped {
            return (0.0, 0.0);
        }
        let (pl, dl) = law.state_dlambda(s.piece, s.t);
        let g = s.dapproach + s.dload / u.kbar;
        if g.abs() > 0.0 {
            (
                pl - s.dload * (dl + pl / u.kbar) / g,
                -(dl + pl / u.kbar) / g,
            )
        } else {
            (0.0, 0.0)
        }
    }

    /// The residuals of the points `rows` at parameters x, each on the piece its `base` state had:
    /// [`Problem::eval`] with `near`, for those rows alone.
    fn eval_rows(&self, x: &DVector<f64>, base: &[PathState], rows: &[usize]) -> Option<Vec<f64>> {
        let (p, law, u) = self.checked(x)?;
        let states = self.states_near(&p, law, &u, base, rows.iter().copied());
        let r: Vec<f64> = rows
            .iter()
            .zip(&states)
            .map(|(&i, s)| self.residual(&p, &u, i, s))
            .collect();
        r.iter().all(|v| v.is_finite()).then_some(r)
    }

    /// Central differences in column k of the rows `rows`, each point kept on its piece; a
    /// one-sided difference where one side leaves the domain or a branch.
    fn numeric_rows(&self, base: &[PathState], rows: &[usize], k: usize) -> Option<Vec<f64>> {
        let h = 1e-6 * self.x[k].abs().max(1.0);
        let mut xp = self.x.clone();
        xp[k] += h;
        let mut xm = self.x.clone();
        xm[k] -= h;
        match (
            self.eval_rows(&xp, base, rows),
            self.eval_rows(&xm, base, rows),
        ) {
            (Some(rp), Some(rm)) => Some(
                rp.iter()
                    .zip(&rm)
                    .map(|(p, m)| (p - m) / (2.0 * h))
                    .collect(),
            ),
            (rp, _) => {
                // One side left the domain or a branch: a one-sided difference.
                let r0 = self.eval_rows(&self.x, base, rows)?;
                let rp = rp.or_else(|| {
                    self.eval_rows(&xm, base, rows)
                        .map(|rm| r0.iter().zip(&rm).map(|(a, b)| 2.0 * a - b).collect())
                })?;
                Some(rp.iter().zip(&r0).map(|(p, a)| (p - a) / h).collect())
            }
        }
    }

    /// Central differences in the given columns (others zero), each point kept on its piece.
    pub(super) fn numeric_jacobian(
        &self,
        base: &[PathState],
        cols: &[usize],
    ) -> Option<DMatrix<f64>> {
        let all: Vec<usize> = (0..base.len()).collect();
        let mut j = DMatrix::zeros(base.len(), self.n());
        for &k in cols {
            let c = self.numeric_rows(base, &all, k)?;
            j.set_column(k, &DVector::from_vec(c));
        }
        Some(j)
    }
}

/// The starting point of a fit: closed-form estimates from the measured curve.
#[derive(Clone, Copy, Debug)]
pub struct Estimates {
    /// E* from the contact part of the curve taken as Hertzian (Pa).
    pub e_star: f64,
    /// The measured pull-off force (positive, N).
    pub pulloff: f64,
    /// The contact point (m): the tip height at the pull-off, or where the force leaves zero
    /// on a curve without adhesion.
    pub zc: f64,
}

/// The starting point of a fit of the prepared curve `d`, with the tip (a radius is a
/// sphere's) and the spring constant (N/m).
pub fn estimates(d: &Prepared, geometry: impl Into<Geometry>, spring: f64) -> Estimates {
    let geometry = geometry.into();
    let n = d.force.len();
    let (imin, fmin) = d
        .force
        .iter()
        .cloned()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, 0.0));
    let fmax = d.force.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let tip = |i: usize| d.height[i] + d.force[i] / spring;
    let pulloff = (-fmin).max(0.0);
    // DMT: the pull-off at zero indentation; without adhesion, where the force leaves zero.
    let zc = if pulloff > 3.0 * d.noise {
        tip(imin)
    } else {
        let thr = 3.0 * d.noise + 0.02 * fmax;
        (0..n)
            .filter(|&i| d.force[i] > thr)
            .map(tip)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let base = fmin.min(0.0);
    let mut k: Vec<f64> = (0..n)
        .filter(|&i| d.force[i] - base > 0.5 * (fmax - base))
        .filter_map(|i| {
            let delta = zc - tip(i);
            (delta > 0.0).then(|| geometry.punch_stiffness(d.force[i] - base, delta))
        })
        .collect();
    k.sort_by(f64::total_cmp);
    let kk = k.get(k.len() / 2).cloned().unwrap_or(1e9);
    Estimates {
        e_star: 0.75 * kk,
        pulloff,
        zc,
    }
}

pub(super) fn stop_text(t: &TerminationReason) -> String {
    match t {
        TerminationReason::ResidualsZero => "residuals zero".into(),
        TerminationReason::Orthogonal => "gradient orthogonal to the residuals (converged)".into(),
        TerminationReason::Converged { ftol, xtol } => match (ftol, xtol) {
            (true, true) => "converged (relative change of the residual and the parameters)".into(),
            (true, false) => "converged (relative change of the residual)".into(),
            _ => "converged (relative change of the parameters)".into(),
        },
        TerminationReason::LostPatience => "iteration limit reached".into(),
        TerminationReason::NoImprovementPossible(w) => {
            format!("no further improvement possible ({w})")
        }
        TerminationReason::Numerical(w) => format!("numerical failure ({w})"),
        TerminationReason::User(w) => format!("model evaluation failed ({w})"),
        other => format!("{other:?}"),
    }
}

/// Fits one model from a start.
pub(super) fn fit_model(
    model: Model,
    d: &Prepared,
    opt: &FitOptions,
    start: Params,
    w_ref: f64,
    fixed_lambda: Option<f64>,
) -> ModelFit {
    fit_model_for(model, d, opt, start, w_ref, fixed_lambda, PATIENCE, None)
}

/// [`fit_model`] of Maugis-Dugdale started from the fit `from` (its parameters moved by
/// `start`), each point's first search begun at `from`'s state (Newton steps instead of a
/// search from the path's nodes; checked to stay on its stretch).
pub(super) fn fit_md_from(
    from: &ModelFit,
    d: &Prepared,
    opt: &FitOptions,
    start: Params,
    w_ref: f64,
    fixed_lambda: Option<f64>,
    patience: usize,
) -> ModelFit {
    let hints = from.states.as_deref().map(|s| s.as_slice());
    fit_model_for(
        Model::Md,
        d,
        opt,
        start,
        w_ref,
        fixed_lambda,
        patience,
        hints,
    )
}

/// The rms residual (N) of the fit `f` on the points of `d`: a fit made on a curve's bins,
/// read on its points (NaN where its parameters cannot be evaluated). On bins: over their
/// weighted means alone, without their scatter.
pub(super) fn rms_on(f: &ModelFit, d: &Prepared, opt: &FitOptions, w_ref: f64) -> f64 {
    let fixed = f.lambda.filter(|_| opt.z0.is_none());
    let prob = Problem::new(f.model, d, opt, w_ref, fixed);
    let x = prob.internal(&f.params());
    prob.eval(&x, None).map_or(f64::NAN, |(r, _)| {
        (r.norm_squared() / d.count as f64).sqrt() * prob.f_scale
    })
}

/// The scales of a curve's fit parameters: its largest force (N) and its height span (m),
/// those of its points where it is binned.
pub(super) fn scales(d: &Prepared) -> (f64, f64) {
    d.scales
}

impl<'a> Problem<'a> {
    /// The least-squares problem of one model on a prepared curve, scaled by the curve's
    /// largest force and its height span.
    pub(super) fn new(
        model: Model,
        d: &'a Prepared,
        opt: &FitOptions,
        w_ref: f64,
        fixed_lambda: Option<f64>,
    ) -> Problem<'a> {
        let (f_scale, z_scale) = scales(d);
        Problem {
            model,
            meniscus: meniscus(model, opt),
            data: d,
            tip: opt.geometry(),
            spring: opt.spring,
            z0: opt.z0,
            fixed_lambda,
            w_ref,
            z_scale,
            f_scale,
            x: DVector::zeros(0),
            states: RefCell::new(None),
            hints: RefCell::new(None),
            slides: RefCell::new(None),
            jacobians: RefCell::new(0),
            crawl: RefCell::new(None),
        }
    }
}

/// The iteration budget of a fit (MINPACK's: this many evaluations per parameter and one), and
/// the shorter one of a scouting free fit.
pub(super) const PATIENCE: usize = 150;
pub(super) const SCOUT_PATIENCE: usize = 3;

/// The relative tolerance (MINPACK's ftol and xtol) of a fit at fixed lambda, and of a noisy
/// curve's fit finished on its points. Such fits only
/// place the profile of the misfit, read as Delta chi^2 = Delta RSS / s^2 with s^2 = RSS / (m -
/// 5). A fit stops when a step would reduce the RSS by less than this fraction, which leaves it
/// within a few times that of its minimum: Delta chi^2 moves by about 1e-10 m, far below the
/// profile's resolution, and the last iterations of a linear convergence are saved. Free fits
/// keep the crate's 30 epsilon, so that noise-free curves recover their parameters to rounding.
pub(super) const PROFILE_TOL: f64 = 1e-10;

#[allow(clippy::too_many_arguments)]
pub(super) fn fit_model_for(
    model: Model,
    d: &Prepared,
    opt: &FitOptions,
    start: Params,
    w_ref: f64,
    fixed_lambda: Option<f64>,
    patience: usize,
    hints: Option<&[PathState]>,
) -> ModelFit {
    let tol = fixed_lambda.map(|_| PROFILE_TOL);
    fit_model_tol(
        model,
        d,
        opt,
        start,
        w_ref,
        fixed_lambda,
        patience,
        hints,
        tol,
    )
}

/// [`fit_model_for`] with MINPACK's relative tolerances `tol` (ftol and xtol; None: the
/// crate's).
#[allow(clippy::too_many_arguments)]
pub(super) fn fit_model_tol(
    model: Model,
    d: &Prepared,
    opt: &FitOptions,
    start: Params,
    w_ref: f64,
    fixed_lambda: Option<f64>,
    patience: usize,
    hints: Option<&[PathState]>,
    tol: Option<f64>,
) -> ModelFit {
    let mut prob = Problem::new(model, d, opt, w_ref, fixed_lambda);
    prob.x = prob.internal(&start);
    *prob.hints.borrow_mut() = hints
        .filter(|h| h.len() == d.force.len())
        .map(<[_]>::to_vec);
    let scout = patience == SCOUT_PATIENCE;
    if model == Model::Md && fixed_lambda.is_some() {
        *prob.crawl.borrow_mut() = Some(Crawl::new(&prob.x));
    }
    let mut lm = LevenbergMarquardt::new().with_patience(patience);
    if let Some(t) = tol {
        lm = lm.with_ftol(t).with_xtol(t);
    }
    let (mut prob, mut report) = lm.minimize(prob);
    let crawled = prob.end_crawl();
    if crawled {
        report.termination = TerminationReason::LostPatience;
    }
    let x = prob.x.clone();
    let p = prob.params(&x);
    let iterations = *prob.jacobians.borrow();
    let evaluated = prob.eval(&x, None);
    let ok = report.termination.was_successful()
        || matches!(
            report.termination,
            TerminationReason::NoImprovementPossible(_)
        );
    let (status, rms, cov, jtj_inv) = match &evaluated {
        Some((r, _)) if ok || matches!(report.termination, TerminationReason::LostPatience) => {
            // A binned curve's residual sum: its weighted bins and the scatter inside them.
            let m = d.count;
            let n = prob.n();
            let rss = r.norm_squared() + d.within / (prob.f_scale * prob.f_scale);
            let rms = (rss / m as f64).sqrt() * prob.f_scale;
            // A scout's covariance is never read (only its misfit and parameters): its final
            // Jacobian is skipped.
            let inv = (!scout)
                .then(|| prob.jacobian())
                .flatten()
                .and_then(|j| (j.transpose() * &j).try_inverse());
            let cov = inv
                .as_ref()
                .map(|inv| inv * (rss / (m.saturating_sub(n).max(1)) as f64));
            let status = if ok {
                FitStatus::Ok
            } else {
                FitStatus::NotConverged
            };
            (status, rms, cov, inv)
        }
        _ => (FitStatus::NotConverged, f64::NAN, None, None),
    };
    let (e_err, w_err, lambda_err, zc_err) = standard_errors(&prob, &cov, &p, fixed_lambda);
    let pulloff = evaluated.as_ref().filter(|_| !scout).map_or(f64::NAN, |_| {
        let (law, u) = prob.law_units(&p);
        model_pulloff(law, &u, p.zc, d, opt)
    });
    ModelFit {
        model,
        status,
        e_star_pa: p.e_star,
        e_star_pa_stderr: e_err,
        work_of_adhesion_j_m2: if model.adhesive() { p.w } else { 0.0 },
        work_of_adhesion_j_m2_stderr: w_err,
        lambda: model.has_lambda().then_some(p.lambda),
        lambda_stderr: lambda_err,
        contact_point_m: p.zc,
        contact_point_m_stderr: zc_err,
        force_offset_n: p.f0,
        rms_residual_n: rms,
        pulloff_force_model_n: pulloff,
        iterations,
        stop: if crawled {
            Crawl::stop_text()
        } else {
            stop_text(&report.termination)
        },
        cov,
        jtj_inv,
        // Only the Maugis-Dugdale fit is restarted from its states (the search's full fits).
        states: evaluated
            .filter(|_| model == Model::Md)
            .map(|(_, s)| std::sync::Arc::new(s)),
    }
}

/// The standard errors of E*, w, lambda (None where it is not a parameter or a function of
/// them) and the contact point from a fit's covariance in its internal variables.
pub(super) fn standard_errors(
    prob: &Problem,
    cov: &Option<DMatrix<f64>>,
    p: &Params,
    fixed_lambda: Option<f64>,
) -> (f64, f64, Option<f64>, f64) {
    let model = prob.model;
    let var = |i: usize| cov.as_ref().map_or(f64::NAN, |c| c[(i, i)].max(0.0).sqrt());
    let mut i = 1;
    let e_err = p.e_star * var(0);
    let w_err = if prob.has_w() {
        i += 1;
        p.w * var(1)
    } else {
        0.0
    };
    let lambda_err = if prob.has_lambda() {
        i += 1;
        Some(p.lambda * var(i - 1))
    } else if model.has_lambda() && fixed_lambda.is_some() {
        Some(0.0)
    } else if model.has_lambda() {
        // Fixed z0: lambda follows E* and w, ln lambda = c (ln w - ln E*) + const.
        let c2 = prob.tip.z0_slope(p.e_star, p.w).powi(2);
        cov.as_ref().map(|c| {
            let v = c2 * (c[(0, 0)] + c[(1, 1)] - 2.0 * c[(0, 1)]);
            p.lambda * v.max(0.0).sqrt()
        })
    } else {
        None
    };
    let zc_err = var(i) * prob.z_scale;
    (e_err, w_err, lambda_err, zc_err)
}

/// The most tensile load of a law's path (in its units `u`, contact point `zc`) under the
/// cantilever (N, positive), along the fitted segment's direction: the path alone, not the
/// states at the points.
pub(super) fn model_pulloff(
    law: ContactLaw,
    u: &Units,
    zc: f64,
    d: &Prepared,
    opt: &FitOptions,
) -> f64 {
    let top = d
        .height
        .iter()
        .map(|h| (zc - h) / u.approach)
        .fold(1.0, f64::max);
    let dir = if opt.segments == Segments::Approach {
        Direction::Approach
    } else {
        Direction::Retract
    };
    -DrivenPath::of(law, u.kbar, top).min_load(dir).0 * u.force
}
