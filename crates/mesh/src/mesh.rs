//! The snapped triangle mesh of one object, built from a [`RawObject`].

use crate::problem::{Capped, Problem, ProblemKind};
use crate::triangulate::{triangulate, Outcome};
use crate::weld::{snap_all, weld};
use apart_formats::RawObject;
use apart_kernel::predicates::det3_i128;
use apart_kernel::Aabb;
use apart_kernel::{Grid, Int, Vec3};
use rayon::prelude::*;

/// A triangle mesh on the integer grid: welded vertices (distinct grid points) and
/// triangles with non-zero area, each remembering the input face it came from.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Mesh {
    /// Distinct grid points.
    pub vertices: Vec<[i64; 3]>,
    /// Triangles, counter-clockwise seen from outside once validated.
    pub triangles: Vec<[u32; 3]>,
    /// The input face index of each triangle.
    pub source_faces: Vec<u32>,
    /// The first input vertex index that snapped to each vertex.
    pub source_vertices: Vec<u32>,
}

/// Triangles, their source faces, and the faces that were not simply split.
type Chunk = (Vec<[u32; 3]>, Vec<u32>, Vec<(u32, Outcome)>);

/// How many instances of one kind of problem are listed before they are counted.
pub(crate) const LIST: usize = 5;

/// A grid point in input units, for messages: `(1, 0, 2.5)`.
pub fn fmt_point(grid: &Grid, p: &[i64; 3]) -> String {
    let [x, y, z] = p.map(|c| apart_formats::off::number(grid.to_units(c)));
    format!("({x}, {y}, {z})")
}

impl Mesh {
    /// Snaps, welds and triangulates an object. Problems: non-finite or out-of-grid
    /// coordinates and bad indices (errors, no mesh), zero-area faces (dropped, warning),
    /// non-planar or non-simple polygons (split without new vertices, warning).
    pub fn from_raw(raw: &RawObject, grid: &Grid) -> (Option<Mesh>, Vec<Problem>) {
        let mut problems = Vec::new();
        let n = raw.vertices.len();
        if n > u32::MAX as usize {
            problems.push(Problem::error("more than 2^32 vertices").with_kind(ProblemKind::Vertex));
            return (None, problems);
        }
        // Snap; coordinates must be finite and inside the grid.
        let (snapped, bad) = snap_all(&raw.vertices, grid);
        let mut capped = Capped::new(LIST);
        for &i in &bad {
            let v = raw.vertices[i];
            capped.push(|| {
                let what = if v.iter().all(|c| c.is_finite()) {
                    "lies outside the grid chosen for the assembly"
                } else {
                    "has a coordinate that is not a finite number"
                };
                Problem::error(format!("({}, {}, {}) {what}", v[0], v[1], v[2]))
                    .at(format!("vertex {i}"))
                    .with_kind(ProblemKind::Vertex)
            });
        }
        capped.finish("vertices with bad coordinates", &mut problems);
        if let Some(&i) = raw.faces.all_indices().iter().find(|&&i| i as usize >= n) {
            let only = if n == 1 {
                "is only 1 vertex".to_string()
            } else {
                format!("are only {n} vertices")
            };
            problems.push(
                Problem::error(format!("a face refers to vertex {i}, but there {only}"))
                    .with_kind(ProblemKind::Vertex),
            );
        }
        if !problems.is_empty() {
            return (None, problems);
        }
        let welded = weld(&snapped);
        // Triangulate in parallel chunks, keeping the input order.
        const CHUNK: usize = 4096;
        let nf = raw.faces.len();
        let chunks: Vec<Chunk> = (0..nf.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let mut tris = Vec::with_capacity(CHUNK);
                let mut src = Vec::with_capacity(CHUNK);
                let mut notes = Vec::new();
                let mut poly = Vec::new();
                for f in c * CHUNK..((c + 1) * CHUNK).min(nf) {
                    poly.clear();
                    poly.extend(raw.faces.get(f).iter().map(|&i| welded.remap[i as usize]));
                    let before = tris.len();
                    let outcome = triangulate(&poly, &welded.points, &mut tris);
                    src.resize(tris.len(), f as u32);
                    debug_assert!(tris.len() >= before);
                    if outcome != Outcome::Ok {
                        notes.push((f as u32, outcome));
                    }
                }
                (tris, src, notes)
            })
            .collect();
        let total: usize = chunks.iter().map(|c| c.0.len()).sum();
        let mut triangles = Vec::with_capacity(total);
        let mut source_faces = Vec::with_capacity(total);
        let mut zero = Capped::new(LIST);
        let mut nonplanar = Capped::new(LIST);
        let mut nonsimple = Capped::new(LIST);
        for (t, s, notes) in chunks {
            triangles.extend(t);
            source_faces.extend(s);
            for (f, o) in notes {
                let at = format!("face {f}");
                match o {
                    Outcome::ZeroArea => {
                        zero.push(|| Problem::warning("zero area after snapping; dropped").at(at).with_kind(ProblemKind::Face))
                    }
                    Outcome::NonPlanar => nonplanar.push(|| {
                        Problem::warning("not planar after snapping; split into triangles")
                            .at(at)
                            .with_kind(ProblemKind::Face)
                    }),
                    Outcome::NotSimple => nonsimple.push(|| {
                        Problem::warning("not a simple polygon; split into triangles (a fan, or a strip above 32 vertices), which may overlap")
                            .at(at)
                            .with_kind(ProblemKind::Face)
                    }),
                    Outcome::Ok => {}
                }
            }
        }
        zero.finish("faces with zero area", &mut problems);
        nonplanar.finish("non-planar faces", &mut problems);
        nonsimple.finish("non-simple faces", &mut problems);
        // Keep only the vertices the triangles use.
        let mut used = vec![u32::MAX; welded.points.len()];
        for t in &triangles {
            for &v in t {
                used[v as usize] = 0;
            }
        }
        let mut vertices = Vec::new();
        let mut source_vertices = Vec::new();
        for (i, u) in used.iter_mut().enumerate() {
            if *u == 0 {
                *u = vertices.len() as u32;
                vertices.push(welded.points[i]);
                source_vertices.push(welded.first[i]);
            }
        }
        triangles
            .par_iter_mut()
            .with_min_len(8192)
            .for_each(|t| *t = t.map(|v| used[v as usize]));
        (
            Some(Mesh {
                vertices,
                triangles,
                source_faces,
                source_vertices,
            }),
            problems,
        )
    }

    /// The vertices as kernel vectors.
    pub fn points(&self) -> Vec<Vec3> {
        self.vertices.iter().map(|&v| Vec3::from_i64(v)).collect()
    }

    /// The corners of triangle `t`.
    pub fn corners(&self, t: usize) -> [&[i64; 3]; 3] {
        self.triangles[t].map(|v| &self.vertices[v as usize])
    }

    /// Exact six times the signed volume, in grid units (positive for an outward,
    /// closed surface). Computed relative to the first vertex, in `i128` while it fits,
    /// with arbitrary precision otherwise.
    pub fn volume6(&self) -> Int {
        let Some(o) = self.vertices.first() else {
            return Int::ZERO;
        };
        let rel = |p: &[i64; 3]| [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
        let fits = self
            .vertices
            .iter()
            .all(|p| rel(p).iter().all(|c| c.unsigned_abs() < 1 << 40));
        if fits {
            let sum = self
                .triangles
                .par_chunks(4096)
                .map(|ch| {
                    ch.iter().try_fold(0i128, |acc, t| {
                        let [a, b, c] = t.map(|v| rel(&self.vertices[v as usize]));
                        acc.checked_add(det3_i128(&a, &b, &c))
                    })
                })
                .try_reduce(|| 0i128, |x, y| x.checked_add(y));
            if let Some(v) = sum {
                return Int::from(v);
            }
        }
        let mut total = Int::ZERO;
        for t in &self.triangles {
            let [a, b, c] = t.map(|v| Vec3::from_i64(rel(&self.vertices[v as usize])));
            total += a.dot(&b.cross(&c));
        }
        total
    }

    /// The bounding box of the vertices (`None` when there are none).
    pub fn bbox(&self) -> Option<Aabb> {
        Aabb::of_points(&self.vertices)
    }

    /// Reverses every triangle (turns the surface inside out).
    pub fn flip(&mut self) {
        for t in &mut self.triangles {
            t.swap(1, 2);
        }
    }

    /// The mesh in input units (grid points times h), as an object that writers take.
    pub fn to_raw(&self, grid: &Grid, name: Option<String>) -> RawObject {
        RawObject {
            name,
            vertices: self
                .vertices
                .iter()
                .map(|p| p.map(|c| grid.to_units(c)))
                .collect(),
            faces: apart_formats::Polygons::from_triangles(&self.triangles),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_raw(s: f64) -> RawObject {
        crate::test_shapes::cuboid_raw([0.0; 3], [s; 3])
    }

    #[test]
    fn cube_volume_is_exact() {
        let g = Grid::unit(30);
        let (m, p) = Mesh::from_raw(&cube_raw(2.0), &g);
        assert!(p.is_empty(), "{p:?}");
        let m = m.unwrap();
        assert_eq!(m.triangles.len(), 12);
        assert_eq!(m.volume6(), Int::from(48)); // 6 * 2^3
        assert_eq!(m.source_faces[11], 5);
        let mut f = m.clone();
        f.flip();
        assert_eq!(f.volume6(), Int::from(-48));
        // Far from the origin the relative computation still fits and agrees.
        let mut far = cube_raw(2.0);
        far.map_vertices(|v| [v[0] + 1e9, v[1] - 1e9, v[2]]);
        let (m2, _) = Mesh::from_raw(&far, &g);
        assert_eq!(m2.unwrap().volume6(), Int::from(48));
    }

    #[test]
    fn welding_and_zero_area_faces() {
        let mut raw = cube_raw(1.0);
        // Duplicate every vertex (a soup), and add a face that snaps to a sliver.
        let extra = raw.vertices.clone();
        raw.vertices.extend(extra);
        raw.faces.push(&[8, 9, 8]);
        let (m, p) = Mesh::from_raw(&raw, &Grid::unit(30));
        let m = m.unwrap();
        assert_eq!(m.vertices.len(), 8);
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].element.as_deref(), Some("face 6"));
        assert!(p[0].message.contains("zero area"));
    }

    #[test]
    fn bad_coordinates_name_the_vertex() {
        let mut raw = cube_raw(1.0);
        raw.vertices[3][1] = f64::NAN;
        let (m, p) = Mesh::from_raw(&raw, &Grid::unit(30));
        assert!(m.is_none());
        assert_eq!(p[0].element.as_deref(), Some("vertex 3"));
        assert!(p[0].message.contains("not a finite number"));
        let raw = cube_raw(1e12); // beyond 2^30 on the unit grid
        let (m, p) = Mesh::from_raw(&raw, &Grid::unit(30));
        assert!(m.is_none() && p[0].message.contains("outside the grid"));
    }

    #[test]
    fn volume_with_huge_coordinates_uses_big_integers() {
        let g = Grid::unit(53);
        let s = (1u64 << 50) as f64;
        let (m, _) = Mesh::from_raw(&cube_raw(s), &g);
        let v = m.unwrap().volume6();
        assert_eq!(v, Int::from(6) * (Int::from(1) << 150usize));
    }
}
