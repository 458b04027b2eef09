//! Axis-aligned boxes on the grid.

/// A closed axis-aligned box of grid points; empty when some `min > max`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Aabb {
    /// Smallest coordinates.
    pub min: [i64; 3],
    /// Largest coordinates.
    pub max: [i64; 3],
}

impl Aabb {
    /// The empty box (the identity of [`Aabb::union`]).
    pub const EMPTY: Aabb = Aabb {
        min: [i64::MAX; 3],
        max: [i64::MIN; 3],
    };

    /// The box of one point.
    #[inline]
    pub fn point(p: &[i64; 3]) -> Aabb {
        Aabb { min: *p, max: *p }
    }

    /// The smallest box containing the points (`None` for none).
    pub fn of_points(points: &[[i64; 3]]) -> Option<Aabb> {
        let first = points.first()?;
        Some(points.iter().fold(Aabb::point(first), |b, p| b.with(p)))
    }

    /// The box of a triangle or segment.
    #[inline]
    pub fn of<const N: usize>(ps: [&[i64; 3]; N]) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in ps {
            b = b.with(p);
        }
        b
    }

    /// The box grown to contain `p`.
    #[inline]
    pub fn with(mut self, p: &[i64; 3]) -> Aabb {
        for ((lo, hi), &c) in self.min.iter_mut().zip(self.max.iter_mut()).zip(p) {
            *lo = (*lo).min(c);
            *hi = (*hi).max(c);
        }
        self
    }

    /// The smallest box containing both.
    #[inline]
    pub fn union(&self, o: &Aabb) -> Aabb {
        let mut b = *self;
        for k in 0..3 {
            b.min[k] = b.min[k].min(o.min[k]);
            b.max[k] = b.max[k].max(o.max[k]);
        }
        b
    }

    /// The common part (maybe empty).
    #[inline]
    pub fn intersection(&self, o: &Aabb) -> Aabb {
        let mut b = *self;
        for k in 0..3 {
            b.min[k] = b.min[k].max(o.min[k]);
            b.max[k] = b.max[k].min(o.max[k]);
        }
        b
    }

    /// True when the closed boxes share a point.
    #[inline]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        (0..3).all(|k| self.min[k] <= o.max[k] && o.min[k] <= self.max[k])
    }

    /// True when the closed boxes share an interior point (volume, not just a face).
    #[inline]
    pub fn overlaps_open(&self, o: &Aabb) -> bool {
        (0..3).all(|k| self.min[k] < o.max[k] && o.min[k] < self.max[k])
    }

    /// True when the box contains `p`.
    #[inline]
    pub fn contains(&self, p: &[i64; 3]) -> bool {
        (0..3).all(|k| self.min[k] <= p[k] && p[k] <= self.max[k])
    }

    /// True for the empty box.
    #[inline]
    pub fn is_empty(&self) -> bool {
        (0..3).any(|k| self.min[k] > self.max[k])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes() {
        let a = Aabb::of([&[0, 0, 0], &[2, 2, 2]]);
        let b = Aabb::of([&[2, 0, 0], &[3, 1, 1]]);
        assert!(a.overlaps(&b) && !a.overlaps_open(&b));
        assert!(!Aabb::EMPTY.overlaps(&a) && Aabb::EMPTY.is_empty());
        assert_eq!(a.union(&b).max, [3, 2, 2]);
        assert!(a.intersection(&Aabb::of([&[5, 5, 5]])).is_empty());
        assert!(a.contains(&[1, 2, 0]) && !a.contains(&[1, 3, 0]));
    }
}
