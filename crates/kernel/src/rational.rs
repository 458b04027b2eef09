//! Exact rational numbers, for volumes, witness points and other reported quantities.

use crate::int::{self, Int};
use crate::Sign;
use dashu_int::ops::UnsignedAbs;
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

/// A reduced fraction `num / den` with `den > 0`.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Rational {
    num: Int,
    den: Int,
}

impl Rational {
    /// Zero.
    pub fn zero() -> Rational {
        Rational {
            num: Int::ZERO,
            den: Int::ONE,
        }
    }

    /// The integer `v`.
    pub fn from_int(v: impl Into<Int>) -> Rational {
        Rational {
            num: v.into(),
            den: Int::ONE,
        }
    }

    /// `num / den`, reduced. Panics when `den` is zero (a programming error: every caller
    /// divides by a quantity it has checked).
    pub fn new(num: Int, den: Int) -> Rational {
        assert!(den != Int::ZERO, "rational with zero denominator");
        let (num, den) = if int::sign_of(&den) == Sign::Negative {
            (-num, -den)
        } else {
            (num, den)
        };
        let g = int::gcd(&num, &den);
        if g > Int::ONE {
            Rational {
                num: &num / &g,
                den: &den / &g,
            }
        } else {
            Rational { num, den }
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
    pub fn numer(&self) -> &Int {
        &self.num
    }

    /// Denominator (positive).
    pub fn denom(&self) -> &Int {
        &self.den
    }

    /// The sign.
    pub fn sign(&self) -> Sign {
        int::sign_of(&self.num)
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        self.num == Int::ZERO
    }

    /// |self|.
    pub fn abs(&self) -> Rational {
        Rational {
            num: Int::from((&self.num).unsigned_abs()),
            den: self.den.clone(),
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

    /// Nearest `f64` (to within a few ulps).
    pub fn to_f64(&self) -> f64 {
        let (n, d) = (int::to_f64(&self.num), int::to_f64(&self.den));
        if n.is_finite() && d.is_finite() && d != 0.0 {
            return n / d;
        }
        // Scale both down to keep the quotient in range.
        let shift = int::bit_len(&self.num)
            .max(int::bit_len(&self.den))
            .saturating_sub(900) as usize;
        int::to_f64(&(&self.num >> shift)) / int::to_f64(&(&self.den >> shift))
    }
}

impl Add for &Rational {
    type Output = Rational;
    fn add(self, o: &Rational) -> Rational {
        Rational::new(&self.num * &o.den + &o.num * &self.den, &self.den * &o.den)
    }
}

impl Sub for &Rational {
    type Output = Rational;
    fn sub(self, o: &Rational) -> Rational {
        Rational::new(&self.num * &o.den - &o.num * &self.den, &self.den * &o.den)
    }
}

impl Mul for &Rational {
    type Output = Rational;
    fn mul(self, o: &Rational) -> Rational {
        Rational::new(&self.num * &o.num, &self.den * &o.den)
    }
}

impl Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        Rational {
            num: -&self.num,
            den: self.den.clone(),
        }
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Rational {
    fn cmp(&self, o: &Self) -> Ordering {
        (&self.num * &o.den).cmp(&(&o.num * &self.den))
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == Int::ONE {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
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
    }
}
