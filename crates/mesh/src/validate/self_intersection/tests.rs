//! Tests of the self-intersection search against a brute-force oracle.

use super::faces::certified_groups;
use super::pieces::piece_boxes;
use super::planes::Flat;
use super::polygon::{segments_meet, simple_polygon_2d};
use super::*;
use apart_kernel::orient;
use apart_kernel::Aabb;
use apart_kernel::Sign;
use proptest::prelude::*;

fn mesh(vertices: Vec<[i64; 3]>, triangles: Vec<[u32; 3]>) -> Mesh {
    Mesh {
        source_faces: (0..triangles.len() as u32).collect(),
        source_vertices: (0..vertices.len() as u32).collect(),
        vertices,
        triangles,
    }
}

fn bvh(m: &Mesh) -> Bvh {
    Bvh::new(
        (0..m.triangles.len())
            .map(|t| Aabb::of(m.corners(t)))
            .collect(),
    )
}

/// The oracle, the former search without its hierarchy: every pair of triangles
/// whose boxes meet, tested exactly, in order. (The box filter is part of the
/// answer: on degenerate triangles `triangle_pair` may report pairs whose boxes
/// are apart.)
fn brute_force(m: &Mesh) -> Vec<(u32, u32, Contact)> {
    let n = m.triangles.len() as u32;
    let mut out = Vec::new();
    for t in 0..n {
        for u in t + 1..n {
            let (tt, uu) = (m.triangles[t as usize], m.triangles[u as usize]);
            let apart = !Aabb::of(m.corners(t as usize)).overlaps(&Aabb::of(m.corners(u as usize)));
            if apart {
                continue;
            }
            if let Some(c) = triangle_pair(&m.vertices, tt, uu) {
                out.push((t, u, c));
            }
        }
    }
    out
}

/// Compares the broad phases with the oracle (all pairs, and the first few), and
/// returns the number of exact tests.
fn agrees(m: &Mesh) -> Result<usize, TestCaseError> {
    let want = brute_force(m);
    let b = bvh(m);
    let (got, count, tests) = self_intersections_counted(m, &b, usize::MAX);
    prop_assert_eq!(&got, &want);
    prop_assert_eq!(count, want.len());
    let (first, count) = self_intersections(m, &b, 3);
    prop_assert_eq!(&first[..], &want[..want.len().min(3)]);
    prop_assert_eq!(count, want.len());
    Ok(tests)
}

/// A fan of `n` triangles around vertex 0: the apex at the centre of a circle of
/// radius `r` (or on it, like a tessellated cap fanned from one rim vertex), rim
/// points rounded to the grid, lifted by `lift(k)` off the plane.
fn fan(n: usize, r: f64, on_rim: bool, lift: impl Fn(usize) -> i64) -> Mesh {
    let mut v = vec![if on_rim { [r as i64, 0, 0] } else { [0, 0, 0] }];
    let ring = if on_rim { n + 2 } else { n };
    let first = usize::from(on_rim);
    for k in first..ring {
        let a = 2.0 * std::f64::consts::PI * k as f64 / ring as f64;
        v.push([
            (r * a.cos()).round() as i64,
            (r * a.sin()).round() as i64,
            lift(k),
        ]);
    }
    let rim = v.len() as u32 - 1;
    let mut t = Vec::new();
    for k in 1..=n as u32 {
        let next = if on_rim { k + 1 } else { k % rim + 1 };
        if next <= rim {
            t.push([0, k, next]);
        }
    }
    mesh(v, t)
}

/// A fan around the origin whose rim turns `turns` times (radius 1000 on the first
/// turn, 1200 on the second), every triangle from input face 0.
fn one_face_fan(rim: usize, turns: usize) -> Mesh {
    let mut v = vec![[0, 0, 0]];
    for k in 0..rim {
        let a = turns as f64 * std::f64::consts::TAU * k as f64 / rim as f64;
        let r = if k < rim / turns { 1000.0 } else { 1200.0 };
        v.push([
            (r * a.cos()).round() as i64,
            (r * a.sin()).round() as i64,
            0,
        ]);
    }
    let t: Vec<[u32; 3]> = (1..=rim as u32)
        .map(|k| [0, k, k % rim as u32 + 1])
        .collect();
    let mut m = mesh(v, t);
    m.source_faces.fill(0);
    m
}

#[test]
fn a_planar_face_is_certified_only_when_its_triangles_cover_it_once() {
    let certified = |m: &Mesh| {
        let distinct = vec![true; m.triangles.len()];
        let flats: Vec<Flat> = m.triangles.iter().map(|t| Flat::of(m, t)).collect();
        certified_groups(m, &distinct, &flats).len()
    };
    // One turn: a 2-chain bounded by a simple polygon, certified, nothing crosses.
    let m = one_face_fan(32, 1);
    assert_eq!(certified(&m), 1);
    agrees(&m).unwrap();
    // Two turns: the same edge rules hold, but the rim crosses itself and the
    // triangles overlap; not certified, and every pair is found as by the oracle.
    let m = one_face_fan(32, 2);
    assert_eq!(certified(&m), 0);
    agrees(&m).unwrap();
    assert!(!brute_force(&m).is_empty());
    // A triangle flipped, or an edge used twice: not certified.
    let mut m = one_face_fan(32, 1);
    m.triangles[3].swap(1, 2);
    assert_eq!(certified(&m), 0);
    let mut m = one_face_fan(32, 1);
    m.triangles[5] = m.triangles[4];
    assert_eq!(certified(&m), 0);
}

#[test]
fn a_star_cap_is_checked_in_near_linear_time() {
    // A prism over a non-convex star of 4000 sides: its caps' triangles span the
    // star (quadratically many meeting boxes); certified, they are not paired.
    let n = 4000usize;
    let mut v = Vec::new();
    for z in [0, 1000] {
        for k in 0..n {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            let r = if k % 2 == 0 { 1.0e6 } else { 0.7e6 };
            v.push([(r * a.cos()).round(), (r * a.sin()).round(), z as f64]);
        }
    }
    let mut faces: Vec<Vec<u32>> = vec![
        (0..n as u32).rev().collect(),
        (n as u32..2 * n as u32).collect(),
    ];
    for k in 0..n as u32 {
        let j = (k + 1) % n as u32;
        faces.push(vec![k, j, j + n as u32, k + n as u32]);
    }
    let raw = apart_formats::RawObject {
        name: None,
        vertices: v,
        faces: apart_formats::Polygons::from(faces),
    };
    let (m, problems) = Mesh::from_raw(&raw, &apart_kernel::Grid::unit(40));
    let m = m.unwrap();
    assert!(problems.is_empty(), "{problems:?}");
    let (found, count, tests) = self_intersections_counted(&m, &bvh(&m), 10);
    assert!(found.is_empty() && count == 0, "{found:?}");
    assert!(tests < 40 * n, "{tests} exact tests");
}

#[test]
fn large_fans_need_few_exact_tests() {
    for on_rim in [false, true] {
        for lift in [0, 1] {
            let n = 3000;
            let m = fan(n, 1e6, on_rim, |k| lift * ((k as i64 * 7919) % 13));
            let (found, count, tests) = self_intersections_counted(&m, &bvh(&m), 10);
            assert!(found.is_empty() && count == 0, "{on_rim} {lift}: {found:?}");
            // n²/2 = 4.5 million pairs share the apex; a few per triangle are tested.
            assert!(tests < 20 * n, "{on_rim} {lift}: {tests} exact tests");
        }
    }
}

#[test]
fn thin_triangles_are_boxed_in_pieces_and_still_found() {
    // The radial slivers of a fan are cut into slab boxes; triangles laid across the
    // fan in its plane and through it are found exactly as by the oracle.
    let mut m = fan(120, 5000.0, false, |_| 0);
    let b = bvh(&m);
    let cut = (0..m.triangles.len())
        .filter(|&t| piece_boxes(&m, t, &b).len() > 1)
        .count();
    assert!(cut > 60, "{cut} of 120 slivers cut");
    let nv = m.vertices.len() as u32;
    m.vertices.extend([
        [-4000, 300, 0],
        [4000, 700, 0],
        [0, 2500, -50],
        [0, 2400, 60],
    ]);
    m.triangles
        .extend([[nv, nv + 1, 7], [nv + 2, nv + 3, 40], [nv, nv + 3, 90]]);
    let found = agrees(&m).unwrap();
    assert!(found > 0);
    let (got, count, _) = self_intersections_counted(&m, &bvh(&m), usize::MAX);
    assert!(count > 0 && got.len() == count);
}

fn point(r: i64) -> impl Strategy<Value = [i64; 3]> {
    [-r..=r, -r..=r, -r..=r]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// Fans (flat, or with a wavy rim), with triangles added across them: some
    /// in their plane, some through the apex, some on rim vertices.
    #[test]
    fn fans_with_crossing_triangles_match_the_oracle(
        n in 3usize..90,
        on_rim in any::<bool>(),
        wavy in 0i64..3,
        extra in prop::collection::vec(
            (0u32..1000, 0u32..1000, point(1200), any::<bool>(), 0u8..3), 0..6),
    ) {
        let mut m = fan(n, 1000.0, on_rim, |k| wavy * ((k as i64 * 31) % 5 - 2));
        let nv = m.vertices.len() as u32;
        for (a, b, mut p, flat, kind) in extra {
            if flat {
                p[2] = 0;
            }
            m.vertices.push(p);
            let q = m.vertices.len() as u32 - 1;
            let (a, b) = (a % nv, b % nv);
            let tri = match kind {
                0 => [0, a, q],         // through the apex
                1 => [a, b, q],         // on two fan vertices
                _ => [a, q, (a + 1) % nv], // on a rim edge
            };
            if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                m.triangles.push(tri);
            }
        }
        let tests = agrees(&m)?;
        let _ = tests;
    }

    /// Flat fans that are one input face (certified, out of the hierarchy), with a
    /// second fan-face standing across the first or not, and triangles added on
    /// their vertices, rim sides and planes: every pair as by the oracle.
    #[test]
    fn certified_faces_with_crossing_triangles_match_the_oracle(
        n in 16usize..60,
        on_rim in any::<bool>(),
        across in prop::option::of(-1200i64..1200),
        extra in prop::collection::vec(
            (0u32..1000, 0u32..1000, point(1200), 0u8..4, 0u8..3), 0..8),
    ) {
        let mut m = fan(n, 1000.0, on_rim, |_| 0);
        m.source_faces.fill(0);
        let nv = m.vertices.len() as u32;
        if let Some(y) = across {
            // The same fan stood up in the plane y = `y`.
            let base = m.vertices.len() as u32;
            let stood: Vec<[i64; 3]> =
                m.vertices[..nv as usize].iter().map(|p| [p[0], y, p[1]]).collect();
            m.vertices.extend(stood);
            let tris: Vec<[u32; 3]> = m.triangles.iter().map(|t| t.map(|v| v + base)).collect();
            m.source_faces.extend(std::iter::repeat_n(1, tris.len()));
            m.triangles.extend(tris);
        }
        let all = m.vertices.len() as u32;
        for (k, (a, b, mut p, plane, kind)) in extra.into_iter().enumerate() {
            match plane {
                0 => p[2] = 0,
                1 => p[2] = p[2].signum(),
                _ => {}
            }
            m.vertices.push(p);
            let q = m.vertices.len() as u32 - 1;
            let (a, b) = (a % all, b % all);
            let tri = match kind {
                0 => [a, b, q],
                1 => [a, q, (a + 1) % all],
                _ => [0, a, q],
            };
            if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                m.triangles.push(tri);
                m.source_faces.push(2 + k as u32);
            }
        }
        let distinct: Vec<bool> =
            m.triangles.iter().map(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]).collect();
        let flats: Vec<Flat> = m.triangles.iter().map(|t| Flat::of(&m, t)).collect();
        let faces = certified_groups(&m, &distinct, &flats).len();
        prop_assert_eq!(faces, 1 + usize::from(across.is_some()));
        agrees(&m)?;
    }

    /// Polygons on a small grid (touching, folding back, crossing, collinear), and
    /// thin stars: simplicity as decided by every pair of sides.
    #[test]
    fn simple_polygons_match_every_pair_of_sides(
        pts in prop::collection::vec([-4i64..=4, -4i64..=4], 3..12),
        star in prop::option::of((8usize..200, 0.05f64..0.95, any::<u8>())),
    ) {
        let q: Vec<[i64; 2]> = match star {
            None => pts,
            Some((n, inner, bend)) => {
                let mut q: Vec<[i64; 2]> = (0..2 * n)
                    .map(|k| {
                        let a = std::f64::consts::PI * k as f64 / n as f64;
                        let r = if k % 2 == 0 { 1.0e6 } else { 1.0e6 * inner };
                        [(r * a.cos()).round() as i64, (r * a.sin()).round() as i64]
                    })
                    .collect();
                // Sometimes pull a tip across its neighbours.
                if bend % 3 == 0 {
                    let k = 2 * (bend as usize % n);
                    q[k] = [-q[k][0] / 2, -q[k][1] / 2];
                }
                q
            }
        };
        let n = q.len();
        let mut want = true;
        for i in 0..n {
            for j in i + 1..n {
                let (a, b) = (&q[i], &q[(i + 1) % n]);
                let (c, d) = (&q[j], &q[(j + 1) % n]);
                let bad = if j == i + 1 || (i == 0 && j == n - 1) {
                    let (x, m, y) = if j == i + 1 { (a, b, d) } else { (c, d, b) };
                    let back = [0, 1].map(|k| (x[k] - m[k]) as i128 * (y[k] - m[k]) as i128);
                    orient::orient2d(x, m, y) == Sign::Zero && back[0] + back[1] > 0
                } else {
                    segments_meet(a, b, c, d)
                };
                want &= !bad;
            }
        }
        prop_assert_eq!(simple_polygon_2d(&q), want);
    }

    /// Random triangles on a tiny grid: coplanar, collinear and coincident
    /// vertices, repeated indices, doubled faces, big stars.
    #[test]
    fn degenerate_meshes_match_the_oracle(
        verts in prop::collection::vec(point(2), 1..12),
        tris in prop::collection::vec([0u32..12, 0u32..12, 0u32..12], 0..70),
    ) {
        let nv = verts.len() as u32;
        // triangle_pair takes three distinct indices (meshes never repeat one).
        let tris = tris
            .into_iter()
            .map(|t| t.map(|x| x % nv))
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect();
        agrees(&mesh(verts, tris))?;
    }

    /// Big stars on a tiny grid around one vertex (the direction-box path).
    #[test]
    fn big_degenerate_stars_match_the_oracle(
        verts in prop::collection::vec(point(3), 2..40),
        tris in prop::collection::vec((0u32..40, 0u32..40), 25..80),
    ) {
        let nv = verts.len() as u32;
        let tris = tris
            .into_iter()
            .map(|(a, b)| [0, 1 + a % (nv - 1), b % nv])
            .filter(|t| t[2] != 0 && t[1] != t[2])
            .collect();
        agrees(&mesh(verts, tris))?;
    }
}
