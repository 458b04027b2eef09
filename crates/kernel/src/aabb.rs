//! Axis-aligned boxes: on the grid (`Aabb`, integer coordinates, exact), with
//! arbitrary-precision integer corners (`Aabb<Int>`, exact, for pieces beyond machine
//! integers), with rational corners (`Aabb<Rational>`, exact, for placement), and in
//! floating point (`Aabb<f64>`, for filters and pictures only).

use crate::int::Int;
use crate::plane::BigPlane;
use crate::{Rational, Vec3};
use std::cmp::Ordering;
use std::fmt::Debug;

/// A coordinate type of [`Aabb`]: ordered, with the smaller and larger of two values
/// (`i64` and `f64`, see [`Coord`], [`Int`] and [`Rational`]).
pub trait Bound: Clone + PartialOrd + Debug {
    /// The smaller of two values (`f64::min` for floats).
    fn min_of(&self, o: &Self) -> Self;
    /// The larger of two values (`f64::max` for floats).
    fn max_of(&self, o: &Self) -> Self;
}

/// A machine coordinate type of [`Aabb`] and of the broad phase ([`crate::bvh`]): `i64`
/// (grid points) or `f64`.
pub trait Coord: Bound + Copy + Send + Sync + 'static {
    /// The lowest value (the upper end of the empty box).
    const LOWEST: Self;
    /// The highest value (the lower end of the empty box).
    const HIGHEST: Self;
    /// A total order (`f64::total_cmp` for floats), for sorting.
    fn total_cmp(&self, o: &Self) -> Ordering;
    /// The value as a double (`as f64`), for orders that only affect speed.
    fn to_f64(self) -> f64;
    /// `a + b` against `c + d` (exactly for integers; the rounded sums for floats): box
    /// centres compared.
    fn cmp_sums(a: Self, b: Self, c: Self, d: Self) -> Ordering;
    /// `a − b` against `c − d` (exactly for integers; the rounded differences for
    /// floats): box extents compared.
    fn cmp_differences(a: Self, b: Self, c: Self, d: Self) -> Ordering;
}

impl Bound for i64 {
    #[inline]
    fn min_of(&self, o: &i64) -> i64 {
        (*self).min(*o)
    }
    #[inline]
    fn max_of(&self, o: &i64) -> i64 {
        (*self).max(*o)
    }
}

impl Coord for i64 {
    const LOWEST: i64 = i64::MIN;
    const HIGHEST: i64 = i64::MAX;
    #[inline]
    fn total_cmp(&self, o: &i64) -> Ordering {
        self.cmp(o)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn cmp_sums(a: i64, b: i64, c: i64, d: i64) -> Ordering {
        (a as i128 + b as i128).cmp(&(c as i128 + d as i128))
    }
    #[inline]
    fn cmp_differences(a: i64, b: i64, c: i64, d: i64) -> Ordering {
        (a as i128 - b as i128).cmp(&(c as i128 - d as i128))
    }
}

impl Bound for f64 {
    #[inline]
    fn min_of(&self, o: &f64) -> f64 {
        self.min(*o)
    }
    #[inline]
    fn max_of(&self, o: &f64) -> f64 {
        self.max(*o)
    }
}

impl Coord for f64 {
    const LOWEST: f64 = f64::NEG_INFINITY;
    const HIGHEST: f64 = f64::INFINITY;
    #[inline]
    fn total_cmp(&self, o: &f64) -> Ordering {
        f64::total_cmp(self, o)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn cmp_sums(a: f64, b: f64, c: f64, d: f64) -> Ordering {
        (a + b).total_cmp(&(c + d))
    }
    #[inline]
    fn cmp_differences(a: f64, b: f64, c: f64, d: f64) -> Ordering {
        (a - b).total_cmp(&(c - d))
    }
}

impl Bound for Int {
    fn min_of(&self, o: &Int) -> Int {
        self.min(o).clone()
    }
    fn max_of(&self, o: &Int) -> Int {
        self.max(o).clone()
    }
}

impl Bound for Rational {
    fn min_of(&self, o: &Rational) -> Rational {
        if o < self {
            o.clone()
        } else {
            self.clone()
        }
    }
    fn max_of(&self, o: &Rational) -> Rational {
        if o > self {
            o.clone()
        } else {
            self.clone()
        }
    }
}

/// A closed axis-aligned box; empty when some `min > max`. `Aabb` (of `i64`) holds grid
/// points exactly, `Aabb<Rational>` rational points exactly; `Aabb<f64>` serves float
/// filters and pictures.
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

    /// The box of a triangle or segment.
    #[inline]
    pub fn of<const N: usize>(ps: [&[T; 3]; N]) -> Aabb<T> {
        let mut b = Aabb::EMPTY;
        for p in ps {
            b = b.with(p);
        }
        b
    }
}

impl<T: Bound> Aabb<T> {
    /// The box of one point.
    #[inline]
    pub fn point(p: &[T; 3]) -> Aabb<T> {
        Aabb {
            min: p.clone(),
            max: p.clone(),
        }
    }

    /// The smallest box containing the points (`None` for none).
    pub fn of_points(points: &[[T; 3]]) -> Option<Aabb<T>> {
        let first = points.first()?;
        Some(points.iter().fold(Aabb::point(first), |b, p| b.with(p)))
    }

    /// The box from per-axis intervals `[[lo, hi]; 3]`.
    #[inline]
    pub fn from_axes(axes: &[[T; 2]; 3]) -> Aabb<T> {
        Aabb {
            min: [0, 1, 2].map(|k| axes[k][0].clone()),
            max: [0, 1, 2].map(|k| axes[k][1].clone()),
        }
    }

    /// The box grown to contain `p`.
    #[inline]
    pub fn with(mut self, p: &[T; 3]) -> Aabb<T> {
        for ((lo, hi), c) in self.min.iter_mut().zip(self.max.iter_mut()).zip(p) {
            *lo = lo.min_of(c);
            *hi = hi.max_of(c);
        }
        self
    }

    /// The smallest box containing both.
    #[inline]
    pub fn union(&self, o: &Aabb<T>) -> Aabb<T> {
        Aabb {
            min: [0, 1, 2].map(|k| self.min[k].min_of(&o.min[k])),
            max: [0, 1, 2].map(|k| self.max[k].max_of(&o.max[k])),
        }
    }

    /// The common part (maybe empty).
    #[inline]
    pub fn intersection(&self, o: &Aabb<T>) -> Aabb<T> {
        Aabb {
            min: [0, 1, 2].map(|k| self.min[k].max_of(&o.min[k])),
            max: [0, 1, 2].map(|k| self.max[k].min_of(&o.max[k])),
        }
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

    /// True for an empty box (some `min > max`: no point).
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

impl Aabb<Rational> {
    /// The smallest box containing the points `v / den` (integer vectors over one positive
    /// denominator, as a polytope stores its vertices). Panics for no points.
    pub fn of_scaled<'a>(points: impl IntoIterator<Item = &'a Vec3>, den: &Int) -> Aabb<Rational> {
        let mut it = points.into_iter();
        let first = it.next().expect("box of no points").to_ints();
        let (mut lo, mut hi) = (first.clone(), first);
        for v in it {
            for (k, c) in v.to_ints().into_iter().enumerate() {
                if c < lo[k] {
                    lo[k] = c;
                } else if c > hi[k] {
                    hi[k] = c;
                }
            }
        }
        Aabb {
            min: lo.map(|c| Rational::new(c, den.clone())),
            max: hi.map(|c| Rational::new(c, den.clone())),
        }
    }

    /// The box moved by the vector `t`.
    pub fn translated(&self, t: &[Rational; 3]) -> Aabb<Rational> {
        Aabb {
            min: crate::rational::add(&self.min, t),
            max: crate::rational::add(&self.max, t),
        }
    }

    /// A float box enclosing this one: each corner's nearest double moved outwards by
    /// a relative `1e-9` (far more than its rounding), for float broad phases.
    pub fn enclosing_f64(&self) -> Aabb<f64> {
        let pad = |x: f64| x.abs() * 1e-9 + 1e-300;
        Aabb {
            min: [0, 1, 2].map(|k| {
                let x = self.min[k].to_f64();
                x - pad(x)
            }),
            max: [0, 1, 2].map(|k| {
                let x = self.max[k].to_f64();
                x + pad(x)
            }),
        }
    }

    /// The box as six closed half-spaces (reduced): `x_k <= max_k` then `-x_k <= -min_k`
    /// for each axis `k` in turn.
    pub fn halfspaces(&self) -> Vec<BigPlane> {
        let mut out = Vec::with_capacity(6);
        for k in 0..3 {
            let mut n = [Int::ZERO, Int::ZERO, Int::ZERO];
            n[k] = Int::ONE;
            out.push(BigPlane::with_rational_offset(n.clone(), &self.max[k]));
            n[k] = -Int::ONE;
            out.push(BigPlane::with_rational_offset(n, &(-&self.min[k])));
        }
        out
    }

    /// The minimum of `n · p` over the box (at the corner each component of `n` points
    /// away from).
    pub fn min_dot(&self, n: &[Int; 3]) -> Rational {
        let mut s = Rational::zero();
        for (k, c) in n.iter().enumerate() {
            let v = if *c >= Int::ZERO {
                &self.min[k]
            } else {
                &self.max[k]
            };
            s = &s + &(&Rational::from_int(c.clone()) * v);
        }
        s
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
    fn rational_boxes() {
        let r = |n: i64, d: i64| Rational::from_i128(n as i128, d as i128);
        let pts = [Vec3::new(1, -2, 3), Vec3::new(-1, 4, 3), Vec3::new(0, 0, 5)];
        let b = Aabb::of_scaled(&pts, &Int::from(2));
        assert_eq!(b.min, [r(-1, 2), r(-1, 1), r(3, 2)]);
        assert_eq!(b.max, [r(1, 2), r(2, 1), r(5, 2)]);
        let t = b.translated(&[r(1, 2), r(0, 1), r(-3, 2)]);
        assert_eq!((t.min[0].clone(), t.max[2].clone()), (r(0, 1), r(1, 1)));
        let u = b.union(&t);
        assert_eq!((u.min[2].clone(), u.max[0].clone()), (r(0, 1), r(1, 1)));
        assert!(!u.is_empty());
        let e = Aabb {
            min: b.max.clone(),
            max: b.min.clone(),
        };
        assert!(e.is_empty());
        let f = b.enclosing_f64();
        assert!(f.min[0] < -0.5 && f.min[0] > -0.5000001 && f.max[2] > 2.5);
        // x + 2y - z is smallest at (min x, min y, max z) = (-1/2, -1, 5/2).
        assert_eq!(b.min_dot(&[1, 2, -1].map(Int::from)), r(-5, 1));
        let h = b.halfspaces();
        assert_eq!(h.len(), 6);
        let corner = crate::HPoint::from_rationals(&b.max);
        assert!(h.iter().all(|p| p.side(&corner) != crate::Sign::Positive));
        assert_eq!(h[0].side(&corner), crate::Sign::Zero);
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
