//! Convex polytopes from validated convex meshes.
//!
//! `Polytope::from_triangles` checks every vertex against every face plane, which is
//! quadratic; for small meshes (the usual pieces) it is used as is, and its errors name
//! the offending face and vertex. For large meshes already proven convex by validation
//! (closed, one shell, no reflex edge, no self-intersection), the facets are extracted
//! in linear time: triangles grouped by plane, each group's boundary chained into a
//! cycle, straight corners dropped, and handed to `Polytope::from_facets`.

use apart_kernel::int::gcd_u128;
use apart_kernel::orient::{collinear, normal};
use apart_kernel::Vec3;
use apart_mesh::Mesh;
use apart_pieces::{Polytope, PolytopeError};
use std::collections::HashMap;

/// Meshes with at most this many triangles go through `Polytope::from_triangles`.
pub(crate) const QUADRATIC_LIMIT: usize = 2000;

/// The convex polytope of a mesh that validation found convex (for small meshes, any
/// closed outward mesh: non-convexity is then reported by the polytope builder).
pub(crate) fn convex_polytope(mesh: &Mesh) -> Result<Polytope, PolytopeError> {
    if mesh.triangles.len() <= QUADRATIC_LIMIT {
        return Polytope::from_triangles(&mesh.points(), &mesh.triangles);
    }
    let mut planes: HashMap<([i128; 3], i128), usize> = HashMap::new();
    let mut groups: Vec<(Vec3, Vec<usize>)> = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| &mesh.vertices[v as usize]);
        let n = normal(a, b, c);
        let g = gcd_u128(
            gcd_u128(n[0].unsigned_abs(), n[1].unsigned_abs()),
            n[2].unsigned_abs(),
        );
        if g == 0 {
            return Err(PolytopeError::DegenerateTriangle { triangle: t });
        }
        let n = n.map(|x| x / g as i128);
        let off = n[0] * a[0] as i128 + n[1] * a[1] as i128 + n[2] * a[2] as i128;
        let id = *planes.entry((n, off)).or_insert_with(|| {
            groups.push((Vec3::from_i128(n), Vec::new()));
            groups.len() - 1
        });
        groups[id].1.push(t);
    }
    let mut facets = Vec::with_capacity(groups.len());
    for (n, ts) in groups {
        let mut edges: HashMap<(u32, u32), ()> = HashMap::new();
        for &t in &ts {
            let tri = mesh.triangles[t];
            for k in 0..3 {
                edges.insert((tri[k], tri[(k + 1) % 3]), ());
            }
        }
        let mut next: HashMap<u32, u32> = HashMap::new();
        for &(a, b) in edges.keys() {
            if !edges.contains_key(&(b, a)) && next.insert(a, b).is_some() {
                return Err(PolytopeError::NotClosed);
            }
        }
        let Some(&start) = next.keys().min() else {
            return Err(PolytopeError::NotClosed);
        };
        let mut cycle = vec![start];
        let mut v = next[&start];
        while v != start {
            if cycle.len() > next.len() {
                return Err(PolytopeError::NotClosed);
            }
            cycle.push(v);
            v = *next.get(&v).ok_or(PolytopeError::NotClosed)?;
        }
        if cycle.len() != next.len() {
            return Err(PolytopeError::NotClosed); // a facet with a hole or two loops
        }
        // Drop corners where the boundary runs straight on.
        let p = |i: u32| &mesh.vertices[i as usize];
        let m = cycle.len();
        let kept: Vec<u32> = (0..m)
            .filter(|&i| {
                !collinear(
                    p(cycle[(i + m - 1) % m]),
                    p(cycle[i]),
                    p(cycle[(i + 1) % m]),
                )
            })
            .map(|i| cycle[i])
            .collect();
        if kept.len() < 3 {
            return Err(PolytopeError::NotClosed);
        }
        facets.push((n, kept));
    }
    Polytope::from_facets(&mesh.points(), facets)
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_formats::{Polygons, RawObject};
    use apart_kernel::Grid;
    use apart_mesh::validate::check_solid;

    /// A cube of side `k` whose faces are k x k grids of unit quads.
    fn subdivided_cube(k: i64) -> RawObject {
        let mut vertices = Vec::new();
        let mut faces = Vec::new();
        // Each face: origin o, in-plane steps u, v (u × v outward).
        let sides: [([i64; 3], [i64; 3], [i64; 3]); 6] = [
            ([0, 0, 0], [0, 1, 0], [1, 0, 0]),
            ([0, 0, k], [1, 0, 0], [0, 1, 0]),
            ([0, 0, 0], [1, 0, 0], [0, 0, 1]),
            ([0, k, 0], [0, 0, 1], [1, 0, 0]),
            ([0, 0, 0], [0, 0, 1], [0, 1, 0]),
            ([k, 0, 0], [0, 1, 0], [0, 0, 1]),
        ];
        for (o, u, v) in sides {
            let base = vertices.len() as u32;
            for i in 0..=k {
                for j in 0..=k {
                    vertices.push([0, 1, 2].map(|c| (o[c] + i * u[c] + j * v[c]) as f64));
                }
            }
            let id = |i: i64, j: i64| base + (i * (k + 1) + j) as u32;
            for i in 0..k {
                for j in 0..k {
                    faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
        }
        RawObject {
            name: None,
            vertices,
            faces: Polygons::from(faces),
        }
    }

    #[test]
    fn large_convex_mesh_by_facets() {
        let raw = subdivided_cube(20); // 4800 triangles: the linear path
        let grid = Grid::unit(30);
        let (mesh, info, problems) = check_solid(&raw, &grid);
        assert!(problems.is_empty(), "{problems:?}");
        assert!(info.unwrap().convex);
        let mesh = mesh.unwrap();
        assert!(mesh.triangles.len() > QUADRATIC_LIMIT);
        let p = convex_polytope(&mesh).unwrap();
        // Independent: the hull of the eight corners.
        let corners: Vec<Vec3> = (0..8)
            .map(|i| Vec3::new((i & 1) * 20, (i >> 1 & 1) * 20, (i >> 2) * 20))
            .collect();
        let hull = Polytope::hull_of_points(&corners).unwrap();
        assert_eq!(p.facets().len(), 6);
        assert_eq!(p.vertices().len(), 8);
        assert_eq!(p.volume(), hull.volume());
        // The small path agrees on a coarser cube.
        let (m2, _, _) = check_solid(&subdivided_cube(3), &grid);
        let q = convex_polytope(&m2.unwrap()).unwrap();
        assert_eq!(q.facets().len(), 6);
        assert_eq!(q.volume(), apart_kernel::Rational::from_int(27));
    }
}
