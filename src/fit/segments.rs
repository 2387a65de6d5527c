//! Approach and retract from the heights, whatever a file calls its segments: instruments
//! number them differently (a pause before the approach, a dwell at the turning point for
//! stress relaxation or creep, a pause after the retract), and some files keep the whole cycle
//! in one segment.

use super::CurveError;
use crate::law::follow::Direction;
use crate::physics::domain::short;

/// A run of one segment id moves the base by less than this share of the largest run's
/// movement: a dwell or a pause, not part of the force curve.
pub const DWELL_SHARE: f64 = 0.1;

/// The direction of each point (None: a dwell, dropped) and what was done, in words.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentPlan {
    /// Approach, retract, or None for a point of a dwell.
    pub direction: Vec<Option<Direction>>,
    /// One sentence for each dwell dropped or segment split, for the fit's warnings.
    pub notes: Vec<String>,
}

/// Maps a curve's points to approach and retract by its heights (the base's height, larger
/// away from the sample): each run of one segment id is an approach where its heights fall, a
/// retract where they rise, and a dwell, dropped, where the base moves by less than
/// [`DWELL_SHARE`] of the largest run's movement. A curve in a single run is split at its
/// lowest height when that is a clear turning point (the base goes down and back up by at least
/// half the heights' range each way); otherwise the message says that approach and retract are
/// not separated.
pub fn plan_segments(height: &[f64], segment: &[i64]) -> Result<SegmentPlan, CurveError> {
    if height.len() != segment.len() {
        return Err(CurveError::SegmentCount {
            heights: height.len(),
            segments: segment.len(),
        });
    }
    if let Some(i) = height.iter().position(|h| !h.is_finite()) {
        return Err(CurveError::Height {
            value: height[i],
            point: i,
        });
    }
    let runs = runs(segment);
    if runs.len() == 1 {
        return split_single(height);
    }
    let moved = |&(a, b): &(usize, usize)| height[b - 1] - height[a];
    let largest = runs.iter().map(|r| moved(r).abs()).fold(0.0, f64::max);
    let mut plan = SegmentPlan {
        direction: vec![None; height.len()],
        notes: Vec::new(),
    };
    for r in &runs {
        let d = moved(r);
        let dir = if !(d.abs() >= DWELL_SHARE * largest) {
            plan.notes.push(format!(
                "segment {} (points {}..{}) moves the base by {} m of the {} m the curve spans: a dwell, left out of the fit",
                segment[r.0],
                r.0,
                r.1 - 1,
                short(d),
                short(largest)
            ));
            None
        } else if d < 0.0 {
            Some(Direction::Approach)
        } else {
            Some(Direction::Retract)
        };
        plan.direction[r.0..r.1].fill(dir);
    }
    Ok(plan)
}

/// A dwell at the turn: the points left out between the approach's last point and the
/// retract's first, where the base is held (stress relaxation: the force relaxes) or the force
/// is (creep: the indentation grows).
#[derive(Clone, Debug, PartialEq)]
pub struct Dwell {
    /// Its first and last points, numbered as read (from 0).
    pub points: (usize, usize),
    /// The base height at its start and at its end (m).
    pub height: (f64, f64),
    /// The force at its start and at its end (N, as measured: the baseline not removed).
    pub force: (f64, f64),
}

/// The points at each end of a dwell whose median is its value there: a spike is not taken
/// for the start, and a relaxation (fastest at the start) is not averaged away.
const DWELL_ENDS: usize = 5;

/// The dwell at the turn of a planned curve (see [`Dwell`]), or None where nothing is left out
/// between approach and retract.
pub fn dwell_at_turn(
    direction: &[Option<Direction>],
    height: &[f64],
    force: &[f64],
) -> Option<Dwell> {
    let last_approach = direction
        .iter()
        .rposition(|d| *d == Some(Direction::Approach))?;
    let first_retract = direction
        .iter()
        .position(|d| *d == Some(Direction::Retract))?;
    let (a, b) = (last_approach + 1, first_retract);
    if b <= a || b > height.len().min(force.len()) {
        return None;
    }
    let k = DWELL_ENDS.min(b - a);
    let median = |v: &[f64]| {
        let mut s = v.to_vec();
        s.sort_by(f64::total_cmp);
        let m = s.len() / 2;
        if s.len() % 2 == 1 {
            s[m]
        } else {
            0.5 * (s[m - 1] + s[m])
        }
    };
    Some(Dwell {
        points: (a, b - 1),
        height: (median(&height[a..a + k]), median(&height[b - k..b])),
        force: (median(&force[a..a + k]), median(&force[b - k..b])),
    })
}

/// The runs `[start, end)` of equal consecutive segment ids.
fn runs(segment: &[i64]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=segment.len() {
        if i == segment.len() || segment[i] != segment[start] {
            if i > start {
                out.push((start, i));
            }
            start = i;
        }
    }
    out
}

/// One run: approach to the lowest height, retract after it, where that is a clear turn.
fn split_single(height: &[f64]) -> Result<SegmentPlan, CurveError> {
    let n = height.len();
    let (lo, hi) = height
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| {
            (a.min(h), b.max(h))
        });
    let turn = height
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |m| m.0);
    let range = hi - lo;
    let (down, up) = (height[0] - lo, height[n.max(1) - 1] - lo);
    if n < 4 || !(range > 0.0) || down < 0.5 * range || up < 0.5 * range {
        return Err(CurveError::NotSeparated { down, up, range });
    }
    let mut direction = vec![Some(Direction::Approach); n];
    direction[turn + 1..].fill(Some(Direction::Retract));
    Ok(SegmentPlan {
        direction,
        notes: vec![format!(
            "approach and retract were one segment in the file: split at the lowest height (point {turn} of {n})"
        )],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use Direction::{Approach as A, Retract as R};

    #[test]
    fn a_pause_and_a_dwell_are_dropped_and_the_rest_follows_the_heights() {
        // A pause (ids 0), an approach (1), a dwell creeping by 2% (2), a retract (3): the ids
        // of a stress-relaxation file.
        let mut h = vec![10.0; 3];
        h.extend([9.0, 7.0, 5.0, 3.0, 1.0]);
        h.extend([0.9, 0.8]);
        h.extend([2.0, 5.0, 9.0]);
        let seg = [0, 0, 0, 1, 1, 1, 1, 1, 2, 2, 3, 3, 3];
        let p = plan_segments(&h, &seg).unwrap();
        let want = [
            None,
            None,
            None,
            Some(A),
            Some(A),
            Some(A),
            Some(A),
            Some(A),
            None,
            None,
        ]
        .into_iter()
        .chain([Some(R); 3])
        .collect::<Vec<_>>();
        assert_eq!(p.direction, want);
        assert_eq!(p.notes.len(), 2);
        assert!(
            p.notes[1].contains("segment 2 (points 8..9)"),
            "{:?}",
            p.notes
        );
        // Direction from the heights, not the id: a file whose approach is id 1 and retract 0.
        let q = plan_segments(&[3.0, 2.0, 1.0, 2.0, 3.0], &[1, 1, 1, 0, 0]).unwrap();
        assert_eq!(
            q.direction,
            vec![Some(A), Some(A), Some(A), Some(R), Some(R)]
        );
    }

    #[test]
    fn the_dwell_at_the_turn_is_the_points_between_approach_and_retract() {
        // A pause (left out, not a dwell at the turn), the approach, 7 dwell points, the retract.
        let d = [
            None,
            Some(A),
            Some(A),
            None,
            None,
            None,
            None,
            None,
            None,
            None,
            Some(R),
        ];
        let h = [9.0, 5.0, 1.0, 1.0, 1.0, 1.0, 0.9, 0.8, 0.8, 0.8, 2.0];
        // A spike at the dwell's start is not its start: the median of its first 5 points.
        let f = [0.0, 0.0, 5.0, 50.0, 5.0, 4.0, 3.0, 2.0, 2.0, 2.0, 1.0];
        let w = dwell_at_turn(&d, &h, &f).unwrap();
        assert_eq!(w.points, (3, 9));
        assert_eq!(w.height, (1.0, 0.8));
        assert_eq!(w.force, (4.0, 2.0));
        // Two points: the mean of both.
        let two = [Some(A), None, None, Some(R)];
        let w = dwell_at_turn(&two, &[2.0, 1.0, 1.0, 2.0], &[0.0, 4.0, 2.0, 0.0]).unwrap();
        assert_eq!((w.points, w.force), ((1, 2), (3.0, 3.0)));
        // Nothing left out at the turn, or no retract: no dwell.
        assert_eq!(
            dwell_at_turn(&[Some(A), Some(R)], &[1.0, 2.0], &[0.0; 2]),
            None
        );
        assert_eq!(
            dwell_at_turn(&[Some(A), None], &[1.0, 1.0], &[0.0; 2]),
            None
        );
    }

    #[test]
    fn one_segment_is_split_at_a_clear_turn_and_refused_without_one() {
        let h = [5.0, 3.0, 1.0, 0.0, 2.0, 4.0];
        let p = plan_segments(&h, &[0; 6]).unwrap();
        assert_eq!(p.direction[..4], [Some(A); 4]);
        assert_eq!(p.direction[4..], [Some(R); 2]);
        assert!(p.notes[0].contains("point 3 of 6"));
        let e = plan_segments(&[5.0, 4.0, 3.0, 2.0, 1.0], &[0; 5]).unwrap_err();
        assert!(
            matches!(e, super::CurveError::NotSeparated { up, .. } if up == 0.0)
                && e.to_string()
                    .starts_with("approach and retract are not separated"),
            "{e}"
        );
        let e = plan_segments(&[1.0, f64::NAN], &[0, 1]).unwrap_err();
        assert!(
            matches!(e, super::CurveError::Height { point: 1, .. })
                && e.to_string().contains("point 1"),
            "{e}"
        );
    }
}
