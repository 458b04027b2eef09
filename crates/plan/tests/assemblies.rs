//! Partitioning results on assemblies with known answers.

mod common;

use apart_kernel::Vec3;
use apart_plan::{dbg_at, partition_pieces, BlockingRegions, CellKind, Options, Solution};

fn solutions_of(parts: &[apart_plan::Part]) -> Vec<Solution> {
    let r = partition_pieces(parts, &Options::default()).unwrap();
    assert_eq!(r.interlocked, r.solutions.is_empty());
    r.solutions
}

#[test]
fn stacked_cubes_hemisphere_and_equator() {
    let sols = solutions_of(&common::stacked_cubes());
    let (bottom, top) = (0usize, 1usize);
    let faces: Vec<&Solution> = sols.iter().filter(|s| s.cell == CellKind::Face).collect();
    let edges: Vec<&Solution> = sols.iter().filter(|s| s.cell == CellKind::Edge).collect();
    assert!(sols.iter().all(|s| s.cell != CellKind::Vertex));
    // One face each: top up, bottom down, both with 90° clearance.
    assert_eq!(faces.len(), 2);
    for s in &faces {
        let up = s.moving == vec![top];
        assert!(up || s.moving == vec![bottom]);
        assert_eq!(s.unit[2] > 0.0, up);
        assert!((s.clearance_deg - 90.0).abs() < 1e-3, "{}", s.clearance_deg);
    }
    // The equator is one edge where either cube slides off.
    assert_eq!(edges.len(), 2);
    for s in &edges {
        assert_eq!(
            apart_kernel::predicates::dot_sign(&s.direction, &Vec3::new(0, 0, 1)),
            apart_kernel::Sign::Zero
        );
    }
    let mut moving: Vec<Vec<usize>> = edges.iter().map(|s| s.moving.clone()).collect();
    moving.sort();
    assert_eq!(moving, vec![vec![bottom], vec![top]]);
}

#[test]
fn four_cubes_in_a_row() {
    let parts = common::cubes_in_a_row(4);
    let regions = BlockingRegions::compute(&parts).unwrap();
    let all = [0, 1, 2, 3];
    for d in [[0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]] {
        let g = dbg_at(&regions, &all, &Vec3::from(d));
        assert!(g.arcs().is_empty(), "{d:?}: {:?}", g.arcs());
        assert_eq!(
            g.minimal_moving_sets(),
            vec![vec![0], vec![1], vec![2], vec![3]]
        );
    }
    let g = dbg_at(&regions, &all, &Vec3::new(1, 0, 0));
    assert_eq!(g.minimal_moving_sets(), vec![vec![3]]);
    // Every subset of the first i cubes... the cubes from i on move together along +x.
    for i in 1..4 {
        let tail: Vec<usize> = (i..4).collect();
        assert!(g.can_move(&tail));
    }
    let g = dbg_at(&regions, &all, &Vec3::new(-1, 0, 0));
    assert_eq!(g.minimal_moving_sets(), vec![vec![0]]);
    assert!(
        !partition_pieces(&parts, &Options::default())
            .unwrap()
            .interlocked
    );
}

#[test]
fn dovetail_only_along_its_axis() {
    let sols = solutions_of(&common::dovetail());
    let mut got: Vec<(String, Vec<usize>)> = sols
        .iter()
        .map(|s| {
            assert_eq!(s.cell, CellKind::Vertex, "{s:?}");
            (format!("{:?}", s.direction), s.moving.clone())
        })
        .collect();
    got.sort();
    assert_eq!(
        got,
        vec![
            ("(-1, 0, 0)".to_string(), vec![0]),
            ("(1, 0, 0)".to_string(), vec![1])
        ]
    );
}

#[test]
fn peg_leaves_only_along_the_hole_axis() {
    // The exit direction lies on the boundary of several wall pieces' blocked
    // hemispheres that together cover the sphere: only the union of *open* polygons
    // leaves it free.
    let sols = solutions_of(&common::peg_in_hole());
    let mut got: Vec<(String, Vec<usize>, CellKind)> = sols
        .iter()
        .map(|s| (format!("{:?}", s.direction), s.moving.clone(), s.cell))
        .collect();
    got.sort();
    assert_eq!(
        got,
        vec![
            ("(0, 0, -1)".to_string(), vec![0], CellKind::Vertex),
            ("(0, 0, 1)".to_string(), vec![1], CellKind::Vertex)
        ]
    );
}

#[test]
fn linked_rings_are_interlocked() {
    let r = partition_pieces(&common::linked_rings(), &Options::default()).unwrap();
    assert!(r.interlocked, "{:?}", r.solutions);
}

#[test]
fn first_stops_early() {
    let r = partition_pieces(
        &common::split_star(),
        &Options {
            first: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.solutions.len(), 1);
    assert!(!r.interlocked);
    let r = partition_pieces(
        &common::linked_rings(),
        &Options {
            first: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(r.interlocked);
}
