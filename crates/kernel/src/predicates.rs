//! Filtered exact predicates on integer vectors.
//!
//! Every predicate returns the exact sign of a polynomial in the integer inputs. It is
//! evaluated in three tiers:
//! 1. **machine integers**: when every input is a small [`Vec3`] and the polynomial's bit
//!    bound fits in 127 bits, it is computed exactly in `i128` (a few ns, no filter needed);
//! 2. **floating-point filter**: otherwise the polynomial is computed in `f64` from the
//!    inputs' shadows with a rigorous error bound; the sign is returned when the value is
//!    farther from zero than the bound;
//! 3. **exact fallback**: fixed-width 256–512-bit integers when every input fits in
//!    127 bits, arbitrary-precision integers beyond.
//!
//! Error bounds. Inputs enter the filter rounded to nearest with relative error at most
//! `u' = 2^-52` (conservatively twice the unit roundoff `u = 2^-53`). A sum of products of
//! `k` rounded factors evaluated with `m` further roundings differs from the exact value
//! by at most `γ_{2k+m} · P`, where `P` is the same expression with absolute values and
//! `γ_n = n u / (1 - n u)`. `P` itself is computed in floating point and may be too small
//! by a factor `(1 - γ_n)`; the bounds below include that slack.
//!
//! Bit bounds are given for inputs of `b` bits (`|x| < 2^b`); with grid coordinates of
//! `B` bits see the module docs of [`crate::spherical`] for the bits of the derived
//! quantities.

use crate::int::{self, Int};
use crate::vec3::{Components, Vec3};
use crate::wide;
use crate::Sign;

const U: f64 = f64::EPSILON / 2.0; // 2^-53

/// Relative error bound of the dot-product filter: 2 rounded factors (4u), 1 product,
/// 2 additions: γ_7, padded to 10u for the computed `P`.
const DOT_ERR: f64 = 10.0 * U;
/// Relative error bound of the 3x3-determinant filter: 3 rounded factors (6u), 2
/// products, 1 subtraction, 2 additions: γ_11, padded to 16u for the computed `P`.
const DET3_ERR: f64 = 16.0 * U;

#[inline]
fn small_bits(vs: &[&[i64; 3]]) -> u32 {
    let mut m = 0u64;
    for v in vs {
        m |= v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs();
    }
    64 - m.leading_zeros()
}

// ---------------------------------------------------------------------------------------
// Dot product
// ---------------------------------------------------------------------------------------

/// Sign of the dot product a · b.
///
/// Degree 2; bits `bits(a) + bits(b) + 2`. Uses: side of a point with respect to a great
/// circle (normal · point), side of a point with respect to a plane through the origin.
#[inline]
pub fn dot_sign(a: &Vec3, b: &Vec3) -> Sign {
    if let (Some(x), Some(y)) = (a.as_small(), b.as_small()) {
        // Two 62-bit factors: products < 2^124, their sum < 2^126.
        return Sign::of_i128(
            x[0] as i128 * y[0] as i128 + x[1] as i128 * y[1] as i128 + x[2] as i128 * y[2] as i128,
        );
    }
    if let (Some(x), Some(y)) = (a.filter_approx(), b.filter_approx()) {
        if let Some(s) = dot_filter(&x, &y) {
            return s;
        }
    }
    dot_sign_exact(a, b)
}

/// The floating-point filter of [`dot_sign`]: `None` when it cannot certify the sign.
#[inline]
pub fn dot_filter(a: &[f64; 3], b: &[f64; 3]) -> Option<Sign> {
    let v = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let p = (a[0] * b[0]).abs() + (a[1] * b[1]).abs() + (a[2] * b[2]).abs();
    let bound = DOT_ERR * p;
    if !bound.is_finite() {
        return None;
    }
    if v > bound {
        Some(Sign::Positive)
    } else if v < -bound {
        Some(Sign::Negative)
    } else if p == 0.0 {
        // Every product is exactly zero: each has a zero factor (inputs round to zero
        // only when they are zero).
        Some(Sign::Zero)
    } else {
        None
    }
}

/// Exact sign of a · b without the filter: fixed width when the inputs fit 127 bits,
/// arbitrary precision otherwise.
pub fn dot_sign_exact(a: &Vec3, b: &Vec3) -> Sign {
    if let (Some(x), Some(y)) = (a.as_wide(), b.as_wide()) {
        return wide::dot_sign(&x, &y);
    }
    int::sign_of(&a.dot(b))
}

// ---------------------------------------------------------------------------------------
// 3x3 determinant
// ---------------------------------------------------------------------------------------

/// Sign of det[a; b; c] = a · (b × c): the orientation of three direction vectors.
///
/// Positive when (a, b, c) is a right-handed basis; zero when the three are coplanar with
/// the origin (in particular when two are parallel). Degree 3; bits
/// `bits(a) + bits(b) + bits(c) + 3`. Uses: orientation of three sphere points, position of
/// a point along a great circle (`det(n, p, q)`), angular order of great circles through
/// a vertex (`det(n1, n2, v)`).
#[inline]
pub fn det3_sign(a: &Vec3, b: &Vec3, c: &Vec3) -> Sign {
    if let (Some(x), Some(y), Some(z)) = (a.as_small(), b.as_small(), c.as_small()) {
        if small_bits(&[x, y, z]) <= 41 {
            return Sign::of_i128(det3_i128(x, y, z));
        }
    }
    if let (Some(x), Some(y), Some(z)) = (a.filter_approx(), b.filter_approx(), c.filter_approx()) {
        if let Some(s) = det3_filter(&x, &y, &z) {
            return s;
        }
    }
    det3_sign_exact(a, b, c)
}

/// det[a; b; c] in `i128`, exact when every entry has at most 41 bits
/// (each term < 2^123, the sum of six < 2^126).
#[inline]
pub fn det3_i128(a: &[i64; 3], b: &[i64; 3], c: &[i64; 3]) -> i128 {
    let (b0, b1, b2) = (b[0] as i128, b[1] as i128, b[2] as i128);
    let (c0, c1, c2) = (c[0] as i128, c[1] as i128, c[2] as i128);
    a[0] as i128 * (b1 * c2 - b2 * c1)
        + a[1] as i128 * (b2 * c0 - b0 * c2)
        + a[2] as i128 * (b0 * c1 - b1 * c0)
}

/// The floating-point filter of [`det3_sign`]: `None` when it cannot certify the sign.
#[inline]
pub fn det3_filter(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> Option<Sign> {
    let m0 = b[1] * c[2] - b[2] * c[1];
    let m1 = b[2] * c[0] - b[0] * c[2];
    let m2 = b[0] * c[1] - b[1] * c[0];
    let v = a[0] * m0 + a[1] * m1 + a[2] * m2;
    let p0 = (b[1] * c[2]).abs() + (b[2] * c[1]).abs();
    let p1 = (b[2] * c[0]).abs() + (b[0] * c[2]).abs();
    let p2 = (b[0] * c[1]).abs() + (b[1] * c[0]).abs();
    let p = a[0].abs() * p0 + a[1].abs() * p1 + a[2].abs() * p2;
    let bound = DET3_ERR * p;
    if !bound.is_finite() {
        return None;
    }
    if v > bound {
        Some(Sign::Positive)
    } else if v < -bound {
        Some(Sign::Negative)
    } else if p == 0.0 {
        Some(Sign::Zero)
    } else {
        None
    }
}

/// Exact sign of det[a; b; c] without the filter: `i128` for entries of at most 41 bits,
/// fixed width for entries below 2^127, arbitrary precision otherwise.
pub fn det3_sign_exact(a: &Vec3, b: &Vec3, c: &Vec3) -> Sign {
    if let (Some(x), Some(y), Some(z)) = (a.as_small(), b.as_small(), c.as_small()) {
        if small_bits(&[x, y, z]) <= 41 {
            return Sign::of_i128(det3_i128(x, y, z));
        }
    }
    if let (Some(x), Some(y), Some(z)) = (a.as_wide(), b.as_wide(), c.as_wide()) {
        return wide::det3_sign(&x, &y, &z);
    }
    int::sign_of(&det3(a, b, c))
}

/// Exact value of det[a; b; c].
pub fn det3(a: &Vec3, b: &Vec3, c: &Vec3) -> Int {
    a.dot(&b.cross(c))
}

// ---------------------------------------------------------------------------------------
// Derived predicates
// ---------------------------------------------------------------------------------------

/// True when a and b are parallel or one is zero (a × b = 0). Exact; bits
/// `bits(a) + bits(b) + 1`.
pub fn parallel(a: &Vec3, b: &Vec3) -> bool {
    if let (Some(x), Some(y)) = (a.as_small(), b.as_small()) {
        let (x0, x1, x2) = (x[0] as i128, x[1] as i128, x[2] as i128);
        let (y0, y1, y2) = (y[0] as i128, y[1] as i128, y[2] as i128);
        return x1 * y2 == x2 * y1 && x2 * y0 == x0 * y2 && x0 * y1 == x1 * y0;
    }
    a.cross(b).is_zero()
}

/// True when a and b are non-zero and point the same way (the same sphere point).
pub fn same_direction(a: &Vec3, b: &Vec3) -> bool {
    !a.is_zero() && !b.is_zero() && parallel(a, b) && dot_sign(a, b) == Sign::Positive
}

/// Sign of `n · p` for a plane or great circle with normal `n` and a point `p`; an alias
/// of [`dot_sign`] named after its most frequent question.
#[inline]
pub fn side(n: &Vec3, p: &Vec3) -> Sign {
    dot_sign(n, p)
}

/// The components as `i128`, if each fits.
pub fn small_or_none(v: &Vec3) -> Option<[i128; 3]> {
    match v.components() {
        Components::Small(c) => Some([c[0] as i128, c[1] as i128, c[2] as i128]),
        Components::Big(c) => Some([
            int::to_i128(&c[0])?,
            int::to_i128(&c[1])?,
            int::to_i128(&c[2])?,
        ]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn det3_basics() {
        let x = Vec3::new(1, 0, 0);
        let y = Vec3::new(0, 1, 0);
        let z = Vec3::new(0, 0, 1);
        assert_eq!(det3_sign(&x, &y, &z), Sign::Positive);
        assert_eq!(det3_sign(&y, &x, &z), Sign::Negative);
        assert_eq!(det3_sign(&x, &x, &z), Sign::Zero);
    }

    #[test]
    fn filter_declines_near_zero() {
        // (2^60 + 1) * (2^60 - 1) - 2^120 = -1: far below the filter's error bound.
        let a = [((1u64 << 60) + 1) as f64, 0.0, 0.0];
        let b = [((1u64 << 60) - 1) as f64, 0.0, 0.0];
        assert!(dot_filter(&a, &b).is_some()); // no cancellation: a certain positive sign
        let big = Vec3::from_ints([
            (Int::from(1) << 60usize) + 1,
            Int::from(1) << 60usize,
            Int::ZERO,
        ]);
        let other = Vec3::from_ints([
            (Int::from(1) << 60usize) - 1,
            -(Int::from(1) << 60usize),
            Int::ZERO,
        ]);
        // (2^60+1)(2^60-1) - 2^120 = -1
        assert_eq!(dot_filter(&big.approx(), &other.approx()), None);
        assert_eq!(dot_sign(&big, &other), Sign::Negative);
    }
}
