//! Exact rational numbers, for volumes, witness points, placements and other reported
//! quantities.
//!
//! Most rationals apart computes are small (grid coordinates, sheet thicknesses,
//! rotation denominators, the thousands of small linear and quadratic programs of
//! placement). A [`Rational`] keeps a reduced `i64 / i64` when both fit and computes in
//! `i128` before reducing by a binary gcd, with no allocation; beyond that it falls back
//! to arbitrary precision ([`Int`]). The representation is canonical (reduced, positive
//! denominator, machine words whenever they fit), so equality and hashing are exact.

use crate::int::{self, Int};
use crate::Sign;
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A reduced fraction `num / den` with `den > 0`.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Rational(Repr);

#[derive(Clone, PartialEq, Eq, Hash)]
enum Repr {
    /// `n / d`, `d > 0`, reduced, `n != i64::MIN` (so that `-n` fits).
    Small(i64, i64),
    /// `n / d`, `d > 0`, reduced, not both fitting `Small`.
    Big(Box<(Int, Int)>),
}

/// `n` when it fits [`Repr::Small`]'s numerator or denominator.
#[inline]
fn small(n: i128) -> Option<i64> {
    if n > i64::MIN as i128 && n <= i64::MAX as i128 {
        Some(n as i64)
    } else {
        None
    }
}

impl Rational {
    /// Zero.
    pub fn zero() -> Rational {
        Rational(Repr::Small(0, 1))
    }

    /// The integer `v`.
    pub fn from_int(v: impl Into<Int>) -> Rational {
        let v: Int = v.into();
        match int::to_i64(&v) {
            Some(s) if s != i64::MIN => Rational(Repr::Small(s, 1)),
            _ => Rational(Repr::Big(Box::new((v, Int::ONE)))),
        }
    }

    /// `num / den`, reduced. Panics when `den` is zero (a programming error: every caller
    /// divides by a quantity it has checked).
    pub fn new(num: Int, den: Int) -> Rational {
        if let (Some(n), Some(d)) = (int::to_i64(&num), int::to_i64(&den)) {
            return Rational::from_i128(n as i128, d as i128);
        }
        assert!(den != Int::ZERO, "rational with zero denominator");
        let (num, den) = if den < Int::ZERO {
            (-num, -den)
        } else {
            (num, den)
        };
        let g = int::gcd(&num, &den);
        let (num, den) = if g > Int::ONE {
            (num / &g, den / g)
        } else {
            (num, den)
        };
        Rational::reduced(num, den)
    }

    /// `n / d` from machine integers, reduced. Panics when `d` is zero, as
    /// [`Rational::new`].
    #[inline]
    pub fn from_i128(n: i128, d: i128) -> Rational {
        assert!(d != 0, "rational with zero denominator");
        if n == i128::MIN || d == i128::MIN {
            return Rational::new(Int::from(n), Int::from(d));
        }
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        if n == 0 {
            return Rational::zero();
        }
        if d == 1 {
            if let Some(a) = small(n) {
                return Rational(Repr::Small(a, 1));
            }
        }
        let g = int::gcd_u128(n.unsigned_abs(), d as u128) as i128;
        let (n, d) = (n / g, d / g);
        match (small(n), small(d)) {
            (Some(a), Some(b)) => Rational(Repr::Small(a, b)),
            _ => Rational(Repr::Big(Box::new((Int::from(n), Int::from(d))))),
        }
    }

    /// The canonical representation of the reduced `num / den` (`den > 0`).
    fn reduced(num: Int, den: Int) -> Rational {
        match (int::to_i64(&num), int::to_i64(&den)) {
            (Some(a), Some(b)) if a != i64::MIN => Rational(Repr::Small(a, b)),
            _ => Rational(Repr::Big(Box::new((num, den)))),
        }
    }

    /// `2^e` (any sign of `e`).
    pub fn pow2(e: i32) -> Rational {
        let p = Int::ONE << e.unsigned_abs() as usize;
        if e >= 0 {
            Rational::from_int(p)
        } else {
            Rational::new(Int::ONE, p)
        }
    }

    /// Numerator (carries the sign).
    pub fn numer(&self) -> Int {
        match &self.0 {
            Repr::Small(n, _) => Int::from(*n),
            Repr::Big(b) => b.0.clone(),
        }
    }

    /// Denominator (positive).
    pub fn denom(&self) -> Int {
        match &self.0 {
            Repr::Small(_, d) => Int::from(*d),
            Repr::Big(b) => b.1.clone(),
        }
    }

    /// Numerator and denominator as machine words, when both fit `i64`.
    #[inline]
    pub fn as_small(&self) -> Option<(i64, i64)> {
        match self.0 {
            Repr::Small(n, d) => Some((n, d)),
            Repr::Big(_) => None,
        }
    }

    fn parts(&self) -> (Int, Int) {
        (self.numer(), self.denom())
    }

    /// The sign.
    pub fn sign(&self) -> Sign {
        match &self.0 {
            Repr::Small(n, _) => Sign::of_i64(*n),
            Repr::Big(b) => int::sign_of(&b.0),
        }
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Small(0, _))
    }

    /// `1 / self`. Panics when `self` is zero.
    pub fn recip(&self) -> Rational {
        match &self.0 {
            Repr::Small(n, d) => Rational::from_i128(*d as i128, *n as i128),
            Repr::Big(b) => Rational::new(b.1.clone(), b.0.clone()),
        }
    }

    /// |self|.
    pub fn abs(&self) -> Rational {
        if self.sign() == Sign::Negative {
            -self
        } else {
            self.clone()
        }
    }

    /// The exact value of a finite `f64` (every double is a dyadic rational); `None`
    /// for infinities and NaN.
    pub fn from_f64(x: f64) -> Option<Rational> {
        if !x.is_finite() {
            return None;
        }
        let bits = x.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = (bits & ((1u64 << 52) - 1)) as i64;
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1i64 << 52), exp - 1075)
        };
        let m = Int::from(if x < 0.0 { -m } else { m });
        Some(if e >= 0 {
            Rational::from_int(m << e as usize)
        } else {
            Rational::new(m, Int::ONE << (-e) as usize)
        })
    }

    /// Nearest `f64` (to within a few ulps; for machine words `n as f64 / d as f64`).
    pub fn to_f64(&self) -> f64 {
        let b = match &self.0 {
            Repr::Small(n, d) => return *n as f64 / *d as f64,
            Repr::Big(b) => b,
        };
        let (num, den) = (&b.0, &b.1);
        let (n, d) = (int::to_f64(num), int::to_f64(den));
        if n.is_finite() && d.is_finite() && d != 0.0 {
            return n / d;
        }
        // Scale both down to keep the quotient in range.
        let shift = int::bit_len(num).max(int::bit_len(den)).saturating_sub(900) as usize;
        int::to_f64(&(num >> shift)) / int::to_f64(&(den >> shift))
    }
}

impl From<i64> for Rational {
    fn from(v: i64) -> Rational {
        if v == i64::MIN {
            return Rational::from_int(v);
        }
        Rational(Repr::Small(v, 1))
    }
}

impl Add for &Rational {
    type Output = Rational;
    #[inline]
    fn add(self, o: &Rational) -> Rational {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            let (a, b, c, d) = (*a as i128, *b as i128, *c as i128, *d as i128);
            if b == d {
                return Rational::from_i128(a + c, b);
            }
            return Rational::from_i128(a * d + c * b, b * d);
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        Rational::new(&a * &d + &c * &b, b * d)
    }
}

impl Sub for &Rational {
    type Output = Rational;
    #[inline]
    fn sub(self, o: &Rational) -> Rational {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            let (a, b, c, d) = (*a as i128, *b as i128, *c as i128, *d as i128);
            if b == d {
                return Rational::from_i128(a - c, b);
            }
            return Rational::from_i128(a * d - c * b, b * d);
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        Rational::new(&a * &d - &c * &b, b * d)
    }
}

impl Mul for &Rational {
    type Output = Rational;
    #[inline]
    fn mul(self, o: &Rational) -> Rational {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            let n = *a as i128 * *c as i128;
            if *b == 1 && *d == 1 {
                return match small(n) {
                    Some(v) => Rational(Repr::Small(v, 1)),
                    None => Rational(Repr::Big(Box::new((Int::from(n), Int::ONE)))),
                };
            }
            return Rational::from_i128(n, *b as i128 * *d as i128);
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        Rational::new(a * c, b * d)
    }
}

impl Div for &Rational {
    type Output = Rational;
    /// `self / o`. Panics when `o` is zero.
    fn div(self, o: &Rational) -> Rational {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            return Rational::from_i128(*a as i128 * *d as i128, *b as i128 * *c as i128);
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        Rational::new(a * d, b * c)
    }
}

impl Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        match &self.0 {
            Repr::Small(n, d) => Rational(Repr::Small(-n, *d)),
            Repr::Big(b) => Rational(Repr::Big(Box::new((-b.0.clone(), b.1.clone())))),
        }
    }
}

impl Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        -&self
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Rational {
    #[inline]
    fn cmp(&self, o: &Self) -> Ordering {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            return (*a as i128 * *d as i128).cmp(&(*c as i128 * *b as i128));
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        (a * d).cmp(&(c * b))
    }
}

/// `a + b` of two rational points or vectors, componentwise.
pub fn add(a: &[Rational; 3], b: &[Rational; 3]) -> [Rational; 3] {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

/// `a - b` of two rational points or vectors, componentwise.
pub fn sub(a: &[Rational; 3], b: &[Rational; 3]) -> [Rational; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

/// The dot product `a[0] b[0] + a[1] b[1] + a[2] b[2]` of two rational vectors.
pub fn dot(a: &[Rational; 3], b: &[Rational; 3]) -> Rational {
    let s = &(&a[0] * &b[0]) + &(&a[1] * &b[1]);
    &s + &(&a[2] * &b[2])
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Small(n, 1) => write!(f, "{n}"),
            Repr::Small(n, d) => write!(f, "{n}/{d}"),
            Repr::Big(b) if b.1 == Int::ONE => write!(f, "{}", b.0),
            Repr::Big(b) => write!(f, "{}/{}", b.0, b.1),
        }
    }
}

impl fmt::Debug for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_and_display() {
        let a = Rational::new(Int::from(32), Int::from(6));
        assert_eq!(a.to_string(), "16/3");
        let b = Rational::new(Int::from(-2), Int::from(-4));
        assert_eq!(b.to_string(), "1/2");
        assert_eq!((&a + &b).to_string(), "35/6");
        assert_eq!((&a - &a).to_string(), "0");
        assert_eq!((&a * &b).to_string(), "8/3");
        assert!(a > b);
        assert_eq!(Rational::pow2(3).to_string(), "8");
        assert_eq!(Rational::pow2(-2).to_string(), "1/4");
        assert_eq!(Rational::pow2(0).to_string(), "1");
        assert!((a.to_f64() - 16.0 / 3.0).abs() < 1e-15);
        assert_eq!((&a / &b).to_string(), "32/3");
        assert_eq!(a.recip().to_string(), "3/16");
        assert_eq!((-a.clone()).to_string(), "-16/3");
        assert_eq!(Rational::from(-7).to_string(), "-7");
        assert_eq!(Rational::from_i128(6, -4).to_string(), "-3/2");
        let (p, q) = (
            [1, 2, 3].map(Rational::from),
            [a.clone(), b.clone(), a.clone()],
        );
        assert_eq!(dot(&p, &q).to_string(), "67/3");
        assert_eq!(sub(&add(&p, &q), &q), p);
    }

    /// The machine-word path and the arbitrary-precision one give the same canonical
    /// values (so equal values hash equal), near and beyond the `i64` range, and the
    /// nearest double of a small fraction is that of its numerator and denominator
    /// converted apart and divided.
    #[test]
    fn word_path_agrees_with_arbitrary_precision() {
        // The reduced fraction n / d computed on Ints alone.
        let reference = |n: Int, d: Int| -> (Int, Int) {
            let (n, d) = if d < Int::ZERO { (-n, -d) } else { (n, d) };
            let g = int::gcd(&n, &d);
            (n / &g, d / g)
        };
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let edge = [
            0i64,
            1,
            -1,
            2,
            3,
            6,
            i64::MAX,
            i64::MIN,
            i64::MIN + 1,
            1 << 62,
        ];
        let huge = Int::ONE << 100usize;
        for k in 0..4000 {
            let mut pick = |nonzero: bool| -> i64 {
                let v = match k % 3 {
                    0 => edge[(next() % edge.len() as u64) as usize],
                    1 => (next() % 200) as i64 - 100,
                    _ => next() as i64,
                };
                if nonzero && v == 0 {
                    7
                } else {
                    v
                }
            };
            let (a, b, c, d) = (pick(false), pick(true), pick(false), pick(true));
            let x = Rational::new(Int::from(a), Int::from(b));
            let y = Rational::new(Int::from(c), Int::from(d));
            let parts = |r: &Rational| (r.numer(), r.denom());
            assert_eq!(parts(&x), reference(Int::from(a), Int::from(b)));
            // Through the arbitrary-precision path: the same canonical value.
            assert_eq!(x, Rational::new(Int::from(a) * &huge, Int::from(b) * &huge));
            let ((xn, xd), (yn, yd)) = (parts(&x), parts(&y));
            assert_eq!(
                parts(&(&x + &y)),
                reference(&xn * &yd + &yn * &xd, &xd * &yd)
            );
            assert_eq!(
                parts(&(&x - &y)),
                reference(&xn * &yd - &yn * &xd, &xd * &yd)
            );
            assert_eq!(parts(&(&x * &y)), reference(&xn * &yn, &xd * &yd));
            assert_eq!(x.cmp(&y), (&xn * &yd).cmp(&(&yn * &xd)));
            assert_eq!(&(&x + &y) - &y, x);
            assert_eq!(-(-x.clone()), x);
            let f = int::to_f64(&xn) / int::to_f64(&xd);
            assert_eq!(x.to_f64().to_bits(), f.to_bits());
        }
    }

    #[test]
    fn dyadic_doubles_are_exact() {
        let r = |n: i128, d: i128| Rational::from_i128(n, d);
        assert_eq!(Rational::from_f64(0.375).unwrap(), r(3, 8));
        assert_eq!(Rational::from_f64(-12.0).unwrap(), r(-12, 1));
        assert_eq!(Rational::from_f64(0.0).unwrap(), Rational::zero());
        assert_eq!(Rational::from_f64(0.1).unwrap().to_f64(), 0.1);
        assert_eq!(Rational::from_f64(1e300).unwrap().to_f64(), 1e300);
        assert!(Rational::from_f64(f64::NAN).is_none());
    }
}
