//! Separating axes of a piece pair at rest (coordinate axes and facet normals), and
//! what they say of a direction.

use super::{touching_normal, PieceInfo};
use apart_kernel::int::cmp_fractions;
use apart_kernel::{Int, Vec3};
use apart_pieces::interference::{below_along, facet_axes};
use apart_pieces::Polytope;
use std::cmp::Ordering;

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
pub(super) fn cmp_bound(fx: f64, x: &Int, dx: &Int, fy: f64, y: &Int, dy: &Int) -> Ordering {
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
