//! Axis-aligned boxes: on the grid (`Aabb`, integer coordinates, exact) and in floating
//! point (`Aabb<f64>`, for filters and pictures only).

use std::cmp::Ordering;
use std::fmt::Debug;

/// A coordinate type of [`Aabb`]: `i64` (grid points) or `f64`.
pub trait Coord: Copy + PartialOrd + Debug + Send + Sync + 'static {
    /// The lowest value (the upper end of the empty box).
    const LOWEST: Self;
    /// The highest value (the lower end of the empty box).
    const HIGHEST: Self;
    /// The smaller of two values (`f64::min` for floats).
    fn min_of(self, o: Self) -> Self;
    /// The larger of two values (`f64::max` for floats).
    fn max_of(self, o: Self) -> Self;
    /// A total order (`f64::total_cmp` for floats), for sorting.
    fn total_cmp(&self, o: &Self) -> Ordering;
    /// The value as a double (`as f64`), for orders that only affect speed.
    fn to_f64(self) -> f64;
}

impl Coord for i64 {
    const LOWEST: i64 = i64::MIN;
    const HIGHEST: i64 = i64::MAX;
    #[inline]
    fn min_of(self, o: i64) -> i64 {
        self.min(o)
    }
    #[inline]
    fn max_of(self, o: i64) -> i64 {
        self.max(o)
    }
    #[inline]
    fn total_cmp(&self, o: &i64) -> Ordering {
        self.cmp(o)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
}

impl Coord for f64 {
    const LOWEST: f64 = f64::NEG_INFINITY;
    const HIGHEST: f64 = f64::INFINITY;
    #[inline]
    fn min_of(self, o: f64) -> f64 {
        self.min(o)
    }
    #[inline]
    fn max_of(self, o: f64) -> f64 {
        self.max(o)
    }
    #[inline]
    fn total_cmp(&self, o: &f64) -> Ordering {
        f64::total_cmp(self, o)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
}

/// A closed axis-aligned box; empty when some `min > max`. `Aabb` (of `i64`) holds grid
/// points exactly; `Aabb<f64>` serves float filters and pictures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Aabb<T = i64> {
    /// Smallest coordinates.
    pub min: [T; 3],
    /// Largest coordinates.
    pub max: [T; 3],
}

impl<T: Coord> Aabb<T> {
    /// The empty box (the identity of [`Aabb::union`]).
    pub const EMPTY: Aabb<T> = Aabb {
        min: [T::HIGHEST; 3],
        max: [T::LOWEST; 3],
    };

    /// The box of one point.
    #[inline]
    pub fn point(p: &[T; 3]) -> Aabb<T> {
        Aabb { min: *p, max: *p }
    }

    /// The smallest box containing the points (`None` for none).
    pub fn of_points(points: &[[T; 3]]) -> Option<Aabb<T>> {
        let first = points.first()?;
        Some(points.iter().fold(Aabb::point(first), |b, p| b.with(p)))
    }

    /// The box of a triangle or segment.
    #[inline]
    pub fn of<const N: usize>(ps: [&[T; 3]; N]) -> Aabb<T> {
        let mut b = Aabb::EMPTY;
        for p in ps {
            b = b.with(p);
        }
        b
    }

    /// The box from per-axis intervals `[[lo, hi]; 3]`.
    #[inline]
    pub fn from_axes(axes: &[[T; 2]; 3]) -> Aabb<T> {
        Aabb {
            min: [axes[0][0], axes[1][0], axes[2][0]],
            max: [axes[0][1], axes[1][1], axes[2][1]],
        }
    }

    /// The box grown to contain `p`.
    #[inline]
    pub fn with(mut self, p: &[T; 3]) -> Aabb<T> {
        for ((lo, hi), &c) in self.min.iter_mut().zip(self.max.iter_mut()).zip(p) {
            *lo = (*lo).min_of(c);
            *hi = (*hi).max_of(c);
        }
        self
    }

    /// The smallest box containing both.
    #[inline]
    pub fn union(&self, o: &Aabb<T>) -> Aabb<T> {
        let mut b = *self;
        for k in 0..3 {
            b.min[k] = b.min[k].min_of(o.min[k]);
            b.max[k] = b.max[k].max_of(o.max[k]);
        }
        b
    }

    /// The common part (maybe empty).
    #[inline]
    pub fn intersection(&self, o: &Aabb<T>) -> Aabb<T> {
        let mut b = *self;
        for k in 0..3 {
            b.min[k] = b.min[k].max_of(o.min[k]);
            b.max[k] = b.max[k].min_of(o.max[k]);
        }
        b
    }

    /// True when the closed boxes share a point.
    #[inline]
    pub fn overlaps(&self, o: &Aabb<T>) -> bool {
        (0..3).all(|k| self.min[k] <= o.max[k] && o.min[k] <= self.max[k])
    }

    /// True when the closed boxes share an interior point (volume, not just a face).
    #[inline]
    pub fn overlaps_open(&self, o: &Aabb<T>) -> bool {
        (0..3).all(|k| self.min[k] < o.max[k] && o.min[k] < self.max[k])
    }

    /// True when the box contains `p`.
    #[inline]
    pub fn contains(&self, p: &[T; 3]) -> bool {
        (0..3).all(|k| self.min[k] <= p[k] && p[k] <= self.max[k])
    }

    /// True for the empty box.
    #[inline]
    pub fn is_empty(&self) -> bool {
        (0..3).any(|k| self.min[k] > self.max[k])
    }
}

impl Aabb<f64> {
    /// The centre (the origin for the empty box).
    pub fn center(&self) -> [f64; 3] {
        if self.is_empty() {
            return [0.0; 3];
        }
        [0, 1, 2].map(|k| 0.5 * (self.min[k] + self.max[k]))
    }

    /// The length of the diagonal (0 for the empty box).
    pub fn diagonal(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        crate::fvec::norm(crate::fvec::sub(self.max, self.min))
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
        assert!(!Aabb::EMPTY.overlaps(&a) && Aabb::<i64>::EMPTY.is_empty());
        assert_eq!(a.union(&b).max, [3, 2, 2]);
        assert!(a.intersection(&Aabb::of([&[5, 5, 5]])).is_empty());
        assert!(a.contains(&[1, 2, 0]) && !a.contains(&[1, 3, 0]));
    }

    #[test]
    fn float_boxes() {
        let mut b = Aabb::<f64>::EMPTY;
        assert!(b.is_empty() && b.diagonal() == 0.0 && b.center() == [0.0; 3]);
        b = b.with(&[0.0, 0.0, 0.0]).with(&[2.0, 4.0, 4.0]);
        assert_eq!(b.center(), [1.0, 2.0, 2.0]);
        assert_eq!(b.diagonal(), 6.0);
        let c = Aabb::from_axes(&[[1.0, 3.0], [4.0, 5.0], [-1.0, 0.0]]);
        assert!(b.overlaps(&c) && !b.overlaps_open(&c));
    }
}
