//! The fixed parts a new part is placed among: convex shapes placed by rational
//! translations, with a bounding-volume hierarchy over the placed pieces.

use apart_kernel::{Aabb, Bvh, HPoint, Int, Rational, Vec3};
use apart_pieces::Polytope;

/// A fixed piece: an (unplaced) shape moved by a translation, belonging to a part.
#[derive(Clone, Debug)]
pub struct ScenePiece {
    /// Index of its shape.
    pub(crate) shape: usize,
    /// Index of its part.
    pub part: usize,
    /// Its translation.
    pub(crate) translation: HPoint,
    /// Its exact bounding box.
    pub(crate) bbox: Aabb<Rational>,
}

/// Fixed parts made of shared convex shapes (identical stacked parts share them, so
/// their obstacles are computed once).
#[derive(Clone, Debug, Default)]
pub struct Scene {
    shapes: Vec<Polytope>,
    shape_boxes: Vec<Aabb<Rational>>,
    pieces: Vec<ScenePiece>,
    parts: usize,
    bvh: Bvh<f64>,
}

impl Scene {
    /// An empty scene.
    pub fn new() -> Scene {
        Scene::default()
    }

    /// Registers a shape; returns its index.
    pub(crate) fn add_shape(&mut self, p: Polytope) -> usize {
        self.shape_boxes
            .push(Aabb::of_scaled(p.vertices(), p.den()));
        self.shapes.push(p);
        self.shapes.len() - 1
    }

    /// Adds a part made of the given shapes, all moved by `t`; returns its index.
    pub(crate) fn add_part(&mut self, shapes: &[usize], t: &[Rational; 3]) -> usize {
        let part = self.parts;
        self.parts += 1;
        let tp = HPoint::from_rationals(t);
        for &s in shapes {
            self.pieces.push(ScenePiece {
                shape: s,
                part,
                translation: tp.clone(),
                bbox: self.shape_boxes[s].translated(t),
            });
        }
        self.rebuild();
        part
    }

    /// Adds a part whose pieces are given in place (each becomes its own shape).
    pub fn add_fixed_part(&mut self, pieces: &[Polytope]) -> usize {
        let ids: Vec<usize> = pieces.iter().map(|p| self.add_shape(p.clone())).collect();
        let zero = [Rational::zero(), Rational::zero(), Rational::zero()];
        self.add_part(&ids, &zero)
    }

    /// The broad phase over the placed pieces. Median splits, so that detection meets
    /// the pieces in the order placement's cell decomposition has always followed.
    fn rebuild(&mut self) {
        let boxes: Vec<Aabb<f64>> = self.pieces.iter().map(|p| p.bbox.enclosing_f64()).collect();
        self.bvh = Bvh::by_median_splits(boxes);
    }

    /// The shapes.
    pub(crate) fn shapes(&self) -> &[Polytope] {
        &self.shapes
    }

    /// The placed pieces.
    pub fn pieces(&self) -> &[ScenePiece] {
        &self.pieces
    }

    /// Number of parts.
    pub fn part_count(&self) -> usize {
        self.parts
    }

    /// Pieces whose boxes may overlap `b` (closed), by index.
    pub(crate) fn near(&self, b: &Aabb<f64>, out: &mut Vec<usize>) {
        self.bvh.query(b, |k| out.push(k as usize));
    }

    /// Piece `k` as a polytope in place.
    pub fn placed(&self, k: usize) -> Polytope {
        let p = &self.pieces[k];
        translated(&self.shapes[p.shape], &p.translation)
    }

    /// The exact bounding box of every piece (`None` for an empty scene).
    pub(crate) fn bbox(&self) -> Option<Aabb<Rational>> {
        let mut it = self.pieces.iter();
        let first = it.next()?.bbox.clone();
        Some(it.fold(first, |a, p| a.union(&p.bbox)))
    }
}

/// The polytope moved by a rational translation `t = X / W` (its denominator multiplied
/// by `W`).
pub(crate) fn translated(p: &Polytope, t: &HPoint) -> Polytope {
    let den = p.den().clone();
    let shift = Vec3::from_ints(t.num().clone().map(|c| c * &den));
    p.rescaled(t.den())
        .with_den(Int::ONE)
        .translated(&shift)
        .with_den(&den * t.den())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{q, qfrac, unit};
    use apart_pieces::interference::{interiors_disjoint, interiors_meet_translated};

    /// The translated polytope agrees with apart-pieces' separating-axis test for a
    /// translated piece (which placement's detection calls).
    #[test]
    fn translated_overlap_matches_materialized() {
        let a = unit([0, 0, 0]);
        let b = unit([0, 0, 0]);
        for (t, expect) in [
            ([q(1), q(0), q(0)], false),
            ([qfrac(1, 2), qfrac(1, 3), q(0)], true),
            ([qfrac(1, 2), q(1), qfrac(1, 2)], false),
            ([qfrac(-99, 100), qfrac(99, 100), qfrac(1, 7)], true),
        ] {
            let p = HPoint::from_rationals(&t);
            assert_eq!(interiors_meet_translated(&a, &p, &b), expect, "{t:?}");
            let moved = translated(&a, &p);
            assert_eq!(interiors_disjoint(&moved, &b), !expect);
        }
    }
}
