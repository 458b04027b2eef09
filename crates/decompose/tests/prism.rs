//! Right prisms (a polygon with holes extruded straight) are cut in the plane of their
//! cap: checked against the exact verifier, with grid vertices, for tubes along tilted
//! axes, random star-shaped prisms and near-prisms that must take the general partition.

use apart_decompose::{decompose, verify, Decomposition, Options};
use apart_kernel::{Int, Vec3};
use apart_testkit::sheet_metal::extrusion;
use apart_testkit::solids::Lcg;
use proptest::prelude::*;

/// The points `a u + b v + h n` for `(a, b, h)`, as exact vectors.
fn frame(u: [i64; 3], v: [i64; 3], n: [i64; 3]) -> impl Fn(i64, i64, i64) -> [i64; 3] {
    move |a, b, h| [0, 1, 2].map(|k| a * u[k] + b * v[k] + h * n[k])
}

/// A tube of `m` facets around the axis `n` (the frame's third vector; `u × v` a
/// positive multiple of it), radii about 3e5 and 1e5 in the frame's units, `height`
/// high, turned by `phase` facets about the axis: outward triangles.
fn tube(
    m: usize,
    height: i64,
    phase: f64,
    at: &impl Fn(i64, i64, i64) -> [i64; 3],
) -> (Vec<[i64; 3]>, Vec<[u32; 3]>) {
    let ring = |r: f64| -> Vec<[i64; 2]> {
        (0..m)
            .map(|k| {
                let t = std::f64::consts::TAU * (k as f64 + phase) / m as f64;
                [(r * t.cos()).round() as i64, (r * t.sin()).round() as i64]
            })
            .collect()
    };
    let (outer, inner) = (ring(3e5), ring(1e5));
    let mut pts = Vec::new();
    for h in [0, height] {
        for p in outer.iter().chain(&inner) {
            pts.push(at(p[0], p[1], h));
        }
    }
    let m = m as u32;
    // Index of ring point k: outer 0..m, inner m..2m; +2m on the upper cap.
    let (o, i, up) = (|k: u32| k % m, |k: u32| m + k % m, 2 * m);
    let mut tris = Vec::new();
    for k in 0..m {
        let (a, b) = (k, k + 1);
        // Upper cap (counter-clockwise seen from +n), lower cap reversed.
        tris.push([o(a) + up, o(b) + up, i(b) + up]);
        tris.push([o(a) + up, i(b) + up, i(a) + up]);
        tris.push([o(a), i(b), o(b)]);
        tris.push([o(a), i(a), i(b)]);
        // Outer wall facing out, inner wall facing the axis.
        tris.push([o(a), o(b), o(b) + up]);
        tris.push([o(a), o(b) + up, o(a) + up]);
        tris.push([i(a), i(b) + up, i(b)]);
        tris.push([i(a), i(a) + up, i(b) + up]);
    }
    (pts, tris)
}

fn run(pts: &[[i64; 3]], tris: &[[u32; 3]]) -> Decomposition {
    let points: Vec<Vec3> = pts.iter().map(|p| Vec3::from_i64(*p)).collect();
    let d = decompose(&points, tris, &Options::default()).expect("decompose");
    verify(&points, tris, &d.pieces).expect("verify");
    d
}

/// Cut in the cap: no partition step, every piece on the grid.
fn assert_cap_path(d: &Decomposition) {
    assert_eq!(d.stats.splits, 0);
    assert!(d.pieces.iter().all(|p| p.den() == &Int::ONE));
}

#[test]
fn tubes_along_axes_and_tilted_axes_are_cut_in_their_caps() {
    let m = 48;
    for (u, v, n) in [
        ([1, 0, 0], [0, 1, 0], [0, 0, 1]),
        ([0, 1, 0], [0, 0, 1], [1, 0, 0]),
        // Tilted: (1, -1, 0) × (0, 0, 1) = (-1, -1, 0), so n = -(1, 1, 0) keeps u, v, n
        // right-handed.
        ([1, -1, 0], [0, 0, 1], [-1, -1, 0]),
        ([2, -1, 0], [0, 0, 1], [-1, -2, 0]),
    ] {
        let (pts, tris) = tube(m, 70_001, 0.0, &frame(u, v, n));
        let d = run(&pts, &tris);
        assert_cap_path(&d);
        // One wedge per facet: no two neighbouring wedges have a convex union.
        assert_eq!(d.pieces.len(), m, "axis {n:?}");
        assert_eq!(d.reflex_edges, m);
    }
}

#[test]
fn a_tube_with_one_vertex_off_its_cap_takes_the_partition() {
    let (mut pts, tris) = tube(48, 50_000, 0.0, &frame([1, 0, 0], [0, 1, 0], [0, 0, 1]));
    // An upper outer vertex raised: no longer a prism (the walls there lean).
    pts[2 * 48 + 5][2] += 7;
    let d = run(&pts, &tris);
    assert!(d.stats.splits > 0);
}

#[test]
fn blocky_prisms_keep_the_partitions_fewer_pieces() {
    // A comb's reflex vertices line up on its base line, where the partition cuts them
    // all at once (41 pieces); merging the cap's triangles could not (about 80).
    let teeth = 40;
    let mut comb: Vec<[i64; 2]> = vec![[0, 0], [20 * teeth - 10, 0]];
    for t in (0..teeth).rev() {
        let x = 20 * t;
        comb.extend([[x + 10, 40], [x, 40]]);
        if t > 0 {
            comb.extend([[x, 10], [x - 10, 10]]);
        }
    }
    let m = extrusion(&comb, 30);
    assert!(m.triangles.len() >= 256);
    let d = run(&m.points, &m.triangles);
    assert_eq!(d.pieces.len(), teeth as usize + 1);
}

/// A star-shaped polygon: `k` corners at increasing angles, random radii.
fn star(k: usize, seed: u64) -> Vec<[i64; 2]> {
    let mut rng = Lcg(seed);
    (0..k)
        .map(|i| {
            let t =
                std::f64::consts::TAU * (i as f64 + 0.5 * rng.below(100) as f64 / 100.0) / k as f64;
            let r = 2_000.0 + rng.below(8_000) as f64;
            [(r * t.cos()).round() as i64, (r * t.sin()).round() as i64]
        })
        .collect()
}

/// Right-handed frames `(u, v, n)`: the coordinate axes and tilted ones.
const FRAMES: [([i64; 3], [i64; 3], [i64; 3]); 5] = [
    ([1, 0, 0], [0, 1, 0], [0, 0, 1]),
    ([0, 1, 0], [0, 0, 1], [1, 0, 0]),
    ([0, 0, 1], [1, 0, 0], [0, 1, 0]),
    ([1, -1, 0], [0, 0, 1], [-1, -1, 0]),
    ([2, -1, 0], [0, 0, 1], [-1, -2, 0]),
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Tessellated tubes of any facet count, phase, height and frame: cut in the cap,
    /// exactly (verified), one grid wedge per facet.
    #[test]
    fn random_tubes_are_cut_in_their_caps(
        m in 32usize..300,
        phase in 0.0f64..1.0,
        height in 1i64..1_000_000,
        f in 0usize..FRAMES.len(),
    ) {
        let (u, v, n) = FRAMES[f];
        let (pts, tris) = tube(m, height, phase, &frame(u, v, n));
        let d = run(&pts, &tris);
        prop_assert_eq!(d.stats.splits, 0);
        prop_assert!(d.pieces.iter().all(|p| p.den() == &Int::ONE));
        prop_assert_eq!(d.pieces.len(), m);
    }

    /// Star-shaped prisms: the pieces are exact (verified) whichever way they are cut;
    /// when in the cap, they are on the grid and at most r + 1. (Merging an ear-clipped
    /// star's triangles leaves about 1.3 r pieces, so these take the partition.)
    #[test]
    fn star_prisms_are_cut_exactly(k in 3usize..160, seed in any::<u64>(), length in 1i64..5_000) {
        let m = extrusion(&star(k, seed), length);
        let d = run(&m.points, &m.triangles);
        if m.triangles.len() < 256 {
            prop_assert!(d.stats.splits > 0 || d.pieces.len() == 1);
        }
        if d.stats.splits == 0 {
            prop_assert!(d.pieces.iter().all(|p| p.den() == &Int::ONE));
            prop_assert!(d.pieces.len() <= d.reflex_edges + 1);
        }
    }
}
