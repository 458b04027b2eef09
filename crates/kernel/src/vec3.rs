//! Exact integer 3-vectors: points on the grid, direction vectors, great-circle normals.
//!
//! A [`Vec3`] keeps machine integers while every component is below 2^62 and switches to
//! arbitrary precision above; the representation is canonical (a value has exactly one
//! form), so `==` and `Hash` are exact equality of the integer vectors. Large vectors
//! carry a cached `f64` shadow for the floating-point filter of the predicates.

use crate::int::{self, Int};
use std::fmt;

/// Components of a small vector stay strictly below this many bits.
pub const SMALL_BITS: u32 = 62;
const SMALL_LIMIT: i64 = 1 << SMALL_BITS;

/// An exact integer vector.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Vec3(Repr);

#[derive(Clone, PartialEq, Eq, Hash)]
enum Repr {
    /// All components strictly inside (-2^62, 2^62).
    Small([i64; 3]),
    /// At least one component of 62 bits or more.
    Big(Box<BigVec>),
}

#[derive(Clone)]
struct BigVec {
    c: [Int; 3],
    /// The components as `i128` when every one fits (for the fixed-width exact tier).
    wide: Option<[i128; 3]>,
    /// The components times 2^-s for a shift s that brings the largest into [1, 2), each
    /// within relative error 2^-52. Sign predicates are homogeneous in each argument, so
    /// they may use this shadow however large the integers are.
    approx: [f64; 3],
    /// False when some non-zero component falls below 2^-300 after scaling (a dynamic
    /// range the filter's products could underflow on): predicates then go exact.
    filterable: bool,
}

impl PartialEq for BigVec {
    fn eq(&self, o: &Self) -> bool {
        self.c == o.c
    }
}
impl Eq for BigVec {}
impl std::hash::Hash for BigVec {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        self.c.hash(h)
    }
}

/// Scales `raw` by a power of two so its largest magnitude lies in [1, 2) (exact), and
/// tells whether every non-zero value stays above 2^-300 (so that products of three
/// shadows stay far from underflow).
fn scaled_shadow(raw: &[f64; 3]) -> ([f64; 3], bool) {
    let m = raw.iter().fold(0f64, |m, v| m.max(v.abs()));
    if m == 0.0 || !m.is_finite() || !m.is_normal() {
        return (*raw, m == 0.0);
    }
    // ⌊log2 m⌋ from the exponent field (m is normal).
    let e = ((m.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let out = raw.map(|v| v * pow2(-e));
    let ok = out.iter().all(|v| *v == 0.0 || v.abs() >= pow2(-300));
    (out, ok)
}

/// `2^k` exactly, for `k` in the normal range `-1022..=1023` (without `powi`'s loop).
#[inline]
fn pow2(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((k + 1023) as u64) << 52)
}

#[inline]
fn fits_small(v: i128) -> bool {
    v > -(SMALL_LIMIT as i128) && v < SMALL_LIMIT as i128
}

/// Either representation of the components, for code that must branch on size.
pub enum Components<'a> {
    /// Machine integers, each of at most 62 bits.
    Small(&'a [i64; 3]),
    /// Arbitrary precision.
    Big(&'a [Int; 3]),
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Vec3 = Vec3(Repr::Small([0, 0, 0]));

    /// A vector from machine integers (any `i64`).
    #[inline]
    pub fn new(x: i64, y: i64, z: i64) -> Vec3 {
        Vec3::from_i128([x as i128, y as i128, z as i128])
    }

    /// A vector from `i64` components.
    #[inline]
    pub fn from_i64(c: [i64; 3]) -> Vec3 {
        Vec3::new(c[0], c[1], c[2])
    }

    /// A vector from `i128` components.
    #[inline]
    pub fn from_i128(c: [i128; 3]) -> Vec3 {
        if fits_small(c[0]) && fits_small(c[1]) && fits_small(c[2]) {
            Vec3(Repr::Small([c[0] as i64, c[1] as i64, c[2] as i64]))
        } else {
            let wide = if c.contains(&i128::MIN) {
                None
            } else {
                Some(c)
            };
            let (approx, filterable) = scaled_shadow(&c.map(|v| v as f64));
            Vec3(Repr::Big(Box::new(BigVec {
                c: c.map(Int::from),
                wide,
                approx,
                filterable,
            })))
        }
    }

    /// A vector from arbitrary-precision components.
    pub fn from_ints(c: [Int; 3]) -> Vec3 {
        let small = [int::to_i64(&c[0]), int::to_i64(&c[1]), int::to_i64(&c[2])];
        if let [Some(x), Some(y), Some(z)] = small {
            if fits_small(x as i128) && fits_small(y as i128) && fits_small(z as i128) {
                return Vec3(Repr::Small([x, y, z]));
            }
        }
        Vec3::from_big(c)
    }

    fn from_big(c: [Int; 3]) -> Vec3 {
        // Each component separately: keep its top 64 bits (truncation error below 2^-63
        // relative), round to a double (2^-53), and scale by an exact power of two so the
        // largest component lands near 1. A component more than 300 bits below the largest
        // would approach underflow in the filter's products: the vector then skips the
        // filter.
        let bits = c.iter().map(int::bit_len).max().unwrap_or(0) as i32;
        let mut filterable = true;
        let approx = [0, 1, 2].map(|k| {
            let v = &c[k];
            if *v == Int::ZERO {
                return 0.0;
            }
            let bl = int::bit_len(v) as i32;
            if bits - bl > 300 {
                filterable = false;
            }
            let s = (bl - 64).max(0);
            let m = int::to_f64(&(v >> s as usize));
            m * pow2((s - (bits - 1)).max(-1000))
        });
        let wide = match [
            int::to_i128(&c[0]),
            int::to_i128(&c[1]),
            int::to_i128(&c[2]),
        ] {
            // Keep i128::MIN out so that negation stays in range.
            [Some(x), Some(y), Some(z)] if x != i128::MIN && y != i128::MIN && z != i128::MIN => {
                Some([x, y, z])
            }
            _ => None,
        };
        Vec3(Repr::Big(Box::new(BigVec {
            c,
            wide,
            approx,
            filterable,
        })))
    }

    /// The components, borrowed in whichever representation they are stored.
    #[inline]
    pub fn components(&self) -> Components<'_> {
        match &self.0 {
            Repr::Small(c) => Components::Small(c),
            Repr::Big(b) => Components::Big(&b.c),
        }
    }

    /// The components as machine integers when every one is below 2^62.
    #[inline]
    pub fn as_small(&self) -> Option<&[i64; 3]> {
        match &self.0 {
            Repr::Small(c) => Some(c),
            Repr::Big(_) => None,
        }
    }

    /// The components as `i128` when each fits (|c| < 2^127).
    #[inline]
    pub fn as_wide(&self) -> Option<[i128; 3]> {
        match &self.0 {
            Repr::Small(c) => Some([c[0] as i128, c[1] as i128, c[2] as i128]),
            Repr::Big(b) => b.wide,
        }
    }

    /// Component `i` (0, 1 or 2) as an arbitrary-precision integer.
    pub fn get(&self, i: usize) -> Int {
        match &self.0 {
            Repr::Small(c) => Int::from(c[i]),
            Repr::Big(b) => b.c[i].clone(),
        }
    }

    /// All components as arbitrary-precision integers.
    pub fn to_ints(&self) -> [Int; 3] {
        [self.get(0), self.get(1), self.get(2)]
    }

    /// The components as arbitrary-precision integers, borrowed when stored that way
    /// (small components convert without allocating).
    #[inline]
    fn ints(&self) -> std::borrow::Cow<'_, [Int; 3]> {
        match &self.0 {
            Repr::Small(c) => std::borrow::Cow::Owned(c.map(Int::from)),
            Repr::Big(b) => std::borrow::Cow::Borrowed(&b.c),
        }
    }

    /// Floating-point values proportional to the components (the components themselves
    /// for vectors below 2^62; scaled by a power of two above), each within relative
    /// error 2^-52. Good for directions and for sign predicates, not for magnitudes.
    #[inline]
    pub fn approx(&self) -> [f64; 3] {
        match &self.0 {
            Repr::Small(c) => [c[0] as f64, c[1] as f64, c[2] as f64],
            Repr::Big(b) => b.approx,
        }
    }

    /// The floating-point shadow for predicate filters, `None` when the components'
    /// dynamic range is too wide for a safe filter.
    #[inline]
    pub fn filter_approx(&self) -> Option<[f64; 3]> {
        match &self.0 {
            Repr::Small(c) => Some([c[0] as f64, c[1] as f64, c[2] as f64]),
            Repr::Big(b) => b.filterable.then_some(b.approx),
        }
    }

    /// The unit vector in this direction, in floating point (for output only).
    pub fn unit_f64(&self) -> [f64; 3] {
        let a = self.approx();
        let scale = a.iter().fold(0f64, |m, v| m.max(v.abs()));
        if scale == 0.0 || !scale.is_finite() {
            // Huge vectors: rescale through the exact value.
            return self.unit_f64_slow();
        }
        let s = [a[0] / scale, a[1] / scale, a[2] / scale];
        let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
        if n == 0.0 {
            return [0.0; 3];
        }
        [s[0] / n, s[1] / n, s[2] / n]
    }

    fn unit_f64_slow(&self) -> [f64; 3] {
        let c = self.to_ints();
        let bits = self.bits();
        if bits == 0 {
            return [0.0; 3];
        }
        let shift = bits.saturating_sub(60) as usize;
        let s: Vec<f64> = c.iter().map(|v| int::to_f64(&(v >> shift))).collect();
        let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
        [s[0] / n, s[1] / n, s[2] / n]
    }

    /// Largest bit length of the components' magnitudes (0 for the zero vector).
    #[inline]
    pub fn bits(&self) -> u32 {
        match &self.0 {
            Repr::Small(c) => int::bit_len_i64(c[0])
                .max(int::bit_len_i64(c[1]))
                .max(int::bit_len_i64(c[2])),
            Repr::Big(b) => int::bit_len(&b.c[0])
                .max(int::bit_len(&b.c[1]))
                .max(int::bit_len(&b.c[2])),
        }
    }

    /// True for the zero vector.
    #[inline]
    pub fn is_zero(&self) -> bool {
        matches!(&self.0, Repr::Small([0, 0, 0]))
    }

    /// -v.
    pub fn neg(&self) -> Vec3 {
        match &self.0 {
            Repr::Small(c) => Vec3(Repr::Small([-c[0], -c[1], -c[2]])),
            Repr::Big(b) => Vec3::from_big([-&b.c[0], -&b.c[1], -&b.c[2]]),
        }
    }

    /// a + b.
    pub fn add(&self, o: &Vec3) -> Vec3 {
        match (&self.0, &o.0) {
            (Repr::Small(a), Repr::Small(b)) => Vec3::from_i128([
                a[0] as i128 + b[0] as i128,
                a[1] as i128 + b[1] as i128,
                a[2] as i128 + b[2] as i128,
            ]),
            _ => {
                let (a, b) = (self.ints(), o.ints());
                Vec3::from_ints([&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]])
            }
        }
    }

    /// a - b.
    pub fn sub(&self, o: &Vec3) -> Vec3 {
        match (&self.0, &o.0) {
            (Repr::Small(a), Repr::Small(b)) => Vec3::from_i128([
                a[0] as i128 - b[0] as i128,
                a[1] as i128 - b[1] as i128,
                a[2] as i128 - b[2] as i128,
            ]),
            _ => {
                let (a, b) = (self.ints(), o.ints());
                Vec3::from_ints([&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]])
            }
        }
    }

    /// k * v.
    pub fn scale(&self, k: &Int) -> Vec3 {
        let a = self.ints();
        Vec3::from_ints([&a[0] * k, &a[1] * k, &a[2] * k])
    }

    /// Cross product a × b. Bits: bits(a) + bits(b) + 1.
    pub fn cross(&self, o: &Vec3) -> Vec3 {
        match (&self.0, &o.0) {
            (Repr::Small(a), Repr::Small(b)) => {
                let (a0, a1, a2) = (a[0] as i128, a[1] as i128, a[2] as i128);
                let (b0, b1, b2) = (b[0] as i128, b[1] as i128, b[2] as i128);
                // Each product is below 2^124, each difference below 2^125: no overflow.
                Vec3::from_i128([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])
            }
            _ => {
                let (a, b) = (self.ints(), o.ints());
                Vec3::from_ints([
                    &a[1] * &b[2] - &a[2] * &b[1],
                    &a[2] * &b[0] - &a[0] * &b[2],
                    &a[0] * &b[1] - &a[1] * &b[0],
                ])
            }
        }
    }

    /// Exact dot product a · b. Bits: bits(a) + bits(b) + 2.
    pub fn dot(&self, o: &Vec3) -> Int {
        match (&self.0, &o.0) {
            (Repr::Small(a), Repr::Small(b)) => {
                // Products below 2^124, sum of three below 2^126.
                Int::from(
                    a[0] as i128 * b[0] as i128
                        + a[1] as i128 * b[1] as i128
                        + a[2] as i128 * b[2] as i128,
                )
            }
            _ => {
                let (a, b) = (self.ints(), o.ints());
                &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
            }
        }
    }

    /// The primitive vector with the same direction: components divided by their gcd.
    /// The zero vector stays zero. Two non-zero vectors point the same way exactly when
    /// their primitive vectors are equal, which makes directions hashable.
    pub fn primitive(&self) -> Vec3 {
        match &self.0 {
            Repr::Small(c) => {
                let g = int::gcd_u128(c[0].unsigned_abs() as u128, c[1].unsigned_abs() as u128);
                if g == 1 {
                    return self.clone();
                }
                let g = int::gcd_u128(g, c[2].unsigned_abs() as u128);
                if g <= 1 {
                    return self.clone();
                }
                let g = g as i64;
                Vec3(Repr::Small([c[0] / g, c[1] / g, c[2] / g]))
            }
            Repr::Big(b) => {
                if let Some(w) = b.wide {
                    let g = int::gcd_u128(w[0].unsigned_abs(), w[1].unsigned_abs());
                    if g == 1 {
                        return self.clone();
                    }
                    let g = int::gcd_u128(g, w[2].unsigned_abs()) as i128;
                    if g <= 1 {
                        return self.clone();
                    }
                    return Vec3::from_i128([w[0] / g, w[1] / g, w[2] / g]);
                }
                let g = int::gcd(&int::gcd(&b.c[0], &b.c[1]), &b.c[2]);
                if g <= Int::ONE {
                    return self.clone();
                }
                Vec3::from_ints([&b.c[0] / &g, &b.c[1] / &g, &b.c[2] / &g])
            }
        }
    }

    /// The components as decimal strings, for exact output.
    pub fn to_strings(&self) -> [String; 3] {
        match &self.0 {
            Repr::Small(c) => [c[0].to_string(), c[1].to_string(), c[2].to_string()],
            Repr::Big(b) => [b.c[0].to_string(), b.c[1].to_string(), b.c[2].to_string()],
        }
    }
}

impl fmt::Debug for Vec3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [x, y, z] = self.to_strings();
        write!(f, "({x}, {y}, {z})")
    }
}

impl fmt::Display for Vec3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

impl From<[i64; 3]> for Vec3 {
    fn from(c: [i64; 3]) -> Vec3 {
        Vec3::from_i64(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_representation() {
        let big = Vec3::new(1 << 62, 0, 0);
        assert!(big.as_small().is_none());
        let back = big.sub(&Vec3::new(1, 0, 0));
        assert_eq!(back, Vec3::new((1 << 62) - 1, 0, 0));
        assert!(back.as_small().is_some());
        // Equal values are equal whatever path built them.
        let a = Vec3::from_ints([Int::from(5), Int::from(-3), Int::from(0)]);
        assert_eq!(a, Vec3::new(5, -3, 0));
    }

    #[test]
    fn cross_dot_primitive() {
        let a = Vec3::new(1, 2, 3);
        let b = Vec3::new(-4, 5, 6);
        let c = a.cross(&b);
        assert_eq!(c, Vec3::new(2 * 6 - 3 * 5, 3 * -4 - 6, 5 + 8));
        assert_eq!(c.dot(&a), Int::ZERO);
        assert_eq!(Vec3::new(6, -9, 12).primitive(), Vec3::new(2, -3, 4));
        assert_eq!(Vec3::ZERO.primitive(), Vec3::ZERO);
        let huge = Vec3::new(1 << 61, 1 << 61, 0);
        let h2 = huge.cross(&Vec3::new(0, 0, 1 << 61));
        assert!(h2.as_small().is_none());
        assert_eq!(h2.primitive(), Vec3::new(1, -1, 0));
    }
}
