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
    /// Every `|n_i| < 2^62` and `|c| < 2^126`: then `n · p - c` fits `i128` for every
    /// `|p_i| < 2^62`, from 64-bit products (see [`Plane::side_int`]).
    narrow: bool,
}

/// Bound of the narrow tier of [`Plane::side_int`].
const NARROW: u128 = 1 << 62;

impl PartialEq for Plane {
    fn eq(&self, o: &Self) -> bool {
        // The offset first (it tells most planes apart), then the normal component by
        // component (`==` on `[i128; 3]` compiles to a `memcmp` call).
        self.c == o.c && self.n[0] == o.n[0] && self.n[1] == o.n[1] && self.n[2] == o.n[2]
    }
}

impl Plane {
    /// Whether `o` is this plane with its sides swapped (`−n · x = −c`).
    pub fn is_flip_of(&self, o: &Plane) -> bool {
        self.c == -o.c && self.n[0] == -o.n[0] && self.n[1] == -o.n[1] && self.n[2] == -o.n[2]
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
            narrow: n.iter().all(|v| v.unsigned_abs() < NARROW) && c.unsigned_abs() < 1 << 126,
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
            narrow: self.narrow,
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
        if self.narrow && p.iter().all(|v| (v.unsigned_abs() as u128) < NARROW) {
            // Each product is below 2^124 and the sum below 2^127: no overflow.
            let m = |k: usize| (self.n[k] as i64 as i128) * (p[k] as i128);
            return Sign::of_i128(m(0) + m(1) + m(2) - self.c);
        }
        match dot_minus(&self.n, p, self.c) {
            Some(v) => Sign::of_i128(v),
            None => int::sign_of(&big_side(&self.n, self.c, &p.map(Int::from), &Int::ONE)),
        }
    }

    /// Exact sign of `n · p - c`: positive above the plane (outside the inner side).
    #[inline]
    pub fn side(&self, p: &HPoint) -> Sign {
        if let Some(q) = p.as_int() {
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
    /// `[X, W]` when all four fit `i64` (grid points have `W = 1`).
    small: Option<[i64; 4]>,
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
            small: Some([p[0], p[1], p[2], 1]),
        }
    }

    /// The point `x / w` (`w != 0`), reduced.
    pub fn from_wide(x: [i128; 3], w: i128) -> HPoint {
        debug_assert!(w != 0);
        let (x, w) = if w < 0 { (x.map(|v| -v), -w) } else { (x, w) };
        // From the denominator on, stopping at 1 (the usual case).
        let mut g = w as u128;
        for v in &x {
            if g == 1 {
                break;
            }
            g = int::gcd_u128(g, v.unsigned_abs());
        }
        let g = g as i128;
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
        let wide = |v: &Int| int::to_i128(v).filter(|&v| v != i128::MIN);
        if let [Some(a), Some(b), Some(c), Some(d)] = [&x[0], &x[1], &x[2], &w].map(wide) {
            return HPoint::from_wide([a, b, c], d);
        }
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
        let small = fast4(&x, &w);
        // Machine words convert as the arbitrary-precision values would (nearest double).
        let (xf, wf) = match &small {
            Some(s) => ([s[0] as f64, s[1] as f64, s[2] as f64], s[3] as f64),
            None => (x.each_ref().map(int::to_f64), int::to_f64(&w)),
        };
        let f = xf.map(|v| v / wf);
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
            small,
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
        match &self.small {
            Some(s) if s[3] == 1 => s[..3].try_into().ok(),
            _ => None,
        }
    }

    /// The point of three exact rationals.
    pub fn from_rationals(r: &[Rational; 3]) -> HPoint {
        if let [Some((n0, d0)), Some((n1, d1)), Some((n2, d2))] =
            r.each_ref().map(Rational::as_small)
        {
            // In machine words when the least common denominator and the numerators over
            // it fit `i128` (always for placement's small denominators), else below.
            let lcm = |a: u128, b: u128| (a / int::gcd_u128(a, b)).checked_mul(b);
            let w = lcm(d0 as u128, d1 as u128).and_then(|w| lcm(w, d2 as u128));
            if let Some(w) = w.filter(|&w| w <= i128::MAX as u128) {
                let w = w as i128;
                let x = [(n0, d0), (n1, d1), (n2, d2)]
                    .map(|(n, d)| (n as i128).checked_mul(w / d as i128));
                if let [Some(a), Some(b), Some(c)] = x {
                    return HPoint::from_reduced_wide([a, b, c], w);
                }
            }
        }
        let d = r.each_ref().map(Rational::denom);
        let den = int::lcm(&int::lcm(&d[0], &d[1]), &d[2]);
        let num = [0, 1, 2].map(|k| r[k].numer() * (&den / &d[k]));
        // Already reduced: a prime dividing W to the power of some coordinate's reduced
        // denominator does not divide that coordinate's X.
        HPoint::from_reduced(num, den)
    }

    /// The point `x / w` of machine coordinates already reduced (`w > 0`,
    /// `gcd(x, w) = 1`).
    fn from_reduced_wide(x: [i128; 3], w: i128) -> HPoint {
        if w == 1 && x.iter().all(|v| i64::try_from(*v).is_ok()) {
            return HPoint::int(x.map(|v| v as i64));
        }
        HPoint::finish(x.map(Int::from), Int::from(w))
    }

    /// The point `x / w` of coordinates already reduced (`w > 0`, `gcd(x, w) = 1`).
    fn from_reduced(x: [Int; 3], w: Int) -> HPoint {
        if w == Int::ONE {
            if let [Some(a), Some(b), Some(c)] =
                [int::to_i64(&x[0]), int::to_i64(&x[1]), int::to_i64(&x[2])]
            {
                return HPoint::int([a, b, c]);
            }
        }
        HPoint::finish(x, w)
    }

    /// The coordinates as exact rationals.
    pub fn to_rationals(&self) -> [Rational; 3] {
        match self.as_int() {
            Some(p) => p.map(Rational::from_int),
            None => self.x.clone().map(|n| Rational::new(n, self.w.clone())),
        }
    }

    /// `self + t`, the point moved by the vector `t`.
    pub fn add(&self, t: &HPoint) -> HPoint {
        let x = [0, 1, 2].map(|i| &self.x[i] * &t.w + &t.x[i] * &self.w);
        HPoint::from_big(x, &self.w * &t.w)
    }

    /// `self - o`, the vector from `o` to `self` (or the point moved by `-o`).
    pub fn sub(&self, o: &HPoint) -> HPoint {
        let x = [0, 1, 2].map(|i| &self.x[i] * &o.w - &o.x[i] * &self.w);
        HPoint::from_big(x, &self.w * &o.w)
    }

    /// `-self`, the point reflected through the origin.
    pub fn neg(&self) -> HPoint {
        HPoint::from_reduced(self.x.clone().map(|c| -c), self.w.clone())
    }

    /// The smallest grid box containing the point (coordinates beyond the `i64` range
    /// clamped to `±2^62`).
    pub fn bbox(&self) -> Aabb {
        if let Some(p) = self.as_int() {
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

/// `[a, b]` as machine words, when all four fit.
fn fast4(a: &[Int; 3], b: &Int) -> Option<[i64; 4]> {
    Some([
        int::to_i64(&a[0])?,
        int::to_i64(&a[1])?,
        int::to_i64(&a[2])?,
        int::to_i64(b)?,
    ])
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

/// An arbitrary-precision plane `n · x = c` with its floating-point shadow; as a
/// half-space, `n · x <= c` is its inner side.
///
/// Equality and hashing are those of `(n, c)`; the shadows only serve the filters.
#[derive(Clone, Debug)]
pub struct BigPlane {
    /// Normal (any non-zero integer vector).
    pub n: [Int; 3],
    /// Offset.
    pub c: Int,
    nf: [f64; 3],
    cf: f64,
    filterable: bool,
    /// `[n, c]` when all four fit `i64`.
    small: Option<[i64; 4]>,
}

impl PartialEq for BigPlane {
    fn eq(&self, o: &Self) -> bool {
        self.n == o.n && self.c == o.c
    }
}
impl Eq for BigPlane {}
impl Hash for BigPlane {
    fn hash<H: Hasher>(&self, h: &mut H) {
        self.n.hash(h);
        self.c.hash(h);
    }
}

impl BigPlane {
    /// The plane `n · x = c`.
    pub fn new(n: [Int; 3], c: Int) -> BigPlane {
        let small = fast4(&n, &c);
        // Machine words convert as the arbitrary-precision values would (nearest double).
        let (nf, cf) = match &small {
            Some(s) => ([s[0] as f64, s[1] as f64, s[2] as f64], s[3] as f64),
            None => (n.each_ref().map(int::to_f64), int::to_f64(&c)),
        };
        let filterable = nf.iter().all(|v| v.is_finite()) && cf.is_finite();
        BigPlane {
            n,
            c,
            nf,
            cf,
            filterable,
            small,
        }
    }

    /// The plane `n · x = c` divided by the gcd of `n` and `c`, so that equal
    /// half-spaces are equal values. Panics when `n` is zero.
    pub fn reduced(n: [Int; 3], c: Int) -> BigPlane {
        let wide = |v: &Int| int::to_i128(v).filter(|&v| v != i128::MIN);
        if let [Some(a), Some(b), Some(d), Some(e)] = [&n[0], &n[1], &n[2], &c].map(wide) {
            return BigPlane::reduced_wide([a, b, d], e);
        }
        let mut g = int::gcd(&int::gcd(&n[0], &n[1]), &n[2]);
        assert!(g != Int::ZERO, "plane with a zero normal");
        if g != Int::ONE {
            g = int::gcd(&g, &c);
        }
        if g > Int::ONE {
            BigPlane::new(n.map(|v| v / &g), c / g)
        } else {
            BigPlane::new(n, c)
        }
    }

    /// [`BigPlane::reduced`] on machine integers (`n != 0`, no `i128::MIN`).
    fn reduced_wide(n: [i128; 3], c: i128) -> BigPlane {
        let g = gcd3(&n);
        assert!(g != 0, "plane with a zero normal");
        let g = int::gcd_u128(g, c.unsigned_abs()) as i128;
        BigPlane::new(n.map(|v| Int::from(v / g)), Int::from(c / g))
    }

    /// The half-space `n · x <= c` for a rational `c`, scaled to integers and
    /// [reduced](BigPlane::reduced).
    pub fn with_rational_offset(n: [Int; 3], c: &Rational) -> BigPlane {
        let d = c.denom();
        BigPlane::reduced(n.map(|v| v * &d), c.numer())
    }

    /// The same plane with the opposite orientation (the complementary closed
    /// half-space `n · x >= c`).
    pub fn flipped(&self) -> BigPlane {
        BigPlane {
            n: self.n.clone().map(|v| -v),
            c: -self.c.clone(),
            nf: self.nf.map(|v| -v),
            cf: -self.cf,
            filterable: self.filterable,
            small: self.small.and_then(|s| {
                Some([
                    s[0].checked_neg()?,
                    s[1].checked_neg()?,
                    s[2].checked_neg()?,
                    s[3].checked_neg()?,
                ])
            }),
        }
    }

    /// The plane moved by the vector `t` (`{x + t}` for `x` on it), reduced.
    pub fn translated(&self, t: &HPoint) -> BigPlane {
        if let (Some(h), Some(x)) = (&self.small, &t.small) {
            // Products of two words fit `i128`; the sums are checked.
            let w = x[3] as i128;
            let nt = (h[0] as i128 * x[0] as i128)
                .checked_add(h[1] as i128 * x[1] as i128)
                .and_then(|v| v.checked_add(h[2] as i128 * x[2] as i128));
            if let Some(c) = nt.and_then(|v| v.checked_add(h[3] as i128 * w)) {
                if c != i128::MIN {
                    let n = [h[0], h[1], h[2]].map(|v| v as i128 * w);
                    return BigPlane::reduced_wide(n, c);
                }
            }
        }
        let nt = dot_big(&self.n, &t.x);
        BigPlane::reduced(self.n.clone().map(|v| v * &t.w), &self.c * &t.w + nt)
    }

    /// Exact sign of `n · X - c · W` (filtered as [`Plane::side`], after a
    /// machine-word path when the plane and the point fit `i64`).
    #[inline]
    pub fn side(&self, p: &HPoint) -> Sign {
        if let (Some(h), Some(x)) = (&self.small, &p.small) {
            let t = [0, 1, 2, 3].map(|i| h[i] as i128 * x[i] as i128);
            if let Some(v) = t[0]
                .checked_add(t[1])
                .and_then(|v| v.checked_add(t[2]))
                .and_then(|v| v.checked_sub(t[3]))
            {
                return Sign::of_i128(v);
            }
        }
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
    // Filter: each shadow component is within u of its integer, the products and sums
    // add at most 6u more: the computed value is within 9u of the exact one relative to
    // the permanent `P` (padded, as the side filter, to 32u of the computed `P`).
    let (x, y, z) = (&a.nf, &b.nf, &c.nf);
    let m = [
        (y[1] * z[2], y[2] * z[1]),
        (y[2] * z[0], y[0] * z[2]),
        (y[0] * z[1], y[1] * z[0]),
    ];
    let det = x[0] * (m[0].0 - m[0].1) + x[1] * (m[1].0 - m[1].1) + x[2] * (m[2].0 - m[2].1);
    let perm = x[0].abs() * (m[0].0.abs() + m[0].1.abs())
        + x[1].abs() * (m[1].0.abs() + m[1].1.abs())
        + x[2].abs() * (m[2].0.abs() + m[2].1.abs());
    let bound = SIDE_ERR * perm;
    if det > bound {
        return Sign::Positive;
    }
    if det < -bound {
        return Sign::Negative;
    }
    if a.narrow && b.narrow {
        // det = c · (a × b); the cross product of normals below 2^62 fits i128.
        let (x, y) = (&a.n, &b.n);
        let u = [
            x[1] * y[2] - x[2] * y[1],
            x[2] * y[0] - x[0] * y[2],
            x[0] * y[1] - x[1] * y[0],
        ];
        if u == [0; 3] {
            return Sign::Zero;
        }
        if !c.n.contains(&i128::MIN) {
            return crate::wide::dot_sign(&u, &c.n);
        }
    }
    if [a, b, c].iter().all(|p| !p.n.contains(&i128::MIN)) {
        return crate::wide::det3_sign(&a.n, &b.n, &c.n);
    }
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
        assert_eq!(q.as_int(), Some(&[1, 2, 1]));
        // A rational point: x = 1, y = 2, 3z = 4.
        let z = Plane::new([1, 1, 3], 7);
        let q = HPoint::meet(&x, &y, &z).unwrap();
        assert_eq!(q.den(), &Int::from(3));
        assert_eq!(z.side(&q), Sign::Zero);
        assert_eq!(d.side(&q), Sign::Positive);
        let s = HPoint::on_segment(&[0, 0, 0], &[3, 3, 3], &Plane::new([1, 0, 0], 1));
        assert_eq!(s.unwrap().as_int(), Some(&[1, 1, 1]));
    }

    #[test]
    fn point_arithmetic_and_big_planes() {
        let r = |n: i64, d: i64| Rational::from_i128(n as i128, d as i128);
        let p = HPoint::from_rationals(&[r(1, 2), r(1, 3), r(2, 1)]);
        assert_eq!(p.den(), &Int::from(6));
        assert_eq!(p.as_int(), None);
        let q = HPoint::from_rationals(&[r(1, 2), r(2, 3), r(-2, 1)]);
        assert_eq!(p.add(&q).as_int(), Some(&[1, 1, 0]));
        assert_eq!(p.sub(&q).to_rationals(), [r(0, 1), r(-1, 3), r(4, 1)]);
        assert_eq!(p.neg().add(&p), HPoint::int([0, 0, 0]));
        // x <= 1/2, as 2x <= 1 (and 4x <= 2 reduces to it).
        let h = BigPlane::reduced([4, 0, 0].map(Int::from), Int::from(2));
        assert_eq!(
            h,
            BigPlane::with_rational_offset([1, 0, 0].map(Int::from), &r(1, 2))
        );
        assert_eq!((h.n[0].clone(), h.c.clone()), (Int::from(2), Int::from(1)));
        assert_eq!(h.side(&p), Sign::Zero);
        let moved = h.translated(&HPoint::from_rationals(&[r(1, 4), r(0, 1), r(0, 1)]));
        assert_eq!(moved.side(&p), Sign::Negative);
        assert_eq!(moved.flipped().side(&p), Sign::Positive);
        // Beyond the machine words: the same signs by the filter or exactly.
        let big = Int::from(1) << 80usize;
        let far = BigPlane::reduced([big.clone(), Int::ZERO, Int::ZERO], &big * Int::from(3));
        assert_eq!(far.side(&HPoint::int([3, 7, 7])), Sign::Zero);
        assert_eq!(far.side(&p), Sign::Negative);
        assert_eq!(far.flipped().side(&p), Sign::Positive);
        // The machine-word and arbitrary-precision paths of `translated` and `reduced`
        // agree: (n·w) · x <= c·w + n·X, divided by the common gcd.
        for plane in [&h, &moved, &far, &far.flipped()] {
            for t in [&p, &q, &HPoint::int([i64::MAX, 1, -3])] {
                let (x, w) = (t.num(), t.den());
                let n = plane.n.clone().map(|v| v * w);
                let c =
                    &plane.c * w + &plane.n[0] * &x[0] + &plane.n[1] * &x[1] + &plane.n[2] * &x[2];
                let g = int::gcd(&int::gcd(&int::gcd(&n[0], &n[1]), &n[2]), &c);
                let want = BigPlane::new(n.map(|v| v / &g), c / &g);
                let got = plane.translated(t);
                assert_eq!((&got.n, &got.c), (&want.n, &want.c));
                assert_eq!(got.small, want.small);
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]
        /// The 64-bit-product tier of `side_int` agrees with arbitrary precision, at
        /// and around its bounds (normals, offsets and points near 2^62 and 2^126) and
        /// on points exactly on the plane.
        #[test]
        fn side_int_tiers_agree(
            nb in proptest::sample::select(vec![3u32, 30, 61, 62, 63, 70]),
            pb in proptest::sample::select(vec![3u32, 31, 61, 62, 63]),
            raw in proptest::array::uniform3(proptest::num::i64::ANY),
            pr in proptest::array::uniform3(proptest::num::i64::ANY),
            on in proptest::bool::ANY,
            dc in -2i128..=2,
        ) {
            let clip = |v: i64, b: u32| if b >= 63 { v } else { v >> (63 - b) };
            let n: [i128; 3] = std::array::from_fn(|k| {
                let v = clip(raw[k], nb.min(63)) as i128;
                if nb > 63 { v << (nb - 63) } else { v }
            });
            let p: [i64; 3] = std::array::from_fn(|k| clip(pr[k], pb));
            let exact = |c: i128| {
                let v = Int::from(n[0]) * Int::from(p[0])
                    + Int::from(n[1]) * Int::from(p[1])
                    + Int::from(n[2]) * Int::from(p[2])
                    - Int::from(c);
                int::sign_of(&v)
            };
            // An offset through p (when it fits) or a large one.
            let through = n[0].checked_mul(p[0] as i128)
                .and_then(|a| a.checked_add(n[1].checked_mul(p[1] as i128)?))
                .and_then(|a| a.checked_add(n[2].checked_mul(p[2] as i128)?));
            let c = match (on, through) {
                (true, Some(c)) => c.saturating_add(dc),
                _ => (raw[0] as i128) << 62,
            };
            let h = Plane::new(n, c);
            proptest::prop_assert_eq!(h.side_int(&p), exact(c));
            proptest::prop_assert_eq!(h.flipped().side_int(&p), -exact(c));
        }
    }

    proptest::proptest! {
        /// The fixed-width determinant of three normals agrees with arbitrary precision.
        #[test]
        fn normals_det_tiers_agree(
            raw in proptest::array::uniform9(proptest::num::i64::ANY),
            shift in 0u32..64,
            dependent in proptest::bool::ANY,
        ) {
            let v = |k: usize| [0, 1, 2].map(|i| (raw[3 * k + i] as i128) << shift);
            let (a, b) = (v(0), v(1));
            // A third normal in the span of the first two when asked (det 0).
            let sum = [0, 1, 2].map(|i| a[i].checked_sub(b[i]));
            let c = match sum {
                [Some(x), Some(y), Some(z)] if dependent => [x, y, z],
                _ => v(2),
            };
            let big = |n: [i128; 3]| n.map(Int::from);
            let want = int::sign_of(&dot_big(&big(a), &cross_big(&big(b), &big(c))));
            let pl = |n: [i128; 3]| Plane::new(n, 0);
            proptest::prop_assert_eq!(normals_det_sign(&pl(a), &pl(b), &pl(c)), want);
        }
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
