//! Exact planes (half-spaces) and the homogeneous points where they meet, with the
//! float filter of their side test.
//!
//! A [`Plane`] is `n · x = c` with a primitive `i128` normal, and as a half-space its
//! inner side `n · x <= c`; a [`BigPlane`] is the same with arbitrary-precision
//! coefficients. An [`HPoint`] has homogeneous integer coordinates `(X, W)`, `W > 0`,
//! reduced by their gcd, so that equal points have equal representations; it carries a
//! float shadow for the side filter.
//!
//! Bit bounds for planes through three points with coordinates below `2^B` (or planes of
//! an axis-aligned box): the primitive normal has at most `2B + 3` bits and the offset
//! at most `3B + 5` (`B <= 40`: both fit `i128`). A point built from its definition (a
//! grid point, the intersection of a segment with a plane, or of three planes), never
//! by chaining constructions, has for three planes `W = det(n1, n2, n3)` of at most
//! `6B + 12` bits and `X` of at most `7B + 15`; a side test `n·X - c·W` at most `9B + 20`.

use crate::aabb::Aabb;
use crate::int::{self, Int};
use crate::{Rational, Sign};
use std::hash::{Hash, Hasher};

const U: f64 = f64::EPSILON / 2.0;
/// Relative error bound of the side filter. Inputs: normal components and offset rounded
/// once (u each), point coordinates X_i / W from two roundings and a division (2u + 2u + u
/// with the kernel's 2^-52 conversion bound); products add u, three additions add 3u: the
/// value is within 12u of `P = Σ|n_i x_i| + |c|`. Padded to 32u for the computed `P`.
const SIDE_ERR: f64 = 32.0 * U;

/// The plane `n · x = c`; as a half-space, `n · x <= c` is its inner side.
///
/// Equality and hashing are those of `(n, c)`; the floating-point shadow only serves
/// the filter.
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    /// Normal, a primitive integer vector.
    pub n: [i128; 3],
    /// Offset.
    pub c: i128,
    nf: [f64; 3],
    cf: f64,
}

impl PartialEq for Plane {
    fn eq(&self, o: &Self) -> bool {
        self.n == o.n && self.c == o.c
    }
}
impl Eq for Plane {}
impl Hash for Plane {
    fn hash<H: Hasher>(&self, h: &mut H) {
        self.n.hash(h);
        self.c.hash(h);
    }
}

fn gcd3(v: &[i128; 3]) -> u128 {
    let g = int::gcd_u128(v[0].unsigned_abs(), v[1].unsigned_abs());
    int::gcd_u128(g, v[2].unsigned_abs())
}

impl Plane {
    /// The plane `n · x = c` (`n` primitive).
    pub fn new(n: [i128; 3], c: i128) -> Plane {
        Plane {
            n,
            c,
            nf: n.map(|v| v as f64),
            cf: c as f64,
        }
    }

    /// The plane through `a`, `b`, `c` with normal `(b - a) × (c - a)` made primitive, or
    /// `None` when the points are collinear. Coordinates must be below `2^41`.
    pub fn through(a: &[i64; 3], b: &[i64; 3], c: &[i64; 3]) -> Option<Plane> {
        let u = sub(b, a);
        let v = sub(c, a);
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        Plane::with_normal(n, a)
    }

    /// The plane with normal direction `n` (any non-zero integer vector, made primitive)
    /// through the integer point `a`.
    pub fn with_normal(n: [i128; 3], a: &[i64; 3]) -> Option<Plane> {
        let g = gcd3(&n);
        if g == 0 {
            return None;
        }
        let g = g as i128;
        let n = [n[0] / g, n[1] / g, n[2] / g];
        let c = n[0] * a[0] as i128 + n[1] * a[1] as i128 + n[2] * a[2] as i128;
        Some(Plane::new(n, c))
    }

    /// The same plane with the opposite orientation.
    pub fn flipped(&self) -> Plane {
        Plane {
            n: self.n.map(|v| -v),
            c: -self.c,
            nf: self.nf.map(|v| -v),
            cf: -self.cf,
        }
    }

    /// The orientation-free representative: the first non-zero normal component positive.
    pub fn unoriented(&self) -> Plane {
        let first = self.n.iter().find(|&&v| v != 0).copied().unwrap_or(0);
        if first < 0 {
            self.flipped()
        } else {
            *self
        }
    }

    /// Exact sign of `n · p - c` for an integer point.
    #[inline]
    pub fn side_int(&self, p: &[i64; 3]) -> Sign {
        match dot_minus(&self.n, p, self.c) {
            Some(v) => Sign::of_i128(v),
            None => int::sign_of(&big_side(&self.n, self.c, &p.map(Int::from), &Int::ONE)),
        }
    }

    /// Exact sign of `n · p - c`: positive above the plane (outside the inner side).
    #[inline]
    pub fn side(&self, p: &HPoint) -> Sign {
        if let Some(q) = &p.int {
            return self.side_int(q);
        }
        if p.filterable {
            let (n, c) = (self.nf, self.cf);
            let t = [n[0] * p.f[0], n[1] * p.f[1], n[2] * p.f[2]];
            let v = t[0] + t[1] + t[2] - c;
            let bound = SIDE_ERR * (t[0].abs() + t[1].abs() + t[2].abs() + c.abs());
            if v > bound {
                return Sign::Positive;
            }
            if v < -bound {
                return Sign::Negative;
            }
        }
        int::sign_of(&big_side(&self.n, self.c, &p.x, &p.w))
    }

    /// The normal as arbitrary-precision integers.
    pub fn normal_ints(&self) -> [Int; 3] {
        self.n.map(Int::from)
    }
}

fn sub(b: &[i64; 3], a: &[i64; 3]) -> [i128; 3] {
    [
        b[0] as i128 - a[0] as i128,
        b[1] as i128 - a[1] as i128,
        b[2] as i128 - a[2] as i128,
    ]
}

/// `n · p - c` in `i128`, or `None` on overflow.
#[inline]
fn dot_minus(n: &[i128; 3], p: &[i64; 3], c: i128) -> Option<i128> {
    let a = n[0].checked_mul(p[0] as i128)?;
    let b = n[1].checked_mul(p[1] as i128)?;
    let d = n[2].checked_mul(p[2] as i128)?;
    a.checked_add(b)?.checked_add(d)?.checked_sub(c)
}

fn big_side(n: &[i128; 3], c: i128, x: &[Int; 3], w: &Int) -> Int {
    Int::from(n[0]) * &x[0] + Int::from(n[1]) * &x[1] + Int::from(n[2]) * &x[2] - Int::from(c) * w
}

/// A point with homogeneous integer coordinates `X / W`, `W > 0`, reduced.
#[derive(Clone, Debug)]
pub struct HPoint {
    x: [Int; 3],
    w: Int,
    /// `X / W` in floating point, each within relative error 5u.
    f: [f64; 3],
    /// False when the shadow could not be computed safely (values beyond the f64 range).
    filterable: bool,
    /// The coordinates when `W = 1` and they fit `i64`.
    int: Option<[i64; 3]>,
}

impl PartialEq for HPoint {
    fn eq(&self, o: &Self) -> bool {
        self.w == o.w && self.x == o.x
    }
}
impl Eq for HPoint {}
impl Hash for HPoint {
    fn hash<H: Hasher>(&self, h: &mut H) {
        self.x.hash(h);
        self.w.hash(h);
    }
}

impl HPoint {
    /// An integer point.
    pub fn int(p: [i64; 3]) -> HPoint {
        HPoint {
            x: p.map(Int::from),
            w: Int::ONE,
            f: p.map(|v| v as f64),
            filterable: true,
            int: Some(p),
        }
    }

    /// The point `x / w` (`w != 0`), reduced.
    pub fn from_wide(x: [i128; 3], w: i128) -> HPoint {
        debug_assert!(w != 0);
        let (x, w) = if w < 0 { (x.map(|v| -v), -w) } else { (x, w) };
        let g = int::gcd_u128(gcd3(&x), w as u128) as i128;
        let (x, w) = if g > 1 {
            (x.map(|v| v / g), w / g)
        } else {
            (x, w)
        };
        if w == 1 && x.iter().all(|v| i64::try_from(*v).is_ok()) {
            return HPoint::int(x.map(|v| v as i64));
        }
        HPoint::finish(x.map(Int::from), Int::from(w))
    }

    /// The point `x / w` (`w != 0`), reduced.
    pub fn from_big(x: [Int; 3], w: Int) -> HPoint {
        debug_assert!(w != Int::ZERO);
        let (x, w) = if w < Int::ZERO {
            (x.map(|v| -v), -w)
        } else {
            (x, w)
        };
        let g = if w == Int::ONE {
            Int::ONE
        } else {
            int::gcd(&int::gcd(&int::gcd(&x[0], &x[1]), &x[2]), &w)
        };
        let (x, w) = if g > Int::ONE {
            (x.map(|v| v / &g), w / &g)
        } else {
            (x, w)
        };
        if w == Int::ONE {
            if let [Some(a), Some(b), Some(c)] =
                [int::to_i64(&x[0]), int::to_i64(&x[1]), int::to_i64(&x[2])]
            {
                return HPoint::int([a, b, c]);
            }
        }
        HPoint::finish(x, w)
    }

    fn finish(x: [Int; 3], w: Int) -> HPoint {
        let wf = int::to_f64(&w);
        let f = [
            int::to_f64(&x[0]) / wf,
            int::to_f64(&x[1]) / wf,
            int::to_f64(&x[2]) / wf,
        ];
        let filterable = wf.is_finite()
            && wf != 0.0
            && f.iter()
                .zip(&x)
                .all(|(v, xi)| v.is_finite() && (*v != 0.0 || *xi == Int::ZERO));
        HPoint {
            x,
            w,
            f,
            filterable,
            int: None,
        }
    }

    /// The intersection point of three planes, `None` when they do not meet in one point.
    pub fn meet(a: &Plane, b: &Plane, c: &Plane) -> Option<HPoint> {
        if let Some(p) = meet_wide(a, b, c) {
            return p;
        }
        let n = [a.normal_ints(), b.normal_ints(), c.normal_ints()];
        let k = [Int::from(a.c), Int::from(b.c), Int::from(c.c)];
        meet_big(&n, &k)
    }

    /// The point where the line through the integer points `a` and `b` crosses `h`, when
    /// the segment is not parallel to it.
    pub fn on_segment(a: &[i64; 3], b: &[i64; 3], h: &Plane) -> Option<HPoint> {
        let d = sub(b, a);
        // D = n·(b - a), N = c - n·a; the point is a + (b - a) N / D.
        let wide = || -> Option<Option<HPoint>> {
            let den = h.n[0]
                .checked_mul(d[0])?
                .checked_add(h.n[1].checked_mul(d[1])?)?
                .checked_add(h.n[2].checked_mul(d[2])?)?;
            if den == 0 {
                return Some(None);
            }
            let num = dot_minus(&h.n, a, h.c)?.checked_neg()?;
            let mut x = [0i128; 3];
            for i in 0..3 {
                x[i] = (a[i] as i128)
                    .checked_mul(den)?
                    .checked_add(d[i].checked_mul(num)?)?;
            }
            Some(Some(HPoint::from_wide(x, den)))
        };
        if let Some(p) = wide() {
            return p;
        }
        let n = h.normal_ints();
        on_segment_big(&a.map(Int::from), &b.map(Int::from), &n, &Int::from(h.c))
    }

    /// Whether [`HPoint::approx`] holds the coordinates within a few ulps (false only
    /// beyond the f64 range).
    pub fn filterable(&self) -> bool {
        self.filterable
    }

    /// Floating-point coordinates (relative error a few ulps), for bounding boxes only.
    pub fn approx(&self) -> [f64; 3] {
        self.f
    }

    /// The homogeneous coordinates `X`.
    pub fn num(&self) -> &[Int; 3] {
        &self.x
    }

    /// The homogeneous weight `W > 0`.
    pub fn den(&self) -> &Int {
        &self.w
    }

    /// The coordinates when the point is a grid point (`W = 1`) that fits `i64`.
    #[inline]
    pub fn as_int(&self) -> Option<&[i64; 3]> {
        self.int.as_ref()
    }

    /// The point of three exact rationals.
    pub fn from_rationals(r: &[Rational; 3]) -> HPoint {
        let d = r.each_ref().map(Rational::denom);
        let den = int::lcm(&int::lcm(&d[0], &d[1]), &d[2]);
        let num = [0, 1, 2].map(|k| r[k].numer() * (&den / &d[k]));
        HPoint::from_big(num, den)
    }

    /// The coordinates as exact rationals.
    pub fn to_rationals(&self) -> [Rational; 3] {
        match &self.int {
            Some(p) => p.map(Rational::from_int),
            None => self.x.clone().map(|n| Rational::new(n, self.w.clone())),
        }
    }

    /// The smallest grid box containing the point (coordinates beyond the `i64` range
    /// clamped to `±2^62`).
    pub fn bbox(&self) -> Aabb {
        if let Some(p) = &self.int {
            return Aabb::point(p);
        }
        let lo = self.x.clone().map(|n| clamp_i64(&floor_div(&n, &self.w)));
        let hi = self.x.clone().map(|n| clamp_i64(&-floor_div(&-n, &self.w)));
        Aabb { min: lo, max: hi }
    }
}

/// `floor(n / d)` for `d > 0`.
fn floor_div(n: &Int, d: &Int) -> Int {
    let q = n / d;
    if n < &Int::ZERO && &(&q * d) != n {
        q - Int::ONE
    } else {
        q
    }
}

fn clamp_i64(v: &Int) -> i64 {
    i64::try_from(v).unwrap_or(if v < &Int::ZERO {
        i64::MIN / 2
    } else {
        i64::MAX / 2
    })
}

fn meet_wide(a: &Plane, b: &Plane, c: &Plane) -> Option<Option<HPoint>> {
    let cross = |u: &[i128; 3], v: &[i128; 3]| -> Option<[i128; 3]> {
        Some([
            u[1].checked_mul(v[2])?
                .checked_sub(u[2].checked_mul(v[1])?)?,
            u[2].checked_mul(v[0])?
                .checked_sub(u[0].checked_mul(v[2])?)?,
            u[0].checked_mul(v[1])?
                .checked_sub(u[1].checked_mul(v[0])?)?,
        ])
    };
    let dot = |u: &[i128; 3], v: &[i128; 3]| -> Option<i128> {
        u[0].checked_mul(v[0])?
            .checked_add(u[1].checked_mul(v[1])?)?
            .checked_add(u[2].checked_mul(v[2])?)
    };
    let bc = cross(&b.n, &c.n)?;
    let w = dot(&a.n, &bc)?;
    if w == 0 {
        return Some(None);
    }
    let ca = cross(&c.n, &a.n)?;
    let ab = cross(&a.n, &b.n)?;
    let mut x = [0i128; 3];
    for i in 0..3 {
        x[i] =
            a.c.checked_mul(bc[i])?
                .checked_add(b.c.checked_mul(ca[i])?)?
                .checked_add(c.c.checked_mul(ab[i])?)?;
    }
    Some(Some(HPoint::from_wide(x, w)))
}

fn cross_big(u: &[Int; 3], v: &[Int; 3]) -> [Int; 3] {
    [
        &u[1] * &v[2] - &u[2] * &v[1],
        &u[2] * &v[0] - &u[0] * &v[2],
        &u[0] * &v[1] - &u[1] * &v[0],
    ]
}

fn dot_big(u: &[Int; 3], v: &[Int; 3]) -> Int {
    &u[0] * &v[0] + &u[1] * &v[1] + &u[2] * &v[2]
}

/// The intersection of the planes `n_i · x = c_i` (arbitrary precision), `None` when the
/// normals are linearly dependent.
pub fn meet_big(n: &[[Int; 3]; 3], c: &[Int; 3]) -> Option<HPoint> {
    let bc = cross_big(&n[1], &n[2]);
    let w = dot_big(&n[0], &bc);
    if w == Int::ZERO {
        return None;
    }
    let ca = cross_big(&n[2], &n[0]);
    let ab = cross_big(&n[0], &n[1]);
    let x = [0, 1, 2].map(|i| &c[0] * &bc[i] + &c[1] * &ca[i] + &c[2] * &ab[i]);
    Some(HPoint::from_big(x, w))
}

/// Where the line through `a`, `b` (exact points `X / W` with `W = 1`) meets the plane
/// `n · x = c` (arbitrary precision), `None` when parallel.
pub fn on_segment_big(a: &[Int; 3], b: &[Int; 3], n: &[Int; 3], c: &Int) -> Option<HPoint> {
    let d = [&b[0] - &a[0], &b[1] - &a[1], &b[2] - &a[2]];
    let den = dot_big(n, &d);
    if den == Int::ZERO {
        return None;
    }
    let num = c - dot_big(n, a);
    let x = [0, 1, 2].map(|i| &a[i] * &den + &d[i] * &num);
    Some(HPoint::from_big(x, den))
}

/// An arbitrary-precision plane `n · x = c` with its floating-point shadow.
#[derive(Clone, Debug)]
pub struct BigPlane {
    /// Normal (any non-zero integer vector).
    pub n: [Int; 3],
    /// Offset.
    pub c: Int,
    nf: [f64; 3],
    cf: f64,
    filterable: bool,
}

impl BigPlane {
    /// The plane `n · x = c`.
    pub fn new(n: [Int; 3], c: Int) -> BigPlane {
        let nf = [0, 1, 2].map(|i| int::to_f64(&n[i]));
        let cf = int::to_f64(&c);
        let filterable = nf.iter().all(|v| v.is_finite()) && cf.is_finite();
        BigPlane {
            n,
            c,
            nf,
            cf,
            filterable,
        }
    }

    /// Exact sign of `n · X - c · W` (filtered as [`Plane::side`]).
    pub fn side(&self, p: &HPoint) -> Sign {
        if self.filterable && p.filterable {
            let t = [0, 1, 2].map(|i| self.nf[i] * p.f[i]);
            let v = t[0] + t[1] + t[2] - self.cf;
            let bound = SIDE_ERR * (t[0].abs() + t[1].abs() + t[2].abs() + self.cf.abs());
            if bound.is_finite() {
                if v > bound {
                    return Sign::Positive;
                }
                if v < -bound {
                    return Sign::Negative;
                }
            }
        }
        int::sign_of(&self.value(p))
    }

    /// The exact value `n · X - c · W` for the point `X / W` (its sign is [`BigPlane::side`]).
    pub fn value(&self, p: &HPoint) -> Int {
        dot_big(&self.n, &p.x) - &self.c * &p.w
    }
}

/// Exact sign of `det[a; b; c]` of three plane normals (zero when they are dependent).
pub fn normals_det_sign(a: &Plane, b: &Plane, c: &Plane) -> Sign {
    int::sign_of(&dot_big(
        &a.normal_ints(),
        &cross_big(&b.normal_ints(), &c.normal_ints()),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_and_points() {
        let p = Plane::through(&[0, 0, 0], &[2, 0, 0], &[0, 2, 0]).unwrap();
        assert_eq!(p, Plane::new([0, 0, 1], 0));
        assert_eq!(p.side_int(&[5, 5, 1]), Sign::Positive);
        assert!(Plane::through(&[0, 0, 0], &[1, 1, 1], &[2, 2, 2]).is_none());
        let x = Plane::new([1, 0, 0], 1);
        let y = Plane::new([0, 1, 0], 2);
        let d = Plane::new([1, 1, 1], 4);
        let q = HPoint::meet(&x, &y, &d).unwrap();
        assert_eq!(q.int, Some([1, 2, 1]));
        // A rational point: x = 1, y = 2, 3z = 4.
        let z = Plane::new([1, 1, 3], 7);
        let q = HPoint::meet(&x, &y, &z).unwrap();
        assert_eq!(q.den(), &Int::from(3));
        assert_eq!(z.side(&q), Sign::Zero);
        assert_eq!(d.side(&q), Sign::Positive);
        let s = HPoint::on_segment(&[0, 0, 0], &[3, 3, 3], &Plane::new([1, 0, 0], 1));
        assert_eq!(s.unwrap().int, Some([1, 1, 1]));
    }

    #[test]
    fn big_path_agrees() {
        // Normals near 2^80 force the arbitrary-precision path.
        let big = 1i128 << 80;
        let a = Plane::new([big + 1, 3, 0], 7);
        let b = Plane::new([1, big - 1, 5], -11);
        let c = Plane::new([0, 2, big + 3], 13);
        let p = HPoint::meet(&a, &b, &c).unwrap();
        for pl in [&a, &b, &c] {
            assert_eq!(pl.side(&p), Sign::Zero);
        }
        let shifted = Plane::new(a.n, a.c + 1);
        assert_eq!(shifted.side(&p), Sign::Negative);
    }
}
