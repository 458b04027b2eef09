//! Property tests of partitioning against the brute-force oracle (ARCHITECTURE.md, invariants).
//!
//! Oracle: part `i` moving along `d` hits part `j` iff for some piece pair the open ray
//! `{k d : k > 0}` meets the interior of `M = b ⊕ (−a)`, i.e. some `k > 0` satisfies every
//! facet inequality of `M` strictly. `M` is built independently of the Minkowski code
//! (boxes: the box of differences; other pieces: the hull of all vertex differences).
//! At every vertex, at an exact sample of every edge and face, and at random directions,
//! the blocking graph read from the motion space must equal the oracle's. Solutions must
//! be valid, (S, d) must pair with (rest, −d), and a face solution's set must be free
//! at every direction within its reported clearance.

mod common;

use apart_kernel::Vec3;
use apart_pieces::Polytope;
use apart_plan::{dbg_at, partition_subset, BlockingRegions, CellKind, Options, Part};
use common::oracle::Oracle;
use proptest::prelude::*;

fn check(parts: &[Part], random_dirs: &[[i64; 3]]) -> Result<(), TestCaseError> {
    let oracle = Oracle::new(parts);
    let regions = BlockingRegions::compute(parts).unwrap();
    let all: Vec<usize> = (0..parts.len()).collect();
    let (result, ms) = partition_subset(&regions, &all, &Options::default());
    let arr = ms.arrangement();
    let st = ms.statuses();
    for v in ms.real_vertices() {
        let d = &arr.vertices()[v].point;
        prop_assert_eq!(ms.dbg(&st.vertices[v]), oracle.dbg(d), "vertex {:?}", d);
    }
    for cell in ms.edge_cells() {
        for &e in cell {
            let d = arr.edge_arc(e).interior_point();
            prop_assert_eq!(
                ms.dbg(&st.edges[e.index()]),
                oracle.dbg(&d),
                "edge point {:?}",
                d
            );
        }
    }
    for f in 0..arr.faces().len() {
        let d = ms.face_sample(apart_sphere::FaceId::new(f));
        prop_assert_eq!(ms.dbg(&st.faces[f]), oracle.dbg(&d), "face sample {:?}", d);
    }
    for d in random_dirs {
        let d = Vec3::from(*d);
        if d.is_zero() {
            continue;
        }
        prop_assert_eq!(
            dbg_at(&regions, &all, &d),
            oracle.dbg(&d),
            "direction {:?}",
            d
        );
    }
    prop_assert_eq!(result.interlocked, result.solutions.is_empty());
    for s in &result.solutions {
        let g = oracle.dbg(&s.direction);
        prop_assert!(
            g.can_move(&s.moving),
            "solution {:?} is blocked: {:?}",
            s,
            g.arcs()
        );
        let rest: Vec<usize> = all
            .iter()
            .copied()
            .filter(|k| !s.moving.contains(k))
            .collect();
        prop_assert!(
            oracle.dbg(&s.direction.neg()).can_move(&rest),
            "antipode of {:?}",
            s
        );
        if s.cell == CellKind::Face {
            prop_assert!(s.clearance_deg > 0.0, "{:?}", s);
            for q in common::cap_directions(&s.unit, 0.97 * s.clearance_deg.to_radians()) {
                prop_assert!(
                    oracle.dbg(&q).can_move(&s.moving),
                    "{:?} is blocked at {:?}, inside its clearance",
                    s,
                    q
                );
            }
        }
    }
    Ok(())
}

/// Random voxel assemblies: a small grid of unit-scaled cells, each cell a box piece of a
/// random part (touching everywhere, many coplanar faces, shared edges and vertices).
fn voxel_assembly() -> impl Strategy<Value = Vec<Part>> {
    (2usize..=4, prop::collection::vec(0usize..6, 12), 1i64..=3)
        .prop_map(|(k, owners, scale)| {
            let mut parts: Vec<Vec<Polytope>> = vec![Vec::new(); k];
            for (c, &o) in owners.iter().enumerate() {
                if o >= k {
                    continue; // empty cell
                }
                let (x, y, z) = ((c % 3) as i64, ((c / 3) % 2) as i64, (c / 6) as i64);
                parts[o].push(common::cuboid(
                    [x * scale, y * 2, z],
                    [(x + 1) * scale, y * 2 + 2, z + 1],
                ));
            }
            parts
                .into_iter()
                .enumerate()
                .filter(|(_, p)| !p.is_empty())
                .map(|(i, p)| common::part(&format!("p{i}"), p))
                .collect::<Vec<_>>()
        })
        .prop_filter("at least two parts", |p| p.len() >= 2)
}

/// Random convex pieces in separate cells of a grid (cells of size 4 touching along
/// planes, pieces reaching cell boundaries often).
fn polytope_assembly() -> impl Strategy<Value = Vec<Part>> {
    let piece = prop::collection::vec(prop::array::uniform3(0i64..=4), 4..7);
    (prop::collection::vec((0usize..3, piece), 2..5)).prop_filter_map("flat pieces", |cells| {
        let mut parts: Vec<Vec<Polytope>> = vec![Vec::new(); 3];
        for (c, (owner, pts)) in cells.into_iter().enumerate() {
            let off = [(c % 2) as i64 * 4, (c / 2) as i64 * 4, 0];
            let v: Vec<Vec3> = pts
                .iter()
                .map(|p| Vec3::new(p[0] + off[0], p[1] + off[1], p[2] + off[2]))
                .collect();
            parts[owner].push(Polytope::hull_of_points(&v).ok()?);
        }
        let parts: Vec<Part> = parts
            .into_iter()
            .enumerate()
            .filter(|(_, p)| !p.is_empty())
            .map(|(i, p)| common::part(&format!("p{i}"), p))
            .collect();
        (parts.len() >= 2).then_some(parts)
    })
}

fn dirs() -> impl Strategy<Value = Vec<[i64; 3]>> {
    prop::collection::vec(prop::array::uniform3(-2i64..=2), 12)
}

/// `b ⊕ (−a)` as facet inequalities, the slow way: the hull of all vertex differences.
fn difference_hull(a: &Polytope, b: &Polytope) -> Vec<(Vec3, apart_kernel::Int)> {
    let mut s = Vec::new();
    for y in b.vertices() {
        for x in a.vertices() {
            s.push(y.sub(x));
        }
    }
    let m = Polytope::hull_of_points(&s).unwrap();
    m.facets()
        .iter()
        .map(|f| (f.normal.clone(), f.offset.clone()))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The oracle's linear program agrees with the ray test on the hull of differences,
    /// on touching and overlapping pieces and axis directions (degenerate on purpose).
    #[test]
    fn sweep_test_agrees_with_the_hull_of_differences(
        pa in prop::collection::vec(prop::array::uniform3(0i64..=3), 4..7),
        pb in prop::collection::vec(prop::array::uniform3(0i64..=3), 4..7),
        shift in prop::array::uniform3(-3i64..=3),
        d in prop::array::uniform3(-2i64..=2),
    ) {
        let a = Polytope::hull_of_points(&pa.iter().map(|&p| Vec3::from(p)).collect::<Vec<_>>());
        let b = Polytope::hull_of_points(
            &pb.iter()
                .map(|p| Vec3::new(p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]))
                .collect::<Vec<_>>(),
        );
        let (Ok(a), Ok(b)) = (a, b) else { return Ok(()) };
        let d = Vec3::from(d);
        prop_assume!(!d.is_zero());
        prop_assert_eq!(
            common::oracle::sweep_meets_interior(&a, &b, &d),
            common::oracle::ray_meets_interior(&difference_hull(&a, &b), &d)
        );
    }

    #[test]
    fn voxel_assemblies_match_the_oracle(parts in voxel_assembly(), d in dirs()) {
        check(&parts, &d)?;
    }

    #[test]
    fn polytope_assemblies_match_the_oracle(parts in polytope_assembly(), d in dirs()) {
        check(&parts, &d)?;
    }
}

#[test]
fn split_star_matches_the_oracle() {
    let d: Vec<[i64; 3]> = (0..27)
        .map(|k| [k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1])
        .collect();
    check(&common::split_star(), &d).unwrap();
}

#[test]
fn named_assemblies_match_the_oracle() {
    for parts in [
        common::dovetail(),
        common::peg_in_hole(),
        common::linked_rings(),
        common::cubes_in_a_row(4),
    ] {
        check(&parts, &[[1, 0, 0], [0, 1, 1], [1, -2, 1]]).unwrap();
    }
}
