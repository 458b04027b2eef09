//! Central projection of a convex polytope onto the sphere of directions.
//!
//! The projection of a convex polytope `M` from the origin is the spherical polygon of
//! directions `d` whose ray `{k d : k > 0}` meets `M`; the ray meets the *interior* of
//! `M` exactly when `d` lies in the polygon's interior. Where the origin lies decides
//! the shape:
//! - outside `M`: a pointed polygon bounded by the silhouette, the planes through the
//!   origin and an edge between a facet facing the origin and one facing away (or
//!   edge-on, when the origin lies in its plane);
//! - in the relative interior of a facet: the closed hemisphere behind that facet;
//! - in the relative interior of an edge: the lune of its two facets;
//! - at a vertex: the tangent cone of that vertex;
//! - in the interior: every direction (the parts overlap, which validation rejects).

use apart_kernel::int::sign_of;
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::{Sign, Vec3};
use apart_pieces::Polytope;
use apart_sphere::polygon::PolygonError;
use apart_sphere::{Arc, SphericalPolygon};

/// Where the origin lies relative to a convex polytope, with the projection.
#[derive(Clone, Debug)]
pub enum Projection {
    /// The origin is outside, on a facet, an edge or at a vertex: the closed polygon of
    /// directions whose rays meet `M` (its interior: rays meeting the interior of `M`).
    Polygon(SphericalPolygon),
    /// The origin is inside `M`: every ray meets its interior.
    Everything,
}

/// Projects `m` centrally from the origin onto the sphere.
pub fn project(m: &Polytope) -> Result<Projection, PolygonError> {
    // Sign of each facet's offset: offset < 0 means the origin is outside that facet.
    let signs: Vec<Sign> = m.facets().iter().map(|f| sign_of(&f.offset)).collect();
    if signs.contains(&Sign::Negative) {
        return silhouette(m, &signs).map(Projection::Polygon);
    }
    let active: Vec<usize> = (0..signs.len())
        .filter(|&i| signs[i] == Sign::Zero)
        .collect();
    match active.len() {
        0 => Ok(Projection::Everything),
        1 => Ok(Projection::Polygon(SphericalPolygon::hemisphere(
            &m.facets()[active[0]].normal.neg(),
        ))),
        2 => {
            let (q1, q2) = (
                m.facets()[active[0]].normal.neg(),
                m.facets()[active[1]].normal.neg(),
            );
            Ok(Projection::Polygon(SphericalPolygon::lune(&q1, &q2)))
        }
        _ => vertex_cone(m, &active).map(Projection::Polygon),
    }
}

/// The polygon when the origin is outside: one side per silhouette edge.
fn silhouette(m: &Polytope, signs: &[Sign]) -> Result<SphericalPolygon, PolygonError> {
    let mut arcs = Vec::new();
    let mut primitive: Vec<Option<Vec3>> = vec![None; m.vertices().len()];
    for e in m.edges() {
        let (f, g) = (e.facets[0] as usize, e.facets[1] as usize);
        let (front, _back) = match (signs[f], signs[g]) {
            (Sign::Negative, Sign::Negative) => continue,
            (Sign::Negative, _) => (f, g),
            (_, Sign::Negative) => (g, f),
            _ => continue,
        };
        let front = &m.facets()[front].cycle;
        arcs.push(silhouette_side(
            m.vertices(),
            e.ends,
            None,
            front,
            &mut primitive,
        )?);
    }
    polygon_of_sides(arcs, m.vertices().len())
}

/// The polygon bounded by silhouette sides ([`silhouette_side`]'s answers, each with
/// the numbers of its start and end vertex), chained through those numbers; through the
/// sides' points ([`SphericalPolygon::from_arcs`]) when an edge projected to a point
/// (its ends share a direction) or the numbers do not close one cycle.
pub(crate) fn polygon_of_sides(
    sides: Vec<Option<([u32; 2], Arc)>>,
    vertices: usize,
) -> Result<SphericalPolygon, PolygonError> {
    let by_numbers = || -> Option<Vec<usize>> {
        let mut from = vec![u32::MAX; vertices];
        for (k, side) in sides.iter().enumerate() {
            let start = &mut from[side.as_ref()?.0[0] as usize];
            if *start != u32::MAX {
                return None;
            }
            *start = k as u32;
        }
        let mut order = Vec::with_capacity(sides.len());
        let mut k = 0;
        for _ in 0..sides.len() {
            order.push(k);
            k = from[sides[k].as_ref()?.0[1] as usize] as usize;
            if k >= sides.len() {
                return None;
            }
        }
        (k == 0).then_some(order)
    };
    match by_numbers() {
        Some(order) => {
            let mut slots = sides;
            SphericalPolygon::from_cycle(
                order
                    .into_iter()
                    .map(|k| slots[k].take().expect("each side once").1)
                    .collect(),
            )
        }
        None => SphericalPolygon::from_arcs(sides.into_iter().flatten().map(|s| s.1).collect()),
    }
}

/// The side of a projection on the silhouette edge `ends` of a convex polytope with
/// vertices `vs`, whose facet facing the origin has the cycle `front`, with the numbers
/// of its start and end vertex; `None` when the edge's line passes through the origin
/// (it projects to a point). `primitive` caches each vertex made primitive (it ends two
/// silhouette edges). The points may be any positive multiples of the vertices; `dir`,
/// when given, is a direction of the edge (either sign), whose cross product with the
/// first end spans the same plane as the two ends' and is shorter.
pub(crate) fn silhouette_side(
    vs: &[Vec3],
    ends: [u32; 2],
    dir: Option<&Vec3>,
    front: &[u32],
    primitive: &mut [Option<Vec3>],
) -> Result<Option<([u32; 2], Arc)>, PolygonError> {
    let (v0, v1) = (&vs[ends[0] as usize], &vs[ends[1] as usize]);
    let n = v0.cross(dir.unwrap_or(v1));
    if n.is_zero() {
        return Ok(None);
    }
    // Inward normal: the side where the rest of the front facet lies.
    let w = front
        .iter()
        .map(|&i| &vs[i as usize])
        .find(|w| dot_sign(&n, w) != Sign::Zero)
        .ok_or_else(|| PolygonError("front facet lies in a plane through the origin".into()))?;
    let q = if dot_sign(&n, w) == Sign::Positive {
        n.primitive()
    } else {
        n.neg().primitive()
    };
    // `Arc::on_circle(&q, v0, v1)`, without making the primitive `q` primitive again
    // and with each vertex made primitive once.
    let (a, b) = match det3_sign(&q, v0, v1) {
        Sign::Positive => (ends[0], ends[1]),
        Sign::Negative => (ends[1], ends[0]),
        Sign::Zero => panic!("silhouette edge endpoints are independent"),
    };
    let mut unit = |i: u32| -> Vec3 {
        primitive[i as usize]
            .get_or_insert_with(|| vs[i as usize].primitive())
            .clone()
    };
    let (start, end) = (unit(a), unit(b));
    Ok(Some((
        [a, b],
        Arc {
            normal: q,
            start,
            end,
        },
    )))
}

/// The tangent cone at the vertex of `m` at the origin (three or more facets through it).
fn vertex_cone(m: &Polytope, active: &[usize]) -> Result<SphericalPolygon, PolygonError> {
    let origin = m
        .vertices()
        .iter()
        .position(|v| v.is_zero())
        .ok_or_else(|| PolygonError("origin on three facets but not a vertex".into()))?
        as u32;
    let mut arcs = Vec::new();
    for &f in active {
        let facet = &m.facets()[f];
        let c = &facet.cycle;
        let k = c
            .iter()
            .position(|&v| v == origin)
            .ok_or_else(|| PolygonError("active facet misses the origin".into()))?;
        let prev = &m.vertices()[c[(k + c.len() - 1) % c.len()] as usize];
        let next = &m.vertices()[c[(k + 1) % c.len()] as usize];
        let q = facet.normal.neg();
        arcs.push(
            Arc::on_circle(&q, prev, next)
                .ok_or_else(|| PolygonError("flat vertex in a facet".into()))?,
        );
    }
    SphericalPolygon::from_arcs(arcs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sum::minkowski_difference;
    use apart_kernel::Vec3;

    fn boxp(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    fn poly(p: Projection) -> SphericalPolygon {
        match p {
            Projection::Polygon(p) => p,
            Projection::Everything => panic!("origin inside"),
        }
    }

    #[test]
    fn stacked_cubes_give_a_hemisphere() {
        // Top cube moving along d hits the bottom cube iff d points down.
        let bottom = boxp([0, 0, 0], [1, 1, 1]);
        let top = boxp([0, 0, 1], [1, 1, 2]);
        let q = poly(project(&minkowski_difference(&bottom, &top).unwrap()).unwrap());
        assert_eq!(q.normals().len(), 1);
        assert!(q.contains_open(&Vec3::new(0, 0, -1)));
        assert!(!q.contains_open(&Vec3::new(1, 0, 0))); // sliding is free
        assert!(!q.contains_open(&Vec3::new(0, 1, 1)));
    }

    #[test]
    fn edge_and_vertex_contacts() {
        let a = boxp([0, 0, 0], [1, 1, 1]);
        // Touching along an edge: a lune.
        let b = boxp([1, 1, 0], [2, 2, 1]);
        let q = poly(project(&minkowski_difference(&b, &a).unwrap()).unwrap());
        assert_eq!(q.normals().len(), 2);
        assert!(q.contains_open(&Vec3::new(1, 1, 0)));
        assert!(!q.contains_open(&Vec3::new(1, 0, 0)));
        // Touching at a vertex: a cone (the positive octant).
        let c = boxp([1, 1, 1], [2, 2, 2]);
        let q = poly(project(&minkowski_difference(&c, &a).unwrap()).unwrap());
        assert_eq!(q.normals().len(), 3);
        assert!(q.contains_open(&Vec3::new(1, 1, 1)));
        assert!(q.contains_open(&Vec3::new(1, 2, 3)));
        assert!(!q.contains_open(&Vec3::new(1, 1, 0)));
    }

    #[test]
    fn separated_boxes_give_a_pointed_polygon() {
        let a = boxp([0, 0, 0], [1, 1, 1]);
        let b = boxp([3, 0, 0], [4, 1, 1]);
        let q = poly(project(&minkowski_difference(&b, &a).unwrap()).unwrap());
        // M = [2,4]x[-1,1]x[-1,1]: the silhouette seen from the origin has 4 sides.
        assert_eq!(q.boundary().len(), 4);
        assert!(q.contains_open(&Vec3::new(1, 0, 0)));
        assert!(!q.contains_open(&Vec3::new(2, 1, 0)));
        assert!(q.contains_open(&Vec3::new(3, 1, 0)));
        // Edge-on facets: the origin in the plane of two facets of M.
        let c = boxp([2, 1, 1], [3, 2, 2]);
        let q = poly(project(&minkowski_difference(&c, &a).unwrap()).unwrap());
        assert!(q.contains_open(&Vec3::new(3, 1, 1)));
        assert!(!q.contains_open(&Vec3::new(1, 0, 0)));
    }

    #[test]
    fn overlapping_boxes_block_everything() {
        let a = boxp([0, 0, 0], [2, 2, 2]);
        let b = boxp([1, 1, 1], [3, 3, 3]);
        assert!(matches!(
            project(&minkowski_difference(&b, &a).unwrap()).unwrap(),
            Projection::Everything
        ));
    }
}
