//! Snapping input coordinates once to an integer grid of step h = 2^e.
//!
//! Every coordinate is replaced by the nearest multiple of `h` (ties away from zero), the
//! multiple being stored as an integer `q` with `|q| < 2^B`. Snapping is a function of the
//! value alone, so equal inputs give equal integers and contacts between parts survive.
//! Dividing by a power of two is exact in binary floating point, so the only rounding is
//! the final one to an integer.

use std::fmt;

/// Default number of bits of a snapped coordinate.
pub const DEFAULT_BITS: u32 = 30;
/// Smallest accepted number of grid bits.
pub const MIN_BITS: u32 = 4;
/// Largest accepted number of grid bits. Below 2^52 an `f64` still has a spacing of at
/// most 1/2, so a scaled coordinate keeps the fraction that snapping rounds, and the
/// mesh crate's snapper rejects every scaled value of 2^52 or more. (With 53 bits the
/// grid chosen for a non-integer input put the largest coordinate in [2^52, 2^53): every
/// such input was rejected as outside the grid.)
pub const MAX_BITS: u32 = 52;

/// The integer grid an assembly is snapped to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Grid {
    /// The step is `2^exp` input units.
    pub exp: i32,
    /// Every snapped coordinate satisfies `|q| < 2^bits`.
    pub bits: u32,
}

/// Why no grid could be chosen.
#[derive(Clone, Debug, PartialEq)]
pub enum GridError {
    /// `bits` outside [`MIN_BITS`, `MAX_BITS`].
    BitsOutOfRange(u32),
    /// A NaN or infinite coordinate reached the grid (loaders reject these first).
    NotFinite(f64),
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GridError::BitsOutOfRange(b) => write!(
                f,
                "grid bits must be between {MIN_BITS} and {MAX_BITS}, got {b}"
            ),
            GridError::NotFinite(v) => write!(f, "coordinate {v} is not a finite number"),
        }
    }
}

impl std::error::Error for GridError {}

/// 2^k as an f64, for -1022 <= k <= 1023.
fn pow2(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((1023 + k as i64) as u64) << 52)
}

/// v * 2^k, exact unless the result leaves the f64 range; done in two steps so that the
/// factors themselves stay representable for every exponent a finite input can produce.
fn scale2(v: f64, k: i32) -> f64 {
    let half = k / 2;
    v * pow2(half) * pow2(k - half)
}

impl Grid {
    /// The unit grid (h = 1).
    pub fn unit(bits: u32) -> Grid {
        Grid { exp: 0, bits }
    }

    /// Chooses the grid for a set of coordinates: h = 1 when every value is an integer
    /// with fewer than `bits` bits; otherwise the finest h = 2^e such that every snapped
    /// value satisfies `|q| < 2^bits`.
    pub fn choose(values: impl IntoIterator<Item = f64>, bits: u32) -> Result<Grid, GridError> {
        if !(MIN_BITS..=MAX_BITS).contains(&bits) {
            return Err(GridError::BitsOutOfRange(bits));
        }
        let limit = pow2(bits as i32);
        let mut max_abs = 0f64;
        let mut all_integers = true;
        for v in values {
            if !v.is_finite() {
                return Err(GridError::NotFinite(v));
            }
            max_abs = max_abs.max(v.abs());
            all_integers &= v.fract() == 0.0;
        }
        if max_abs == 0.0 || (all_integers && max_abs < limit) {
            return Ok(Grid { exp: 0, bits });
        }
        // max_abs = m * 2^k with m in [0.5, 1): max_abs < 2^k.
        let k = frexp_exponent(max_abs);
        let mut grid = Grid {
            exp: k - bits as i32,
            bits,
        };
        // Rounding may reach 2^bits exactly; then one step coarser is the finest that fits.
        if grid.snap_raw(max_abs).abs() >= limit {
            grid.exp += 1;
        }
        Ok(grid)
    }

    /// The step h = 2^exp in input units.
    pub fn step(&self) -> f64 {
        scale2(1.0, self.exp)
    }

    fn snap_raw(&self, v: f64) -> f64 {
        scale2(v, -self.exp).round()
    }

    /// The grid integer nearest to `v` (ties away from zero). `v` must be finite and
    /// within the range the grid was chosen for.
    pub fn snap(&self, v: f64) -> i64 {
        self.snap_raw(v) as i64
    }

    /// The input-unit value of grid integer `q`.
    pub fn to_units(&self, q: i64) -> f64 {
        scale2(q as f64, self.exp)
    }

    /// |v - snap(v) * h|: how far snapping moved `v`.
    pub fn displacement(&self, v: f64) -> f64 {
        (v - self.to_units(self.snap(v))).abs()
    }
}

fn frexp_exponent(v: f64) -> i32 {
    debug_assert!(v > 0.0 && v.is_finite());
    let bits = v.to_bits();
    let raw = ((bits >> 52) & 0x7ff) as i32;
    if raw == 0 {
        // Subnormal: scale up first.
        return frexp_exponent(v * pow2(64)) - 64;
    }
    raw - 1022
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_that_fit_stay_unscaled() {
        let g = Grid::choose([-2.0, 0.0, 2.0, 1.0], 30).unwrap();
        assert_eq!(g.exp, 0);
        assert_eq!(g.snap(-2.0), -2);
    }

    #[test]
    fn finest_grid_that_fits() {
        let g = Grid::choose([0.1, -0.75, 0.3], 10).unwrap();
        // 0.75 < 2^0, so h = 2^-10 and 0.75 -> 768 < 1024.
        assert_eq!(g.exp, -10);
        assert_eq!(g.snap(-0.75), -768);
        assert_eq!(g.snap(0.1), 102); // 102.4 -> 102
        assert!(g.displacement(0.1) <= g.step() / 2.0);
        // A value that rounds up to the limit forces a coarser grid.
        let g = Grid::choose([0.99999], 4).unwrap();
        assert!(g.snap(0.99999).abs() < 16);
        assert_eq!(g.exp, -3);
    }

    #[test]
    fn large_integers_are_scaled() {
        let g = Grid::choose([3.0e9, 1.0], 30).unwrap();
        assert!(g.exp > 0);
        assert!(g.snap(3.0e9).abs() < 1 << 30);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(Grid::choose([f64::NAN], 30).is_err());
        assert!(Grid::choose([1.0], 2).is_err());
        assert!(Grid::choose([1.0], 60).is_err());
    }

    #[test]
    fn symmetric_under_negation() {
        let g = Grid::choose([0.3, 1.7, -2.5], 12).unwrap();
        for v in [0.3, 1.7, 2.5, 0.000_122_070_312_5] {
            assert_eq!(g.snap(-v), -g.snap(v));
        }
    }
}
