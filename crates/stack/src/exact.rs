//! Exact numbers of placement: rationals, homogeneous points and half-spaces.
//!
//! Positions are rational (`[Q; 3]`) where arithmetic is done, and homogeneous integer
//! points ([`Point`]) where many signs are taken against integer half-spaces
//! ([`HalfSpace`]): a side test is then one integer dot product, no fraction reduced.

use apart_kernel::int::{self, Int};
use apart_kernel::{Sign, Vec3};

pub use crate::rational::Q;

/// The integer `v` as a rational.
pub fn q(v: i64) -> Q {
    Q::from_i64(v)
}

/// The integer `v` as a rational.
pub fn qz(v: &Int) -> Q {
    Q::from_int(v.clone())
}

/// `n / d` (`d != 0`).
pub fn qfrac(n: i64, d: i64) -> Q {
    Q::from_i128(n as i128, d as i128)
}

/// `a / b` (`b != 0`).
pub fn qdiv(a: &Q, b: &Q) -> Q {
    Q::new(a.numer() * b.denom(), a.denom() * b.numer())
}

/// The exact value of a finite `f64` (every double is a dyadic rational); `None` for
/// infinities and NaN.
pub fn q_from_f64(x: f64) -> Option<Q> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some(q(0));
    }
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { -1i64 } else { 1 };
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = (bits & ((1u64 << 52) - 1)) as i64;
    let (mant, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1i64 << 52), exp - 1075)
    };
    let m = Int::from(sign * mant);
    Some(if e >= 0 {
        Q::from_int(m << e as usize)
    } else {
        Q::new(m, Int::ONE << (-e) as usize)
    })
}

/// `Σ a_i b_i` of two rational triples.
pub fn qdot(a: &[Q; 3], b: &[Q; 3]) -> Q {
    let mut s = &a[0] * &b[0];
    s = &s + &(&a[1] * &b[1]);
    &s + &(&a[2] * &b[2])
}

/// `a + b` componentwise.
pub fn qadd3(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

/// `a - b` componentwise.
pub fn qsub3(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

/// The stored integer vector `v` of a polytope with denominator `den`, as true
/// rational coordinates.
pub fn q3_of(v: &Vec3, den: &Int) -> [Q; 3] {
    let d = den.clone();
    [0, 1, 2].map(|i| Q::new(v.get(i), d.clone()))
}

/// Nearest doubles of a rational triple.
pub fn f3(p: &[Q; 3]) -> [f64; 3] {
    [p[0].to_f64(), p[1].to_f64(), p[2].to_f64()]
}

/// Least common multiple of positive integers.
pub fn lcm(a: &Int, b: &Int) -> Int {
    let g = int::gcd(a, b);
    if g == Int::ONE {
        a * b
    } else {
        a / &g * b
    }
}

/// A point `x / w` with integer `x` and `w > 0`, reduced (`gcd(x, w) = 1`), so that
/// equal points are equal values.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Point {
    /// Numerators.
    pub x: [Int; 3],
    /// Common positive denominator.
    pub w: Int,
    /// The same as machine words when they fit (a cache for fast signs).
    fast: Option<[i64; 4]>,
}

fn fast4(a: &[Int; 3], b: &Int) -> Option<[i64; 4]> {
    Some([
        int::to_i64(&a[0])?,
        int::to_i64(&a[1])?,
        int::to_i64(&a[2])?,
        int::to_i64(b)?,
    ])
}

impl Point {
    /// The origin.
    pub fn origin() -> Point {
        Point::raw([Int::ZERO, Int::ZERO, Int::ZERO], Int::ONE)
    }

    fn raw(x: [Int; 3], w: Int) -> Point {
        let fast = fast4(&x, &w);
        Point { x, w, fast }
    }

    /// `x / w`, reduced; `w` must not be zero (its sign is moved into `x`).
    pub fn new(x: [Int; 3], w: Int) -> Point {
        assert!(w != Int::ZERO, "point with zero denominator");
        let (x, w) = if w < Int::ZERO {
            (x.map(|c| -c), -w)
        } else {
            (x, w)
        };
        let mut g = w.clone();
        for c in &x {
            if g == Int::ONE {
                break;
            }
            g = int::gcd(&g, c);
        }
        if g > Int::ONE {
            Point::raw(x.map(|c| c / &g), w / g)
        } else {
            Point::raw(x, w)
        }
    }

    /// A rational triple as one fraction.
    pub fn from_q(p: &[Q; 3]) -> Point {
        let w = lcm(&lcm(&p[0].denom(), &p[1].denom()), &p[2].denom());
        let x = [0, 1, 2].map(|i| p[i].numer() * &(&w / p[i].denom()));
        Point::raw(x, w)
    }

    /// An integer point.
    pub fn from_vec(v: &Vec3) -> Point {
        Point::raw(v.to_ints(), Int::ONE)
    }

    /// The stored integers `v` of a polytope with denominator `den`.
    pub fn stored(v: &Vec3, den: &Int) -> Point {
        Point::new(v.to_ints(), den.clone())
    }

    /// The rational coordinates.
    pub fn to_q(&self) -> [Q; 3] {
        [0, 1, 2].map(|i| Q::new(self.x[i].clone(), self.w.clone()))
    }

    /// Nearest doubles.
    pub fn to_f64(&self) -> [f64; 3] {
        f3(&self.to_q())
    }

    /// `self + o`.
    pub fn add(&self, o: &Point) -> Point {
        let x = [0, 1, 2].map(|i| &self.x[i] * &o.w + &o.x[i] * &self.w);
        Point::new(x, &self.w * &o.w)
    }

    /// `self - o`.
    pub fn sub(&self, o: &Point) -> Point {
        let x = [0, 1, 2].map(|i| &self.x[i] * &o.w - &o.x[i] * &self.w);
        Point::new(x, &self.w * &o.w)
    }

    /// `-self`.
    pub fn neg(&self) -> Point {
        Point::raw(self.x.clone().map(|c| -c), self.w.clone())
    }
}

/// The closed half-space `n · p <= off` of true coordinates `p`, with integer `n != 0`
/// and `off`, reduced by their common divisor (so equal half-spaces are equal values).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct HalfSpace {
    /// Outward normal.
    pub n: [Int; 3],
    /// Offset.
    pub off: Int,
    /// The same as machine words when they fit (a cache for fast signs).
    fast: Option<[i64; 4]>,
}

impl HalfSpace {
    /// `n · p <= off`, reduced.
    pub fn new(n: [Int; 3], off: Int) -> HalfSpace {
        let mut g = int::gcd(&n[0], &n[1]);
        g = int::gcd(&g, &n[2]);
        assert!(g != Int::ZERO, "half-space with a zero normal");
        if g != Int::ONE {
            g = int::gcd(&g, &off);
        }
        if g > Int::ONE {
            HalfSpace::raw(n.map(|c| c / &g), off / g)
        } else {
            HalfSpace::raw(n, off)
        }
    }

    fn raw(n: [Int; 3], off: Int) -> HalfSpace {
        let fast = fast4(&n, &off);
        HalfSpace { n, off, fast }
    }

    /// The half-space as doubles: unit normal and offset (`None` beyond the range).
    pub fn to_float(&self) -> Option<([f64; 3], f64)> {
        let (a, b) = match self.fast {
            Some(f) => ([f[0] as f64, f[1] as f64, f[2] as f64], f[3] as f64),
            None => (
                self.n.clone().map(|c| int::to_f64(&c)),
                int::to_f64(&self.off),
            ),
        };
        let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        if !norm.is_finite() || !b.is_finite() || norm == 0.0 {
            return None;
        }
        Some((a.map(|v| v / norm), b / norm))
    }

    /// `n · p <= off` with a rational offset.
    pub fn with_q(n: [Int; 3], off: &Q) -> HalfSpace {
        let d = off.denom();
        HalfSpace::new(n.map(|c| c * &d), off.numer())
    }

    /// The facet plane `normal · x <= offset` of a polytope whose stored integers are
    /// `den` times its coordinates, in true coordinates.
    pub fn of_facet(normal: &Vec3, offset: &Int, den: &Int) -> HalfSpace {
        HalfSpace::new(normal.to_ints().map(|c| c * den), offset.clone())
    }

    /// The normal as a vector.
    pub fn normal(&self) -> Vec3 {
        Vec3::from_ints(self.n.clone())
    }

    /// Sign of `n · p - off`: negative inside, zero on the plane, positive outside.
    pub fn side(&self, p: &Point) -> Sign {
        if let (Some(h), Some(x)) = (&self.fast, &p.fast) {
            let t = [0, 1, 2, 3].map(|i| h[i] as i128 * x[i] as i128);
            if let Some(v) = t[0]
                .checked_add(t[1])
                .and_then(|v| v.checked_add(t[2]))
                .and_then(|v| v.checked_sub(t[3]))
            {
                return Sign::of_i128(v);
            }
        }
        let mut s = &self.n[0] * &p.x[0];
        s += &self.n[1] * &p.x[1];
        s += &self.n[2] * &p.x[2];
        s -= &self.off * &p.w;
        int::sign_of(&s)
    }

    /// The complementary closed half-space `n · p >= off`.
    pub fn flipped(&self) -> HalfSpace {
        HalfSpace::raw(self.n.clone().map(|c| -c), -self.off.clone())
    }

    /// The half-space moved by `t`: `{p + t}` for `p` in `self`.
    pub fn translated(&self, t: &Point) -> HalfSpace {
        let nt = &self.n[0] * &t.x[0] + &self.n[1] * &t.x[1] + &self.n[2] * &t.x[2];
        HalfSpace::new(self.n.clone().map(|c| c * &t.w), &self.off * &t.w + nt)
    }

    /// `n · p` for a rational point.
    pub fn eval(&self, p: &[Q; 3]) -> Q {
        let n = self.n.clone().map(Q::from_int);
        qdot(&n, p)
    }

    /// The offset as a rational (for `n · p <= off`).
    pub fn offset(&self) -> Q {
        qz(&self.off)
    }
}

/// A closed box `lo <= p <= hi` with rational corners.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct QBox {
    /// Lower corner.
    pub lo: [Q; 3],
    /// Upper corner.
    pub hi: [Q; 3],
}

impl QBox {
    /// The bounding box of stored integer points with denominator `den`.
    pub fn of_points<'a>(points: impl IntoIterator<Item = &'a Vec3>, den: &Int) -> QBox {
        let mut lo: Option<[Int; 3]> = None;
        let mut hi: Option<[Int; 3]> = None;
        for v in points {
            let c = v.to_ints();
            match (&mut lo, &mut hi) {
                (Some(l), Some(h)) => {
                    for i in 0..3 {
                        if c[i] < l[i] {
                            l[i] = c[i].clone();
                        }
                        if c[i] > h[i] {
                            h[i] = c[i].clone();
                        }
                    }
                }
                _ => {
                    lo = Some(c.clone());
                    hi = Some(c);
                }
            }
        }
        let lo = lo.expect("box of no points");
        let hi = hi.expect("box of no points");
        QBox {
            lo: lo.map(|c| Q::new(c, den.clone())),
            hi: hi.map(|c| Q::new(c, den.clone())),
        }
    }

    /// The smallest box containing both.
    pub fn union(&self, o: &QBox) -> QBox {
        QBox {
            lo: [0, 1, 2].map(|i| self.lo[i].clone().min(o.lo[i].clone())),
            hi: [0, 1, 2].map(|i| self.hi[i].clone().max(o.hi[i].clone())),
        }
    }

    /// The box moved by `t`.
    pub fn translated(&self, t: &[Q; 3]) -> QBox {
        QBox {
            lo: qadd3(&self.lo, t),
            hi: qadd3(&self.hi, t),
        }
    }

    /// True when `lo <= hi` on every axis.
    pub fn is_empty(&self) -> bool {
        (0..3).any(|i| self.lo[i] > self.hi[i])
    }

    /// Doubles enclosing the box (rounded outwards by a relative 1e-9).
    pub fn to_f64(&self) -> [[f64; 3]; 2] {
        let pad = |x: f64| x.abs() * 1e-9 + 1e-300;
        [
            [0, 1, 2].map(|i| {
                let x = self.lo[i].to_f64();
                x - pad(x)
            }),
            [0, 1, 2].map(|i| {
                let x = self.hi[i].to_f64();
                x + pad(x)
            }),
        ]
    }

    /// The six half-spaces of the box.
    pub fn halfspaces(&self) -> Vec<HalfSpace> {
        let mut out = Vec::with_capacity(6);
        for i in 0..3 {
            let mut n = [Int::ZERO, Int::ZERO, Int::ZERO];
            n[i] = Int::ONE;
            out.push(HalfSpace::with_q(n.clone(), &self.hi[i]));
            n[i] = -Int::ONE;
            out.push(HalfSpace::with_q(n, &(-&self.lo[i])));
        }
        out
    }

    /// `min` over the box of `n · p`.
    pub fn min_dot(&self, n: &[Int; 3]) -> Q {
        let mut s = q(0);
        for (i, c) in n.iter().enumerate() {
            let v = if *c >= Int::ZERO {
                &self.lo[i]
            } else {
                &self.hi[i]
            };
            s = &s + &(&qz(c) * v);
        }
        s
    }
}

/// A rational `r >= sqrt(s)` within a relative `2^-20` of it, for `s >= 0`.
pub fn sqrt_upper(s: &Int) -> Q {
    if *s == Int::ZERO {
        return q(0);
    }
    const K: usize = 20;
    let scaled = s << (2 * K);
    let approx = int::to_f64(&scaled).sqrt();
    let mut r = q_from_f64(approx.floor())
        .map(|v| v.numer())
        .unwrap_or(Int::ZERO);
    // Make r the smallest integer with r² >= s·4^K.
    while &r * &r < scaled {
        r += Int::ONE;
    }
    while r > Int::ZERO && (&r - Int::ONE) * (&r - Int::ONE) >= scaled {
        r -= Int::ONE;
    }
    Q::new(r, Int::ONE << K)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dyadic_doubles_are_exact() {
        assert_eq!(q_from_f64(0.375).unwrap(), qfrac(3, 8));
        assert_eq!(q_from_f64(-12.0).unwrap(), q(-12));
        assert_eq!(q_from_f64(0.1).unwrap().to_f64(), 0.1);
    }

    #[test]
    fn points_and_halfspaces() {
        let p = Point::from_q(&[qfrac(1, 2), qfrac(1, 3), q(2)]);
        assert_eq!(p.w, Int::from(6));
        let h = HalfSpace::new([2, 0, 0].map(Int::from), Int::from(1)); // x <= 1/2
        assert_eq!(h.side(&p), Sign::Zero);
        let moved = h.translated(&Point::from_q(&[qfrac(1, 4), q(0), q(0)]));
        assert_eq!(moved.side(&p), Sign::Negative);
        assert_eq!(moved.flipped().side(&p), Sign::Positive);
    }

    #[test]
    fn square_root_bound() {
        for s in [1i64, 2, 3, 50, 1 << 40] {
            let r = sqrt_upper(&Int::from(s));
            assert!(&r * &r >= q(s));
            assert!((r.to_f64() - (s as f64).sqrt()) / (s as f64).sqrt() < 1e-5);
        }
    }
}
