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
use apart_kernel::{Int, Vec3};
use apart_minkowski::{project, sum_prepared, Projection, Summand};
use apart_pieces::Polytope;
use apart_sphere::SphericalPolygon;
use std::cmp::Ordering;
use std::sync::OnceLock;

/// A piece with the data the exact culls need.
pub(crate) struct PieceInfo {
    lo: [Int; 3],
    hi: [Int; 3],
    small: Option<Vec<[i64; 3]>>,
    fixed: OnceLock<Summand>,
    reflected: OnceLock<Summand>,
}

impl PieceInfo {
    pub(crate) fn new(p: &Polytope) -> PieceInfo {
        let lo = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).min().unwrap());
        let hi = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).max().unwrap());
        let small = p
            .vertices()
            .iter()
            .map(|v| v.as_small().copied())
            .collect::<Option<Vec<_>>>()
            .filter(|v| v.iter().flatten().all(|c| c.unsigned_abs() < 1 << 40));
        PieceInfo {
            lo,
            hi,
            small,
            fixed: OnceLock::new(),
            reflected: OnceLock::new(),
        }
    }

    /// `(min, max)` of `n · v` over the stored vertices.
    fn range(&self, p: &Polytope, n: &Vec3) -> (Int, Int) {
        if let (Some(vs), Some(nn)) = (&self.small, n.as_small()) {
            if nn.iter().all(|c| c.unsigned_abs() < 1 << 40) {
                let (mut lo, mut hi) = (i128::MAX, i128::MIN);
                for c in vs {
                    let d = nn[0] as i128 * c[0] as i128
                        + nn[1] as i128 * c[1] as i128
                        + nn[2] as i128 * c[2] as i128;
                    lo = lo.min(d);
                    hi = hi.max(d);
                }
                return (Int::from(lo), Int::from(hi));
            }
        }
        let mut it = p.vertices().iter().map(|v| n.dot(v));
        let first = it.next().expect("a polytope has vertices");
        it.fold((first.clone(), first), |(lo, hi), d| {
            (
                if d < lo { d.clone() } else { lo },
                if d > hi { d } else { hi },
            )
        })
    }

    pub(crate) fn fixed(&self, p: &Polytope) -> &Summand {
        self.fixed.get_or_init(|| Summand::new(p.clone()))
    }

    pub(crate) fn reflected(&self, p: &Polytope) -> &Summand {
        self.reflected.get_or_init(|| Summand::new(p.reflected()))
    }
}

/// Compares `x / dx` with `y / dy` (positive denominators).
fn cmp_scaled(x: &Int, dx: &Int, y: &Int, dy: &Int) -> Ordering {
    if dx == dy {
        x.cmp(y)
    } else {
        (x * dy).cmp(&(y * dx))
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
    let (da, db) = (a.den(), b.den());
    let mut out = Vec::new();
    for k in 0..3 {
        let mut e = [0i64; 3];
        // a below b along +e_k: hi_a <= lo_b.
        match cmp_scaled(&ia.hi[k], da, &ib.lo[k], db) {
            Ordering::Less | Ordering::Equal => {
                e[k] = 1;
                out.push(Axis {
                    n: Vec3::from_i64(e),
                    strict: cmp_scaled(&ia.hi[k], da, &ib.lo[k], db) == Ordering::Less,
                });
            }
            Ordering::Greater => {}
        }
        match cmp_scaled(&ib.hi[k], db, &ia.lo[k], da) {
            Ordering::Less | Ordering::Equal => {
                e[k] = -1;
                out.push(Axis {
                    n: Vec3::from_i64(e),
                    strict: cmp_scaled(&ib.hi[k], db, &ia.lo[k], da) == Ordering::Less,
                });
            }
            Ordering::Greater => {}
        }
    }
    if out.iter().any(|x| x.strict) {
        return out; // strictly apart: nothing more to learn at rest
    }
    // Facets of a: a <= off_a along n; below b when min_b n·x >= off_a.
    for f in a.facets() {
        let (bmin, _) = ib.range(b, &f.normal);
        match cmp_scaled(&f.offset, da, &bmin, db) {
            Ordering::Greater => {}
            o => out.push(Axis {
                n: f.normal.clone(),
                strict: o == Ordering::Less,
            }),
        }
    }
    // Facets of b: b <= off_b along n, so a lies below b along −n when min_a n·x >= off_b.
    for f in b.facets() {
        let (amin, _) = ia.range(a, &f.normal);
        match cmp_scaled(&f.offset, db, &amin, da) {
            Ordering::Greater => {}
            o => out.push(Axis {
                n: f.normal.neg(),
                strict: o == Ordering::Less,
            }),
        }
    }
    out
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
    let m =
        sum_prepared(ib.fixed(b), ia.reflected(a)).map_err(|e| format!("Minkowski sum: {e}"))?;
    match project(&m) {
        Ok(Projection::Polygon(p)) => {
            let contact = m.facets().iter().all(|f| f.offset >= Int::ZERO);
            Ok(PairPolygon::Polygon(p, contact))
        }
        Ok(Projection::Everything) => Ok(PairPolygon::Overlap),
        Err(e) => Err(format!("projection: {e}")),
    }
}

/// The hull of the support face of `p` along `n` and the neighbours of its vertices.
fn face_neighbourhood(p: &Polytope, n: &Vec3) -> Option<Polytope> {
    let (_, face) = p.support(n);
    let mut keep = vec![false; p.vertices().len()];
    for &v in &face {
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
        return Some(p.clone());
    }
    Polytope::hull_of_points(&pts)
        .ok()
        .map(|h| h.with_den(p.den().clone()))
}

/// The contact cone of two pieces touching across the plane with normal `n` (from `a` to
/// `b`), from the small sum of their face neighbourhoods; `None` when they do not touch
/// (or a neighbourhood is degenerate): the caller then sums the whole pieces.
pub(crate) fn contact_polygon(
    a: &Polytope,
    b: &Polytope,
    n: &Vec3,
) -> Option<Result<PairPolygon, String>> {
    let a2 = face_neighbourhood(a, n)?;
    let b2 = face_neighbourhood(b, &n.neg())?;
    let m = match sum_prepared(&Summand::new(b2), &Summand::new(a2.reflected())) {
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
        if let Some(r) = contact_polygon(a, b, &t.n) {
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
