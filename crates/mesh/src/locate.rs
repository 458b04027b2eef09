//! Exact point location in a closed solid: inside, on the boundary, or outside.
//!
//! The winding number of the surface around a point is counted along a ray in the +x
//! direction from the point, symbolically perturbed to `(x, y + ε, z + ε²)` (simulation
//! of simplicity). The perturbed ray never passes through an edge or a vertex, so every
//! crossing is a clean crossing of one triangle's interior, counted +1 when the triangle
//! faces +x and -1 otherwise. Points on the surface are detected first, exactly. Points
//! may be grid points or exact rational points ([`HPoint`]), e.g. witnesses of overlaps.

use crate::mesh::Mesh;
use apart_kernel::orient::{normal, on_triangle, orient2d_point, orient3d_point, P3};
use apart_kernel::{Aabb, Bvh, HPoint, Sign};

/// Point location in one mesh, with a hierarchy over its triangles.
pub struct Locator<'m> {
    mesh: &'m Mesh,
    bvh: Bvh,
}

impl<'m> Locator<'m> {
    /// Prepares point location in `mesh` (a closed, consistently oriented surface).
    pub fn new(mesh: &'m Mesh) -> Locator<'m> {
        let boxes = (0..mesh.triangles.len())
            .map(|t| Aabb::of(mesh.corners(t)))
            .collect();
        Locator {
            mesh,
            bvh: Bvh::new(boxes),
        }
    }

    /// Point location in `mesh` with a hierarchy already built over its triangle boxes
    /// (in triangle order).
    pub fn with_bvh(mesh: &'m Mesh, bvh: Bvh) -> Locator<'m> {
        Locator { mesh, bvh }
    }

    /// The mesh.
    pub fn mesh(&self) -> &'m Mesh {
        self.mesh
    }

    /// The hierarchy over the triangles (triangle indices).
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The winding number of the triangles `t` with `keep(t)` around `p`, or `None`
    /// when `p` lies on one of them. For a valid solid it is 1 inside and 0 outside.
    pub fn winding_filtered(&self, p: &HPoint, keep: impl Fn(u32) -> bool) -> Option<i64> {
        let b = p.bbox();
        let ray = Aabb {
            min: b.min,
            max: [i64::MAX, b.max[1], b.max[2]],
        };
        let mut w = 0i64;
        let mut on = false;
        self.bvh.query(&ray, |t| {
            if on || !keep(t) {
                return;
            }
            let [a, b, c] = self.mesh.corners(t as usize);
            let s = orient3d_point(a, b, c, p);
            if s == Sign::Zero && on_triangle(p, a, b, c) {
                on = true;
                return;
            }
            let n = normal(a, b, c);
            let nx = Sign::of_i128(n[0]);
            if nx == Sign::Zero {
                return;
            }
            let sos = |u: &P3, v: &P3| {
                let d = orient2d_point(u, v, p, 0);
                if d != Sign::Zero {
                    d
                } else if v[2] != u[2] {
                    Sign::of_i64(u[2] - v[2])
                } else {
                    Sign::of_i64(v[1] - u[1])
                }
            };
            let e1 = sos(a, b);
            if e1 != sos(b, c) || e1 != sos(c, a) {
                return;
            }
            // Crossing ahead of the point when n·(p - a) and n_x have opposite signs.
            let sp = if s != Sign::Zero {
                s
            } else if n[1] != 0 {
                Sign::of_i128(n[1])
            } else {
                Sign::of_i128(n[2])
            };
            if sp == -nx {
                w += nx.as_i32() as i64;
            }
        });
        (!on).then_some(w)
    }

    /// The winding number around `p`, `None` on the surface.
    pub fn winding(&self, p: &HPoint) -> Option<i64> {
        self.winding_filtered(p, |_| true)
    }

    /// True when `p` lies strictly inside the solid.
    pub fn strictly_inside(&self, p: &HPoint) -> bool {
        matches!(self.winding(p), Some(w) if w > 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::{Grid, Int};

    pub(crate) fn cube(lo: i64, hi: i64) -> Mesh {
        let raw = crate::test_shapes::cuboid_raw([lo as f64; 3], [hi as f64; 3]);
        Mesh::from_raw(&raw, &Grid::unit(30)).0.unwrap()
    }

    #[test]
    fn cube_location() {
        let m = cube(0, 4);
        let l = Locator::new(&m);
        assert_eq!(l.winding(&HPoint::int([2, 2, 2])), Some(1));
        assert_eq!(l.winding(&HPoint::int([5, 2, 2])), Some(0));
        assert_eq!(l.winding(&HPoint::int([-1, 2, 2])), Some(0));
        // On faces, edges, vertices.
        assert_eq!(l.winding(&HPoint::int([4, 2, 2])), None);
        assert_eq!(l.winding(&HPoint::int([4, 4, 2])), None);
        assert_eq!(l.winding(&HPoint::int([0, 0, 0])), None);
        // Rays through edges and vertices of the far side (degenerate for a plain ray).
        assert_eq!(l.winding(&HPoint::int([-3, 0, 0])), Some(0));
        assert_eq!(l.winding(&HPoint::int([-3, 4, 4])), Some(0));
        assert_eq!(l.winding(&HPoint::int([1, 2, 0])), None);
        assert_eq!(l.winding(&HPoint::int([1, 0, 2])), None);
        assert_eq!(l.winding(&HPoint::int([-3, 2, 2])), Some(0));
        // Inside, on the diagonal planes of the face triangulation.
        assert_eq!(l.winding(&HPoint::int([1, 1, 1])), Some(1));
        assert_eq!(l.winding(&HPoint::int([1, 3, 3])), Some(1));
        // Rational points.
        let q = |x: i64, y: i64, z: i64, d: i64| {
            HPoint::from_big([Int::from(x), Int::from(y), Int::from(z)], Int::from(d))
        };
        assert_eq!(l.winding(&q(7, 1, 1, 2)), Some(1)); // (3.5, .5, .5)
        assert_eq!(l.winding(&q(9, 1, 1, 2)), Some(0)); // (4.5, ...)
        assert_eq!(l.winding(&q(8, 1, 1, 2)), None); // on x = 4
        assert_eq!(l.winding(&q(-1, -1, -1, -3)), Some(1)); // (1/3, 1/3, 1/3)
        assert!(l.strictly_inside(&HPoint::int([3, 3, 3])));
    }

    #[test]
    fn brute_force_agreement_on_a_lattice() {
        let m = cube(-2, 2);
        let l = Locator::new(&m);
        for x in -3..=3 {
            for y in -3..=3 {
                for z in -3..=3 {
                    let inside = [x, y, z].iter().all(|c: &i64| c.abs() < 2);
                    let on = !inside && [x, y, z].iter().all(|c: &i64| c.abs() <= 2);
                    let w = l.winding(&HPoint::int([x, y, z]));
                    if on {
                        assert_eq!(w, None, "{x} {y} {z}");
                    } else {
                        assert_eq!(w, Some(inside as i64), "{x} {y} {z}");
                    }
                }
            }
        }
    }
}
