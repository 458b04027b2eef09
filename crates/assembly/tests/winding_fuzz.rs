//! The winding-number path of the loader, fuzzed: soups damaged the way exports are
//! (faces deleted, flipped, duplicated, shells copied over each other, random triangles
//! added) never make `load` panic, and whenever such a part loads as a solid, its convex
//! pieces are exactly the points where the surface it closed winds at least once: at
//! sample points off that surface, "strictly inside a piece" agrees with the independent
//! exact winding oracle of `apart_testkit::winding`, and no point is strictly inside two
//! pieces.

use apart_assembly::{
    load_description, Decompose, DescribedPart, Description, LoadOptions, MeshSource,
};
use apart_kernel::{Int, Vec3};
use apart_pieces::Polytope;
use apart_testkit::soups::families;
use apart_testkit::winding::{TriSoup, WindingOracle};
use proptest::prelude::*;

/// A damaged copy of a family's defective part, or of random triangles.
fn damaged(
    family: usize,
    delete: &[usize],
    flip: &[usize],
    copy_shift: Option<[i64; 3]>,
    junk: &[[[i64; 3]; 3]],
) -> TriSoup {
    let fams = families();
    let mut s = fams[family % fams.len()].case.soup.clone();
    let n = s.triangles.len();
    for &f in flip {
        s.triangles[f % n].swap(1, 2);
    }
    let mut gone: Vec<usize> = delete.iter().map(|d| d % n).collect();
    gone.sort_unstable();
    gone.dedup();
    for &d in gone.iter().rev() {
        s.triangles.remove(d);
    }
    if let Some(t) = copy_shift {
        let (pts, tris) = (s.points.clone(), s.triangles.clone());
        let off = s.points.len() as u32;
        s.points
            .extend(pts.iter().map(|p| [p[0] + t[0], p[1] + t[1], p[2] + t[2]]));
        s.triangles.extend(tris.iter().map(|t| t.map(|v| v + off)));
    }
    for tri in junk {
        let off = s.points.len() as u32;
        s.points.extend_from_slice(tri);
        s.triangles.push([off, off + 1, off + 2]);
    }
    s
}

fn described(s: &TriSoup) -> Description {
    Description {
        name: "fuzz".into(),
        parts: vec![DescribedPart::new(
            "part",
            MeshSource::Arrays {
                vertices: s.points.iter().map(|p| p.map(|c| c as f64)).collect(),
                triangles: s.triangles.clone(),
            },
        )],
    }
}

/// Sign of `normal · (q / 2) - offset / den` for each facet: strictly inside, or not.
fn strictly_inside(p: &Polytope, q: [i64; 3]) -> bool {
    let x = Vec3::new(q[0], q[1], q[2]);
    let two = Int::from(2);
    p.facets()
        .iter()
        .all(|f| f.normal.dot(&x) * p.den() < &two * &f.offset)
}

fn coordinate() -> impl Strategy<Value = [i64; 3]> {
    [-4i64..16, -4i64..16, -4i64..16]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    #[test]
    fn damaged_soups_load_or_are_refused_and_their_pieces_are_the_winding_solid(
        family in 0usize..8,
        delete in prop::collection::vec(any::<usize>(), 0..3),
        flip in prop::collection::vec(any::<usize>(), 0..3),
        copy in prop::option::of([-3i64..4, -3i64..4, -3i64..4]),
        junk in prop::collection::vec([coordinate(), coordinate(), coordinate()], 0..2),
        samples in prop::collection::vec([-10i64..50, -10i64..50, -10i64..50], 40),
    ) {
        let soup = damaged(family, &delete, &flip, copy, &junk);
        // One part: decomposed always, so that every valid part has its pieces.
        let opts = LoadOptions { decompose: Decompose::Always, ..LoadOptions::default() };
        let Ok(loaded) = load_description(described(&soup), &opts) else {
            return Ok(());
        };
        if !loaded.is_valid() {
            return Ok(());
        }
        let part = &loaded.assembly.parts[0];
        let grid = &loaded.assembly.grid;
        // Integer input on a unit grid keeps its coordinates. The oracle reads the
        // surface the loader closed (repaired, loops capped, oriented): which loops to
        // cap is the loader's decision; that its pieces are exactly where that surface
        // winds at least once is what is checked.
        prop_assume!(grid.exp == 0);
        let Some(mesh) = &part.mesh else { return Ok(()) };
        let surface = TriSoup { points: mesh.vertices.clone(), triangles: mesh.triangles.clone() };
        let oracle = WindingOracle::new(&surface, 2);
        for q in samples {
            // Sample points on the half-integer lattice (doubled coordinates).
            let q = q.map(|c| 2 * c + 1);
            let Some(w) = oracle.winding(q) else { continue };
            let inside: usize = part.pieces.iter().filter(|p| strictly_inside(p, q)).count();
            prop_assert!(inside <= 1, "{q:?} strictly inside {inside} pieces");
            if inside == 1 {
                prop_assert!(w >= 1, "{q:?} inside a piece with winding number {w}");
            } else if w >= 1 {
                // Off every piece's interior with w >= 1: it must lie on a piece.
                let on = part.pieces.iter().any(|p| {
                    let x = Vec3::new(q[0], q[1], q[2]);
                    let two = Int::from(2);
                    p.facets().iter().all(|f| f.normal.dot(&x) * p.den() <= &two * &f.offset)
                });
                prop_assert!(on, "{q:?} has winding number {w} but lies in no piece");
            }
        }
    }
}
