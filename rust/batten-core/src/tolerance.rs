//! The model tolerance: one distance that decides when two points are the same point.

use serde::{Deserialize, Serialize};

/// A tolerance that is zero, negative or not finite (the value given); it becomes
/// [`Error::Tolerance`](crate::Error::Tolerance) with `?`.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("tolerance {0} must be a positive finite number of metres")]
pub struct InvalidTolerance(pub f64);

/// Model tolerance in metres: points closer than this are the same point.
///
/// Every geometric comparison in batten derives its threshold from one `Tolerance`, never from
/// a bare literal (the fornjot `validation/config.rs` practice). It is always positive and finite.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct Tolerance(f64);

impl Tolerance {
    /// The default model tolerance, [`DEFAULT_TOLERANCE`](crate::DEFAULT_TOLERANCE) (0.1 mm).
    pub const DEFAULT: Tolerance = Tolerance(crate::defaults::DEFAULT_TOLERANCE);

    /// Validated constructor: rejects zero, negative and non-finite values.
    pub fn try_new(value: f64) -> Result<Self, InvalidTolerance> {
        if value.is_finite() && value > 0.0 {
            Ok(Tolerance(value))
        } else {
            Err(InvalidTolerance(value))
        }
    }

    /// The tolerance in metres.
    pub fn get(self) -> f64 {
        self.0
    }

    /// Distance below which two things are "nearly" touching: a gap between the tolerance and
    /// this is reported as a near miss rather than silently joined or left apart (10× tolerance).
    pub fn near_miss(self) -> f64 {
        10.0 * self.0
    }

    // --- topology and patches ---

    /// Accuracy to which the arc length of a face's side segment is measured (patch
    /// boundaries, H-rep §3.2.1): a tenth of the tolerance, well below the tolerance that a
    /// side must exceed and fine enough for dividing a composite side's parameter by lengths.
    pub fn side_length_accuracy(self) -> f64 {
        0.1 * self.0
    }

    // --- network and fairing ---

    /// Accuracy of the arc length that decides whether a curve is shorter than the tolerance:
    /// a thousandth of it, so the quadrature does not blur the decision.
    pub fn length_check_accuracy(self) -> f64 {
        self.0 * 1e-3
    }

    /// Accuracy of the closest points and arc lengths of the node search: a hundredth of the
    /// tolerance, so that a distance compared with the tolerance is decided by the curves and
    /// not by the search.
    pub fn search_accuracy(self) -> f64 {
        self.0 * 1e-2
    }

    /// Where Newton's method on the distance of two curves stops (distance, or step length):
    /// 10⁻⁴ tolerance, far below what the clustering of nodes can see.
    pub fn newton_accuracy(self) -> f64 {
        self.0 * 1e-4
    }

    /// Margin by which the broad phase grows every piece's box: half the near-miss distance,
    /// so the boxes of two pieces closer than that overlap.
    pub fn sweep_margin(self) -> f64 {
        0.5 * self.near_miss()
    }

    /// A curve meeting itself is a self-intersection only where the two parameters lie
    /// farther apart along it than this (twice the near-miss distance); closer, the pieces are
    /// neighbours.
    pub fn self_crossing_min_arc(self) -> f64 {
        2.0 * self.near_miss()
    }

    /// A near miss is reported only farther than this from every join of the same two curves
    /// (twice the near-miss distance): the approach beside a crossing is not a second finding.
    pub fn near_miss_clearance(self) -> f64 {
        2.0 * self.near_miss()
    }

    /// Near misses of one pair of curves closer to each other than this (10× the near-miss
    /// distance) are one finding, reported at the smallest gap.
    pub fn near_miss_merge(self) -> f64 {
        10.0 * self.near_miss()
    }

    /// Two curves share a stretch where one stays within this of the other (half the
    /// tolerance): the end of the stretch found by bisection is then well within the tolerance
    /// of where the curves part, or one of them ends.
    pub fn shared_stretch(self) -> f64 {
        0.5 * self.0
    }

    /// Shortest stretch along which two curves within tolerance make an overlap rather than a
    /// tangential touch (100 tolerances, with a fraction of the shorter curve), and the
    /// farthest a join of nearly tangent curves is moved to a curve end or a third curve's join.
    pub fn overlap_min_length(self) -> f64 {
        100.0 * self.0
    }
}

impl Default for Tolerance {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl TryFrom<f64> for Tolerance {
    type Error = InvalidTolerance;
    fn try_from(value: f64) -> Result<Self, InvalidTolerance> {
        Tolerance::try_new(value)
    }
}

impl From<Tolerance> for f64 {
    fn from(t: Tolerance) -> f64 {
        t.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_non_positive_and_non_finite() {
        for bad in [0.0, -1e-4, f64::NAN, f64::INFINITY] {
            assert!(Tolerance::try_new(bad).is_err(), "{bad} must be rejected");
        }
        assert_eq!(Tolerance::try_new(1e-3).unwrap().get(), 1e-3, "value kept");
        assert_eq!(Tolerance::DEFAULT.near_miss(), 1e-3, "near miss is 10x");
    }
}
