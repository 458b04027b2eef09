//! C-space obstacles of convex piece pairs: `conv{b − a} = b ⊕ (−a)`. The moving piece
//! `a` translated by `p` and the fixed piece `b` have overlapping interiors exactly when
//! `p` lies in the interior of the obstacle (touching is allowed).
//!
//! Each obstacle carries both representations paper 004 §VI-A.2 uses: half-spaces
//! (for free-space cells, clearance and subtraction) and vertices (for extrapolation and
//! quick rejection). Construction is `apart_minkowski::minkowski_difference`, exact and
//! output-sensitive.

use apart_kernel::int::{ceil_sqrt, Int};
use apart_kernel::{Aabb, BigPlane, HPoint, Rational, Vec3};
use apart_pieces::{Polytope, PolytopeError};
use rustc_hash::FxHashMap as HashMap;

/// The obstacle of a fixed convex piece for translations of a moving convex piece,
/// both in their own (unplaced) frames.
#[derive(Clone, Debug)]
pub struct ObstacleShape {
    /// Vertices, stored as `den` times their coordinates.
    pub vertices: Vec<Vec3>,
    /// Common denominator of the vertices.
    pub den: Int,
    /// Facets as half-spaces of true coordinates, in the order of `cycles`.
    pub halfspaces: Vec<BigPlane>,
    /// Each facet's vertex cycle (indices into `vertices`), counter-clockwise outside.
    pub(crate) cycles: Vec<Vec<u32>>,
}

impl ObstacleShape {
    /// `fixed ⊕ (−moving)`, computed from scratch.
    pub fn compute(fixed: &Polytope, moving: &Polytope) -> Result<ObstacleShape, PolytopeError> {
        let m = apart_minkowski::minkowski_difference(fixed, moving)?;
        Ok(ObstacleShape::from_polytope(m))
    }

    /// Wraps an obstacle polytope.
    pub(crate) fn from_polytope(polytope: Polytope) -> ObstacleShape {
        let halfspaces = polytope
            .facets()
            .iter()
            .map(|f| facet_plane(&f.normal, &f.offset, polytope.den()))
            .collect();
        ObstacleShape {
            vertices: polytope.vertices().to_vec(),
            den: polytope.den().clone(),
            halfspaces,
            cycles: polytope.facets().iter().map(|f| f.cycle.clone()).collect(),
        }
    }

    /// The obstacle moved by `t` (the fixed piece placed at `t`), grown by a horizontal
    /// clearance when given.
    pub(crate) fn placed(&self, t: &HPoint, clearance: Option<&Rational>) -> Obstacle {
        let halfspaces: Vec<BigPlane> = self
            .halfspaces
            .iter()
            .map(|h| {
                let h = h.translated(t);
                match clearance {
                    Some(c) if !c.is_zero() => grow_horizontally(&h, c),
                    _ => h,
                }
            })
            .collect();
        let vertices = match clearance {
            Some(c) if !c.is_zero() => None,
            _ => Some(
                self.vertices
                    .iter()
                    .map(|v| HPoint::from_big(v.to_ints(), self.den.clone()).add(t))
                    .collect(),
            ),
        };
        let bbox = vertices
            .as_ref()
            .map(|_| Aabb::of_scaled(&self.vertices, &self.den).translated(&t.to_rationals()));
        Obstacle {
            halfspaces,
            vertices,
            bbox,
        }
    }
}

/// `n · p <= off + clearance · r` with `r >= ‖(n_x, n_y)‖` (a rational upper bound
/// within 2^-20): the paper's shift of each inequality's right-hand side (§VI-A.2),
/// horizontal only so that a part can still rest on the one below.
pub(crate) fn grow_horizontally(h: &BigPlane, clearance: &Rational) -> BigPlane {
    let s = &h.n[0] * &h.n[0] + &h.n[1] * &h.n[1];
    let r = sqrt_upper(&s);
    let shift = clearance * &r;
    let off = &Rational::from_int(h.c.clone()) + &shift;
    BigPlane::with_rational_offset(h.n.clone(), &off)
}

/// A rational `r >= sqrt(s)` within a relative `2^-20` of it, for `s >= 0`:
/// `⌈sqrt(s · 4^20)⌉ / 2^20`.
fn sqrt_upper(s: &Int) -> Rational {
    const K: usize = 20;
    Rational::new(ceil_sqrt(&(s << (2 * K))), Int::ONE << K)
}

/// The facet plane `normal · x <= offset` of a polytope whose stored integers are `den`
/// times its coordinates, as a half-space of true coordinates (reduced).
pub(crate) fn facet_plane(normal: &Vec3, offset: &Int, den: &Int) -> BigPlane {
    BigPlane::reduced(normal.to_ints().map(|c| c * den), offset.clone())
}

/// A placed (and possibly grown) obstacle: the moving piece at `p` overlaps the fixed
/// one (or comes closer than the clearance) exactly when `p` is in its interior.
#[derive(Clone, Debug)]
pub(crate) struct Obstacle {
    /// Half-spaces whose intersection is the closed obstacle.
    pub(crate) halfspaces: Vec<BigPlane>,
    /// Its vertices when known (not for grown obstacles).
    pub(crate) vertices: Option<Vec<HPoint>>,
    /// Its bounding box when known (not for grown obstacles).
    pub(crate) bbox: Option<Aabb<Rational>>,
}

impl Obstacle {
    /// True when `p` lies in the open obstacle.
    pub(crate) fn contains_open(&self, p: &HPoint) -> bool {
        self.halfspaces
            .iter()
            .all(|h| h.side(p) == apart_kernel::Sign::Negative)
    }
}

/// For each vertex of `sum = fixed ⊕ (−moving)`, the pair `(i, j)` with
/// `sum_vertex = fixed_j − moving_i` (unique for a vertex of a Minkowski sum).
pub(crate) fn provenance(
    sum: &ObstacleShape,
    fixed: &Polytope,
    moving: &Polytope,
) -> Option<Vec<(u32, u32)>> {
    let d = &sum.den;
    let scale = |p: &Polytope| -> Int { d / p.den() };
    let (kf, km) = (scale(fixed), scale(moving));
    let mut index: HashMap<Vec3, u32> = HashMap::default();
    for (i, v) in moving.vertices().iter().enumerate() {
        index.insert(v.scale(&km), i as u32);
    }
    let fixed_scaled: Vec<Vec3> = fixed.vertices().iter().map(|v| v.scale(&kf)).collect();
    sum.vertices
        .iter()
        .map(|s| {
            fixed_scaled
                .iter()
                .enumerate()
                .find_map(|(j, b)| index.get(&b.sub(s)).map(|&i| (i, j as u32)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::q;

    #[test]
    fn square_root_bound() {
        for s in [0i64, 1, 2, 3, 50, 1 << 40] {
            let r = sqrt_upper(&Int::from(s));
            assert!(&r * &r >= q(s));
            if s > 0 {
                assert!((r.to_f64() - (s as f64).sqrt()) / (s as f64).sqrt() < 1e-5);
            }
        }
        assert_eq!(sqrt_upper(&Int::from(4)), q(2));
    }
}
