//! `Q`: exact rationals with a machine-word fast path.
//!
//! Placement runs thousands of small linear and quadratic programs whose numbers are
//! mostly small (grid coordinates, sheet thicknesses, rotation denominators). `Q` keeps
//! a reduced `i64 / i64` when both fit and computes in `i128` before reducing, falling
//! back to arbitrary precision (`apart_kernel::Int`) otherwise. The representation is
//! canonical (reduced, positive denominator, machine words whenever they fit), so
//! equality and hashing are exact.

use apart_kernel::int::{self, Int};
use apart_kernel::Sign;
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

/// An exact rational number.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Q(Repr);

#[derive(Clone, PartialEq, Eq, Hash)]
enum Repr {
    /// `n / d`, `d > 0`, reduced, `n != i64::MIN`.
    Small(i64, i64),
    /// `n / d`, `d > 0`, reduced, not both fitting in `i64`.
    Big(Box<(Int, Int)>),
}

#[inline]
fn gcd_u64(mut a: u64, mut b: u64) -> u64 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

#[inline]
fn small(n: i128) -> Option<i64> {
    if n > i64::MIN as i128 && n <= i64::MAX as i128 {
        Some(n as i64)
    } else {
        None
    }
}

impl Q {
    /// The integer `v`.
    #[inline]
    pub fn from_i64(v: i64) -> Q {
        if v == i64::MIN {
            return Q::from_int(Int::from(v));
        }
        Q(Repr::Small(v, 1))
    }

    /// The integer `v`.
    pub fn from_int(v: impl Into<Int>) -> Q {
        let v: Int = v.into();
        match int::to_i64(&v) {
            Some(s) if s != i64::MIN => Q(Repr::Small(s, 1)),
            _ => Q(Repr::Big(Box::new((v, Int::ONE)))),
        }
    }

    /// `n / d`, reduced (`d != 0`).
    pub fn new(n: Int, d: Int) -> Q {
        if let (Some(a), Some(b)) = (int::to_i64(&n), int::to_i64(&d)) {
            return Q::from_i128(a as i128, b as i128);
        }
        assert!(d != Int::ZERO, "rational with zero denominator");
        let (n, d) = if d < Int::ZERO { (-n, -d) } else { (n, d) };
        let g = int::gcd(&n, &d);
        let (n, d) = if g > Int::ONE {
            (n / &g, d / g)
        } else {
            (n, d)
        };
        match (int::to_i64(&n), int::to_i64(&d)) {
            (Some(a), Some(b)) if a != i64::MIN => Q(Repr::Small(a, b)),
            _ => Q(Repr::Big(Box::new((n, d)))),
        }
    }

    /// `n / d` from machine integers, reduced (`d != 0`).
    #[inline]
    pub fn from_i128(n: i128, d: i128) -> Q {
        assert!(d != 0, "rational with zero denominator");
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        if n == 0 {
            return Q(Repr::Small(0, 1));
        }
        let g = if (n.unsigned_abs() | d as u128) >> 64 == 0 {
            gcd_u64(n.unsigned_abs() as u64, d as u64) as i128
        } else {
            int::gcd_u128(n.unsigned_abs(), d as u128) as i128
        };
        let (n, d) = (n / g, d / g);
        match (small(n), small(d)) {
            (Some(a), Some(b)) => Q(Repr::Small(a, b)),
            _ => Q(Repr::Big(Box::new((Int::from(n), Int::from(d))))),
        }
    }

    /// Zero.
    pub fn zero() -> Q {
        Q(Repr::Small(0, 1))
    }

    /// The numerator (carries the sign).
    pub fn numer(&self) -> Int {
        match &self.0 {
            Repr::Small(n, _) => Int::from(*n),
            Repr::Big(b) => b.0.clone(),
        }
    }

    /// The positive denominator.
    pub fn denom(&self) -> Int {
        match &self.0 {
            Repr::Small(_, d) => Int::from(*d),
            Repr::Big(b) => b.1.clone(),
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

    /// `1 / self` (`self != 0`).
    pub fn recip(&self) -> Q {
        match &self.0 {
            Repr::Small(n, d) => Q::from_i128(*d as i128, *n as i128),
            Repr::Big(b) => Q::new(b.1.clone(), b.0.clone()),
        }
    }

    /// `|self|`.
    pub fn abs(&self) -> Q {
        if self.sign() == Sign::Negative {
            -self
        } else {
            self.clone()
        }
    }

    /// Nearest double (to a few ulps).
    pub fn to_f64(&self) -> f64 {
        match &self.0 {
            Repr::Small(n, d) => *n as f64 / *d as f64,
            Repr::Big(b) => apart_kernel::Rational::new(b.0.clone(), b.1.clone()).to_f64(),
        }
    }

    /// As the kernel's rational type.
    pub fn to_rational(&self) -> apart_kernel::Rational {
        let (n, d) = self.parts();
        apart_kernel::Rational::new(n, d)
    }
}

impl From<i64> for Q {
    fn from(v: i64) -> Q {
        Q::from_i64(v)
    }
}

impl Add for &Q {
    type Output = Q;
    #[inline]
    fn add(self, o: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            if b == d {
                return Q::from_i128(*a as i128 + *c as i128, *b as i128);
            }
            return Q::from_i128(
                *a as i128 * *d as i128 + *c as i128 * *b as i128,
                *b as i128 * *d as i128,
            );
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        Q::new(&a * &d + &c * &b, b * d)
    }
}

impl Sub for &Q {
    type Output = Q;
    #[inline]
    fn sub(self, o: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            if b == d {
                return Q::from_i128(*a as i128 - *c as i128, *b as i128);
            }
            return Q::from_i128(
                *a as i128 * *d as i128 - *c as i128 * *b as i128,
                *b as i128 * *d as i128,
            );
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        Q::new(&a * &d - &c * &b, b * d)
    }
}

impl Mul for &Q {
    type Output = Q;
    #[inline]
    fn mul(self, o: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            if *d == 1 && *b == 1 {
                return match (*a as i128).checked_mul(*c as i128).and_then(small) {
                    Some(v) => Q(Repr::Small(v, 1)),
                    None => Q::from_i128(*a as i128 * *c as i128, 1),
                };
            }
            return Q::from_i128(*a as i128 * *c as i128, *b as i128 * *d as i128);
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        Q::new(a * c, b * d)
    }
}

impl Neg for &Q {
    type Output = Q;
    fn neg(self) -> Q {
        match &self.0 {
            Repr::Small(n, d) => Q(Repr::Small(-n, *d)),
            Repr::Big(b) => Q(Repr::Big(Box::new((-b.0.clone(), b.1.clone())))),
        }
    }
}

impl Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        -&self
    }
}

impl PartialOrd for Q {
    fn partial_cmp(&self, o: &Q) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Q {
    fn cmp(&self, o: &Q) -> Ordering {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            return (*a as i128 * *d as i128).cmp(&(*c as i128 * *b as i128));
        }
        let ((a, b), (c, d)) = (self.parts(), o.parts());
        (a * d).cmp(&(c * b))
    }
}

impl fmt::Display for Q {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (n, d) = self.parts();
        if d == Int::ONE {
            write!(f, "{n}")
        } else {
            write!(f, "{n}/{d}")
        }
    }
}

impl fmt::Debug for Q {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn big(n: i64, d: i64) -> apart_kernel::Rational {
        apart_kernel::Rational::new(Int::from(n), Int::from(d))
    }

    proptest! {
        /// Every operation agrees with the kernel's arbitrary-precision rationals,
        /// including values near and beyond the machine-word range.
        #[test]
        fn agrees_with_big_rationals(
            a in prop_oneof![-50i64..50, any::<i64>()],
            b in prop_oneof![1i64..50, 1i64..i64::MAX],
            c in prop_oneof![-50i64..50, any::<i64>()],
            d in prop_oneof![1i64..50, 1i64..i64::MAX],
        ) {
            let (x, y) = (Q::new(Int::from(a), Int::from(b)), Q::new(Int::from(c), Int::from(d)));
            let (bx, by) = (big(a, b), big(c, d));
            prop_assert_eq!((&x + &y).to_rational(), &bx + &by);
            prop_assert_eq!((&x - &y).to_rational(), &bx - &by);
            prop_assert_eq!((&x * &y).to_rational(), &bx * &by);
            prop_assert_eq!(x.cmp(&y), bx.cmp(&by));
            // Canonical: a value computed two ways is equal and hashes equal.
            let z = &(&x + &y) - &y;
            prop_assert_eq!(&z, &x);
        }
    }
}
