//! The fixed parts a new part is placed among: convex shapes placed by rational
//! translations, with a bounding-volume hierarchy over the placed pieces.

use crate::bvh::{Bvh, FBox};
use crate::exact::{Point, QBox, Q};
use apart_pieces::Polytope;

/// A fixed piece: an (unplaced) shape moved by a translation, belonging to a part.
#[derive(Clone, Debug)]
pub struct ScenePiece {
    /// Index of its shape.
    pub(crate) shape: usize,
    /// Index of its part.
    pub part: usize,
    /// Its translation.
    pub(crate) translation: Point,
    /// Its exact bounding box.
    pub(crate) bbox: QBox,
}

/// Fixed parts made of shared convex shapes (identical stacked parts share them, so
/// their obstacles are computed once).
#[derive(Clone, Debug, Default)]
pub struct Scene {
    shapes: Vec<Polytope>,
    shape_boxes: Vec<QBox>,
    pieces: Vec<ScenePiece>,
    parts: usize,
    bvh: Bvh,
}

impl Scene {
    /// An empty scene.
    pub fn new() -> Scene {
        Scene::default()
    }

    /// Registers a shape; returns its index.
    pub(crate) fn add_shape(&mut self, p: Polytope) -> usize {
        self.shape_boxes
            .push(QBox::of_points(p.vertices(), p.den()));
        self.shapes.push(p);
        self.shapes.len() - 1
    }

    /// Adds a part made of the given shapes, all moved by `t`; returns its index.
    pub(crate) fn add_part(&mut self, shapes: &[usize], t: &[Q; 3]) -> usize {
        let part = self.parts;
        self.parts += 1;
        let tp = Point::from_q(t);
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
        let zero = [crate::exact::q(0), crate::exact::q(0), crate::exact::q(0)];
        self.add_part(&ids, &zero)
    }

    fn rebuild(&mut self) {
        let boxes: Vec<FBox> = self.pieces.iter().map(|p| p.bbox.to_f64()).collect();
        self.bvh = Bvh::build(boxes);
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
    pub(crate) fn near(&self, b: &FBox, out: &mut Vec<usize>) {
        self.bvh.query(b, out);
    }

    /// Piece `k` as a polytope in place.
    pub fn placed(&self, k: usize) -> Polytope {
        let p = &self.pieces[k];
        crate::interference::translated(&self.shapes[p.shape], &p.translation)
    }

    /// The exact bounding box of every piece (`None` for an empty scene).
    pub(crate) fn bbox(&self) -> Option<QBox> {
        let mut it = self.pieces.iter();
        let first = it.next()?.bbox.clone();
        Some(it.fold(first, |a, p| a.union(&p.bbox)))
    }
}
