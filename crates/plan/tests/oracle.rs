//! Property tests of partitioning against the brute-force oracle (ALGORITHMS.md §6).
//!
//! Oracle: part `i` moving along `d` hits part `j` iff for some piece pair the open ray
//! `{k d : k > 0}` meets the interior of `M = b ⊕ (−a)`, i.e. some `k > 0` satisfies every
//! facet inequality of `M` strictly. `M` is built independently of the Minkowski code
//! (boxes: the box of differences; other pieces: the hull of all vertex differences).
//! At every vertex, at an exact sample of every edge and face, and at random directions,
//! the blocking graph read from the motion space must equal the oracle's. Solutions must
//! be valid, and (S, d) must pair with (rest, −d).

mod common;

use apart_kernel::{Int, Rational, Vec3};
use apart_pieces::Polytope;
use apart_plan::{dbg_at, partition_subset, BlockingRegions, Dbg, Options, PartPieces};
use proptest::prelude::*;

fn box_bounds(p: &Polytope) -> Option<([Int; 3], [Int; 3])> {
    if p.vertices().len() != 8 || p.facets().len() != 6 {
        return None;
    }
    let axis = |n: &Vec3| (0..3).filter(|&k| n.get(k) != Int::ZERO).count() == 1;
    if !p.facets().iter().all(|f| axis(&f.normal)) {
        return None;
    }
    let lo = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).min().unwrap());
    let hi = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).max().unwrap());
    Some((lo, hi))
}

/// `b ⊕ (−a)` as facet inequalities `n · x <= c`.
fn difference_facets(b: &Polytope, a: &Polytope) -> Facets {
    if let (Some((alo, ahi)), Some((blo, bhi))) = (box_bounds(a), box_bounds(b)) {
        let mut out = Vec::new();
        for k in 0..3 {
            let mut e = [0i64; 3];
            e[k] = 1;
            out.push((Vec3::from_i64(e), &bhi[k] - &alo[k]));
            e[k] = -1;
            out.push((Vec3::from_i64(e), -(&blo[k] - &ahi[k])));
        }
        return out;
    }
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

fn ray_meets_interior(facets: &[(Vec3, Int)], d: &Vec3) -> bool {
    let mut lo = Rational::zero();
    let mut hi: Option<Rational> = None;
    for (n, c) in facets {
        let nd = n.dot(d);
        if nd == Int::ZERO {
            if *c <= Int::ZERO {
                return false;
            }
        } else if nd > Int::ZERO {
            let b = Rational::new(c.clone(), nd);
            if hi.as_ref().is_none_or(|h| b < *h) {
                hi = Some(b);
            }
        } else {
            let b = Rational::new(c.clone(), nd);
            if b > lo {
                lo = b;
            }
        }
    }
    hi.is_none_or(|h| lo < h)
}

/// Facet inequalities `n · x <= c` of one convex sum.
type Facets = Vec<(Vec3, Int)>;

struct Oracle {
    n: usize,
    /// facets[i][j]: for each piece pair, the facets of b ⊕ (−a), a in part i, b in j.
    facets: Vec<Vec<Vec<Facets>>>,
}

impl Oracle {
    fn new(parts: &[PartPieces]) -> Oracle {
        let n = parts.len();
        let facets = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        if i == j {
                            return Vec::new();
                        }
                        let mut v = Vec::new();
                        for a in &parts[i].pieces {
                            for b in &parts[j].pieces {
                                v.push(difference_facets(b, a));
                            }
                        }
                        v
                    })
                    .collect()
            })
            .collect();
        Oracle { n, facets }
    }

    fn dbg(&self, d: &Vec3) -> Dbg {
        let mut arcs = Vec::new();
        for i in 0..self.n {
            for j in 0..self.n {
                if i != j && self.facets[i][j].iter().any(|f| ray_meets_interior(f, d)) {
                    arcs.push((i, j));
                }
            }
        }
        Dbg::new(self.n, arcs)
    }
}

fn check(parts: &[PartPieces], random_dirs: &[[i64; 3]]) -> Result<(), TestCaseError> {
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
                ms.dbg(&st.edges[e as usize]),
                oracle.dbg(&d),
                "edge point {:?}",
                d
            );
        }
    }
    for f in 0..arr.faces().len() {
        let d = ms.face_sample(f as u32);
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
    }
    Ok(())
}

/// Random voxel assemblies: a small grid of unit-scaled cells, each cell a box piece of a
/// random part (touching everywhere, many coplanar faces, shared edges and vertices).
fn voxel_assembly() -> impl Strategy<Value = Vec<PartPieces>> {
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
fn polytope_assembly() -> impl Strategy<Value = Vec<PartPieces>> {
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
        let parts: Vec<PartPieces> = parts
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

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
