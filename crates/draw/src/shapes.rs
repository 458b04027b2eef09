//! The surfaces of the parts as triangles in input units, for drawing and export.
//!
//! A part with a mesh is drawn from its mesh; a part given only by convex pieces is
//! drawn from the facets of its pieces (faces between pieces lie inside and stay hidden
//! behind the outer ones). Every triangle carries the index of its plane within its part,
//! found exactly from the integer coordinates, so that pictures outline the real faces
//! of a part and not the triangulation.

use apart_assembly::Assembly;
use apart_kernel::fvec::{add, cross, normalize, sub};
use apart_kernel::int::to_f64;
use apart_kernel::{Aabb, Rational, Vec3};
use std::collections::HashMap;

/// One part's surface.
#[derive(Clone, Debug, Default)]
pub struct PartShape {
    /// Triangles, counter-clockwise seen from outside, in input units.
    pub triangles: Vec<[[f64; 3]; 3]>,
    /// For each triangle, the index of its plane among the part's planes (coplanar
    /// triangles share one).
    pub plane: Vec<u32>,
}

impl PartShape {
    /// The unit outward normal of triangle `t` (zero for a degenerate one).
    pub fn normal(&self, t: usize) -> [f64; 3] {
        let [a, b, c] = self.triangles[t];
        normalize(cross(sub(b, a), sub(c, a)))
    }
}

/// The surface of every part, in part order.
pub fn part_shapes(assembly: &Assembly) -> Vec<PartShape> {
    let h = assembly.grid.step();
    assembly
        .parts
        .iter()
        .map(|part| match &part.mesh {
            Some(mesh) if !mesh.triangles.is_empty() => {
                let mut planes = Planes::default();
                let mut shape = PartShape::default();
                for t in &mesh.triangles {
                    let v = t.map(|i| mesh.vertices[i as usize]);
                    let [a, b, c] = v.map(Vec3::from);
                    let n = b.sub(&a).cross(&c.sub(&a));
                    if n.is_zero() {
                        continue;
                    }
                    let n = n.primitive();
                    let offset = Rational::from_int(n.dot(&a));
                    shape.plane.push(planes.index(n, offset));
                    shape
                        .triangles
                        .push(v.map(|p| p.map(|q| assembly.grid.to_units(q))));
                }
                shape
            }
            _ => pieces_shape(&part.pieces, h),
        })
        .collect()
}

/// The surface of a part given by convex pieces (integer or rational), in input units
/// for a grid of the given step: every facet of every piece (faces between pieces lie
/// inside and stay hidden behind the outer ones).
pub fn pieces_shape(pieces: &[apart_pieces::Polytope], step: f64) -> PartShape {
    let mut planes = Planes::default();
    let mut shape = PartShape::default();
    for piece in pieces {
        let den = piece.den();
        let scale = step / to_f64(den);
        let pts: Vec<[f64; 3]> = piece
            .vertices()
            .iter()
            .map(|v| v.to_ints().map(|c| to_f64(&c) * scale))
            .collect();
        for f in piece.facets() {
            let plane = planes.index(
                f.normal.clone(),
                Rational::new(f.offset.clone(), den.clone()),
            );
            let c = &f.cycle;
            for k in 1..c.len().saturating_sub(1) {
                shape.triangles.push([
                    pts[c[0] as usize],
                    pts[c[k] as usize],
                    pts[c[k + 1] as usize],
                ]);
                shape.plane.push(plane);
            }
        }
    }
    shape
}

/// The bounds of all shapes, each translated by `offsets[k]` when given.
pub fn bounds_of(shapes: &[PartShape], offsets: Option<&[[f64; 3]]>) -> Aabb<f64> {
    let mut b = Aabb::EMPTY;
    for (k, s) in shapes.iter().enumerate() {
        let o = offsets.map_or([0.0; 3], |o| o[k]);
        for t in &s.triangles {
            for p in t {
                b = b.with(&add(*p, o));
            }
        }
    }
    b
}

/// Exact plane identities of one part: primitive normal and offset.
#[derive(Default)]
struct Planes(HashMap<(Vec3, Rational), u32>);

impl Planes {
    fn index(&mut self, normal: Vec3, offset: Rational) -> u32 {
        let n = self.0.len() as u32;
        *self.0.entry((normal, offset)).or_insert(n)
    }
}
