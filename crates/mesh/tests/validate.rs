//! Validation of hand-built solids against hand-computed facts.

use apart_formats::{Polygons, RawObject};
use apart_kernel::{Grid, Int, Rational};
use apart_mesh::validate::{check_solid, MeshInfo};
use apart_mesh::{Problem, Severity};
use apart_testkit::solids::{cuboid_corners, CUBOID_QUADS};

/// The 6 quads of the box [lo, hi], outward.
fn box_faces(base: u32) -> Vec<Vec<u32>> {
    CUBOID_QUADS
        .iter()
        .map(|q| q.iter().map(|i| i + base).collect())
        .collect()
}

fn box_vertices(lo: [f64; 3], hi: [f64; 3]) -> Vec<[f64; 3]> {
    cuboid_corners(lo, hi)
}

/// Boxes in one object; `outward[k]` false reverses box k.
fn boxes(list: &[([f64; 3], [f64; 3], bool)]) -> RawObject {
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for (k, &(lo, hi, outward)) in list.iter().enumerate() {
        vertices.extend(box_vertices(lo, hi));
        for mut f in box_faces(8 * k as u32) {
            if !outward {
                f.reverse();
            }
            faces.push(f);
        }
    }
    RawObject {
        name: None,
        vertices,
        faces: Polygons::from(faces),
    }
}

fn check(raw: &RawObject) -> (MeshInfo, Vec<Problem>) {
    let grid = Grid::choose(raw.vertices.iter().flatten().copied(), 30).unwrap();
    let (_, info, problems) = check_solid(raw, &grid);
    (info.expect("a mesh"), problems)
}

fn volume(info: &MeshInfo) -> Rational {
    info.volume().expect("closed")
}

fn rat(n: i64, d: i64) -> Rational {
    Rational::new(Int::from(n), Int::from(d))
}

fn errors(p: &[Problem]) -> Vec<&Problem> {
    p.iter().filter(|p| p.severity == Severity::Error).collect()
}

#[test]
fn cube_is_a_convex_solid() {
    let (info, p) = check(&boxes(&[([0.0; 3], [2.0; 3], true)]));
    assert!(p.is_empty(), "{p:?}");
    assert!(info.closed && info.convex);
    assert_eq!(
        (info.vertices, info.triangles, info.faces, info.edges),
        (8, 12, 6, 18)
    );
    assert_eq!(volume(&info), rat(8, 1));
    assert_eq!(info.reflex_edges, 0);
    assert_eq!(info.shells, 1);
}

#[test]
fn inside_out_is_flipped_with_a_warning() {
    let (info, p) = check(&boxes(&[([0.0; 3], [2.0; 3], false)]));
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].severity, Severity::Warning);
    assert!(p[0].message.contains("inside out"));
    assert!(info.flipped && info.convex);
    assert_eq!(volume(&info), rat(8, 1));
}

#[test]
fn open_boundary_lists_edges_in_input_units() {
    let mut raw = boxes(&[([0.0; 3], [0.5, 0.5, 0.5], true)]);
    let faces: Vec<Vec<u32>> = raw.faces.iter().skip(1).map(|f| f.to_vec()).collect();
    raw.faces = Polygons::from(faces);
    let (info, p) = check(&raw);
    assert!(!info.closed && info.volume6.is_none());
    let e = errors(&p);
    assert_eq!(e.len(), 4, "{p:?}"); // the missing quad's 4 edges
    assert!(e.iter().all(|p| p.message.contains("open boundary")));
    assert!(
        e.iter()
            .any(|p| p.element.as_deref() == Some("edge (0, 2) at (0, 0, 0)-(0, 0.5, 0)")),
        "{e:?}"
    );
}

#[test]
fn inconsistent_orientation_names_a_face_pair() {
    let mut raw = boxes(&[([0.0; 3], [1.0; 3], true)]);
    let mut faces: Vec<Vec<u32>> = raw.faces.iter().map(|f| f.to_vec()).collect();
    faces[3].reverse();
    raw.faces = Polygons::from(faces);
    let (info, p) = check(&raw);
    assert!(!info.closed);
    let e = errors(&p);
    assert!(!e.is_empty());
    assert!(e
        .iter()
        .all(|p| p.message.contains("inconsistent orientation")));
    assert!(
        e.iter()
            .any(|p| p.element.as_deref() == Some("faces 0 and 3")),
        "{e:?}"
    );
}

#[test]
fn three_faces_on_one_edge_are_non_manifold() {
    let mut raw = boxes(&[([0.0; 3], [1.0; 3], true)]);
    raw.vertices.push([0.5, -1.0, -1.0]);
    raw.faces.push(&[0, 1, 8]); // a fin on the edge (0, 1)
    let (_, p) = check(&raw);
    assert!(
        errors(&p)
            .iter()
            .any(|p| p.message.contains("non-manifold edge")
                && p.element
                    .as_deref()
                    .is_some_and(|e| e.starts_with("edge (0, 1)"))),
        "{p:?}"
    );
}

#[test]
fn cubes_touching_along_an_edge_are_valid() {
    // Diagonal neighbours in a voxel puzzle: one solid touching itself along x = y = 1.
    let (info, p) = check(&boxes(&[
        ([0.0; 3], [1.0; 3], true),
        ([1.0, 1.0, 0.0], [2.0, 2.0, 1.0], true),
    ]));
    assert!(errors(&p).is_empty(), "{p:?}");
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].severity, Severity::Note);
    assert!(p[0]
        .message
        .contains("touches itself along this edge (4 faces"));
    assert_eq!(info.touching_edges, 1);
    assert_eq!(info.shells, 2);
    assert!(!info.convex);
    assert_eq!(volume(&info), rat(2, 1));
}

#[test]
fn cubes_touching_at_a_vertex_are_valid() {
    let (info, p) = check(&boxes(&[
        ([0.0; 3], [1.0; 3], true),
        ([1.0; 3], [2.0; 3], true),
    ]));
    assert!(errors(&p).is_empty(), "{p:?}");
    assert_eq!(info.touching_vertices, 1);
    assert!(p[0].message.contains("touches itself at this vertex"));
    assert_eq!(volume(&info), rat(2, 1));
}

#[test]
fn bowtie_of_two_pyramids_is_valid() {
    // Two square pyramids sharing their apex (0, 0, 0).
    let vertices = vec![
        [0.0, 0.0, 0.0],
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, 1.0],
        [-1.0, -1.0, -1.0],
        [1.0, -1.0, -1.0],
        [1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0],
    ];
    let faces = vec![
        vec![1, 2, 3, 4],
        vec![0, 2, 1],
        vec![0, 3, 2],
        vec![0, 4, 3],
        vec![0, 1, 4],
        vec![5, 8, 7, 6],
        vec![0, 5, 6],
        vec![0, 6, 7],
        vec![0, 7, 8],
        vec![0, 8, 5],
    ];
    let raw = RawObject {
        name: None,
        vertices,
        faces: Polygons::from(faces),
    };
    let (info, p) = check(&raw);
    assert!(errors(&p).is_empty(), "{p:?}");
    assert_eq!(info.touching_vertices, 1);
    assert!(p
        .iter()
        .any(|p| p.element.as_deref() == Some("vertex 0 at (0, 0, 0)")));
    // Each pyramid: base 4, height 1: volume 4/3.
    assert_eq!(volume(&info), rat(8, 3));
}

#[test]
fn overlapping_shells_intersect() {
    let (info, p) = check(&boxes(&[
        ([0.0; 3], [2.0; 3], true),
        ([1.0; 3], [3.0; 3], true),
    ]));
    assert!(info.self_intersections > 0);
    assert!(errors(&p)
        .iter()
        .any(|p| p.message.contains("self-intersection")));
    assert!(!info.convex);
}

#[test]
fn coincident_faces_overlap() {
    // Two cubes sharing a face, each closed: the shared face appears twice.
    let (info, p) = check(&boxes(&[
        ([0.0; 3], [1.0; 3], true),
        ([1.0, 0.0, 0.0], [2.0, 1.0, 1.0], true),
    ]));
    assert!(info.self_intersections > 0, "{p:?}");
    assert!(errors(&p)
        .iter()
        .any(|p| p.message.contains("overlap (coplanar)")));
}

#[test]
fn cavity_is_valid_and_nested_shells_are_not() {
    let cavity = boxes(&[([0.0; 3], [4.0; 3], true), ([1.0; 3], [2.0; 3], false)]);
    let (info, p) = check(&cavity);
    assert!(p.is_empty(), "{p:?}");
    assert_eq!(volume(&info), rat(63, 1));
    assert_eq!(info.shells, 2);
    let nested = boxes(&[([0.0; 3], [4.0; 3], true), ([1.0; 3], [2.0; 3], true)]);
    let (_, p) = check(&nested);
    assert!(
        errors(&p)
            .iter()
            .any(|p| p.message.contains("lies inside the solid")),
        "{p:?}"
    );
    let loose = boxes(&[([0.0; 3], [4.0; 3], true), ([5.0; 3], [6.0; 3], false)]);
    let (_, p) = check(&loose);
    assert!(
        errors(&p)
            .iter()
            .any(|p| p.message.contains("bounds no cavity")),
        "{p:?}"
    );
}

#[test]
fn l_prism_has_one_reflex_edge() {
    // An L-shaped prism: the L (area 3) extruded by 2.
    let l = [
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [1.0, 2.0],
        [0.0, 2.0],
    ];
    let mut vertices: Vec<[f64; 3]> = l.iter().map(|p| [p[0], p[1], 0.0]).collect();
    vertices.extend(l.iter().map(|p| [p[0], p[1], 2.0]));
    let mut faces = vec![vec![5, 4, 3, 2, 1, 0], vec![6, 7, 8, 9, 10, 11]];
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        faces.push(vec![i, j, j + 6, i + 6]);
    }
    let raw = RawObject {
        name: None,
        vertices,
        faces: Polygons::from(faces),
    };
    let (info, p) = check(&raw);
    assert!(p.is_empty(), "{p:?}");
    assert_eq!(info.reflex_edges, 1);
    assert!(!info.convex);
    assert_eq!(volume(&info), rat(6, 1));
}

#[test]
fn flat_double_triangle_has_zero_volume() {
    let raw = RawObject {
        name: None,
        vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        faces: Polygons::from(vec![vec![0, 1, 2], vec![0, 2, 1]]),
    };
    let (_, p) = check(&raw);
    assert!(
        errors(&p).iter().any(|p| p.message.contains("zero volume")),
        "{p:?}"
    );
}

#[test]
fn empty_and_degenerate_meshes() {
    let raw = RawObject {
        name: None,
        vertices: vec![[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]],
        faces: Polygons::from(vec![vec![0, 1, 2]]),
    };
    let (info, p) = check(&raw);
    assert_eq!(info.triangles, 0);
    assert!(p
        .iter()
        .any(|p| p.severity == Severity::Warning && p.message.contains("zero area")));
    assert!(errors(&p).iter().any(|p| p.message.contains("empty mesh")));
}

#[test]
fn snapping_collapses_a_tiny_face_and_welds() {
    // A unit cube split at z = 0.5 by vertices 1e-12 apart: on a 30-bit grid they weld.
    let mut raw = boxes(&[([0.0; 3], [1.0; 3], true)]);
    raw.vertices.push([0.0, 0.0, 1.0 + 1e-12]);
    raw.faces.push(&[4, 8, 5]); // a sliver that snaps onto the edge (4, 5)... degenerate
    let grid = Grid::choose(raw.vertices.iter().flatten().copied(), 30).unwrap();
    let (mesh, info, p) = check_solid(&raw, &grid);
    let info = info.unwrap();
    assert!(info.closed, "{p:?}");
    assert_eq!(mesh.unwrap().vertices.len(), 8);
    assert!(p.iter().all(|p| p.severity == Severity::Warning), "{p:?}");
    assert_eq!(info.volume_units(&grid).unwrap(), rat(1, 1));
}

#[test]
fn volume_in_input_units() {
    let raw = boxes(&[([0.0; 3], [0.5, 0.25, 3.0], true)]);
    let grid = Grid::choose(raw.vertices.iter().flatten().copied(), 30).unwrap();
    let (_, info, _) = check_solid(&raw, &grid);
    assert_eq!(info.unwrap().volume_units(&grid).unwrap(), rat(3, 8));
}

/// Validation's problems carry their kind, which callers match on instead of the text.
#[test]
fn problems_carry_their_kind() {
    use apart_mesh::ProblemKind;
    let mut open = boxes(&[([0.0; 3], [0.5, 0.5, 0.5], true)]);
    let faces: Vec<Vec<u32>> = open.faces.iter().skip(1).map(|f| f.to_vec()).collect();
    open.faces = Polygons::from(faces);
    let (_, p) = check(&open);
    let e = errors(&p);
    assert!(!e.is_empty());
    assert!(
        e.iter().all(|p| p.kind == ProblemKind::OpenBoundary),
        "{e:?}"
    );

    let (_, p) = check(&boxes(&[
        ([0.0; 3], [2.0; 3], true),
        ([1.0; 3], [3.0; 3], true),
    ]));
    let crossing: Vec<_> = p
        .iter()
        .filter(|p| p.message.starts_with("self-intersection"))
        .collect();
    assert!(!crossing.is_empty());
    assert!(crossing
        .iter()
        .all(|p| p.kind == ProblemKind::SelfIntersection));

    let flat = RawObject {
        name: None,
        vertices: vec![[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]],
        faces: Polygons::from(vec![vec![0, 1, 2]]),
    };
    let (_, p) = check(&flat);
    let empty = errors(&p)
        .into_iter()
        .find(|p| p.message.starts_with("empty mesh"))
        .expect("an empty-mesh error");
    assert_eq!(empty.kind, ProblemKind::EmptyMesh);
    assert!(p
        .iter()
        .filter(|p| p.message.starts_with("zero area"))
        .all(|p| p.kind == ProblemKind::Face));
}
