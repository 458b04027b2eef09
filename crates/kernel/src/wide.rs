//! The fixed-width exact tier: polynomials of `i128` inputs evaluated in 256- to
//! 512-bit integers (`bnum`), several times faster than arbitrary precision for the
//! sizes the partitioner builds (great-circle intersections have at most 4B + 7 = 127
//! bits for the default B = 30).

use crate::Sign;
use bnum::cast::CastFrom;

type I256 = bnum::Int<32>;
type I384 = bnum::Int<48>;
type I512 = bnum::Int<64>;

#[inline]
fn bits128(v: &[i128; 3]) -> u32 {
    let m = v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs();
    128 - m.leading_zeros()
}

macro_rules! sign_of {
    ($v:expr) => {{
        let v = $v;
        if v.is_zero() {
            Sign::Zero
        } else if v.is_negative() {
            Sign::Negative
        } else {
            Sign::Positive
        }
    }};
}

/// Exact sign of a · b for components below 2^127 in magnitude.
/// Products stay below 2^254; the sum of three needs at most 256 bits.
pub fn dot_sign(a: &[i128; 3], b: &[i128; 3]) -> Sign {
    if bits128(a) + bits128(b) + 2 <= 255 {
        let m = |x: i128, y: i128| I256::cast_from(x) * I256::cast_from(y);
        sign_of!(m(a[0], b[0]) + m(a[1], b[1]) + m(a[2], b[2]))
    } else {
        let m = |x: i128, y: i128| I384::cast_from(x) * I384::cast_from(y);
        sign_of!(m(a[0], b[0]) + m(a[1], b[1]) + m(a[2], b[2]))
    }
}

/// Exact sign of det[a; b; c] for components below 2^127 in magnitude.
/// The 2x2 minors of b and c stay below 2^255 (fit 256 bits); the full determinant needs
/// at most `bits(a) + bits(b) + bits(c) + 3` bits, 384 or 512 by that bound.
pub fn det3_sign(a: &[i128; 3], b: &[i128; 3], c: &[i128; 3]) -> Sign {
    let m = |x: i128, y: i128| I256::cast_from(x) * I256::cast_from(y);
    let m0 = m(b[1], c[2]) - m(b[2], c[1]);
    let m1 = m(b[2], c[0]) - m(b[0], c[2]);
    let m2 = m(b[0], c[1]) - m(b[1], c[0]);
    if bits128(a) + bits128(b) + bits128(c) + 3 <= 383 {
        let w = I384::cast_from;
        sign_of!(
            I384::cast_from(a[0]) * w(m0)
                + I384::cast_from(a[1]) * w(m1)
                + I384::cast_from(a[2]) * w(m2)
        )
    } else {
        let w = I512::cast_from;
        sign_of!(
            I512::cast_from(a[0]) * w(m0)
                + I512::cast_from(a[1]) * w(m1)
                + I512::cast_from(a[2]) * w(m2)
        )
    }
}
