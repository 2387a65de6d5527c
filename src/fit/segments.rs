//! Approach and retract from the heights, whatever a file calls its segments: instruments
//! number them differently (a pause before the approach, a dwell at the turning point for
//! stress relaxation or creep, a pause after the retract), and some files keep the whole cycle
//! in one segment.

use super::path::Direction;
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
pub fn plan_segments(height: &[f64], segment: &[i64]) -> Result<SegmentPlan, String> {
    if height.len() != segment.len() {
        return Err(format!(
            "{} heights but {} segment values: give one segment value per point",
            height.len(),
            segment.len()
        ));
    }
    if let Some(i) = height.iter().position(|h| !h.is_finite()) {
        return Err(format!(
            "height {} at point {i} is not a finite number",
            height[i]
        ));
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
fn split_single(height: &[f64]) -> Result<SegmentPlan, String> {
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
        return Err(format!(
            "approach and retract are not separated: the curve is one segment and its heights have no clear turning point (the base goes down by {} m and back up by {} m of a {} m range); give the segment of each point (0 approach, 1 retract)",
            short(down),
            short(up),
            short(range)
        ));
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
    fn one_segment_is_split_at_a_clear_turn_and_refused_without_one() {
        let h = [5.0, 3.0, 1.0, 0.0, 2.0, 4.0];
        let p = plan_segments(&h, &[0; 6]).unwrap();
        assert_eq!(p.direction[..4], [Some(A); 4]);
        assert_eq!(p.direction[4..], [Some(R); 2]);
        assert!(p.notes[0].contains("point 3 of 6"));
        let e = plan_segments(&[5.0, 4.0, 3.0, 2.0, 1.0], &[0; 5]).unwrap_err();
        assert!(
            e.starts_with("approach and retract are not separated"),
            "{e}"
        );
        let e = plan_segments(&[1.0, f64::NAN], &[0, 1]).unwrap_err();
        assert!(e.contains("point 1"), "{e}");
    }
}
