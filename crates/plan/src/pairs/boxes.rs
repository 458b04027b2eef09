//! Exact tests of a piece pair against a ray from its pieces' boxes alone: whether
//! the ray meets the box of their sum, and for pairs of axis-aligned boxes whether it
//! enters their open box of differences or grazes it.

use super::PieceInfo;
use apart_kernel::int::cmp_fractions;
use apart_kernel::{Aabb, Int, Vec3};
use apart_pieces::Polytope;
use std::cmp::Ordering;

/// Whether the ray `{t x : t > 0}` meets the closed box of every `b ⊕ −a` (`a` with
/// bounds `ia` and denominator `da`, `b` likewise): when it does not, `x` lies outside
/// the closed projection `P_ab`, whatever the pieces' shapes. Exact: the box is
/// `[lo_b db⁻¹ − hi_a da⁻¹, hi_b db⁻¹ − lo_a da⁻¹]`, scaled by `da db`, and each
/// coordinate bounds `t` by a fraction.
pub(crate) fn ray_meets_box(ia: &PieceInfo, da: &Int, ib: &PieceInfo, db: &Int, x: &Vec3) -> bool {
    if let (Some(a), Some(b), Some(x)) = (&ia.small, &ib.small, x.as_small()) {
        return ray_meets_small_box(a, b, x);
    }
    ray_meets_box_exact(ia, da, ib, db, x)
}

/// [`ray_meets_box`] for pieces on the grid (denominator 1) with bounds below 2^61 and a
/// direction below 2^62: box bounds below 2^62, products of fractions below 2^124, all
/// exact in `i128`.
fn ray_meets_small_box(a: &Aabb, b: &Aabb, x: &[i64; 3]) -> bool {
    ray_meets_int_box(
        std::array::from_fn(|k| b.min[k] as i128 - a.max[k] as i128),
        std::array::from_fn(|k| b.max[k] as i128 - a.min[k] as i128),
        x,
    )
}

/// Whether the ray `{t x : t > 0}` meets the closed box `[lo, hi]`, exactly, for bounds
/// below 2^62 in magnitude and a direction below 2^62 (products below 2^124).
pub(crate) fn ray_meets_int_box(lo: [i128; 3], hi: [i128; 3], x: &[i64; 3]) -> bool {
    let mut lower: (i128, i128) = (0, 1);
    let mut upper: Option<(i128, i128)> = None;
    for (k, &xk) in x.iter().enumerate() {
        let (lo, hi) = (lo[k], hi[k]);
        let xk = xk as i128;
        let (l, u, den) = match xk.cmp(&0) {
            Ordering::Equal => {
                if lo > 0 || hi < 0 {
                    return false;
                }
                continue;
            }
            Ordering::Greater => (lo, hi, xk),
            Ordering::Less => (-hi, -lo, -xk),
        };
        // l / den > lower.0 / lower.1, denominators positive.
        if l * lower.1 > lower.0 * den {
            lower = (l, den);
        }
        if upper.is_none_or(|(n, d)| u * d < n * den) {
            upper = Some((u, den));
        }
    }
    match upper {
        None => true,
        Some((u, du)) => u > 0 && lower.0 * du <= u * lower.1,
    }
}

/// For two axis-aligned boxes `a`, `b` (bounds `ia`, `ib`, denominators `da`, `db`),
/// whose sum `b ⊕ −a` is their box of differences: whether the open ray `{t x : t > 0}`
/// meets that box's interior, i.e. whether `x` lies in the open projection `P_ab` (`a`
/// moving along `x` hits `b`). `None` when the interior holds the origin (the pieces
/// overlap: the polygon's computation reports it). Exact, as [`ray_meets_box`].
pub(crate) fn open_box_blocks(
    ia: &PieceInfo,
    da: &Int,
    ib: &PieceInfo,
    db: &Int,
    x: &Vec3,
) -> Option<bool> {
    if let (Some(a), Some(b), Some(x)) = (&ia.small, &ib.small, x.as_small()) {
        return open_small_box_blocks(a, b, x);
    }
    // Scaled bounds of the box of differences (by da db > 0) and of t (by the same).
    let (mut lo, mut hi): ([Int; 3], [Int; 3]) = Default::default();
    for k in 0..3 {
        lo[k] = &ib.bounds.min[k] * da - &ia.bounds.max[k] * db;
        hi[k] = &ib.bounds.max[k] * da - &ia.bounds.min[k] * db;
    }
    if (0..3).all(|k| lo[k] < Int::ZERO && hi[k] > Int::ZERO) {
        return None;
    }
    // The open intervals of t, as fractions with positive denominators: t > 0, and
    // lo_k < t x_k < hi_k for every k.
    let mut lower: (Int, Int) = (Int::ZERO, Int::ONE);
    let mut upper: Option<(Int, Int)> = None;
    for k in 0..3 {
        let xk = x.get(k);
        let (l, u, den) = match xk.cmp(&Int::ZERO) {
            Ordering::Equal => {
                if lo[k] >= Int::ZERO || hi[k] <= Int::ZERO {
                    return Some(false);
                }
                continue;
            }
            Ordering::Greater => (lo[k].clone(), hi[k].clone(), xk),
            Ordering::Less => (-hi[k].clone(), -lo[k].clone(), -xk),
        };
        if cmp_fractions(&l, &den, &lower.0, &lower.1) == Ordering::Greater {
            lower = (l, den.clone());
        }
        if upper
            .as_ref()
            .is_none_or(|(n, d)| cmp_fractions(&u, &den, n, d) == Ordering::Less)
        {
            upper = Some((u, den));
        }
    }
    Some(match upper {
        None => false,
        Some((u, du)) => cmp_fractions(&lower.0, &lower.1, &u, &du) == Ordering::Less,
    })
}

/// For two axis-aligned boxes (as [`open_box_blocks`]) whose box of differences the ray
/// along `x` touches only on its boundary, at one point away from the origin: a normal
/// `c` (square to `x`) such that `a` moving along `x + εy` (`ε → 0⁺`) hits `b` only if
/// `c · y > 0`. The ray enters the box through a face of axis `k` and leaves it through
/// a face of axis `m` at the same point; tilting it (`x_k → x_k + ε y_k`) moves the
/// entry to `t (1 − ε y_k / x_k)` and the exit to `t (1 − ε y_m / x_m)`, so it crosses
/// the interior only when `y_k / x_k > y_m / x_m`. `None` otherwise (the ray meets the
/// box along a segment or at the origin, or a face parallel to `x` holds the point).
pub(crate) fn box_graze_normal(
    ia: &PieceInfo,
    da: &Int,
    ib: &PieceInfo,
    db: &Int,
    x: &Vec3,
) -> Option<Vec3> {
    // The latest entry and earliest exit of the line, as fractions with positive
    // denominators (scaled by da db > 0), with their axes.
    let mut entry: Option<(Int, Int, usize)> = None;
    let mut exit: Option<(Int, Int, usize)> = None;
    for k in 0..3 {
        let lo = &ib.bounds.min[k] * da - &ia.bounds.max[k] * db;
        let hi = &ib.bounds.max[k] * da - &ia.bounds.min[k] * db;
        let xk = x.get(k);
        let (l, u, den) = match xk.cmp(&Int::ZERO) {
            Ordering::Equal => {
                if lo >= Int::ZERO || hi <= Int::ZERO {
                    return None;
                }
                continue;
            }
            Ordering::Greater => (lo, hi, xk),
            Ordering::Less => (-hi, -lo, -xk),
        };
        if entry
            .as_ref()
            .is_none_or(|(n, d, _)| cmp_fractions(&l, &den, n, d) == Ordering::Greater)
        {
            entry = Some((l, den.clone(), k));
        }
        if exit
            .as_ref()
            .is_none_or(|(n, d, _)| cmp_fractions(&u, &den, n, d) == Ordering::Less)
        {
            exit = Some((u, den, k));
        }
    }
    let ((l, dl, k), (u, du, m)) = (entry?, exit?);
    if l <= Int::ZERO || k == m || cmp_fractions(&l, &dl, &u, &du) != Ordering::Equal {
        return None;
    }
    // c = e_k / x_k − e_m / x_m, times |x_k x_m|.
    let (xk, xm) = (x.get(k), x.get(m));
    let abs = |v: &Int| {
        if *v < Int::ZERO {
            -v.clone()
        } else {
            v.clone()
        }
    };
    let with_sign_of = |v: Int, s: &Int| if *s < Int::ZERO { -v } else { v };
    let mut c = [Int::ZERO, Int::ZERO, Int::ZERO];
    c[k] = with_sign_of(abs(&xm), &xk);
    c[m] = -with_sign_of(abs(&xk), &xm);
    Some(Vec3::from_ints(c).primitive())
}

/// [`open_box_blocks`] for pieces on the grid with bounds below 2^61 and a direction
/// below 2^62, in `i128` (as [`ray_meets_small_box`]).
pub(super) fn open_small_box_blocks(a: &Aabb, b: &Aabb, x: &[i64; 3]) -> Option<bool> {
    let lo: [i128; 3] = std::array::from_fn(|k| b.min[k] as i128 - a.max[k] as i128);
    let hi: [i128; 3] = std::array::from_fn(|k| b.max[k] as i128 - a.min[k] as i128);
    if (0..3).all(|k| lo[k] < 0 && hi[k] > 0) {
        return None;
    }
    let mut lower: (i128, i128) = (0, 1);
    let mut upper: Option<(i128, i128)> = None;
    for k in 0..3 {
        let xk = x[k] as i128;
        let (l, u, den) = match xk.cmp(&0) {
            Ordering::Equal => {
                if lo[k] >= 0 || hi[k] <= 0 {
                    return Some(false);
                }
                continue;
            }
            Ordering::Greater => (lo[k], hi[k], xk),
            Ordering::Less => (-hi[k], -lo[k], -xk),
        };
        if l * lower.1 > lower.0 * den {
            lower = (l, den);
        }
        if upper.is_none_or(|(n, d)| u * d < n * den) {
            upper = Some((u, den));
        }
    }
    Some(upper.is_some_and(|(u, du)| lower.0 * du < u * lower.1))
}

/// True when `p` is an axis-aligned box: eight vertices and six facets, each normal
/// along a coordinate axis.
pub(crate) fn is_axis_box(p: &Polytope) -> bool {
    let axis = |n: &Vec3| (0..3).filter(|&k| n.get(k) != Int::ZERO).count() == 1;
    p.vertices().len() == 8 && p.facets().len() == 6 && p.facets().iter().all(|f| axis(&f.normal))
}

/// [`ray_meets_box`] in arbitrary precision.
pub(super) fn ray_meets_box_exact(
    ia: &PieceInfo,
    da: &Int,
    ib: &PieceInfo,
    db: &Int,
    x: &Vec3,
) -> bool {
    // Bounds on t (scaled), as fractions with positive denominators: the largest lower
    // and the smallest upper, starting from t > 0 (lower 0, exclusive) and no upper.
    let mut lower: (Int, Int) = (Int::ZERO, Int::ONE);
    let mut upper: Option<(Int, Int)> = None;
    for k in 0..3 {
        let lo = &ib.bounds.min[k] * da - &ia.bounds.max[k] * db;
        let hi = &ib.bounds.max[k] * da - &ia.bounds.min[k] * db;
        let xk = x.get(k);
        let (l, u, den) = match xk.cmp(&Int::ZERO) {
            Ordering::Equal => {
                if lo > Int::ZERO || hi < Int::ZERO {
                    return false;
                }
                continue;
            }
            Ordering::Greater => (lo, hi, xk),
            Ordering::Less => (-hi, -lo, -xk),
        };
        if cmp_fractions(&l, &den, &lower.0, &lower.1) == Ordering::Greater {
            lower = (l, den.clone());
        }
        if upper
            .as_ref()
            .is_none_or(|(n, d)| cmp_fractions(&u, &den, n, d) == Ordering::Less)
        {
            upper = Some((u, den));
        }
    }
    match upper {
        // Every coordinate of x is zero: not a direction.
        None => true,
        // t in [lower, upper] with t > 0: upper must be positive and not below lower.
        Some((u, du)) => {
            u > Int::ZERO && cmp_fractions(&lower.0, &lower.1, &u, &du) != Ordering::Greater
        }
    }
}
