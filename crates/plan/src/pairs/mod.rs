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

mod axes;
mod boxes;
mod contact;
#[cfg(test)]
mod tests;

pub(crate) use axes::{
    axes, below_along_any, classify, classify_boxes, first_touching_axis, Axis, Sep,
};
pub(crate) use boxes::{
    box_graze_normal, is_axis_box, open_box_blocks, ray_meets_box, ray_meets_int_box,
};
pub(crate) use contact::contact_polygon;

use crate::PlanError;
use apart_kernel::int;
use apart_kernel::{Aabb, Int, Vec3};
use apart_minkowski::{project, project_apart, sum_prepared, Projection, Summand};
use apart_pieces::Polytope;
use apart_sphere::SphericalPolygon;
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
