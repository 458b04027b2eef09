//! Repair of CAD-export defects, checked against the answers the generators of
//! apart-testkit are built to have (exact volumes, numbers of injected defects), never
//! against the repair's own output; and fuzzed: garbage never panics and repair ends.

use apart_formats::{read_bytes, Format, Polygons, RawObject};
use apart_kernel::orient::collinear;
use apart_kernel::{Grid, Int};
use apart_mesh::repair::{bodies, repair, RepairOptions, RepairReport};
use apart_mesh::validate::validate;
use apart_mesh::{Mesh, Problem};
use apart_testkit::defects::*;
use apart_testkit::Soup;
use proptest::prelude::*;

fn raw(soup: &Soup) -> RawObject {
    RawObject {
        name: None,
        vertices: soup.vertices.clone(),
        faces: Polygons::from(soup.faces.clone()),
    }
}

fn snap(soup: &Soup, grid: &Grid) -> Mesh {
    let (m, p) = Mesh::from_raw(&raw(soup), grid);
    assert!(p.is_empty(), "{p:?}");
    m.unwrap()
}

fn errors(p: &[Problem]) -> Vec<&Problem> {
    p.iter().filter(|p| p.is_error()).collect()
}

/// Mesh invariants that every repair must keep.
fn check_invariants(m: &Mesh, input_faces: usize) {
    assert_eq!(m.triangles.len(), m.source_faces.len());
    assert_eq!(m.vertices.len(), m.source_vertices.len());
    let mut used = vec![false; m.vertices.len()];
    for (t, tri) in m.triangles.iter().enumerate() {
        for &v in tri {
            used[v as usize] = true;
        }
        let [a, b, c] = m.corners(t);
        assert!(!collinear(a, b, c), "zero-area triangle {t} left");
        assert!((m.source_faces[t] as usize) < input_faces);
    }
    assert!(used.iter().all(|u| *u), "unused vertex left");
}

/// The bodies of `m` partition its triangles: every triangle (as grid points, with its
/// source face) lands in exactly one body.
fn check_bodies(m: &Mesh) {
    let key = |m: &Mesh, t: usize| (m.corners(t).map(|p| *p), m.source_faces[t]);
    let mut all: Vec<_> = (0..m.triangles.len()).map(|t| key(m, t)).collect();
    let parts = bodies(m);
    let mut got: Vec<_> = parts
        .iter()
        .flat_map(|b| (0..b.triangles.len()).map(move |t| key(b, t)))
        .collect();
    all.sort_unstable();
    got.sort_unstable();
    assert_eq!(all, got);
    for b in &parts {
        assert_eq!(b.vertices.len(), b.source_vertices.len());
        assert!(!b.triangles.is_empty());
    }
}

/// Snaps on the unit grid, repairs, checks the report, validates without error and
/// checks the exact volume; returns the repaired mesh.
fn repaired(soup: &Soup, expect: RepairReport, volume: i128) -> Mesh {
    let grid = Grid::unit(30);
    let mut m = snap(soup, &grid);
    let r = repair(&mut m, &RepairOptions::default());
    assert_eq!(r, expect, "report: {r}");
    check_invariants(&m, soup.faces.len());
    assert_eq!(m.volume6(), Int::from(6 * volume));
    let (info, p) = validate(&mut m.clone(), &grid);
    assert!(errors(&p).is_empty(), "{p:?}");
    assert!(!info.flipped, "repair left a shell inside out");
    // Repairing again finds nothing.
    let mut again = m.clone();
    assert_eq!(
        repair(&mut again, &RepairOptions::default()),
        RepairReport::default()
    );
    m
}

fn vol(e: [u64; 3]) -> i128 {
    e.iter().map(|&x| x as i128).product()
}

#[test]
fn seams_are_split() {
    let div = [[2, 3], [1, 1], [4, 1], [1, 2], [3, 3], [1, 5]];
    let e = [0, 1, 2].map(|k| 2 * seamed_box_extent_unit(&div, k));
    let soup = seamed_box(e, div);
    // Unrepaired, validation sees open boundaries.
    let grid = Grid::unit(30);
    let (_, p) = validate(&mut snap(&soup, &grid), &grid);
    assert!(p.iter().any(|p| p.message.contains("open boundary")));
    let n = seamed_box_tjunctions(&div);
    assert!(n > 0);
    let m = repaired(
        &soup,
        RepairReport {
            tjunctions: n,
            ..Default::default()
        },
        vol(e),
    );
    // Split triangles keep their source face: each lies in its source face's plane.
    for (t, &f) in m.source_faces.iter().enumerate() {
        let src = &soup.faces[f as usize];
        let p = |i: u32| soup.vertices[i as usize];
        let [a, b, c] = [p(src[0]), p(src[1]), p(src[2])];
        // The plane of an axis-aligned box face: the coordinate all three share.
        let axis = (0..3).find(|&k| a[k] == b[k] && b[k] == c[k]).unwrap();
        for q in m.corners(t) {
            assert_eq!(q[axis] as f64, a[axis]);
        }
    }
}

#[test]
fn float32_rounded_stl_with_seams() {
    let div = [[1, 1], [3, 2], [1, 1], [2, 1], [1, 1], [4, 4]];
    let e = [0, 1, 2].map(|k| 5 * seamed_box_extent_unit(&div, k));
    let soup = decimal_seamed_box(e, div);
    let mut stl = Vec::new();
    soup.write_binary_stl(&mut stl).unwrap();
    let objects = read_bytes(&stl, Format::Stl, None).unwrap();
    let grid = Grid { exp: -10, bits: 30 };
    let (m, p) = Mesh::from_raw(&objects[0], &grid);
    assert!(p.is_empty(), "{p:?}");
    let mut m = m.unwrap();
    let r = repair(&mut m, &RepairOptions::default());
    assert_eq!(
        r,
        RepairReport {
            tjunctions: seamed_box_tjunctions(&div),
            ..Default::default()
        }
    );
    let (lo, hi) = decimal_seamed_box_corners(e);
    let s = |v: f64| (v * 1024.0).round() as i128;
    let expect: i128 = (0..3).map(|k| s(hi[k]) - s(lo[k])).product();
    assert_eq!(m.volume6(), Int::from(6 * expect));
    let (_, p) = validate(&mut m, &grid);
    assert!(errors(&p).is_empty(), "{p:?}");
}

#[test]
fn duplicates_and_flips() {
    let e = [3, 4, 5];
    repaired(
        &duplicated_faces(e, &[0, 5, 5, 11]),
        RepairReport {
            duplicate_faces: 4,
            ..Default::default()
        },
        vol(e),
    );
    repaired(
        &flipped_faces(e, &[1, 6, 7]),
        RepairReport {
            flipped_faces: 3,
            ..Default::default()
        },
        vol(e),
    );
    repaired(
        &inside_out_box(e),
        RepairReport {
            flipped_shells: 1,
            ..Default::default()
        },
        vol(e),
    );
    // An inside-out box with two faces the right way: one shell and two faces.
    let mut soup = inside_out_box(e);
    soup.faces[3].reverse();
    soup.faces[8].reverse();
    repaired(
        &soup,
        RepairReport {
            flipped_shells: 1,
            flipped_faces: 2,
            ..Default::default()
        },
        vol(e),
    );
}

#[test]
fn a_flipped_face_on_a_seam_counts_once() {
    // The coarse -x face (2 triangles) meets split faces: each of its triangles is
    // split at the seam vertices, and the reversed one still counts as one face.
    let div = [[1, 1], [3, 2], [2, 5], [4, 1], [1, 3], [2, 2]];
    let e = [0, 1, 2].map(|k| seamed_box_extent_unit(&div, k));
    let mut soup = seamed_box(e, div);
    soup.faces[1].reverse();
    repaired(
        &soup,
        RepairReport {
            tjunctions: seamed_box_tjunctions(&div),
            flipped_faces: 1,
            ..Default::default()
        },
        vol(e),
    );
}

#[test]
fn a_duplicated_face_with_its_flipped_copy_cancels_and_is_closed_again() {
    // A face present three times, once the other way: one duplicate, one cancelled
    // pair, and the hole left behind is closed by one triangle.
    let e = [2, 2, 2];
    let mut soup = duplicated_faces(e, &[4]);
    let mut f = soup.faces[4].clone();
    f.reverse();
    soup.faces.push(f);
    repaired(
        &soup,
        RepairReport {
            duplicate_faces: 1,
            cancelled_faces: 2,
            holes_closed: 1,
            hole_triangles: 1,
            ..Default::default()
        },
        vol(e),
    );
}

#[test]
fn holes_of_every_size_up_to_the_limit() {
    for k in 3..=20 {
        let e = [40, 30, 7];
        repaired(
            &holed_box(e, k),
            RepairReport {
                holes_closed: 1,
                hole_triangles: k - 2,
                ..Default::default()
            },
            vol(e),
        );
        // Beyond the limit the hole stays, and validation says so.
        let grid = Grid::unit(30);
        let mut m = snap(&holed_box(e, k), &grid);
        let r = repair(
            &mut m,
            &RepairOptions {
                max_hole_edges: k - 1,
            },
        );
        assert_eq!(r.holes_closed, 0);
        let (_, p) = validate(&mut m, &grid);
        assert!(p.iter().any(|p| p.message.contains("open boundary")));
    }
}

#[test]
fn shared_walls_cancel() {
    let m = repaired(
        &boxes_sharing_a_wall(3),
        RepairReport {
            cancelled_faces: 4,
            ..Default::default()
        },
        2 * 27,
    );
    assert_eq!(bodies(&m).len(), 1);
}

#[test]
fn several_bodies() {
    let (a, b) = ([2, 3, 4], [5, 1, 1]);
    let m = repaired(
        &two_boxes(a, b, 3),
        RepairReport::default(),
        vol(a) + vol(b),
    );
    let parts = bodies(&m);
    assert_eq!(parts.len(), 2);
    assert_eq!(parts[0].volume6(), Int::from(6 * vol(a)));
    assert_eq!(parts[1].volume6(), Int::from(6 * vol(b)));
    assert_eq!(parts[0].triangles.len() + parts[1].triangles.len(), 24);
    // Source faces are kept: the first body has the first 12 faces.
    assert_eq!(parts[0].source_faces, (0..12).collect::<Vec<u32>>());
    assert_eq!(parts[1].source_faces, (12..24).collect::<Vec<u32>>());
    for p in &parts {
        check_invariants(p, 24);
    }

    // Two cubes sharing an edge: valid as one solid, two bodies.
    let m = repaired(&boxes_sharing_an_edge(2), RepairReport::default(), 16);
    let parts = bodies(&m);
    assert_eq!(parts.len(), 2);
    assert!(parts.iter().all(|p| p.volume6() == Int::from(48)));

    // A single body comes back whole.
    let m = repaired(
        &box_soup([0.0; 3], [1.0, 2.0, 3.0]),
        RepairReport::default(),
        6,
    );
    assert_eq!(bodies(&m), vec![m.clone()]);
}

#[test]
fn cavities_face_inward_and_stay_with_their_solid() {
    let (outer, lo, hi) = ([6, 6, 6], [1, 2, 3], [4, 5, 5]);
    let v = vol(outer) - 3 * 3 * 2;
    let m = repaired(
        &hollow_box(outer, lo, hi, false),
        RepairReport::default(),
        v,
    );
    assert_eq!(bodies(&m).len(), 1);
    let m = repaired(
        &hollow_box(outer, lo, hi, true),
        RepairReport {
            flipped_shells: 1,
            ..Default::default()
        },
        v,
    );
    assert_eq!(bodies(&m), vec![m.clone()]);

    // A hollow box, a plain box and another hollow box: three bodies, each cavity with
    // its own solid, in the order of their first faces.
    let mut soup = hollow_box(outer, lo, hi, true);
    soup.append(&box_soup([10.0, 0.0, 0.0], [12.0, 2.0, 2.0]));
    soup.append(&hollow_box(outer, lo, hi, false).translated([20.0, 0.0, 0.0]));
    let m = repaired(
        &soup,
        RepairReport {
            flipped_shells: 1,
            ..Default::default()
        },
        2 * v + 8,
    );
    let parts = bodies(&m);
    let vols: Vec<Int> = parts.iter().map(Mesh::volume6).collect();
    assert_eq!(vols, [v, 8, v].map(|x| Int::from(6 * x)));
    assert_eq!(parts[0].triangles.len(), 24);
    assert_eq!(parts[1].triangles.len(), 12);
}

#[test]
fn a_genuine_fold_is_not_hidden() {
    let soup = self_crossing_fold();
    let grid = Grid::unit(30);
    let mut m = snap(&soup, &grid);
    let before = m.clone();
    let r = repair(&mut m, &RepairOptions::default());
    assert_eq!(r, RepairReport::default());
    assert_eq!(m, before);
    let (info, p) = validate(&mut m, &grid);
    assert!(info.self_intersections > 0);
    assert!(p
        .iter()
        .any(|p| p.is_error() && p.message.contains("self-intersection")));
}

#[test]
fn huge_coordinates_stay_exact() {
    // A seamed box with 2^45-scale extents on a 53-bit grid, far from the origin.
    let div = [[1, 1], [2, 1], [1, 1], [1, 1], [1, 3], [1, 1]];
    let s = 1u64 << 45;
    let e = [0, 1, 2].map(|k| s * seamed_box_extent_unit(&div, k));
    let soup =
        seamed_box(e, div).translated([-((1u64 << 50) as f64), 3.0 * (1u64 << 49) as f64, 0.0]);
    let grid = Grid::unit(53);
    let mut m = snap(&soup, &grid);
    let r = repair(&mut m, &RepairOptions::default());
    assert_eq!(r.tjunctions, seamed_box_tjunctions(&div));
    let expect = Int::from(6) * Int::from(e[0]) * Int::from(e[1]) * Int::from(e[2]);
    assert_eq!(m.volume6(), expect);
    let (_, p) = validate(&mut m, &grid);
    assert!(errors(&p).is_empty(), "{p:?}");
}

/// True when the segment `p q` lies along an edge of the box `0..e`.
fn on_box_edge(p: [f64; 3], q: [f64; 3], e: [u64; 3]) -> bool {
    let extreme = |k: usize, v: f64| v == 0.0 || v == e[k] as f64;
    (0..3).filter(|&k| p[k] == q[k] && extreme(k, p[k])).count() >= 2
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Random seamed boxes with random duplicated and flipped faces (anywhere, seams
    /// included: a face split at a seam still counts once) and an optional
    /// one-triangle hole away from the seams and from the other defects, so that each
    /// defect is repaired exactly once.
    #[test]
    fn random_defects(div in proptest::array::uniform6(proptest::array::uniform2(1u32..6)),
                      scale in 1u64..4,
                      picks in proptest::collection::vec(any::<u32>(), 0..12),
                      hole in proptest::option::of(any::<u32>())) {
        let e = [0, 1, 2].map(|k| scale * seamed_box_extent_unit(&div, k));
        let mut soup = seamed_box(e, div);
        let p = |i: u32| soup.vertices[i as usize];
        let n = soup.faces.len();
        let mut chosen: Vec<usize> = picks.iter().map(|&x| x as usize % n).collect();
        chosen.sort_unstable();
        chosen.dedup();
        let key = |t: usize| {
            let mut v: Vec<[i64; 3]> = soup.faces[t].iter().map(|&i| p(i).map(|c| c as i64)).collect();
            v.sort_unstable();
            v
        };
        // The hole: a triangle with no edge on a box edge (never split); flips and
        // duplicates share no vertex with it.
        let inner: Vec<usize> = (0..n)
            .filter(|&t| {
                let f = &soup.faces[t];
                (0..3).all(|k| !on_box_edge(p(f[k]), p(f[(k + 1) % 3]), e))
            })
            .collect();
        let mut expect = RepairReport { tjunctions: seamed_box_tjunctions(&div), ..Default::default() };
        let mut removed = None;
        if let (Some(h), false) = (hole, inner.is_empty()) {
            let h = inner[h as usize % inner.len()];
            let hv = key(h);
            chosen.retain(|&t| key(t).iter().all(|v| !hv.contains(v)));
            removed = Some(h);
            expect.holes_closed = 1;
            expect.hole_triangles = 1;
        }
        let total = soup.faces.len();
        let (flips, dups) = chosen.split_at(chosen.len() / 2);
        prop_assume!(2 * flips.len() < total);
        for &t in flips {
            soup.faces[t].reverse();
        }
        for &t in dups {
            let f = soup.faces[t].clone();
            soup.faces.push(f);
        }
        expect.flipped_faces = flips.len();
        expect.duplicate_faces = dups.len();
        if let Some(h) = removed {
            soup.faces.remove(h);
        }
        repaired(&soup, expect, vol(e));
    }

    /// Disjoint boxes in a row, some hollow, each shell written either way: every shell
    /// ends up outward (cavities inward), and bodies finds every box with its cavity.
    #[test]
    fn random_nesting(spec in proptest::collection::vec((any::<bool>(), any::<bool>(), any::<bool>()), 1..5)) {
        let mut soup = Soup::default();
        let mut expect_flips = 0;
        let mut vols = Vec::new();
        for (i, &(hollow, outer_out, cavity_in)) in spec.iter().enumerate() {
            let x = 10.0 * i as f64;
            let mut b = box_soup([x, 0.0, 0.0], [x + 6.0, 6.0, 6.0]);
            if !outer_out {
                b.faces.iter_mut().for_each(|f| f.reverse());
                expect_flips += 1;
            }
            let mut v = 216;
            if hollow {
                let mut c = box_soup([x + 1.0, 1.0, 1.0], [x + 3.0, 4.0, 5.0]);
                if !cavity_in {
                    expect_flips += 1;
                } else {
                    c.faces.iter_mut().for_each(|f| f.reverse());
                }
                b.append(&c);
                v -= 24;
            }
            soup.append(&b);
            vols.push(v);
        }
        let m = repaired(&soup, RepairReport { flipped_shells: expect_flips, ..Default::default() },
                         vols.iter().sum());
        let got: Vec<Int> = bodies(&m).iter().map(Mesh::volume6).collect();
        let want: Vec<Int> = vols.iter().map(|v| Int::from(6 * v)).collect();
        prop_assert_eq!(got, want);
    }

    /// Garbage triangles on a small lattice (so that coincidences, collinear points and
    /// T-junctions are frequent): repair never panics, ends, and leaves a mesh whose
    /// invariants hold; validation and bodies then run without panicking.
    #[test]
    fn fuzz_garbage(points in proptest::collection::vec(proptest::array::uniform3(0i32..5), 3..24),
                    tris in proptest::collection::vec(proptest::array::uniform3(any::<u16>()), 0..60),
                    holes in 0usize..8,
                    huge in any::<bool>()) {
        let n = points.len();
        // With `huge`, the lattice is spread over 52-bit coordinates (the exact
        // predicates' slow paths).
        let (step, shift) = if huge { ((1i64 << 48) as f64, -((1i64 << 50) as f64)) } else { (1.0, 0.0) };
        let soup = Soup {
            vertices: points.iter().map(|p| p.map(|c| c as f64 * step + shift)).collect(),
            faces: tris.iter().map(|t| t.iter().map(|&i| i as u32 % n as u32).collect()).collect(),
        };
        let grid = Grid::unit(if huge { 53 } else { 30 });
        let (m, _) = Mesh::from_raw(&raw(&soup), &grid);
        let mut m = m.unwrap();
        check_bodies(&m); // bodies also takes unrepaired meshes
        let _ = repair(&mut m, &RepairOptions { max_hole_edges: holes });
        check_invariants(&m, soup.faces.len());
        check_bodies(&m);
        let _ = validate(&mut m, &grid);
    }

    /// Mutated defect meshes: random triangles of a seamed box dropped, reversed or
    /// repeated. Repair ends and keeps the mesh invariants; bodies and validation run.
    #[test]
    fn fuzz_mutated(div in proptest::array::uniform6(proptest::array::uniform2(1u32..4)),
                    ops in proptest::collection::vec((0u8..3, any::<u32>()), 0..20)) {
        let e = [0, 1, 2].map(|k| seamed_box_extent_unit(&div, k));
        let mut soup = seamed_box(e, div);
        for (op, x) in ops {
            let n = soup.faces.len();
            if n == 0 {
                break;
            }
            let t = x as usize % n;
            match op {
                0 => { soup.faces.remove(t); }
                1 => soup.faces[t].reverse(),
                _ => { let f = soup.faces[t].clone(); soup.faces.push(f); }
            }
        }
        let grid = Grid::unit(30);
        let (m, _) = Mesh::from_raw(&raw(&soup), &grid);
        let mut m = m.unwrap();
        let _ = repair(&mut m, &RepairOptions::default());
        check_invariants(&m, soup.faces.len());
        check_bodies(&m);
        let _ = validate(&mut m, &grid);
    }
}
