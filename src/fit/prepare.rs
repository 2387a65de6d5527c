//! A curve made ready for fitting: checked, its spikes dropped, its baseline removed, its
//! points sorted into segments and sides of the measured jump.

use super::*;

/// A curve made ready for fitting: baseline removed, the points of the fitted segments.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// Base height of each fitted point (m).
    pub height: Vec<f64>,
    /// Force at each fitted point, baseline removed (N).
    pub force: Vec<f64>,
    /// Each point's segment.
    pub dir: Vec<Direction>,
    /// Each point's side of its segment's measured jump (Any where none was measured).
    pub side: Vec<Side>,
    /// Each point's weight: 1, or a bin's count of points ([`Prepared::binned`]).
    pub weight: Vec<f64>,
    /// The bins' scatter about their means (N^2), the part of a residual sum of squares that
    /// the weighted means do not carry; 0 for a curve not binned.
    pub within: f64,
    /// The number of measured points the fitted ones stand for.
    pub count: usize,
    /// The scales of the fit's parameters: the largest force (N) and the height span (m).
    pub scales: (f64, f64),
    /// The last points before a measured jump: fitted by their distance to the model's curve
    /// (`law::follow::fold_distance`), which stays smooth in the parameters where the model's fold
    /// passes them.
    pub at_jump: Vec<bool>,
    /// The removed baseline `(b0, b1)`: force `b0 + b1 height` (N, N/m; b1 is 0 without
    /// [`FitOptions::tilt`]).
    pub baseline: (f64, f64),
    /// The rms of the baseline's points about it (N): the force noise.
    pub noise: f64,
    /// What preparing the curve changed or found (outliers dropped, jittering heights): warnings.
    pub notes: Vec<String>,
    /// The dwell between approach and retract, if the curve had one.
    pub dwell: Option<DwellReport>,
}

/// Fewer points than this in the fitted segments, or in contact, and a curve is refused or warned.
pub const MIN_POINTS: usize = 20;
/// Fewer points in contact than this and a curve is warned about (see [`MIN_POINTS`]).
pub const MIN_CONTACT_POINTS: usize = 10;

/// Checks a curve and removes its baseline.
pub fn prepare(curve: &Curve, opt: &FitOptions) -> Result<Prepared, (FitStatus, Message)> {
    // The options' one check (the spring constant and the radius among them).
    if let Err(e) = opt.validate() {
        return refused(e.message);
    }
    for (i, (&h, &f)) in curve.height.iter().zip(&curve.force).enumerate() {
        if !h.is_finite() || !f.is_finite() {
            return refused(format!(
                "point {} has height_m = {h} and force_n = {f}: remove or repair non-finite values",
                i + 1
            ));
        }
    }
    if let Some(m) = &curve.refused {
        return refused(m.to_string());
    }
    let mut notes = curve.notes.clone();
    if let Err(m) = check_cycles(curve) {
        return refused(m.to_string());
    }
    for d in [Direction::Approach, Direction::Retract] {
        match check_order(curve, d) {
            Err(m) => return refused(m.to_string()),
            Ok(Some(note)) => notes.push(note),
            Ok(None) => {}
        }
    }
    // Outliers (spikes far beyond the noise) would steer the fit and the baseline: dropped.
    let cleaned;
    let curve = match drop_spikes(curve) {
        Some((c, note)) => {
            notes.push(note);
            cleaned = c;
            &cleaned
        }
        None => curve,
    };
    let ((b0, b1), noise) = baseline(curve, opt);
    let dwell = curve
        .dwell
        .as_ref()
        .map(|w| dwell_report(w, (b0, b1), noise, opt.spring));
    // A retract after a relaxing dwell is no loading curve: the approach is fitted instead.
    let mut segments = opt.segments;
    if let Some(w) = dwell
        .as_ref()
        .filter(|w| w.relaxed && segments != Segments::Approach)
    {
        segments = Segments::Approach;
        notes.insert(0, relaxed_dwell_note(w));
    }
    let fitted: Vec<usize> = (0..curve.len())
        .filter(|&i| segments.takes(curve.segment[i]))
        .collect();
    if fitted.is_empty() {
        return refused(no_segment(segments));
    }
    if fitted.len() < MIN_POINTS {
        return refused(format!(
            "only {} points in the fitted segments: at least {MIN_POINTS} are needed",
            fitted.len()
        ));
    }
    let height: Vec<f64> = fitted.iter().map(|&i| curve.height[i]).collect();
    let force: Vec<f64> = fitted
        .iter()
        .map(|&i| curve.force[i] - b0 - b1 * curve.height[i])
        .collect();
    if !shows_contact(&force, noise) {
        return Err(no_contact(curve, segments, &force, (b0, b1), noise));
    }
    let dir: Vec<Direction> = fitted.iter().map(|&i| curve.segment[i]).collect();
    let side = measured_sides(&force, &dir, noise);
    let at_jump = last_before_jump(&side, &dir);
    let scales = scales_of(&force, &height);
    Ok(Prepared {
        weight: vec![1.0; force.len()],
        within: 0.0,
        count: force.len(),
        scales,
        side,
        at_jump,
        dir,
        height,
        force,
        baseline: (b0, b1),
        noise,
        notes,
        dwell,
    })
}

/// The scales of a curve's fit parameters: its largest force (N) and its height span (m).
fn scales_of(force: &[f64], height: &[f64]) -> (f64, f64) {
    let f = force.iter().fold(0.0f64, |m, f| m.max(f.abs())).max(1e-30);
    let hspan = height.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - height.iter().cloned().fold(f64::INFINITY, f64::min);
    (f, hspan.max(1e-30))
}

/// The advice to fit the segment `d` instead, keyed by the segment option's choice
/// (`segments=approach`: Python adds its argument).
fn the_other(d: Direction) -> Message {
    let (key, words) = match d {
        Direction::Approach => ("segments=approach", "the approach segment instead"),
        Direction::Retract => ("segments=retract", "the retract segment instead"),
    };
    Message::new().phrase(key, words)
}

/// Why a curve without the segments to fit is refused.
fn no_segment(segments: Segments) -> Message {
    match segments {
        Segments::Retract => Message::new()
            .text("no retract segment: fit ")
            .then(the_other(Direction::Approach))
            .text(", or check the segment column (approach/retract or 0/1)"),
        Segments::Approach => Message::new()
            .text("no approach segment: fit ")
            .then(the_other(Direction::Retract))
            .text(", or check the segment column"),
        Segments::Both => "no points".into(),
    }
}

/// A curve refused as invalid input, with why.
fn refused<T>(why: impl Into<Message>) -> Result<T, (FitStatus, Message)> {
    Err((FitStatus::InvalidInput, why.into()))
}

/// Whether a segment's forces (baseline removed) rise above the baseline: beyond five times
/// its noise and a thousandth of their range.
fn shows_contact(force: &[f64], noise: f64) -> bool {
    let fmax = force.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let fmin = force.iter().cloned().fold(f64::INFINITY, f64::min);
    fmax > 5.0 * noise && fmax > 1e-3 * (fmax - fmin).abs() && fmax > 0.0
}

/// Why fitted segments that never rise above the baseline cannot be fitted: `no_contact` where
/// no segment of the curve does, else the segment that does, to be fitted instead.
fn no_contact(
    curve: &Curve,
    segments: Segments,
    force: &[f64],
    (b0, b1): (f64, f64),
    noise: f64,
) -> (FitStatus, Message) {
    let fmax = force.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let mut largest = fmax;
    for other in [Direction::Approach, Direction::Retract] {
        if segments.takes(other) {
            continue;
        }
        let f: Vec<f64> = segment_points(curve, other)
            .into_iter()
            .map(|i| curve.force[i] - b0 - b1 * curve.height[i])
            .collect();
        largest = f.iter().cloned().fold(largest, f64::max);
        if shows_contact(&f, noise) {
            // One segment was fitted: the other one.
            let fitted = seg_name(match other {
                Direction::Approach => Direction::Retract,
                Direction::Retract => Direction::Approach,
            });
            let top = f.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            return (
                FitStatus::InvalidInput,
                Message::new()
                    .text(format!(
                        "the {} never rises above five times the baseline's noise (largest {fmax:.3e} N, noise {noise:.2e} N) while the {} does (up to {top:.3e} N), so it holds too little contact to fit; fit ",
                        fitted,
                        seg_name(other),
                    ))
                    .then(the_other(other)),
            );
        }
    }
    (
        FitStatus::NoContact,
        format!(
            "no contact: no segment of the curve rises above the baseline (largest {largest:.3e} N, noise {noise:.2e} N); check the sign of force_n (positive is repulsive)"
        )
        .into(),
    )
}

/// A dwell read against the baseline and the cantilever: its forces, relaxation and creep.
fn dwell_report(w: &segments::Dwell, (b0, b1): (f64, f64), noise: f64, spring: f64) -> DwellReport {
    let start = w.force.0 - b0 - b1 * w.height.0;
    let end = w.force.1 - b0 - b1 * w.height.1;
    let advance = w.height.0 - w.height.1;
    let fall = start - end;
    let in_contact = start > 5.0 * noise;
    DwellReport {
        first_point: w.points.0,
        last_point: w.points.1,
        force_start_n: start,
        force_end_n: end,
        relaxation: in_contact.then(|| fall / start),
        base_advance_m: advance,
        indentation_creep_m: advance + fall / spring,
        relaxed: in_contact && fall > DWELL_RELAXED_SHARE * start && fall > 5.0 * noise,
    }
}

/// The fit's note where a relaxing dwell makes it fit the approach.
fn relaxed_dwell_note(w: &DwellReport) -> String {
    format!(
        "the approach was fitted, not the retract: the retract follows a dwell (points {}..{}) in which the force relaxed from {:.3e} N to {:.3e} N ({:.0}%), so it unloads a relaxed contact and is not a loading curve of the one the approach made",
        w.first_point,
        w.last_point,
        w.force_start_n,
        w.force_end_n,
        100.0 * w.relaxation.unwrap_or(0.0)
    )
}

/// The baseline: a line (flat without `opt.tilt`) through the far part of the approach (of the
/// retract where the approach has fewer than 5 points), and the rms of the points about it.
pub(super) fn baseline(curve: &Curve, opt: &FitOptions) -> ((f64, f64), f64) {
    let far_of = |d: Direction| -> Vec<usize> {
        let mut idx: Vec<usize> = (0..curve.len())
            .filter(|&i| curve.segment[i] == d)
            .collect();
        idx.sort_by(|&a, &b| curve.height[b].total_cmp(&curve.height[a]));
        let n = ((idx.len() as f64 * opt.baseline_fraction).ceil() as usize).max(3);
        idx.truncate(n);
        idx
    };
    let mut far = far_of(Direction::Approach);
    if far.len() < 5 {
        far = far_of(Direction::Retract);
    }
    let (b0, b1) = line_fit(
        &far.iter().map(|&i| curve.height[i]).collect::<Vec<_>>(),
        &far.iter().map(|&i| curve.force[i]).collect::<Vec<_>>(),
        opt.tilt,
    );
    let resid: Vec<f64> = far
        .iter()
        .map(|&i| curve.force[i] - b0 - b1 * curve.height[i])
        .collect();
    // The rms, scaled so that huge forces (1e200) do not overflow to an infinite noise.
    let scale = resid.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    let noise = if scale > 0.0 {
        scale
            * (resid.iter().map(|r| (r / scale).powi(2)).sum::<f64>() / resid.len().max(1) as f64)
                .sqrt()
    } else {
        0.0
    };
    ((b0, b1), noise)
}

/// The indices of a curve's points in one segment, in time order.
pub(super) fn segment_points(curve: &Curve, d: Direction) -> Vec<usize> {
    (0..curve.len())
        .filter(|&i| curve.segment[i] == d)
        .collect()
}

pub(super) fn seg_name(d: Direction) -> &'static str {
    if d == Direction::Approach {
        "approach"
    } else {
        "retract"
    }
}

/// One approach and one retract at most: a curve whose segment goes back to one it has left
/// holds several cycles (repeated cycles, or curves with the same id or pixel merged).
pub(super) fn check_cycles(curve: &Curve) -> Result<(), CurveError> {
    let changes: Vec<usize> = (1..curve.len())
        .filter(|&i| curve.segment[i] != curve.segment[i - 1])
        .collect();
    if changes.len() >= 2 {
        let at = changes[1];
        return Err(CurveError::Cycles {
            cycles: (changes.len() + 1).div_ceil(2),
            from: seg_name(curve.segment[at - 1]),
            to: seg_name(curve.segment[at]),
            point: at + 1,
        });
    }
    Ok(())
}

/// A segment's heights must run its way (the approach lowers the base, the retract raises it).
/// Measured heights jitter, by more than their step where the sampling is dense: what is
/// refused is a segment that runs the wrong way overall or goes back by a large part of its
/// span (a restart, or points out of time order); jitter is a note.
pub(super) fn check_order(curve: &Curve, d: Direction) -> Result<Option<String>, CurveError> {
    let idx = segment_points(curve, d);
    if idx.len() < 3 {
        return Ok(None);
    }
    let sign = if d == Direction::Approach { -1.0 } else { 1.0 };
    let name = seg_name(d);
    let h = |k: usize| curve.height[idx[k]];
    let n = idx.len();
    let (first, last) = (h(0), h(n - 1));
    let lo = (0..n).map(h).fold(f64::INFINITY, f64::min);
    let hi = (0..n).map(h).fold(f64::NEG_INFINITY, f64::max);
    let span = hi - lo;
    if !(sign * (last - first) > 0.0) {
        return Err(CurveError::Order {
            segment: name,
            first,
            last,
        });
    }
    // The largest way back: progress sign*h should grow; its largest fall below its running
    // maximum, and where.
    let (mut top, mut back, mut at) = (f64::NEG_INFINITY, 0.0f64, 0usize);
    for k in 0..n {
        let p = sign * h(k);
        top = top.max(p);
        if top - p > back {
            back = top - p;
            at = k;
        }
    }
    if back > 0.25 * span {
        return Err(CurveError::GoesBack {
            segment: name,
            back,
            span,
            point: idx[at] + 1,
        });
    }
    let wrong = (1..n).filter(|&k| sign * (h(k) - h(k - 1)) < 0.0).count();
    Ok((wrong * 4 > n).then(|| {
        format!(
            "the {name} heights jitter by up to {} m, more than their mean step of {} m ({wrong} of {} steps go back): they are fitted as measured",
            crate::physics::domain::short(back),
            crate::physics::domain::short(span / (n - 1) as f64),
            n - 1
        )
    }))
}

/// The quantile q (0..1) of sorted values.
pub(super) fn quantile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// The longest run of consecutive points taken for a spike.
pub(super) const MAX_SPIKE_RUN: usize = 3;

/// The points of one segment's forces (in time order) that are isolated spikes: outside the
/// segment's robust range (its 2%..98% quantiles widened by half their span on each side),
/// more than ten robust noise levels (the MAD of the second differences) from their
/// neighbours' line, and standing out against how much those neighbours differ themselves (so
/// that a sharp but genuine pull-off or snap-in is kept).
pub(super) fn spikes(f: &[f64]) -> Vec<usize> {
    let n = f.len();
    if n < 5 {
        return Vec::new();
    }
    let mut sorted = f.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (q02, q98) = (quantile(&sorted, 0.02), quantile(&sorted, 0.98));
    let range = q98 - q02;
    let out = |v: f64| v < q02 - 0.5 * range || v > q98 + 0.5 * range;
    let mut second: Vec<f64> = (1..n - 1)
        .map(|i| (f[i + 1] - 2.0 * f[i] + f[i - 1]).abs())
        .collect();
    second.sort_by(f64::total_cmp);
    // Of white noise sigma the second differences have sigma sqrt 6; the median of their
    // absolute values is 0.6745 of that.
    let sigma = (quantile(&second, 0.5) / 0.6745 / 6f64.sqrt()).max(1e-4 * range);
    let mut candidates: Vec<bool> = f.iter().map(|&v| out(v)).collect();
    // A spike is isolated: a run of more than MAX_SPIKE_RUN points beyond the range, or one at
    // either end of the segment, is the curve itself (the contact at the end of an approach
    // that is mostly baseline lies far beyond its quantiles), not a glitch.
    let mut i = 0;
    while i < n {
        if !candidates[i] {
            i += 1;
            continue;
        }
        let end = (i..n).find(|&j| !candidates[j]).unwrap_or(n);
        if end - i > MAX_SPIKE_RUN || i == 0 || end == n {
            candidates[i..end].fill(false);
        }
        i = end;
    }
    // The nearest points on each side that are not candidates.
    let left = |i: usize| (0..i).rev().find(|&j| !candidates[j]);
    let right = |i: usize| (i + 1..n).find(|&j| !candidates[j]);
    (0..n)
        .filter(|&i| candidates[i])
        .filter(|&i| {
            let (dev, spread) = match (left(i), right(i)) {
                (Some(a), Some(b)) => (f[i] - 0.5 * (f[a] + f[b]), (f[b] - f[a]).abs()),
                (None, Some(b)) => match right(b) {
                    Some(c) => (f[i] - f[b], (f[c] - f[b]).abs()),
                    None => return false,
                },
                (Some(a), None) => match left(a) {
                    Some(c) => (f[i] - f[a], (f[a] - f[c]).abs()),
                    None => return false,
                },
                (None, None) => return false,
            };
            dev.abs() > 10.0 * sigma && dev.abs() > 3.0 * spread
        })
        .collect()
}

/// The curve without its spikes and a note naming them, or None where there are none.
pub(super) fn drop_spikes(curve: &Curve) -> Option<(Curve, String)> {
    let mut drop = vec![false; curve.len()];
    let mut named = Vec::new();
    for d in [Direction::Approach, Direction::Retract] {
        let idx = segment_points(curve, d);
        let f: Vec<f64> = idx.iter().map(|&i| curve.force[i]).collect();
        for k in spikes(&f) {
            drop[idx[k]] = true;
            named.push(idx[k]);
        }
    }
    if named.is_empty() {
        return None;
    }
    named.sort_unstable();
    let keep = |v: &[f64]| -> Vec<f64> {
        v.iter()
            .zip(&drop)
            .filter(|(_, &x)| !x)
            .map(|(v, _)| *v)
            .collect()
    };
    let c = Curve {
        height: keep(&curve.height),
        force: keep(&curve.force),
        segment: curve
            .segment
            .iter()
            .zip(&drop)
            .filter(|(_, &x)| !x)
            .map(|(s, _)| *s)
            .collect(),
        ..curve.clone()
    };
    let list: Vec<String> = named
        .iter()
        .take(5)
        .map(|&i| {
            format!(
                "point {} (force {} N)",
                i + 1,
                crate::physics::domain::short(curve.force[i])
            )
        })
        .collect();
    let note = format!(
        "dropped {} outlier point{} far beyond the noise, isolated spikes that would steer the fit: {}{}",
        named.len(),
        if named.len() == 1 { "" } else { "s" },
        list.join(", "),
        if named.len() > 5 { ", ..." } else { "" }
    );
    Some((c, note))
}

/// The measured jump of each segment: on retract the largest rise of the force between
/// consecutive points (the jump-out), on approach the largest fall (the snap-in), where it is
/// larger than five times the noise and a third of the segment's most tensile force.
pub(super) fn measured_sides(force: &[f64], dir: &[Direction], noise: f64) -> Vec<Side> {
    let mut side = vec![Side::Any; force.len()];
    for d in [Direction::Approach, Direction::Retract] {
        let idx: Vec<usize> = (0..force.len()).filter(|&i| dir[i] == d).collect();
        if idx.len() < 3 {
            continue;
        }
        let sign = if d == Direction::Retract { 1.0 } else { -1.0 };
        let Some((k, step)) = idx
            .windows(2)
            .enumerate()
            .map(|(k, w)| (k, sign * (force[w[1]] - force[w[0]])))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            continue;
        };
        let tensile = idx.iter().map(|&i| -force[i]).fold(0.0, f64::max);
        if step > 5.0 * noise && step > tensile / 3.0 && tensile > 0.0 {
            for (n, &i) in idx.iter().enumerate() {
                side[i] = if n <= k {
                    Side::BeforeJump
                } else {
                    Side::AfterJump
                };
            }
        }
    }
    side
}

/// Points fitted by their distance to the curve: this many before each measured jump (the fold's
/// point and its neighbour, which the fitted fold may pass while the fit moves).
pub(super) const AT_JUMP_POINTS: usize = 2;

pub(super) fn last_before_jump(side: &[Side], dir: &[Direction]) -> Vec<bool> {
    let mut out = vec![false; side.len()];
    for d in [Direction::Approach, Direction::Retract] {
        let before: Vec<usize> = (0..side.len())
            .filter(|&i| dir[i] == d && side[i] == Side::BeforeJump)
            .collect();
        for &i in before.iter().rev().take(AT_JUMP_POINTS) {
            out[i] = true;
        }
    }
    out
}

pub(super) fn line_fit(x: &[f64], y: &[f64], tilt: bool) -> (f64, f64) {
    let n = x.len() as f64;
    let my = y.iter().sum::<f64>() / n;
    if !tilt || x.len() < 3 {
        return (my, 0.0);
    }
    let mx = x.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|v| (v - mx) * (v - mx)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let b1 = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (my - b1 * mx, b1)
}
