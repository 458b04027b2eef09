//! Piece pairs without their Minkowski sums when a cheaper exact argument decides.
//!
//! For a piece `a` of a moving part and `b` of a fixed one, `P_ab` is the central
//! projection of `M = b ⊕ (−a)`; `d` is blocked iff `d` lies in the open `P_ab`, i.e.
//! `(a + t d) ∩ int b ≠ ∅` for some `t > 0`, and `d` lies in the closed `P_ab` iff
//! `(a + t d) ∩ b ≠ ∅` for some `t > 0`.
//!
//! - *Separating axes.* When `a` lies weakly below `b` along an axis `n`
//!   (`max_a n·x <= min_b n·x`), `P_ab` lies in the closed hemisphere `{n·x >= 0}`
//!   (`min_M n·x >= 0`), so every `d` with `n·d <= 0` is free, and every `d` with
//!   `n·d < 0` (or `n·d <= 0` when strictly below) is outside the closed `P_ab`. The axes
//!   tried are the coordinate axes (exact integer boxes) and the facet normals of both
//!   pieces; all comparisons are exact (integers cross-multiplied by the denominators).
//! - *Contact cones.* When the pieces touch, `P_ab` is the tangent cone of `M` at the
//!   origin, whose normal cone is `N_b(c) ∩ −N_a(c)` for any common point `c`. With a
//!   touching plane `n` (a separating axis with equality), every common point lies in
//!   the support faces `F_a` (of `a` along `n`) and `F_b` (of `b` along `−n`); the hull
//!   of a face's vertices and their neighbours has the same tangent cone as the piece at
//!   every point of the face, so the small sum `b' ⊕ (−a')` of those hulls has the origin
//!   on its boundary exactly when the pieces touch, and then the same projection as `M`
//!   (same active facet normals; the cone's corner rays are the same primitive vectors).

use crate::PlanError;
use apart_kernel::int::{self, cmp_fractions};
use apart_kernel::{Aabb, Int, Vec3};
use apart_minkowski::{project, project_apart, sum_prepared, Projection, Summand};
use apart_pieces::interference::{below_along, facet_axes};
use apart_pieces::Polytope;
use apart_sphere::SphericalPolygon;
use std::cmp::Ordering;
use std::sync::OnceLock;

/// A box `(lo, hi)` in floating point.
pub(crate) type FloatBox = ([f64; 3], [f64; 3]);

/// A piece with the data the exact culls need.
pub(crate) struct PieceInfo {
    /// The box of the piece's integer vertices (the piece's box times its denominator).
    bounds: Aabb<Int>,
    /// The piece's box in true coordinates, floating point (each bound correctly
    /// rounded: for preferences and widened float bounds only).
    pub(crate) float_bounds: FloatBox,
    /// `bounds` in machine integers when the piece is on the grid itself (denominator 1)
    /// and every bound is below 2^61: the ray–box test's fast path.
    small: Option<Aabb>,
    fixed: OnceLock<Summand>,
    reflected: OnceLock<Summand>,
}

impl PieceInfo {
    pub(crate) fn new(p: &Polytope) -> PieceInfo {
        let lo = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).min().unwrap());
        let hi = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).max().unwrap());
        let fits = |c: &[Int; 3]| {
            c.clone()
                .map(|v| int::to_i64(&v).filter(|v| v.unsigned_abs() < 1 << 61))
        };
        let small = match (*p.den() == Int::ONE, fits(&lo), fits(&hi)) {
            (true, [Some(a), Some(b), Some(c)], [Some(d), Some(e), Some(f)]) => Some(Aabb {
                min: [a, b, c],
                max: [d, e, f],
            }),
            _ => None,
        };
        let float = |c: &[Int; 3]| {
            c.clone()
                .map(|v| apart_kernel::Rational::new(v, p.den().clone()).to_f64())
        };
        PieceInfo {
            float_bounds: (float(&lo), float(&hi)),
            bounds: Aabb { min: lo, max: hi },
            small,
            fixed: OnceLock::new(),
            reflected: OnceLock::new(),
        }
    }

    pub(crate) fn fixed(&self, p: &Polytope) -> &Summand {
        self.fixed.get_or_init(|| Summand::new(p.clone()))
    }

    pub(crate) fn reflected(&self, p: &Polytope) -> &Summand {
        self.reflected.get_or_init(|| Summand::new(p.reflected()))
    }
}

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
fn open_small_box_blocks(a: &Aabb, b: &Aabb, x: &[i64; 3]) -> Option<bool> {
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
fn ray_meets_box_exact(ia: &PieceInfo, da: &Int, ib: &PieceInfo, db: &Int, x: &Vec3) -> bool {
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

/// An axis along which `a` lies weakly below `b` (`max_a n·x <= min_b n·x`); `strict`
/// when strictly.
#[derive(Clone, Debug)]
pub(crate) struct Axis {
    pub(crate) n: Vec3,
    pub(crate) strict: bool,
}

/// How a direction relates to a piece pair's closed projection.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Sep {
    /// Outside the closed projection: irrelevant at this direction.
    Outside,
    /// Not in the open projection (free), possibly on its boundary.
    Free,
    /// Undecided by the axes.
    Unknown,
}

/// The separating axes of a piece pair at rest (coordinate axes and facet normals), each
/// oriented from `a` to `b`.
pub(crate) fn axes(a: &Polytope, ia: &PieceInfo, b: &Polytope, ib: &PieceInfo) -> Vec<Axis> {
    let mut out: Vec<Axis> = coordinate_axes(a, ia, b, ib).collect();
    if out.iter().any(|x| x.strict) {
        return out; // strictly apart: nothing more to learn at rest
    }
    // Facet normals of a, and negated ones of b (exact, behind a float filter).
    out.extend(
        facet_axes(a, b)
            .into_iter()
            .map(|(n, strict)| Axis { n, strict }),
    );
    out
}

/// The coordinate axes of [`axes`] (which lists them first, in this order: `+e_0`,
/// `−e_0`, `+e_1`, ...).
fn coordinate_axes<'a>(
    a: &'a Polytope,
    ia: &'a PieceInfo,
    b: &'a Polytope,
    ib: &'a PieceInfo,
) -> impl Iterator<Item = Axis> + 'a {
    let (da, db) = (a.den(), b.den());
    let ((fa_lo, fa_hi), (fb_lo, fb_hi)) = (ia.float_bounds, ib.float_bounds);
    let (ia, ib) = (&ia.bounds, &ib.bounds);
    (0..3).flat_map(move |k| {
        // a below b along +e_k: hi_a <= lo_b; b below a along -e_k likewise.
        let below = [
            (
                1,
                cmp_bound(fa_hi[k], &ia.max[k], da, fb_lo[k], &ib.min[k], db),
            ),
            (
                -1,
                cmp_bound(fb_hi[k], &ib.max[k], db, fa_lo[k], &ia.min[k], da),
            ),
        ];
        below
            .into_iter()
            .filter(|(_, order)| *order != Ordering::Greater)
            .map(move |(sign, order)| {
                let mut e = [0i64; 3];
                e[k] = sign;
                Axis {
                    n: Vec3::from_i64(e),
                    strict: order == Ordering::Less,
                }
            })
    })
}

/// [`classify`] of a pair of axis-aligned boxes, from their coordinate axes alone (their
/// facet axes are the same axes again), without making the list; and whether some axis
/// is not strict (the boxes may touch).
pub(crate) fn classify_boxes(
    a: &Polytope,
    ia: &PieceInfo,
    b: &Polytope,
    ib: &PieceInfo,
    x: &Vec3,
) -> (Sep, bool) {
    let (mut outside, mut free, mut touching) = (false, false, false);
    for ax in coordinate_axes(a, ia, b, ib) {
        touching |= !ax.strict;
        match apart_kernel::predicates::dot_sign(&ax.n, x) {
            apart_kernel::Sign::Negative => outside = true,
            apart_kernel::Sign::Zero => {
                outside |= ax.strict;
                free = true;
            }
            apart_kernel::Sign::Positive => {}
        }
    }
    let sep = if outside {
        Sep::Outside
    } else if free {
        Sep::Free
    } else {
        Sep::Unknown
    };
    (sep, touching)
}

/// [`touching_normal`] of [`axes`], without making the facet axes when a coordinate axis
/// already answers: a touching coordinate axis comes first in the list, and a strict
/// one leaves only coordinate axes in it.
pub(crate) fn first_touching_axis(
    a: &Polytope,
    ia: &PieceInfo,
    b: &Polytope,
    ib: &PieceInfo,
) -> Option<Vec3> {
    let mut strict = false;
    for ax in coordinate_axes(a, ia, b, ib) {
        if !ax.strict {
            return Some(ax.n);
        }
        strict = true;
    }
    if strict {
        return None;
    }
    touching_normal(&axes(a, ia, b, ib)).cloned()
}

/// `x / dx` against `y / dy` (positive denominators), exactly: by their floats `fx` and
/// `fy` (each within a few ulps of its fraction) when those are apart by far more than
/// that, else by the fractions.
fn cmp_bound(fx: f64, x: &Int, dx: &Int, fy: f64, y: &Int, dy: &Int) -> Ordering {
    let margin = 1e-12 * (fx.abs() + fy.abs()) + 1e-300;
    if fx < fy - margin {
        Ordering::Less
    } else if fx > fy + margin {
        Ordering::Greater
    } else {
        cmp_fractions(x, dx, y, dy)
    }
}

/// Whether `a` lies weakly below `b` along some normal of `h` that is a facet normal of
/// `a` or the negated facet normal of `b` (the facet axes [`axes`] skips for pairs a
/// coordinate axis already separates strictly).
pub(crate) fn below_along_any(a: &Polytope, b: &Polytope, h: &rustc_hash::FxHashSet<Vec3>) -> bool {
    a.facets()
        .iter()
        .any(|f| h.contains(&f.normal) && below_along(a, b, &f.normal).is_some())
        || b.facets().iter().any(|f| {
            let n = f.normal.neg();
            h.contains(&n) && below_along(a, b, &n).is_some()
        })
}

/// What the axes say about direction `x`.
pub(crate) fn classify(axes: &[Axis], x: &Vec3) -> Sep {
    let mut free = false;
    for ax in axes {
        match apart_kernel::predicates::dot_sign(&ax.n, x) {
            apart_kernel::Sign::Negative => return Sep::Outside,
            apart_kernel::Sign::Zero => {
                if ax.strict {
                    return Sep::Outside;
                }
                free = true;
            }
            apart_kernel::Sign::Positive => {}
        }
    }
    if free {
        Sep::Free
    } else {
        Sep::Unknown
    }
}

/// A piece pair's projection.
#[derive(Clone, Debug)]
pub(crate) enum PairPolygon {
    /// The closed polygon `P_ab` and whether the pieces touch.
    Polygon(SphericalPolygon, bool),
    /// The pieces' interiors overlap.
    Overlap,
}

/// The projection from the full Minkowski sum (as `BlockingRegions` computes it).
pub(crate) fn full_polygon(
    a: &Polytope,
    ia: &PieceInfo,
    b: &Polytope,
    ib: &PieceInfo,
) -> Result<PairPolygon, String> {
    let (sb, sa) = (ib.fixed(b), ia.reflected(a));
    if let Some(p) = project_apart(sb, sa) {
        return p
            .map(|p| PairPolygon::Polygon(p, false))
            .map_err(|e| format!("projection: {e}"));
    }
    let m = sum_prepared(sb, sa).map_err(|e| format!("Minkowski sum: {e}"))?;
    match project(&m) {
        Ok(Projection::Polygon(p)) => {
            let contact = m.facets().iter().all(|f| f.offset >= Int::ZERO);
            Ok(PairPolygon::Polygon(p, contact))
        }
        Ok(Projection::Everything) => Ok(PairPolygon::Overlap),
        Err(e) => Err(format!("projection: {e}")),
    }
}

/// Pieces with at most this many vertices are summed whole in [`contact_polygon`]: the
/// sum of two such pieces (prepared once per piece) costs less than the exact hull of a
/// neighbourhood (for a piece cut out of a tessellated part, of vertices over a long
/// common denominator: 8 here cost the 2 x 2 rack 8 % more instructions than 64), and
/// has the same tangent cone at the origin. Many-sided pieces (a shaft's 1,250 sides)
/// still take the neighbourhood.
const SMALL_PIECE: usize = 64;

/// [`face_neighbourhood`], or the whole piece (`Some(None)`) when it is small.
fn neighbourhood(p: &Polytope, face: &[u32]) -> Option<Option<Polytope>> {
    if p.vertices().len() <= SMALL_PIECE && !face.is_empty() {
        return Some(None);
    }
    face_neighbourhood(p, face)
}

/// The hull of the vertices `face` of `p` and their neighbours: `Some(None)` when that
/// is all of `p`.
fn face_neighbourhood(p: &Polytope, face: &[u32]) -> Option<Option<Polytope>> {
    if face.is_empty() {
        return None;
    }
    let mut keep = vec![false; p.vertices().len()];
    for &v in face {
        keep[v as usize] = true;
    }
    let mut with = keep.clone();
    for e in p.edges() {
        let [u, v] = e.ends;
        if keep[u as usize] || keep[v as usize] {
            with[u as usize] = true;
            with[v as usize] = true;
        }
    }
    let pts: Vec<Vec3> = (0..p.vertices().len())
        .filter(|&k| with[k])
        .map(|k| p.vertices()[k].clone())
        .collect();
    if pts.len() == p.vertices().len() {
        return Some(None);
    }
    Polytope::hull(&pts)
        .ok()
        .map(|h| Some(h.with_den(p.den().clone())))
}

/// The support face of `p` along `n` as a boundary cycle (a facet's cycle, an edge's two
/// ends, or one vertex), as stored integers.
fn support_face(p: &Polytope, n: &Vec3) -> Vec<u32> {
    let (_, ids) = p.support(n);
    if ids.len() >= 3 {
        let n = n.primitive();
        if let Some(f) = p.facets().iter().find(|f| f.normal == n) {
            return f.cycle.clone();
        }
    }
    ids
}

fn points(p: &Polytope, ids: &[u32]) -> Vec<Vec3> {
    ids.iter()
        .map(|&v| p.vertices()[v as usize].clone())
        .collect()
}

/// The vertices of the edges of the facet cycle `ids` of `p` that are not strictly
/// separated, in their common plane (normal `n`), from the hull of `other` (denominator
/// `dother`): every common point of the facet and `other` lies on one of these edges
/// when none lies in the facet's relative interior. All of `ids` when it has at most
/// eight vertices (nothing to gain).
fn edges_meeting(p: &Polytope, ids: &[u32], other: &[Vec3], dother: &Int, n: &Vec3) -> Vec<u32> {
    let k = ids.len();
    if k <= 8 {
        return ids.to_vec();
    }
    let dp = p.den();
    let v = |i: usize| &p.vertices()[ids[i % k] as usize];
    // Strictly on the far side of a line g·x = h (the side without `own`).
    let beyond = |g: &Vec3, h: &Int, own: Ordering, pts: &[Vec3], dp_: &Int, dh: &Int| {
        pts.iter()
            .all(|w| cmp_fractions(&g.dot(w), dp_, h, dh) == own.reverse())
    };
    // Exact boxes: an edge whose box misses the other set's box cannot meet it.
    let lo = [0, 1, 2].map(|t| other.iter().map(|w| w.get(t)).min().unwrap());
    let hi = [0, 1, 2].map(|t| other.iter().map(|w| w.get(t)).max().unwrap());
    let misses = |u: &Vec3, w: &Vec3| {
        (0..3).any(|t| {
            let (a, b) = (u.get(t), w.get(t));
            let (mn, mx) = if a < b { (a, b) } else { (b, a) };
            cmp_fractions(&mx, dp, &lo[t], dother) == Ordering::Less
                || cmp_fractions(&mn, dp, &hi[t], dother) == Ordering::Greater
        })
    };
    let mut keep = vec![false; k];
    for e in 0..k {
        let (u, w) = (v(e), v(e + 1));
        if misses(u, w) {
            continue;
        }
        let seg = [u.clone(), w.clone()];
        // The segment's line (either side), then the other hull's edge lines.
        let g = n.cross(&w.sub(u));
        let h = g.dot(u);
        let mut apart = beyond(&g, &h, Ordering::Less, other, dother, dp)
            || beyond(&g, &h, Ordering::Greater, other, dother, dp);
        let m = other.len();
        if !apart && m >= 2 {
            for i in 0..if m == 2 { 1 } else { m } {
                let (x, y) = (&other[i], &other[(i + 1) % m]);
                let g = n.cross(&y.sub(x));
                let h = g.dot(x);
                let own = other
                    .iter()
                    .map(|z| g.dot(z).cmp(&h))
                    .find(|o| *o != Ordering::Equal);
                let sides: &[Ordering] = match own {
                    Some(Ordering::Less) => &[Ordering::Less],
                    Some(_) => &[Ordering::Greater],
                    None => &[Ordering::Less, Ordering::Greater],
                };
                if sides.iter().any(|&s| beyond(&g, &h, s, &seg, dp, dother)) {
                    apart = true;
                    break;
                }
            }
        }
        if !apart {
            keep[e] = true;
            keep[(e + 1) % k] = true;
        }
    }
    (0..k).filter(|&i| keep[i]).map(|i| ids[i]).collect()
}

/// Whether the relative interior of the facet `fa` (a cycle of at least three points of
/// the plane with normal `n`, stored with denominator `da`) meets the convex hull of the
/// points `fb` of the same plane (denominator `db`). They are disjoint exactly when a line
/// of the plane separates them weakly, and then (two-dimensional separating axes) the
/// line through an edge of `fa` or of `fb` does.
fn approx(x: &Int) -> f64 {
    apart_kernel::int::to_f64(x)
}

fn meets_relative_interior(fa: &[Vec3], da: &Int, fb: &[Vec3], db: &Int, n: &Vec3) -> bool {
    let separated = |cycle: &[Vec3], dc: &Int, other: &[Vec3], dother: &Int| -> bool {
        let k = cycle.len();
        let edges = if k == 2 { 1 } else { k };
        // Edges near the other set first (the separating one, when there is one, is
        // usually there); the order changes nothing but the time.
        let (fc, fo) = (approx(dc), approx(dother));
        let target = other[0].approx().map(|t| t / fo);
        let dist = |e: usize| {
            let u = cycle[e].approx();
            (0..3).map(|t| (u[t] / fc - target[t]).powi(2)).sum::<f64>()
        };
        let order: Vec<usize> = if edges > 8 {
            // Each distance once (a many-sided cap has a thousand edges).
            let mut by: Vec<(f64, usize)> = (0..edges).map(|e| (dist(e), e)).collect();
            by.sort_by(|x, y| x.0.total_cmp(&y.0));
            by.into_iter().map(|(_, e)| e).collect()
        } else {
            (0..edges).collect()
        };
        order.into_iter().any(|e| {
            let (u, v) = (&cycle[e], &cycle[(e + 1) % k]);
            let g = n.cross(&v.sub(u));
            let h = g.dot(u);
            // The side of the cycle (a third point, when there is one), then every other
            // point weakly on the far side.
            let own = cycle
                .iter()
                .map(|w| g.dot(w).cmp(&h))
                .find(|o| *o != Ordering::Equal);
            let all_one_side = |want: Ordering| {
                other.iter().all(|w| {
                    let o = cmp_fractions(&g.dot(w), dother, &h, dc);
                    o == Ordering::Equal || o == want
                })
            };
            match own {
                Some(s) => all_one_side(s.reverse()),
                // A segment: either side of its line.
                None => all_one_side(Ordering::Less) || all_one_side(Ordering::Greater),
            }
        })
    };
    let apart = separated(fa, da, fb, db) || (fb.len() >= 2 && separated(fb, db, fa, da));
    !apart
}

/// Whether the centroid of the points `pts` (denominator `dp`), which lie in the plane of
/// the facet of `p` with outward normal `n`, lies in that facet's relative interior:
/// strictly inside every other facet's half-space. A cheap sufficient test for
/// [`meets_relative_interior`].
///
/// A facet whose plane the float centroid clears by more than the shadow's error bound
/// is decided without exact arithmetic (a many-sided piece has many such facets).
fn centroid_in_relative_interior(p: &Polytope, n: &Vec3, pts: &[Vec3], dp: &Int) -> bool {
    let n = n.primitive();
    let sum = pts.iter().skip(1).fold(pts[0].clone(), |s, w| s.add(w));
    // p's stored integers are den_p times coordinates; the centroid is sum / (k dp).
    let scale = Int::from(pts.len() as i64) * dp;
    let c = sum.scale(p.den());
    // The centroid in floats (each coordinate within a relative 2^-50).
    let filter = p.shadow().and_then(|s| {
        let d = approx(&scale) * approx(p.den());
        let x = [0, 1, 2].map(|k| approx(&c.get(k)) / d);
        let m = x.iter().fold(s.magnitude, |m, v| m.max(v.abs()));
        (d.is_finite() && d > 0.0 && x.iter().all(|v| v.is_finite())).then_some((
            s,
            x,
            m * 2f64.powi(-44),
        ))
    });
    p.facets().iter().enumerate().all(|(i, f)| {
        if let Some((s, x, err)) = &filter {
            let u = &s.facet_units[i];
            if x[0] * u[0] + x[1] * u[1] + x[2] * u[2] < s.facet_levels[i] - 2.0 * err {
                return true; // clearly strictly inside (and not the facet with normal n)
            }
        }
        f.normal == n || f.normal.dot(&c) < &f.offset * &scale
    })
}

/// The contact cone of two pieces touching across the plane with normal `n` (from `a` to
/// `b`); `None` when they do not touch (or a neighbourhood is degenerate): the caller
/// then sums the whole pieces.
///
/// When a facet of either piece in that plane meets the other piece's face in its
/// relative interior, the normal cone `N_b(c) ∩ −N_a(c)` at such a common point `c` is
/// the ray of `−n`, and the cone is the hemisphere `{n·x >= 0}` (what the full sum's
/// single facet through the origin projects to). Otherwise the contact lies on the
/// faces' boundaries and the small sum of the face neighbourhoods gives the cone (of a
/// facet with many vertices, only the edges that reach the other face: every common
/// point lies on one of them, and the tangent cones there are kept).
///
/// A neighbourhood that is the whole piece is summed through the piece's prepared
/// summand in `ia` or `ib` (made once per piece, shared by all its pairs).
pub(crate) fn contact_polygon(
    a: &Polytope,
    ia: &PieceInfo,
    b: &Polytope,
    ib: &PieceInfo,
    n: &Vec3,
) -> Option<Result<PairPolygon, String>> {
    let (ida, idb) = (support_face(a, n), support_face(b, &n.neg()));
    let (fa, fb) = (points(a, &ida), points(b, &idb));
    let face = |f: &[Vec3]| f.len() >= 3;
    if (face(&fa) && centroid_in_relative_interior(a, n, &fb, b.den()))
        || (face(&fb) && centroid_in_relative_interior(b, &n.neg(), &fa, a.den()))
        || (face(&fa) && meets_relative_interior(&fa, a.den(), &fb, b.den(), n))
        || (face(&fb) && meets_relative_interior(&fb, b.den(), &fa, a.den(), n))
    {
        return Some(Ok(PairPolygon::Polygon(
            SphericalPolygon::hemisphere(n),
            true,
        )));
    }
    // The contact lies on the faces' boundaries: only the edges of a large facet that
    // reach the other face matter (their neighbourhoods keep the tangent cones there).
    let ida = if face(&fa) {
        edges_meeting(a, &ida, &fb, b.den(), n)
    } else {
        ida
    };
    let idb = if face(&fb) {
        edges_meeting(b, &idb, &fa, a.den(), n)
    } else {
        idb
    };
    let a2 = neighbourhood(a, &ida)?.map(|a2| Summand::new(a2.reflected()));
    let b2 = neighbourhood(b, &idb)?.map(Summand::new);
    let (sa, sb) = (
        a2.as_ref().unwrap_or_else(|| ia.reflected(a)),
        b2.as_ref().unwrap_or_else(|| ib.fixed(b)),
    );
    let m = match sum_prepared(sb, sa) {
        Ok(m) => m,
        Err(e) => return Some(Err(format!("Minkowski sum: {e}"))),
    };
    if m.facets().iter().any(|f| f.offset < Int::ZERO) {
        return None; // the origin lies outside: the pieces do not touch
    }
    Some(match project(&m) {
        Ok(Projection::Polygon(p)) => Ok(PairPolygon::Polygon(p, true)),
        Ok(Projection::Everything) => Ok(PairPolygon::Overlap),
        Err(e) => Err(format!("projection: {e}")),
    })
}

/// The projection of a piece pair: the contact cone when a touching axis shows the
/// pieces touch, else the full sum's projection.
pub(crate) fn pair_polygon(
    a: &Polytope,
    ia: &PieceInfo,
    b: &Polytope,
    ib: &PieceInfo,
    axes: &[Axis],
) -> Result<(PairPolygon, bool), String> {
    if let Some(t) = axes.iter().find(|x| !x.strict) {
        if let Some(r) = contact_polygon(a, ia, b, ib, &t.n) {
            return r.map(|p| (p, false));
        }
    }
    full_polygon(a, ia, b, ib).map(|p| (p, true))
}

/// The touching axes' normals of a pair (directions of face contacts).
pub(crate) fn touching_normal(axes: &[Axis]) -> Option<&Vec3> {
    axes.iter().find(|x| !x.strict).map(|x| &x.n)
}

/// Wraps a pair error with part names.
pub(crate) fn internal(names: (&str, &str), e: String) -> PlanError {
    PlanError::Internal(format!("pieces of {} and {}: {e}", names.0, names.1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::regions::Part;
    use apart_testkit::curved;

    proptest::proptest! {
        /// The float-first comparison of box bounds agrees with the exact one, on equal
        /// fractions in other terms, neighbours one unit apart over huge denominators,
        /// and bounds of either sign around zero.
        #[test]
        fn box_bounds_compare_as_their_fractions(
            x in -(1i64 << 62)..(1i64 << 62),
            near in -2i64..=2,
            dx_bits in 0u32..200,
            k in 1i64..1000,
            odd in 0u32..3,
        ) {
            let dx = (Int::ONE << dx_bits as usize) + Int::from(odd);
            let x = Int::from(x);
            // y / dy: x / dx in other terms (times k), moved by `near` units of dy.
            let dy = &dx * Int::from(k);
            let y = &x * Int::from(k) + Int::from(near);
            let f = |n: &Int, d: &Int| apart_kernel::Rational::new(n.clone(), d.clone()).to_f64();
            for (a, da, b, db) in [(&x, &dx, &y, &dy), (&y, &dy, &x, &dx)] {
                proptest::prop_assert_eq!(
                    cmp_bound(f(a, da), a, da, f(b, db), b, db),
                    cmp_fractions(a, da, b, db)
                );
            }
        }
    }

    fn generated(name: &str, parts: &[curved::NamedSoup]) -> Vec<Part> {
        let dir = std::env::temp_dir().join(format!("apart-pairs-{}-{name}", std::process::id()));
        curved::write_off_dir(parts, &dir).unwrap();
        let loaded = apart_assembly::load(&dir, &Default::default()).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        assert!(loaded.is_valid(), "{:?}", loaded.problems);
        crate::parts_of(&loaded.assembly).unwrap().to_vec()
    }

    fn normals(p: &SphericalPolygon) -> Vec<[String; 3]> {
        let mut v: Vec<[String; 3]> = p.normals().iter().map(|q| q.to_strings()).collect();
        v.sort();
        v.dedup();
        v
    }

    /// The `i128` ray–box test agrees with the arbitrary-precision one: random boxes with
    /// touching, overlapping and far-apart bounds (degenerate: shared faces, zero
    /// direction components), up to the fast path's 2^61 bounds and 2^62 directions.
    #[test]
    fn small_ray_box_test_agrees_with_the_exact_one() {
        let mut rng = apart_testkit::solids::Lcg(7);
        let scales = [3i64, 1000, 1 << 40, (1 << 61) - 1];
        let mut met = [0usize; 2];
        for round in 0..20_000 {
            let s = scales[round % scales.len()];
            let coord = |r: &mut apart_testkit::solids::Lcg| -> i64 {
                // Few distinct values in each scale: shared faces and touching boxes.
                let k = r.range(-3, 4);
                (k * (s / 3)).clamp(-s, s)
            };
            let mut boxes = Vec::new();
            for _ in 0..2 {
                let (mut lo, mut hi) = ([0i64; 3], [0i64; 3]);
                for k in 0..3 {
                    let (u, v) = (coord(&mut rng), coord(&mut rng));
                    lo[k] = u.min(v);
                    hi[k] = u.max(v).max(lo[k] + 1).min(s);
                    lo[k] = lo[k].min(hi[k] - 1);
                }
                boxes.push(Polytope::cuboid(lo, hi).unwrap());
            }
            let xs = 1i64 << rng.below(62);
            let x = Vec3::from_i64([0, 1, 2].map(|_| rng.range(-2, 3) * (xs / 2).max(1)));
            if x.is_zero() {
                continue;
            }
            let (ia, ib) = (PieceInfo::new(&boxes[0]), PieceInfo::new(&boxes[1]));
            assert!(ia.small.is_some() && ib.small.is_some() && x.as_small().is_some());
            let fast = ray_meets_box(&ia, &Int::ONE, &ib, &Int::ONE, &x);
            let exact = ray_meets_box_exact(&ia, &Int::ONE, &ib, &Int::ONE, &x);
            assert_eq!(fast, exact, "{:?} {:?} {x:?}", ia.bounds.min, ib.bounds.max);
            met[fast as usize] += 1;
        }
        assert!(met[0] > 1000 && met[1] > 1000, "{met:?}");
    }

    /// Every contact cone equals the full sum's projection (same inward normals), and the
    /// axes never cull a direction the full polygon holds.
    #[test]
    fn contact_cones_and_axes_agree_with_full_sums() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
        let mut cases: Vec<Vec<Part>> = Vec::new();
        for name in [
            "peg-in-the-hole",
            "dovetail-and-cap",
            "hinge",
            "split-star-5",
        ] {
            let loaded = apart_assembly::load(&dir.join(name), &Default::default()).unwrap();
            cases.push(crate::parts_of(&loaded.assembly).unwrap().to_vec());
        }
        cases.push(generated("plug", &curved::plug_and_socket(20 * 16 - 8)));
        cases.push(generated("pin", &curved::pin_in_hole(12, 12, 0.0)));
        cases.push(generated("nut", &curved::nut_on_bolt(10, 2)));
        // A tessellated cone's tip on a box's edge, on a box's corner and on another
        // tip: the contacts lie on no face's relative interior, so the tip's
        // neighbourhood (the tip and a 120-point ring, not the whole piece) is hulled.
        let cone = |s: i64| {
            let mut pts = vec![Vec3::new(0, 0, 0)];
            for (z, r) in [(100.0, 1000.0), (1000.0, 3000.0)] {
                for k in 0..120 {
                    let t = k as f64 * std::f64::consts::TAU / 120.0;
                    let (x, y) = ((r * t.cos()).round() as i64, (r * t.sin()).round() as i64);
                    pts.push(Vec3::new(x, y, s * z as i64));
                }
            }
            Polytope::hull(&pts).unwrap()
        };
        let tip = cone(1).vertices().iter().position(|v| v.is_zero()).unwrap() as u32;
        let Some(Some(near)) = face_neighbourhood(&cone(1), &[tip]) else {
            panic!("the tip's neighbourhood is a part of the cone")
        };
        assert_eq!(near.vertices().len(), 121);
        let part = |name: &str, p: Polytope| Part::from_pieces(name, vec![p]);
        for hi in [[0, 5000, 0], [0, 0, 0]] {
            let block = Polytope::cuboid([-5000, -5000, -5000], hi).unwrap();
            cases.push(vec![part("cone", cone(1)), part("block", block)]);
        }
        cases.push(vec![part("up", cone(1)), part("down", cone(-1))]);
        let dirs: Vec<Vec3> = (0..27)
            .map(|i| Vec3::new(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1))
            .filter(|d| !d.is_zero())
            .chain([Vec3::new(1, 2, 3), Vec3::new(-3, 1, 7)])
            .collect();
        let mut cones = 0;
        for parts in &cases {
            for (i, pi) in parts.iter().enumerate() {
                for pj in &parts[i + 1..] {
                    for a in &pi.pieces {
                        for b in &pj.pieces {
                            let (ia, ib) = (PieceInfo::new(a), PieceInfo::new(b));
                            let ax = axes(a, &ia, b, &ib);
                            let PairPolygon::Polygon(full, contact) =
                                full_polygon(a, &ia, b, &ib).unwrap()
                            else {
                                panic!("overlap")
                            };
                            for d in &dirs {
                                if !ray_meets_box(&ia, a.den(), &ib, b.den(), d) {
                                    assert!(!full.contains_closed(d));
                                }
                                match classify(&ax, d) {
                                    Sep::Outside => assert!(!full.contains_closed(d)),
                                    Sep::Free => assert!(!full.contains_open(d)),
                                    Sep::Unknown => {}
                                }
                            }
                            assert_eq!(
                                first_touching_axis(a, &ia, b, &ib).as_ref(),
                                touching_normal(&ax)
                            );
                            let Some(n) = touching_normal(&ax) else {
                                continue;
                            };
                            match contact_polygon(a, &ia, b, &ib, n) {
                                Some(Ok(PairPolygon::Polygon(p, true))) => {
                                    assert!(contact);
                                    assert_eq!(normals(&p), normals(&full));
                                    cones += 1;
                                }
                                None => assert!(!contact),
                                other => panic!("{other:?}"),
                            }
                        }
                    }
                }
            }
        }
        assert!(cones > 50, "{cones}");
    }

    /// For boxes the sum is the box of [`ray_meets_box`], so the test is exact: it holds
    /// exactly when the closed projection holds the direction (random boxes with
    /// denominators, touching and apart, and directions with zero components).
    #[test]
    fn the_ray_meets_the_box_exactly_when_the_projection_holds_the_direction() {
        let mut rng = apart_testkit::solids::Lcg(5u64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        let mut seen = [0usize; 2];
        for _ in 0..400 {
            let cuboid = |next: &mut dyn FnMut(i64) -> i64| {
                let den = 1 + next(3);
                let lo = [next(13) - 6, next(13) - 6, next(13) - 6];
                let hi = [
                    lo[0] + 1 + next(4),
                    lo[1] + 1 + next(4),
                    lo[2] + 1 + next(4),
                ];
                Polytope::cuboid(lo, hi).unwrap().with_den(Int::from(den))
            };
            let (a, b) = (cuboid(&mut next), cuboid(&mut next));
            let (ia, ib) = (PieceInfo::new(&a), PieceInfo::new(&b));
            let Ok(PairPolygon::Polygon(full, _)) = full_polygon(&a, &ia, &b, &ib) else {
                continue; // interiors overlap: every direction is blocked
            };
            for _ in 0..12 {
                let d = Vec3::new(next(5) - 2, next(5) - 2, next(5) - 2);
                if d.is_zero() {
                    continue;
                }
                let meets = ray_meets_box(&ia, a.den(), &ib, b.den(), &d);
                assert_eq!(meets, full.contains_closed(&d), "{a:?} {b:?} {d:?}");
                seen[usize::from(meets)] += 1;
            }
        }
        assert!(seen[0] > 500 && seen[1] > 200, "{seen:?}");
    }

    /// For boxes the open box of differences decides blocking exactly: the open ray meets
    /// its interior exactly when the open projection holds the direction, and the
    /// interior holds the origin exactly when the pieces overlap (random boxes with
    /// denominators, touching, apart and overlapping, directions with zero components).
    #[test]
    fn the_open_box_decides_blocking_for_boxes() {
        let mut rng = apart_testkit::solids::Lcg(11u64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        let mut seen = [0usize; 4];
        for _ in 0..400 {
            let cuboid = |next: &mut dyn FnMut(i64) -> i64| {
                let den = 1 + next(3);
                let lo = [next(13) - 6, next(13) - 6, next(13) - 6];
                let hi = [
                    lo[0] + 1 + next(4),
                    lo[1] + 1 + next(4),
                    lo[2] + 1 + next(4),
                ];
                Polytope::cuboid(lo, hi).unwrap().with_den(Int::from(den))
            };
            let (a, b) = (cuboid(&mut next), cuboid(&mut next));
            assert!(is_axis_box(&a) && is_axis_box(&b));
            let (ia, ib) = (PieceInfo::new(&a), PieceInfo::new(&b));
            let full = full_polygon(&a, &ia, &b, &ib).unwrap();
            for _ in 0..12 {
                let d = Vec3::new(next(5) - 2, next(5) - 2, next(5) - 2);
                if d.is_zero() {
                    continue;
                }
                let got = open_box_blocks(&ia, a.den(), &ib, b.den(), &d);
                if let (Some(c), PairPolygon::Polygon(p, _)) =
                    (box_graze_normal(&ia, a.den(), &ib, b.den(), &d), &full)
                {
                    // Grazing: on the polygon's boundary, and every perturbed direction
                    // inside it on the positive side of c.
                    assert!(p.contains_closed(&d) && !p.contains_open(&d));
                    assert_eq!(c.dot(&d), Int::ZERO);
                    for y in (0..27).map(|i| Vec3::new(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1)) {
                        if p.contains_open_perturbed(&d, &y) {
                            assert!(c.dot(&y) > Int::ZERO, "{a:?} {b:?} {d:?} {y:?} {c:?}");
                        }
                    }
                    seen[3] += 1;
                }
                let ax = axes(&a, &ia, &b, &ib);
                assert_eq!(
                    classify_boxes(&a, &ia, &b, &ib, &d),
                    (classify(&ax, &d), ax.iter().any(|x| !x.strict))
                );
                if let (Some(sa), Some(sb), Some(x)) = (&ia.small, &ib.small, d.as_small()) {
                    // The i128 path (taken above) and the exact one agree.
                    let (big_a, big_b) = (
                        PieceInfo {
                            small: None,
                            ..PieceInfo::new(&a)
                        },
                        PieceInfo {
                            small: None,
                            ..PieceInfo::new(&b)
                        },
                    );
                    assert_eq!(
                        open_small_box_blocks(sa, sb, x),
                        open_box_blocks(&big_a, a.den(), &big_b, b.den(), &d)
                    );
                }
                match &full {
                    PairPolygon::Polygon(p, _) => {
                        assert_eq!(got, Some(p.contains_open(&d)), "{a:?} {b:?} {d:?}");
                        seen[usize::from(p.contains_open(&d))] += 1;
                    }
                    PairPolygon::Overlap => {
                        assert_eq!(got, None);
                        seen[2] += 1;
                    }
                }
            }
        }
        assert!(
            seen[..3].iter().all(|&k| k > 50) && seen[3] > 20,
            "{seen:?}"
        );
    }
}
