//! Parts given as plain meshes are decomposed exactly, and partitioning them gives the same
//! answer as partitioning the same parts given as declared convex pieces.

mod common;

use apart_plan::{
    dbg_at, partition_pieces, BlockingRegions, CellKind, Options, Part, Partitioning,
};
use proptest::prelude::*;

const DIMS: [usize; 3] = [3, 3, 2];

/// Each part as its voxels (declared unit-cube pieces) and as one welded mesh decomposed.
fn both_ways(owners: &[usize], k: usize) -> Option<(Vec<Part>, Vec<Part>)> {
    let mut boxes = Vec::new();
    let mut meshes = Vec::new();
    for part in 0..k {
        let on: Vec<bool> = owners.iter().map(|&o| o == part).collect();
        if !on.iter().any(|&b| b) {
            continue;
        }
        let mut cubes = Vec::new();
        for (c, _) in on.iter().enumerate().filter(|(_, &b)| b) {
            let (x, y, z) = (
                (c / (DIMS[1] * DIMS[2])) as i64,
                ((c / DIMS[2]) % DIMS[1]) as i64,
                (c % DIMS[2]) as i64,
            );
            cubes.push(common::cuboid([x, y, z], [x + 1, y + 1, z + 1]));
        }
        let shape = apart_testkit::solids::voxels(DIMS, &on);
        let points: Vec<apart_kernel::Vec3> = shape
            .points
            .iter()
            .map(|&p| apart_kernel::Vec3::from_i64(p))
            .collect();
        let d = apart_decompose::decompose(&points, &shape.triangles, &Default::default()).unwrap();
        apart_decompose::verify(&points, &shape.triangles, &d.pieces).unwrap();
        let name = format!("p{part}");
        boxes.push(common::part(&name, cubes));
        meshes.push(common::part(&name, d.pieces));
    }
    (boxes.len() >= 2).then_some((boxes, meshes))
}

/// Every solution of `a` is a solution of the assembly `other_regions` describes (the
/// same moving set is a minimal moving set along the same exact direction).
fn solutions_hold(a: &Partitioning, other: &BlockingRegions) {
    let all: Vec<usize> = (0..other.part_count()).collect();
    for s in &a.solutions {
        let sets = dbg_at(other, &all, &s.direction).minimal_moving_sets();
        assert!(
            sets.contains(&s.moving),
            "{s:?} not a solution of the other decomposition"
        );
    }
}

fn counts(p: &Partitioning) -> [usize; 3] {
    let n = |k| p.solutions.iter().filter(|s| s.cell == k).count();
    [n(CellKind::Face), n(CellKind::Edge), n(CellKind::Vertex)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn decomposed_meshes_partition_like_declared_boxes(owners in prop::collection::vec(0usize..4, 18), k in 2usize..=3) {
        let Some((boxes, meshes)) = both_ways(&owners, k) else { return Ok(()) };
        let (rb, rm) = (BlockingRegions::compute(&boxes).unwrap(), BlockingRegions::compute(&meshes).unwrap());
        let (pb, pm) = (partition_pieces(&boxes, &Options::default()).unwrap(), partition_pieces(&meshes, &Options::default()).unwrap());
        prop_assert_eq!(pb.interlocked, pm.interlocked);
        prop_assert_eq!(counts(&pb), counts(&pm));
        // Vertex solutions are exact directions: identical sets.
        let verts = |p: &Partitioning| {
            let mut v: Vec<(Vec<String>, Vec<usize>)> =
                p.solutions.iter().filter(|s| s.cell == CellKind::Vertex).map(|s| (s.direction.to_strings().to_vec(), s.moving.clone())).collect();
            v.sort();
            v
        };
        prop_assert_eq!(verts(&pb), verts(&pm));
        solutions_hold(&pb, &rm);
        solutions_hold(&pm, &rb);
    }
}
