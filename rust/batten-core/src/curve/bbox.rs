//! Axis-aligned bounding boxes.

use glam::DVec3;

/// An axis-aligned box `[min, max]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner.
    pub max: DVec3,
}

impl Aabb {
    /// The box of one point.
    pub fn from_point(p: DVec3) -> Aabb {
        Aabb { min: p, max: p }
    }

    /// The smallest box holding every point (`None` for no points).
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Option<Aabb> {
        let mut it = points.into_iter();
        let first = it.next()?;
        Some(it.fold(Aabb::from_point(first), |b, p| b.including(p)))
    }

    /// This box grown to hold `p`.
    pub fn including(self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both.
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Length of the diagonal: the box's size.
    pub fn diagonal(&self) -> f64 {
        (self.max - self.min).length()
    }

    /// True when `other` lies inside this box.
    pub fn contains_box(&self, other: &Aabb) -> bool {
        self.min.cmple(other.min).all() && self.max.cmpge(other.max).all()
    }

    /// Distance from `p` to the box (0 inside): a lower bound of the distance to anything in it.
    pub fn distance_to(&self, p: DVec3) -> f64 {
        let d = (self.min - p).max(p - self.max).max(DVec3::ZERO);
        d.length()
    }

    /// Distance between two boxes (0 when they overlap): a lower bound of the distance between
    /// anything inside them.
    pub fn gap_to(&self, other: &Aabb) -> f64 {
        (self.min - other.max)
            .max(other.min - self.max)
            .max(DVec3::ZERO)
            .length()
    }

    /// The box grown by `margin` on every side.
    pub fn expanded(&self, margin: f64) -> Aabb {
        Aabb {
            min: self.min - DVec3::splat(margin),
            max: self.max + DVec3::splat(margin),
        }
    }

    /// True when the boxes overlap (touching counts).
    pub fn intersects(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }
}
