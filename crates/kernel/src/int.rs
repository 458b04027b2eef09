//! Arbitrary-precision integers and the small helpers the kernel needs around them.
//!
//! `Int` is `dashu_int::IBig`: pure Rust, inline storage up to 128 bits, and the
//! fastest pure-Rust big integer we measured (see `BENCHMARKS.md`). Every value that
//! fits in 62 bits is kept as a machine integer by [`crate::Vec3`], so `Int` is only
//! touched by constructed values (great-circle intersections, rational vertices) and
//! by the exact fallback of the predicates.

use crate::Sign;
use dashu_int::ops::{BitTest, Gcd, UnsignedAbs};
pub use dashu_int::IBig as Int;

/// Sign of an [`Int`].
#[inline]
pub fn sign_of(v: &Int) -> Sign {
    let s = v.signum();
    if s == Int::ZERO {
        Sign::Zero
    } else if s == Int::ONE {
        Sign::Positive
    } else {
        Sign::Negative
    }
}

/// Compares the fractions `x / dx` and `y / dy` (positive denominators) exactly, without
/// reducing them: equal denominators compare the numerators.
pub fn cmp_fractions(x: &Int, dx: &Int, y: &Int, dy: &Int) -> std::cmp::Ordering {
    if dx == dy {
        x.cmp(y)
    } else {
        (x * dy).cmp(&(y * dx))
    }
}

/// Number of bits of |v| (0 for 0).
#[inline]
pub fn bit_len(v: &Int) -> u32 {
    // The magnitude's length, read in place (`unsigned_abs` of a reference would copy).
    BitTest::bit_len(v) as u32
}

/// The `f64` nearest to `n / d` (`d > 0`), rounded once (ties to even), so that equal
/// fractions give the same double whatever their representation (`to_f64(n) / to_f64(d)`
/// rounds three times and can differ in the last bit). Infinite beyond the `f64` range;
/// quotients below about 2^-1000 come from that float quotient.
pub fn ratio_to_f64(n: &Int, d: &Int) -> f64 {
    debug_assert!(*d > Int::ZERO, "ratio_to_f64 needs a positive denominator");
    if *n == Int::ZERO {
        return 0.0;
    }
    // Exact operands divide once in IEEE arithmetic.
    const EXACT: u32 = 53;
    if bit_len(n) <= EXACT && bit_len(d) <= EXACT {
        return to_f64(n) / to_f64(d);
    }
    // q = ⌊|n| 2^k / d⌋ with 56 or 57 bits; a nonzero remainder sets its last bit, which
    // lies below the rounding bit, so converting q rounds as the true quotient would.
    let k = 56 - (bit_len(n) as i64 - bit_len(d) as i64);
    if k.abs() > 1000 {
        return to_f64(n) / to_f64(d);
    }
    let a = Int::from(n.unsigned_abs());
    let (a, b) = if k >= 0 {
        (a << k as usize, d.clone())
    } else {
        (a, d << (-k) as usize)
    };
    let (q, r) = (&a / &b, &a % &b);
    let q = u64::try_from(&q).expect("a quotient of at most 57 bits") | u64::from(r != Int::ZERO);
    // Exact scaling by a power of two (both factors within the normal range).
    let m = q as f64 * 2f64.powi(-(k / 2) as i32) * 2f64.powi(-(k - k / 2) as i32);
    if *n < Int::ZERO {
        -m
    } else {
        m
    }
}

/// Number of bits of |v| (0 for 0).
#[inline]
pub fn bit_len_i64(v: i64) -> u32 {
    64 - v.unsigned_abs().leading_zeros()
}

/// Number of bits of |v| (0 for 0).
#[inline]
pub fn bit_len_i128(v: i128) -> u32 {
    128 - v.unsigned_abs().leading_zeros()
}

/// Nearest `f64` of an [`Int`] (relative error at most 2^-52; infinite beyond the f64 range).
#[inline]
pub fn to_f64(v: &Int) -> f64 {
    v.to_f64().value()
}

/// The value as `i64` when it fits.
#[inline]
pub fn to_i64(v: &Int) -> Option<i64> {
    i64::try_from(v).ok()
}

/// The value as `i128` when it fits.
#[inline]
pub fn to_i128(v: &Int) -> Option<i128> {
    i128::try_from(v).ok()
}

/// Greatest common divisor of |a| and |b| (gcd(0, 0) = 0).
pub fn gcd(a: &Int, b: &Int) -> Int {
    if *a == Int::ZERO {
        return Int::from(b.unsigned_abs());
    }
    if *b == Int::ZERO {
        return Int::from(a.unsigned_abs());
    }
    Int::from(a.unsigned_abs().gcd(b.unsigned_abs()))
}

/// Least common multiple of two positive integers.
pub fn lcm(a: &Int, b: &Int) -> Int {
    let g = gcd(a, b);
    if g == Int::ONE {
        a * b
    } else {
        a / &g * b
    }
}

/// `⌈sqrt(v)⌉` for `v >= 0` (0 for `v <= 0`), exactly: the smallest `k` with `k² >= v`.
pub fn ceil_sqrt(v: &Int) -> Int {
    if *v <= Int::ZERO {
        return Int::ZERO;
    }
    let mut k = if bit_len(v) <= 100 {
        // The float root is within one of the true one.
        Int::from(to_f64(v).sqrt().floor() as u128)
    } else {
        // Newton's steps from above (2^⌈bits/2⌉ >= sqrt(v)) decrease to ⌊sqrt(v)⌋.
        let mut k = Int::ONE << (bit_len(v) as usize).div_ceil(2);
        loop {
            let next: Int = (&k + v / &k) >> 1usize;
            if next >= k {
                break k;
            }
            k = next;
        }
    };
    while &k * &k < *v {
        k += Int::ONE;
    }
    while k > Int::ZERO && (&k - Int::ONE) * (&k - Int::ONE) >= *v {
        k -= Int::ONE;
    }
    k
}

/// Greatest common divisor of |a| and |b| on machine words (gcd(0, 0) = 0).
///
/// Binary gcd; switches to 64-bit words as soon as both operands fit, which is where
/// most of the iterations happen for the ~126-bit intersection points.
#[inline]
pub fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    b >>= b.trailing_zeros();
    // Both odd from here on. Branch-free min/difference: the comparison is unpredictable.
    loop {
        if (a | b) >> 64 == 0 {
            return (gcd_odd_u64(a as u64, b as u64) as u128) << shift;
        }
        let lo = a.min(b);
        let hi = a.max(b);
        if lo >> 64 == 0 {
            // One Euclid step brings the other below 2^64 too (instead of as many
            // subtractions as it has bits more); `lo` is odd, so the gcd is, and the
            // remainder's factors of 2 can go.
            let r = hi % lo;
            if r == 0 {
                return lo << shift;
            }
            let r = r >> r.trailing_zeros();
            return (gcd_odd_u64(lo as u64, r as u64) as u128) << shift;
        }
        let d = hi - lo;
        if d == 0 {
            return lo << shift;
        }
        a = lo;
        b = d >> d.trailing_zeros();
    }
}

/// gcd of two odd non-zero words.
///
/// The shift comes from `a - b` taken modulo 2^64, which has the trailing zeros of
/// `|a - b|`: it does not wait for the minimum and the difference, which come alongside.
#[inline]
fn gcd_odd_u64(mut a: u64, mut b: u64) -> u64 {
    loop {
        let d = a.wrapping_sub(b);
        if d == 0 {
            return a;
        }
        let z = d.trailing_zeros();
        let lo = a.min(b);
        b = a.abs_diff(b) >> z;
        a = lo;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratio_to_f64_rounds_once() {
        // Against IEEE division of exactly representable operands, scaled by a common
        // factor that makes both wide: the quotient must not change.
        let mut x: u64 = 0x9e3779b97f4a7c15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let k = Int::from(3).pow(60);
        for _ in 0..20000 {
            let (a, b) = (
                (next() >> 11) as i64 - (1 << 52),
                (next() >> 11).max(1) as i64,
            );
            let want = a as f64 / b as f64;
            let (n, d) = (Int::from(a), Int::from(b));
            assert_eq!(ratio_to_f64(&n, &d).to_bits(), want.to_bits());
            assert_eq!(
                ratio_to_f64(&(&n * &k), &(&d * &k)).to_bits(),
                want.to_bits(),
                "{a}/{b}"
            );
            let big = Int::ONE << 300usize;
            assert_eq!(
                ratio_to_f64(&(&n * &big), &(&d * &big)).to_bits(),
                want.to_bits()
            );
        }
        // Halfway cases: 2^53 + 1 and 2^53 + 3 over 1 tie to even.
        let h = Int::from((1i64 << 53) + 1) * &k;
        assert_eq!(ratio_to_f64(&h, &k), (1u64 << 53) as f64);
        let h = Int::from((1i64 << 53) + 3) * &k;
        assert_eq!(ratio_to_f64(&h, &k), ((1u64 << 53) + 4) as f64);
        // Just above a halfway point rounds up.
        let above = Int::from((1i64 << 53) + 1) * &k + Int::ONE;
        assert_eq!(ratio_to_f64(&above, &k), ((1u64 << 53) + 2) as f64);
        assert_eq!(ratio_to_f64(&Int::ZERO, &k), 0.0);
    }

    #[test]
    fn gcd_matches_euclid() {
        for a in 0u128..60 {
            for b in 0u128..60 {
                let mut x = a;
                let mut y = b;
                while y != 0 {
                    let t = x % y;
                    x = y;
                    y = t;
                }
                assert_eq!(gcd_u128(a, b), x, "gcd({a},{b})");
                assert_eq!(gcd(&Int::from(a), &-Int::from(b)), Int::from(x));
            }
        }
    }

    proptest::proptest! {
        /// Wide operands, of equal or very different sizes, with a planted common
        /// factor (odd or even), against Euclid's algorithm.
        #[test]
        fn gcd_u128_matches_euclid(
            a in proptest::num::u128::ANY,
            b in proptest::num::u128::ANY,
            sa in 0u32..128,
            sb in 0u32..128,
            g in 1u64..1 << 20,
        ) {
            let (a, b) = ((a >> sa) / g as u128 * g as u128, (b >> sb) / g as u128 * g as u128);
            let (mut x, mut y) = (a, b);
            while y != 0 {
                (x, y) = (y, x % y);
            }
            proptest::prop_assert_eq!(gcd_u128(a, b), x);
        }
    }

    #[test]
    fn lcm_and_square_roots() {
        assert_eq!(lcm(&Int::from(4), &Int::from(6)), Int::from(12));
        assert_eq!(lcm(&Int::from(5), &Int::from(7)), Int::from(35));
        for v in (0i64..2000).chain([1 << 40, (1 << 40) + 1, i64::MAX]) {
            let k = ceil_sqrt(&Int::from(v));
            assert!(&k * &k >= Int::from(v), "{v}");
            assert!(
                k == Int::ZERO || (&k - Int::ONE) * (&k - Int::ONE) < Int::from(v),
                "{v}"
            );
        }
        for big in [
            (Int::from(3) << 200usize) + Int::ONE,
            Int::from(1u128 << 100) + Int::from(7),
        ] {
            let k = ceil_sqrt(&big);
            assert!(&k * &k >= big && (&k - Int::ONE) * (&k - Int::ONE) < big);
        }
    }

    #[test]
    fn bit_lengths() {
        assert_eq!(bit_len_i64(0), 0);
        assert_eq!(bit_len_i64(1), 1);
        assert_eq!(bit_len_i64(-8), 4);
        assert_eq!(bit_len_i64(i64::MIN), 64);
        assert_eq!(bit_len(&(Int::from(1) << 100usize)), 101);
        assert_eq!(bit_len_i128(-(1i128 << 100)), 101);
    }
}
