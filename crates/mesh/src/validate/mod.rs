//! Validation of a mesh as one closed solid.
//!
//! Every check runs and reports, none stops the others (except that volume and
//! orientation are only meaningful for a closed surface):
//!
//! | check | finding | severity |
//! |---|---|---|
//! | triangles | none left | error |
//! | edges | used by one face (open boundary) | error, up to 5 listed |
//! | edges | two faces running the same way (inconsistent orientation) | error |
//! | edges | odd or unbalanced use (non-manifold) | error |
//! | edges | 2k faces alternating around the edge | note: touches itself, valid |
//! | vertices | several fans of faces (bowtie) | note: touches itself, valid |
//! | volume | zero | error |
//! | volume | negative (inside out) | warning: every face flipped |
//! | shells | nested wrongly (winding number not 0/1) | error |
//! | faces | two faces meeting beyond what they share | error |
//!
//! Contacts of a solid with itself are valid only through shared (welded) vertices and
//! edges; a vertex of the solid lying inside one of its faces, or two faces touching
//! along a segment that is not a shared edge, is reported as an intersection.

mod convexity;
pub(crate) mod edges;
pub(crate) mod orientation;
mod self_intersection;
mod shells;
mod vertices;

use crate::intersect::Contact;
use crate::locate::Locator;
use crate::mesh::{fmt_point, Mesh, LIST};
use crate::problem::{Capped, Problem, ProblemKind};
use apart_kernel::orient::orient3d_many;
use apart_kernel::Aabb;
use apart_kernel::Bvh;
use apart_kernel::{Grid, HPoint, Int, Rational, Sign};
use rayon::prelude::*;

/// What validation learnt about a mesh.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshInfo {
    /// Number of (welded, used) vertices.
    pub vertices: usize,
    /// Number of triangles.
    pub triangles: usize,
    /// Number of input faces that kept a non-zero area.
    pub faces: usize,
    /// Number of undirected edges.
    pub edges: usize,
    /// Connected components of the surface (across manifold edges).
    pub shells: usize,
    /// Every edge is manifold or a valid contact: the surface is closed and oriented.
    pub closed: bool,
    /// Six times the volume in grid units (after any flip), when closed.
    pub volume6: Option<Int>,
    /// Edges whose dihedral angle inside the solid exceeds 180 degrees.
    pub reflex_edges: usize,
    /// Edges along which the solid touches itself (2k alternating faces).
    pub touching_edges: usize,
    /// Vertices at which the solid touches itself (several fans of faces).
    pub touching_vertices: usize,
    /// Number of pairs of faces meeting beyond what they share.
    pub self_intersections: usize,
    /// The faces were flipped because the volume was negative.
    pub flipped: bool,
    /// The solid is convex (decided exactly).
    pub convex: bool,
    /// Bounding box in grid units.
    pub bbox: Option<Aabb>,
}

/// `v · h³` for a volume `v` in grid units: the same volume in input units, exactly.
pub fn volume_in_units(v: &Rational, grid: &Grid) -> Rational {
    let e = 3 * grid.exp;
    let p = Int::from(1) << (e.unsigned_abs() as usize);
    let scale = if e >= 0 {
        Rational::from_int(p)
    } else {
        Rational::new(Int::ONE, p)
    };
    v * &scale
}

impl MeshInfo {
    /// The exact volume in grid units.
    pub fn volume(&self) -> Option<Rational> {
        self.volume6
            .as_ref()
            .map(|v| Rational::new(v.clone(), Int::from(6)))
    }

    /// The exact volume in input units (`volume6 · h³ / 6`).
    pub fn volume_units(&self, grid: &Grid) -> Option<Rational> {
        self.volume().map(|v| volume_in_units(&v, grid))
    }
}

fn edge_at(mesh: &Mesh, grid: &Grid, a: u32, b: u32) -> String {
    let sv = |v: u32| mesh.source_vertices[v as usize];
    let p = |v: u32| fmt_point(grid, &mesh.vertices[v as usize]);
    format!("edge ({}, {}) at {}-{}", sv(a), sv(b), p(a), p(b))
}

fn faces_at(mesh: &Mesh, t: u32, u: u32) -> String {
    let (f, g) = (mesh.source_faces[t as usize], mesh.source_faces[u as usize]);
    if f == g {
        format!("face {f}")
    } else {
        format!("faces {} and {}", f.min(g), f.max(g))
    }
}

/// Validates `mesh` as one closed solid. Flips every triangle when the volume is
/// negative. `grid` only serves to print coordinates in input units.
pub fn validate(mesh: &mut Mesh, grid: &Grid) -> (MeshInfo, Vec<Problem>) {
    let mut problems = Vec::new();
    let mut info = first_info(mesh);
    if mesh.triangles.is_empty() {
        problems.push(
            Problem::error("empty mesh: no face with a non-zero area")
                .with_kind(ProblemKind::EmptyMesh),
        );
        return (info, problems);
    }

    // Edges and vertices.
    let he = edges::HalfEdges::new(mesh);
    let use_ = edges::classify(mesh, &he);
    info.edges = use_.pairs.len()
        + use_.boundary.len()
        + use_.inconsistent.len()
        + use_.nonmanifold.len()
        + use_.touching.len();
    info.reflex_edges = use_.reflex;
    let convex_edges = use_.convex;
    info.touching_edges = use_.touching.len();
    info.closed = use_.closed();
    report_edges(mesh, grid, &use_, &mut problems);
    let touching_vertices = vertices::touching_vertices(mesh, &he);
    info.touching_vertices = touching_vertices.len();
    report_touching_vertices(mesh, grid, &touching_vertices, &mut problems);
    drop(he);
    let (shell_of, shells) = shells::shells(mesh.triangles.len(), &use_.pairs);
    info.shells = shells;
    drop(use_);

    // Volume and orientation.
    if info.closed {
        check_volume(mesh, &mut info, convex_edges, &mut problems);
    }

    // Self-intersection.
    let (bvh, count) = report_self_intersections(mesh, &info, shells, &mut problems);
    info.self_intersections = count;

    // Nesting of shells.
    if info.closed && info.volume6.is_some() && shells > 1 && count == 0 {
        check_nesting(mesh, bvh, &shell_of, shells, &mut problems);
    }

    let has_errors = problems.iter().any(Problem::is_error);
    info.convex = convexity::is_convex(&info, has_errors);
    (info, problems)
}

/// What is known of `mesh` before any check: its counts and box.
fn first_info(mesh: &Mesh) -> MeshInfo {
    let mut faces: Vec<u32> = mesh.source_faces.clone();
    faces.dedup();
    MeshInfo {
        vertices: mesh.vertices.len(),
        triangles: mesh.triangles.len(),
        faces: faces.len(),
        edges: 0,
        shells: 0,
        closed: false,
        volume6: None,
        reflex_edges: 0,
        touching_edges: 0,
        touching_vertices: 0,
        self_intersections: 0,
        flipped: false,
        convex: false,
        bbox: mesh.bbox(),
    }
}

/// Reports the edges that are open, inconsistently oriented or non-manifold (errors),
/// and those along which the solid touches itself (notes), each kind capped.
fn report_edges(mesh: &Mesh, grid: &Grid, use_: &edges::EdgeUse, problems: &mut Vec<Problem>) {
    let mut c = Capped::new(LIST);
    for &(a, b) in &use_.boundary {
        c.push(|| {
            Problem::error("open boundary: the edge belongs to one face only")
                .at(edge_at(mesh, grid, a, b))
                .with_kind(ProblemKind::OpenBoundary)
        });
    }
    c.finish("boundary edges", problems);
    let mut c = Capped::new(LIST);
    for &(a, b, t, u) in &use_.inconsistent {
        c.push(|| {
            Problem::error(format!(
                "inconsistent orientation: both run along {} in the same direction",
                edge_at(mesh, grid, a, b)
            ))
            .at(faces_at(mesh, t, u))
            .with_kind(ProblemKind::InconsistentOrientation)
        });
    }
    c.finish("inconsistently oriented face pairs", problems);
    let mut c = Capped::new(LIST);
    for &(a, b, n) in &use_.nonmanifold {
        c.push(|| {
            Problem::error(format!(
                "non-manifold edge: shared by {n} faces that do not alternate in direction"
            ))
            .at(edge_at(mesh, grid, a, b))
            .with_kind(ProblemKind::NonManifold)
        });
    }
    c.finish("non-manifold edges", problems);
    let mut c = Capped::new(LIST);
    for &(a, b, n) in &use_.touching {
        c.push(|| {
            Problem::note(format!(
                "the solid touches itself along this edge ({n} faces, alternating): valid"
            ))
            .at(edge_at(mesh, grid, a, b))
            .with_kind(ProblemKind::SelfTouching)
        });
    }
    c.finish("edges where the solid touches itself", problems);
}

/// Notes the vertices at which the solid touches itself (capped).
fn report_touching_vertices(
    mesh: &Mesh,
    grid: &Grid,
    touching_vertices: &[u32],
    problems: &mut Vec<Problem>,
) {
    let mut c = Capped::new(LIST);
    for &v in touching_vertices {
        c.push(|| {
            Problem::note("the solid touches itself at this vertex: valid")
                .at(format!(
                    "vertex {} at {}",
                    mesh.source_vertices[v as usize],
                    fmt_point(grid, &mesh.vertices[v as usize])
                ))
                .with_kind(ProblemKind::SelfTouching)
        });
    }
    c.finish("vertices where the solid touches itself", problems);
}

/// The volume of the closed `mesh`: an error when zero; when negative, every triangle
/// is flipped (the reflex edges become the `convex_edges` of before) with a warning.
fn check_volume(
    mesh: &mut Mesh,
    info: &mut MeshInfo,
    convex_edges: usize,
    problems: &mut Vec<Problem>,
) {
    let mut v6 = mesh.volume6();
    if v6 == Int::ZERO {
        problems
            .push(Problem::error("the solid has zero volume").with_kind(ProblemKind::ZeroVolume));
    } else {
        if v6 < Int::ZERO {
            mesh.flip();
            v6 = -v6;
            info.flipped = true;
            info.reflex_edges = convex_edges;
            problems.push(
                Problem::warning("inside out (negative volume): every face was flipped")
                    .with_kind(ProblemKind::InsideOut),
            );
        }
        info.volume6 = Some(v6);
    }
}

/// Reports the pairs of faces meeting beyond what they share (the first [`LIST`], then
/// how many more): the hierarchy over the triangles' boxes, and the number of pairs.
fn report_self_intersections(
    mesh: &Mesh,
    info: &MeshInfo,
    shells: usize,
    problems: &mut Vec<Problem>,
) -> (Bvh, usize) {
    let boxes: Vec<Aabb> = (0..mesh.triangles.len())
        .into_par_iter()
        .with_min_len(8192)
        .map(|t| Aabb::of(mesh.corners(t)))
        .collect();
    let bvh = Bvh::new(boxes);
    let (pairs, count) = if bounds_convex_body_once(mesh, info, shells, &bvh) {
        (Vec::new(), 0)
    } else {
        self_intersection::self_intersections(mesh, &bvh, LIST)
    };
    for &(t, u, contact) in &pairs {
        let what = match contact {
            Contact::Intersect => "self-intersection: the faces meet beyond their shared vertices",
            Contact::Overlap => "self-intersection: the faces overlap (coplanar)",
        };
        problems.push(
            Problem::error(what)
                .at(faces_at(mesh, t, u))
                .with_kind(ProblemKind::SelfIntersection),
        );
    }
    if count > pairs.len() {
        problems.push(
            Problem::error(format!(
                "... and {} more intersecting face pairs",
                count - pairs.len()
            ))
            .with_kind(ProblemKind::SelfIntersection),
        );
    }
    (bvh, count)
}

/// Checks that the `shells` shells of the closed solid nest properly: each bounds a
/// region of winding number 0 outside it (a positive shell) or 1 (a cavity), and none
/// has zero volume. `shell_of[t]` is the shell of triangle `t`.
fn check_nesting(
    mesh: &Mesh,
    bvh: Bvh,
    shell_of: &[u32],
    shells: usize,
    problems: &mut Vec<Problem>,
) {
    let volumes = orientation::shell_volumes(mesh, shell_of, shells);
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); shells];
    for (t, &s) in shell_of.iter().enumerate() {
        if members[s as usize].len() < 16 {
            members[s as usize].push(t as u32);
        }
    }
    let locator = Locator::with_bvh(mesh, bvh);
    let mut c = Capped::new(LIST);
    for s in 0..shells {
        let shell = format!(
            "shell of face {}",
            mesh.source_faces[members[s][0] as usize]
        );
        let sign = apart_kernel::int::sign_of(&volumes[s]);
        if sign == Sign::Zero {
            c.push(|| {
                Problem::error("this shell has zero volume")
                    .at(shell)
                    .with_kind(ProblemKind::ZeroVolume)
            });
            continue;
        }
        let expected = if sign == Sign::Positive { 0 } else { 1 };
        match orientation::winding_of_others(&locator, shell_of, s as u32, &members[s]) {
            Some(w) if w == expected => {}
            Some(w) => c.push(|| {
                let why = if sign == Sign::Positive {
                    format!("this shell lies inside the solid (winding number {w}): shells with the same orientation are nested")
                } else if w == 0 {
                    "this shell is inside out: its faces point inwards but it bounds no cavity".to_string()
                } else {
                    format!("this cavity lies in a region of winding number {w}")
                };
                Problem::error(why).at(shell).with_kind(ProblemKind::Shell)
            }),
            None => {}
        }
    }
    c.finish("badly nested shells", problems);
}

/// Triangles up to which a closed shell is first tried as the boundary of a convex body
/// (pieces of a decomposition and convex parts), which needs no pairwise test.
const SMALL_CONVEX: usize = 64;

/// True when the small closed shell `mesh` (positive volume, one shell, touching itself
/// nowhere) is the boundary of its convex hull covered once, so that no two of its
/// triangles can meet beyond what they share. Every vertex lies on or below every
/// triangle's plane, so each triangle lies in a face of the hull `K`, facing out; seen
/// from a point inside `K` the shell then covers the hull's boundary the same number of
/// times `d` everywhere (the winding number of that point), and `d = 1` leaves no room
/// for two triangles to overlap or to meet anywhere but along shared edges and
/// vertices. The point is the vertices' centroid, inside `K` since they span space.
fn bounds_convex_body_once(mesh: &Mesh, info: &MeshInfo, shells: usize, bvh: &Bvh) -> bool {
    if !info.closed
        || info.volume6.is_none()
        || shells != 1
        || info.touching_edges > 0
        || info.touching_vertices > 0
        || mesh.triangles.len() > SMALL_CONVEX
    {
        return false;
    }
    let v = &mesh.vertices;
    let below = |t: &[u32; 3], ps: [&[i64; 3]; 3]| {
        orient3d_many(&v[t[0] as usize], &v[t[1] as usize], &v[t[2] as usize], ps)
            .iter()
            .all(|&s| s != Sign::Positive)
    };
    let convex = mesh.triangles.iter().all(|t| {
        v.chunks(3).all(|c| match c {
            [a, b, c] => below(t, [a, b, c]),
            [a, b] => below(t, [a, b, b]),
            [a] => below(t, [a, a, a]),
            _ => true,
        })
    });
    if !convex {
        return false;
    }
    let sum = [0, 1, 2].map(|k| v.iter().map(|p| Int::from(p[k])).sum::<Int>());
    let centroid = HPoint::from_big(sum, Int::from(v.len() as i64));
    Locator::with_bvh(mesh, bvh.clone()).winding(&centroid) == Some(1)
}

/// Reads, snaps, welds, triangulates and validates one object: the mesh (when one
/// could be built), what validation learnt, and every problem found on the way.
pub fn check_solid(
    raw: &apart_formats::RawObject,
    grid: &Grid,
) -> (Option<Mesh>, Option<MeshInfo>, Vec<Problem>) {
    let (mesh, mut problems) = Mesh::from_raw(raw, grid);
    match mesh {
        Some(mut m) => {
            let (info, more) = validate(&mut m, grid);
            problems.extend(more);
            (Some(m), Some(info), problems)
        }
        None => (None, None, problems),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_formats::{Polygons, RawObject};

    fn mesh_of(vertices: Vec<[i64; 3]>, faces: Vec<Vec<usize>>) -> Mesh {
        let raw = RawObject {
            name: None,
            vertices: vertices.iter().map(|p| p.map(|c| c as f64)).collect(),
            faces: Polygons::from(
                faces
                    .iter()
                    .map(|f| f.iter().map(|&i| i as u32).collect())
                    .collect::<Vec<Vec<u32>>>(),
            ),
        };
        Mesh::from_raw(&raw, &Grid::unit(30)).0.unwrap()
    }

    /// Whether the shortcut is taken on `m` (validated first, as `validate` does), after
    /// checking that the pairwise test agrees whenever it is: no intersecting pair.
    fn shortcut(mut m: Mesh) -> bool {
        let (info, _) = validate(&mut m, &Grid::unit(30));
        let boxes: Vec<Aabb> = (0..m.triangles.len())
            .map(|t| Aabb::of(m.corners(t)))
            .collect();
        let bvh = Bvh::new(boxes);
        let taken = bounds_convex_body_once(&m, &info, info.shells, &bvh);
        let (_, count) = self_intersection::self_intersections(&m, &bvh, LIST);
        assert!(
            !taken || count == 0,
            "shortcut taken on a shell with {count} crossings"
        );
        taken
    }

    fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> (Vec<[i64; 3]>, Vec<Vec<usize>>) {
        use crate::test_shapes::{cuboid_corners, CUBOID_QUADS};
        let f = CUBOID_QUADS.iter().map(|q| q.map(|i| i as usize).to_vec());
        (cuboid_corners(lo, hi), f.collect())
    }

    /// The top face (z = hi) as four triangles around its centre, lifted by `dz`.
    fn tented(lo: [i64; 3], hi: [i64; 3], dz: i64) -> Mesh {
        let (mut v, mut f) = cuboid(lo, hi);
        f.remove(1);
        v.push([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2] + dz]);
        for (a, b) in [(4, 5), (5, 7), (7, 6), (6, 4)] {
            f.push(vec![a, b, 8]);
        }
        mesh_of(v, f)
    }

    fn octahedron(c: [i64; 3], r: [i64; 6]) -> Mesh {
        let v = vec![
            [c[0] + r[0], c[1], c[2]],
            [c[0] - r[1], c[1], c[2]],
            [c[0], c[1] + r[2], c[2]],
            [c[0], c[1] - r[3], c[2]],
            [c[0], c[1], c[2] + r[4]],
            [c[0], c[1], c[2] - r[5]],
        ];
        let f = [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        mesh_of(v, f.iter().map(|t| t.to_vec()).collect())
    }

    #[test]
    fn convex_shells_skip_the_pairwise_test_and_others_do_not() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = |n: i64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % n as u64) as i64
        };
        for _ in 0..200 {
            let lo = [next(100) - 50, next(100) - 50, next(100) - 50];
            let hi = [0, 1, 2].map(|k| lo[k] + 2 + 2 * next(20));
            let (v, f) = cuboid(lo, hi);
            assert!(shortcut(mesh_of(v.clone(), f.clone())));
            // Inside out: validation turns it around first.
            let flipped = f
                .iter()
                .map(|q| q.iter().rev().copied().collect())
                .collect();
            assert!(shortcut(mesh_of(v, flipped)));
            // Coplanar triangles in one face, and a convex tent over it.
            assert!(shortcut(tented(lo, hi, 0)));
            assert!(shortcut(tented(lo, hi, 1 + next(5))));
            // A dent: not convex, so the pairwise test runs.
            assert!(!shortcut(tented(lo, hi, -1)));
            let r = [0; 6].map(|_| 1 + next(30));
            assert!(shortcut(octahedron(lo, r)));
            // The top vertex pulled below the bottom one: a folded (valid) shell that is
            // not convex.
            let mut m = octahedron(lo, r);
            m.vertices[4][2] = lo[2] - r[5] - 1 - next(10);
            assert!(!shortcut(m));
        }
    }
}
