//! The part to place: convex pieces (and its mesh when known), exact centroid, and its
//! rotated copies for each orientation.

use crate::orientation::{Base, Orientation};
use apart_kernel::{Aabb, HPoint, Int, Rational, Vec3};
use apart_pieces::Polytope;
use rustc_hash::FxHashMap as HashMap;

pub use crate::qp::ObjectiveError;

/// Why a part or a request cannot be used.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum StackError {
    /// The part has no pieces.
    #[error("the part has no convex pieces")]
    NoPieces,
    /// The objective is not a convex quadratic bounded below.
    #[error("objective: {0}")]
    Objective(#[from] ObjectiveError),
    /// An internal inconsistency (a bug), reported rather than hidden.
    #[error("internal error: {0}")]
    Internal(String),
    /// A bad request (empty region, weight out of range, ...).
    #[error("{0}")]
    Invalid(String),
}

/// A part: convex pieces with disjoint interiors whose union is the part, and its
/// boundary mesh when known.
#[derive(Clone, Debug)]
pub struct PartModel {
    /// Name.
    pub name: String,
    /// Convex pieces.
    pub pieces: Vec<Polytope>,
    /// The boundary (integer points and outward triangles), when known.
    pub mesh: Option<(Vec<Vec3>, Vec<[u32; 3]>)>,
    centroid: [Rational; 3],
    volume: Rational,
}

impl PartModel {
    /// A part from its convex pieces.
    pub fn from_pieces(name: &str, pieces: Vec<Polytope>) -> Result<PartModel, StackError> {
        if pieces.is_empty() {
            return Err(StackError::NoPieces);
        }
        let (centroid, volume) = centroid_of(&pieces);
        Ok(PartModel {
            name: name.to_string(),
            pieces,
            mesh: None,
            centroid,
            volume,
        })
    }

    /// The exact centre of gravity (uniform density).
    pub fn centroid(&self) -> &[Rational; 3] {
        &self.centroid
    }

    /// The exact volume.
    pub fn volume(&self) -> &Rational {
        &self.volume
    }

    /// The part turned to an orientation (about the origin of its coordinates).
    pub fn orient(&self, o: &Orientation) -> OrientedPart {
        let pieces: Vec<Polytope> = self.pieces.iter().map(|p| o.rotate(p)).collect();
        let boxes: Vec<Aabb<Rational>> = pieces
            .iter()
            .map(|p| Aabb::of_scaled(p.vertices(), p.den()))
            .collect();
        let extent = boxes[1..].iter().fold(boxes[0].clone(), |a, b| a.union(b));
        let c = HPoint::from_rationals(&self.centroid);
        let rc = o.apply_scaled(&Vec3::from_ints(c.num().clone()));
        let centroid =
            HPoint::from_big(rc.to_ints(), c.den() * Int::from(o.theta.c)).to_rationals();
        OrientedPart {
            orientation: *o,
            pieces,
            boxes,
            extent,
            centroid,
        }
    }

    /// The pieces turned by a base orientation only (no turn about z).
    pub(crate) fn base_pieces(&self, base: Base) -> Vec<Polytope> {
        let o = Orientation {
            base,
            ..Orientation::IDENTITY
        };
        self.pieces.iter().map(|p| o.rotate(p)).collect()
    }
}

/// The part in one orientation (not yet translated).
#[derive(Clone, Debug)]
pub struct OrientedPart {
    /// The orientation.
    pub orientation: Orientation,
    /// Rotated pieces.
    pub pieces: Vec<Polytope>,
    /// Exact bounding box of each piece.
    pub(crate) boxes: Vec<Aabb<Rational>>,
    /// Exact bounding box of the part.
    pub extent: Aabb<Rational>,
    /// Rotated centre of gravity.
    pub centroid: [Rational; 3],
}

impl OrientedPart {
    /// A key equal for orientations that give the same shape up to translation.
    pub(crate) fn shape_key(&self) -> Vec<Vec<HPoint>> {
        let lo = HPoint::from_rationals(&self.extent.min);
        let mut key: Vec<Vec<HPoint>> = self
            .pieces
            .iter()
            .map(|p| {
                let mut vs: Vec<HPoint> = p
                    .vertices()
                    .iter()
                    .map(|v| HPoint::from_big(v.to_ints(), p.den().clone()).sub(&lo))
                    .collect();
                vs.sort_by_key(|v| (v.num().clone(), v.den().clone()));
                vs
            })
            .collect();
        key.sort_by_key(|v| {
            v.iter()
                .map(|p| (p.num().clone(), p.den().clone()))
                .collect::<Vec<_>>()
        });
        key
    }
}

/// Exact centroid and volume of a union of convex pieces with disjoint interiors.
pub(crate) fn centroid_of(pieces: &[Polytope]) -> ([Rational; 3], Rational) {
    let mut vol = Rational::zero();
    let mut moment = [Rational::zero(), Rational::zero(), Rational::zero()];
    for p in pieces {
        // Tetrahedra from vertex 0 over fans of every facet: volume6 = det, centroid =
        // (o + a + b + c) / 4; stored coordinates are den times true ones.
        let vs = p.vertices();
        let o = &vs[0];
        let mut v6 = Int::ZERO;
        let mut m = [Int::ZERO, Int::ZERO, Int::ZERO];
        for f in p.facets() {
            let c = &f.cycle;
            for k in 1..c.len() - 1 {
                let (a, b, d) = (
                    &vs[c[0] as usize],
                    &vs[c[k] as usize],
                    &vs[c[k + 1] as usize],
                );
                let det = a.sub(o).dot(&b.sub(o).cross(&d.sub(o)));
                if det == Int::ZERO {
                    continue;
                }
                let s = o.add(a).add(b).add(d);
                for (i, mi) in m.iter_mut().enumerate() {
                    *mi += &det * s.get(i);
                }
                v6 += det;
            }
        }
        let den = p.den();
        let d3 = den * den * den;
        // True volume = v6 / (6 den³); true moment = Σ det/(6 den³) · s/(4 den).
        let pv = Rational::new(v6, &d3 * Int::from(6));
        let scale = &d3 * den * Int::from(24);
        for i in 0..3 {
            moment[i] = &moment[i] + &Rational::new(m[i].clone(), scale.clone());
        }
        vol = &vol + &pv;
    }
    let inv = vol.recip();
    (moment.map(|m| &m * &inv), vol)
}

/// The orientations of a part with duplicates (the same shape up to translation, e.g.
/// a cube turned by 90°) removed, keeping the first of each.
pub(crate) fn distinct_orientations(
    part: &PartModel,
    orientations: &[Orientation],
) -> Vec<Orientation> {
    let mut seen: HashMap<Vec<Vec<HPoint>>, ()> = HashMap::default();
    orientations
        .iter()
        .filter(|o| seen.insert(part.orient(o).shape_key(), ()).is_none())
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{q, qfrac};

    fn boxp(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    #[test]
    fn centroid_of_an_l() {
        // Two boxes: [0,2]x[0,1]x[0,1] (volume 2, centre (1, 1/2, 1/2)) and
        // [0,1]x[1,2]x[0,1] (volume 1, centre (1/2, 3/2, 1/2)).
        let part = PartModel::from_pieces(
            "L",
            vec![boxp([0, 0, 0], [2, 1, 1]), boxp([0, 1, 0], [1, 2, 1])],
        )
        .unwrap();
        assert_eq!(*part.volume(), q(3));
        assert_eq!(part.centroid(), &[qfrac(5, 6), qfrac(5, 6), qfrac(1, 2)]);
        let o = Orientation {
            theta: crate::orientation::ZRotation::from_half_tangent(1, 2),
            ..Orientation::IDENTITY
        };
        let op = part.orient(&o);
        // (3/5 x − 4/5 y, 4/5 x + 3/5 y) of (5/6, 5/6) = (−1/6, 7/6).
        assert_eq!(op.centroid, [qfrac(-1, 6), qfrac(7, 6), qfrac(1, 2)]);
    }

    #[test]
    fn symmetric_orientations_collapse() {
        let part = PartModel::from_pieces("cube", vec![boxp([0, 0, 0], [1, 1, 1])]).unwrap();
        let all = crate::orientation::orientations(90.0, &[Base::IDENTITY], 0.05);
        assert_eq!(all.len(), 4);
        assert_eq!(distinct_orientations(&part, &all).len(), 1);
    }
}
