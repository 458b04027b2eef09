//! The result type of every predicate.

use std::ops::{Mul, Neg};

/// The sign of an exactly evaluated polynomial: the only thing a predicate returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Sign {
    /// Strictly below zero.
    Negative,
    /// Exactly zero: the degenerate case, decided exactly.
    Zero,
    /// Strictly above zero.
    Positive,
}

impl Sign {
    /// The sign of an `i128`.
    #[inline]
    pub fn of_i128(v: i128) -> Sign {
        match v.cmp(&0) {
            std::cmp::Ordering::Less => Sign::Negative,
            std::cmp::Ordering::Equal => Sign::Zero,
            std::cmp::Ordering::Greater => Sign::Positive,
        }
    }

    /// The sign of an `i64`.
    #[inline]
    pub fn of_i64(v: i64) -> Sign {
        Sign::of_i128(v as i128)
    }

    /// -1, 0 or 1.
    #[inline]
    pub fn as_i32(self) -> i32 {
        match self {
            Sign::Negative => -1,
            Sign::Zero => 0,
            Sign::Positive => 1,
        }
    }

    /// True for [`Sign::Positive`].
    #[inline]
    pub fn is_positive(self) -> bool {
        self == Sign::Positive
    }

    /// True for [`Sign::Negative`].
    #[inline]
    pub fn is_negative(self) -> bool {
        self == Sign::Negative
    }

    /// True for [`Sign::Zero`].
    #[inline]
    pub fn is_zero(self) -> bool {
        self == Sign::Zero
    }
}

impl Neg for Sign {
    type Output = Sign;
    #[inline]
    fn neg(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
}

impl Mul for Sign {
    type Output = Sign;
    #[inline]
    fn mul(self, rhs: Sign) -> Sign {
        match (self, rhs) {
            (Sign::Zero, _) | (_, Sign::Zero) => Sign::Zero,
            (a, b) if a == b => Sign::Positive,
            _ => Sign::Negative,
        }
    }
}
