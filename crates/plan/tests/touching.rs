//! Touching parts: solutions are reported on the maximal cells of the motion space, never
//! on mislabelled cells.
//!
//! Where the boundary of one pair's open blocked set changes nothing else, the arc and
//! its vertices have the blocking graph of the face outside the set: they belong to that
//! face. Two cubes touching only at a vertex used to list the free direction (−1, 0, 0),
//! 90° inside a free face, as an isolated vertex with clearance 0.
//!
//! Everything is re-checked by the brute-force oracle (`common::oracle`):
//! - every solution's set is a minimal moving set at its direction, and a face solution's
//!   set is free within its clearance;
//! - an edge or vertex solution (and every edge or vertex cell) is maximal: at every
//!   direction close around it the blocking graph differs from its own;
//! - nothing is lost: at sample directions, every minimal moving set appears among the
//!   solutions, as a face solution whenever it is free all around the direction.

mod common;

use apart_kernel::Vec3;
use apart_plan::{
    partition_subset, BlockingRegions, CellKind, DirectionQuery, Options, Part, Solution,
};
use common::oracle::Oracle;
use common::{cuboid, part};

/// Two unit cubes: `a` = [0,1]³ and `b` = [0,1]³ + `shift`.
fn two_cubes(shift: [i64; 3]) -> Vec<Part> {
    vec![
        part("a", vec![cuboid([0, 0, 0], [1, 1, 1])]),
        part(
            "b",
            vec![cuboid(shift, [shift[0] + 1, shift[1] + 1, shift[2] + 1])],
        ),
    ]
}

/// Directions close around `d`: `K d + w` for the 48 signed permutations `w` of
/// (1, 10, 100), which lie on no great circle with a normal of coordinates at most 9 in
/// absolute value through `d` (so they fall in the faces around a vertex or an edge).
fn around(d: &Vec3) -> Vec<Vec3> {
    let k = apart_kernel::Int::from(1i64 << 16);
    let base = d.primitive().scale(&k);
    let mut out = Vec::new();
    for p in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        for s in 0..8 {
            let v = [1i64, 10, 100];
            let mut w = [0i64; 3];
            for i in 0..3 {
                w[p[i]] = if s >> i & 1 == 1 { -v[i] } else { v[i] };
            }
            out.push(base.add(&Vec3::from_i64(w)));
        }
    }
    out
}

/// The oracle's checks above, on every solution, every cell and `dirs`; `step` thins the
/// directions around a cell (the oracle solves linear programs for pieces that are not
/// boxes).
fn check(name: &str, parts: &[Part], dirs: &[Vec3], step: usize) -> Vec<Solution> {
    let oracle = Oracle::new(parts);
    let regions = BlockingRegions::compute(parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    let (result, ms) = partition_subset(&regions, &all, &Options::default());
    let maximal = |d: &Vec3, what: &str| {
        let g = oracle.dbg(d);
        for q in around(d).into_iter().step_by(step) {
            assert_ne!(
                oracle.dbg(&q),
                g,
                "{name}: {what} at {d:?} has the blocking graph of the directions around it \
                 (at {q:?}): it belongs to a larger cell"
            );
        }
    };
    for s in &result.solutions {
        let g = oracle.dbg(&s.direction);
        assert!(
            g.minimal_moving_sets().contains(&s.moving),
            "{name}: {s:?} is no minimal moving set there: {:?}",
            g.arcs()
        );
        match s.cell {
            CellKind::Face => {
                assert!(s.clearance_deg > 0.0, "{name}: {s:?}");
                for q in common::cap_directions(&s.unit, 0.97 * s.clearance_deg.to_radians()) {
                    assert!(
                        oracle.dbg(&q).can_move(&s.moving),
                        "{name}: {s:?} is blocked at {q:?}, inside its clearance"
                    );
                }
            }
            _ => {
                assert_eq!(s.clearance_deg, 0.0, "{name}: {s:?}");
                maximal(&s.direction, "solution");
                assert_eq!(ms.locate(&s.direction).0, s.cell, "{name}: {s:?}");
            }
        }
    }
    let arr = ms.arrangement();
    for v in ms.real_vertices() {
        maximal(&arr.vertices()[v].point, "vertex cell");
    }
    for cell in ms.edge_cells() {
        for &e in cell {
            maximal(&arr.edge_arc(e).interior_point(), "edge cell");
        }
    }
    // Completeness at the sample directions and at the arrangement's vertices.
    let mut samples: Vec<Vec3> = dirs.to_vec();
    samples.extend(arr.vertices().iter().map(|v| v.point.clone()));
    for d in &samples {
        for m in oracle.dbg(d).minimal_moving_sets() {
            let free_around = around(d)
                .iter()
                .step_by(step)
                .all(|q| oracle.dbg(q).can_move(&m));
            assert!(
                result
                    .solutions
                    .iter()
                    .any(|s| s.moving == m && (!free_around || s.cell == CellKind::Face)),
                "{name}: {m:?} moves along {d:?} (free all around: {free_around}) \
                 but no solution says so"
            );
        }
    }
    result.solutions
}

/// The 26 directions of coordinates −1, 0 and 1, and the 124 of −2 to 2.
fn grid_dirs() -> Vec<Vec3> {
    let mut out = Vec::new();
    for x in -2..=2 {
        for y in -2..=2 {
            for z in -2..=2 {
                if (x, y, z) != (0, 0, 0) {
                    out.push(Vec3::new(x, y, z));
                }
            }
        }
    }
    out
}

/// (cell, moving) of every solution, and the face clearances.
fn summary(s: &[Solution]) -> Vec<(CellKind, Vec<usize>)> {
    let mut out: Vec<(CellKind, Vec<usize>)> =
        s.iter().map(|s| (s.cell, s.moving.clone())).collect();
    out.sort();
    out
}

fn face_clearances(s: &[Solution]) -> Vec<f64> {
    s.iter()
        .filter(|s| s.cell == CellKind::Face)
        .map(|s| s.clearance_deg)
        .collect()
}

#[test]
fn cubes_touching_at_a_vertex_leave_through_faces_only() {
    let parts = two_cubes([1, 1, 1]);
    let s = check("vertex", &parts, &grid_dirs(), 1);
    // Each cube is free everywhere except an open octant: one face each, whose deepest
    // direction (away from the octant) is acos(−1/√3) ≈ 125.26° from the octant's corners.
    assert_eq!(
        summary(&s),
        vec![(CellKind::Face, vec![0]), (CellKind::Face, vec![1])]
    );
    let deepest = (-1.0f64 / 3f64.sqrt()).acos().to_degrees();
    for c in face_clearances(&s) {
        assert!((c - deepest).abs() < 1e-6, "{c} vs {deepest}");
    }
    // (−1, 0, 0) lies 90° inside the face where `a` is free, and is located there.
    let q = DirectionQuery::new(&parts).unwrap();
    for d in [Vec3::new(-1, 0, 0), Vec3::new(0, 0, 1), Vec3::new(1, 1, 0)] {
        let answer = q.answer(&d).unwrap();
        assert_eq!(answer.cell, CellKind::Face, "{d:?}");
        assert_eq!(answer.moving, vec![vec![0], vec![1]], "{d:?}");
    }
}

#[test]
fn cubes_touching_along_an_edge_leave_through_faces_only() {
    let parts = two_cubes([1, 1, 0]);
    let s = check("edge", &parts, &grid_dirs(), 1);
    // Each cube is blocked in an open lune (a quarter of the sphere) with the z poles as
    // corners: the farthest any direction gets from the closed lune is 90°.
    assert_eq!(
        summary(&s),
        vec![(CellKind::Face, vec![0]), (CellKind::Face, vec![1])]
    );
    for c in face_clearances(&s) {
        assert!((c - 90.0).abs() < 1e-6, "{c}");
    }
}

#[test]
fn cubes_touching_on_a_face_also_slide() {
    let parts = two_cubes([1, 0, 0]);
    let s = check("face", &parts, &grid_dirs(), 1);
    // Each leaves through an open hemisphere, and both slide along the contact plane: its
    // great circle has the empty blocking graph, unlike either side.
    assert_eq!(
        summary(&s),
        vec![
            (CellKind::Face, vec![0]),
            (CellKind::Face, vec![1]),
            (CellKind::Edge, vec![0]),
            (CellKind::Edge, vec![1]),
        ]
    );
    for c in face_clearances(&s) {
        assert!((c - 90.0).abs() < 1e-6, "{c}");
    }
}

#[test]
fn three_cubes_touching_at_a_face_an_edge_and_a_vertex() {
    // a–b share a face, b–c an edge, a–c only the vertex (1, 1, 1).
    let parts = vec![
        part("a", vec![cuboid([0, 0, 0], [1, 1, 1])]),
        part("b", vec![cuboid([1, 0, 0], [2, 1, 1])]),
        part("c", vec![cuboid([1, 1, 1], [2, 2, 2])]),
    ];
    let s = check("three", &parts, &grid_dirs(), 1);
    assert!(s.iter().any(|s| s.cell == CellKind::Face));
}

#[test]
fn block_of_eight_cubes() {
    // Every kind of contact at once: faces, edges and the centre vertex.
    let mut parts = Vec::new();
    for k in 0..8 {
        let o = [k & 1, k >> 1 & 1, k >> 2 & 1];
        parts.push(part(
            &format!("c{k}"),
            vec![cuboid(o, [o[0] + 1, o[1] + 1, o[2] + 1])],
        ));
    }
    let s = check("block", &parts, &grid_dirs(), 1);
    // A corner cube leaves through the open octant away from the block.
    assert!(s
        .iter()
        .any(|s| s.cell == CellKind::Face && s.moving == vec![7] && s.clearance_deg > 0.0));
}

#[test]
fn split_star_keeps_its_eight_isolated_directions() {
    // (The oracle solves linear programs for these pieces: directions −1 to 1 only.)
    let parts = common::split_star();
    let dirs: Vec<Vec3> = grid_dirs().into_iter().filter(|d| d.bits() <= 1).collect();
    let s = check("split star", &parts, &dirs, 5);
    assert_eq!(s.len(), 8);
    assert!(s.iter().all(|s| s.cell == CellKind::Vertex));
}
