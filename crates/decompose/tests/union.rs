//! The union solid `{w >= 1}` of closed self-crossing surfaces: volumes against hand
//! formulas and a voxel oracle, point membership against the shapes' definitions, and
//! independent checks that the pieces are convex with disjoint interiors.

mod common;

use apart_decompose::{decompose, decompose_union, DecomposeError, Decomposition, Options};
use apart_kernel::{Int, Rational, Sign, Vec3};
use apart_pieces::interference::interiors_disjoint;
use apart_pieces::{Containment, Polytope};
use apart_testkit::shapes;
use proptest::prelude::*;
use std::collections::HashMap;

/// A triangle soup built from convex polygons with their intended outward normals.
#[derive(Default, Clone)]
struct Mesh {
    points: Vec<Vec3>,
    raw: Vec<[i64; 3]>,
    tris: Vec<[u32; 3]>,
    /// Weld equal points of different shells too (always within a shell).
    weld: bool,
    ids: HashMap<[i64; 3], u32>,
}

impl Mesh {
    fn welded() -> Mesh {
        Mesh {
            weld: true,
            ..Mesh::default()
        }
    }

    fn id(&mut self, p: [i64; 3]) -> u32 {
        if let Some(&i) = self.ids.get(&p) {
            return i;
        }
        let i = self.points.len() as u32;
        self.points.push(Vec3::from_i64(p));
        self.raw.push(p);
        self.ids.insert(p, i);
        i
    }

    /// Starts a new shell: unless welding globally, its points get fresh indices.
    fn shell(&mut self) {
        if !self.weld {
            self.ids.clear();
        }
    }

    /// A convex polygon (corners in order), fanned, oriented so that its normal points
    /// along `out`.
    fn poly(&mut self, corners: &[[i64; 3]], out: [i64; 3]) {
        let [a, b, c] = [0, 1, 2].map(|k| corners[k].map(Int::from));
        let (u, v) = (
            [0, 1, 2].map(|k| &b[k] - &a[k]),
            [0, 1, 2].map(|k| &c[k] - &a[k]),
        );
        let n = Vec3::from_ints(u.clone()).cross(&Vec3::from_ints(v));
        let flip = n.dot(&Vec3::from_i64(out)) < Int::ZERO;
        let ids: Vec<u32> = corners.iter().map(|&p| self.id(p)).collect();
        for k in 1..ids.len() - 1 {
            if flip {
                self.tris.push([ids[0], ids[k + 1], ids[k]]);
            } else {
                self.tris.push([ids[0], ids[k], ids[k + 1]]);
            }
        }
    }

    /// The box `[lo, hi]`, outward (or inward).
    fn cuboid(&mut self, lo: [i64; 3], hi: [i64; 3], outward: bool) {
        self.shell();
        let s = if outward { 1 } else { -1 };
        for a in 0..3 {
            let (b, c) = ((a + 1) % 3, (a + 2) % 3);
            for (val, dir) in [(lo[a], -1), (hi[a], 1)] {
                let corner = |x: i64, y: i64| {
                    let mut p = [0; 3];
                    p[a] = val;
                    p[b] = x;
                    p[c] = y;
                    p
                };
                let mut out = [0; 3];
                out[a] = dir * s;
                self.poly(
                    &[
                        corner(lo[b], lo[c]),
                        corner(hi[b], lo[c]),
                        corner(hi[b], hi[c]),
                        corner(lo[b], hi[c]),
                    ],
                    out,
                );
            }
        }
    }
}

fn volume(pieces: &[Polytope]) -> Rational {
    let mut total = Rational::zero();
    for p in pieces {
        total = &total + &p.volume();
    }
    total
}

/// Independent checks: every piece convex and full-dimensional (each facet cycle on its
/// plane and strictly convex, every vertex on the inner side of every facet), interiors
/// pairwise disjoint (exact separating-axis test of the pieces crate).
fn check_pieces(pieces: &[Polytope]) {
    for (i, p) in pieces.iter().enumerate() {
        assert!(p.volume6() > Int::ZERO, "piece {i} is flat");
        let v = p.vertices();
        for f in p.facets() {
            assert!(f.cycle.len() >= 3);
            for (k, &a) in f.cycle.iter().enumerate() {
                let b = f.cycle[(k + 1) % f.cycle.len()];
                let c = f.cycle[(k + 2) % f.cycle.len()];
                assert_eq!(f.normal.dot(&v[a as usize]), f.offset, "piece {i}");
                let (pa, pb, pc) = (&v[a as usize], &v[b as usize], &v[c as usize]);
                let turn = pb.sub(pa).cross(&pc.sub(pb)).dot(&f.normal);
                assert!(turn > Int::ZERO, "piece {i}: facet not strictly convex");
            }
            for x in v {
                assert!(f.normal.dot(x) <= f.offset, "piece {i} is not convex");
            }
        }
    }
    for i in 0..pieces.len() {
        for j in i + 1..pieces.len() {
            assert!(
                interiors_disjoint(&pieces[i], &pieces[j]),
                "pieces {i} and {j} overlap"
            );
        }
    }
}

fn run(m: &Mesh) -> Decomposition {
    let d = decompose_union(&m.points, &m.tris, &Options::default()).expect("decompose_union");
    check_pieces(&d.pieces);
    d
}

/// Checks, at the centre of every unit voxel of `[lo, hi)` (never on the surface), that
/// the point is in some closed piece and interior to at most one when `inside` says so,
/// and touches no piece otherwise.
fn check_voxel_centres(
    pieces: &[Polytope],
    lo: [i64; 3],
    hi: [i64; 3],
    inside: impl Fn([i64; 3]) -> bool,
) {
    for x in lo[0]..hi[0] {
        for y in lo[1]..hi[1] {
            for z in lo[2]..hi[2] {
                let c = [2 * x as i128 + 1, 2 * y as i128 + 1, 2 * z as i128 + 1];
                let loc: Vec<Containment> =
                    pieces.iter().map(|p| common::locate(p, &c, 2)).collect();
                let interior = loc.iter().filter(|c| **c == Containment::Inside).count();
                let closed = loc.iter().filter(|c| **c != Containment::Outside).count();
                if inside([x, y, z]) {
                    assert!(closed >= 1 && interior <= 1, "voxel {x} {y} {z}");
                } else {
                    assert_eq!(closed, 0, "voxel {x} {y} {z} is outside");
                }
            }
        }
    }
}

fn in_box(p: [i64; 3], lo: [i64; 3], hi: [i64; 3]) -> bool {
    (0..3).all(|a| lo[a] <= p[a] && p[a] < hi[a])
}

#[test]
fn two_overlapping_boxes() {
    let (a, b) = (([0, 0, 0], [4, 4, 4]), ([2, 1, 1], [6, 3, 5]));
    let mut m = Mesh::default();
    m.cuboid(a.0, a.1, true);
    m.cuboid(b.0, b.1, true);
    let d = run(&m);
    // 64 + 32 - the overlap [2, 4] x [1, 3] x [1, 4] of volume 12.
    assert_eq!(volume(&d.pieces), Rational::from_int(84));
    assert!(matches!(d.stats.winding, Some((0, 1..=2))));
    check_voxel_centres(&d.pieces, [-1; 3], [7; 3], |p| {
        in_box(p, a.0, a.1) || in_box(p, b.0, b.1)
    });
    // Sequential and unmerged runs give the same solid.
    for (merge, parallel) in [(false, false), (false, true), (true, false)] {
        let opts = Options {
            merge,
            parallel,
            ..Options::default()
        };
        let e = decompose_union(&m.points, &m.tris, &opts).unwrap();
        check_pieces(&e.pieces);
        assert_eq!(volume(&e.pieces), Rational::from_int(84));
        if !merge {
            assert_eq!(
                (e.stats.merges, e.pieces.len()),
                (0, e.stats.partition_pieces)
            );
        }
    }
}

#[test]
fn box_with_a_dent_pushed_through_the_bottom() {
    // The box [0, 4]^3 whose top face has a square well [1, 3]^2 going down to z = -2,
    // through the (intact) bottom face. Inside the well w = 0 above z = 0 and w = -1
    // below: the union is the box minus the column [1, 3]^2 x [0, 4].
    let mut m = Mesh::welded();
    let (o, i) = (
        [[0, 0], [4, 0], [4, 4], [0, 4]],
        [[1, 1], [3, 1], [3, 3], [1, 3]],
    );
    for k in 0..4 {
        let l = (k + 1) % 4;
        let at = |p: [i64; 2], z: i64| [p[0], p[1], z];
        // Top annulus, box side, well wall (facing the well's axis).
        m.poly(
            &[at(o[k], 4), at(o[l], 4), at(i[l], 4), at(i[k], 4)],
            [0, 0, 1],
        );
        let side = [o[l][1] - o[k][1], o[k][0] - o[l][0], 0];
        m.poly(&[at(o[k], 0), at(o[l], 0), at(o[l], 4), at(o[k], 4)], side);
        m.poly(
            &[at(i[k], -2), at(i[l], -2), at(i[l], 4), at(i[k], 4)],
            [-side[0], -side[1], 0],
        );
    }
    m.poly(&o.map(|p| [p[0], p[1], 0]), [0, 0, -1]);
    m.poly(&i.map(|p| [p[0], p[1], -2]), [0, 0, 1]);
    let d = run(&m);
    assert_eq!(volume(&d.pieces), Rational::from_int(48));
    assert_eq!(d.stats.winding, Some((-1, 1)));
    check_voxel_centres(&d.pieces, [-1, -1, -3], [5, 5, 5], |p| {
        in_box(p, [0; 3], [4; 3]) && !in_box(p, [1, 1, 0], [3, 3, 4])
    });
}

#[test]
fn nested_shells() {
    // Same orientation: w = 2 inside the inner box, the union is the outer box.
    let mut m = Mesh::default();
    m.cuboid([0, 0, 0], [6, 6, 6], true);
    m.cuboid([1, 2, 1], [5, 4, 3], true);
    let d = run(&m);
    assert_eq!(volume(&d.pieces), Rational::from_int(216));
    assert!(matches!(d.stats.winding, Some((0, 1..=2))));
    assert_eq!(d.pieces.len(), 1);
    // Opposite orientation: a cavity.
    let mut m = Mesh::default();
    m.cuboid([0, 0, 0], [6, 6, 6], true);
    m.cuboid([1, 2, 1], [5, 4, 3], false);
    let d = run(&m);
    assert_eq!(volume(&d.pieces), Rational::from_int(216 - 16));
    assert_eq!(d.stats.winding, Some((0, 1)));
    check_voxel_centres(&d.pieces, [-1; 3], [7; 3], |p| {
        in_box(p, [0; 3], [6; 3]) && !in_box(p, [1, 2, 1], [5, 4, 3])
    });
}

#[test]
fn coincident_and_touching_boxes() {
    // The same box twice, a box sharing part of a face, and one sharing a face plane.
    let mut m = Mesh::welded();
    m.cuboid([0, 0, 0], [2, 2, 2], true);
    m.cuboid([0, 0, 0], [2, 2, 2], true);
    m.cuboid([2, 1, 0], [4, 3, 2], true);
    m.cuboid([1, 1, 0], [3, 5, 1], true);
    let d = run(&m);
    let inside = |p: [i64; 3]| {
        in_box(p, [0; 3], [2; 3])
            || in_box(p, [2, 1, 0], [4, 3, 2])
            || in_box(p, [1, 1, 0], [3, 5, 1])
    };
    let mut count = 0;
    for x in 0..5 {
        for y in 0..5 {
            for z in 0..3 {
                count += inside([x, y, z]) as i64;
            }
        }
    }
    assert_eq!(volume(&d.pieces), Rational::from_int(count));
    check_voxel_centres(&d.pieces, [-1; 3], [6; 3], inside);
}

#[test]
fn rejections() {
    let mut m = Mesh::default();
    m.cuboid([0, 0, 0], [2, 2, 2], false);
    let err = decompose_union(&m.points, &m.tris, &Options::default()).unwrap_err();
    assert_eq!(err, DecomposeError::NotPositive);
    let mut m = Mesh::default();
    m.cuboid([0, 0, 0], [2, 2, 2], true);
    m.tris.pop();
    let err = decompose_union(&m.points, &m.tris, &Options::default()).unwrap_err();
    assert!(matches!(err, DecomposeError::NotClosed { .. }), "{err}");
    let err = decompose_union(&m.points, &[], &Options::default()).unwrap_err();
    assert_eq!(err, DecomposeError::Empty);
}

/// A convex polytope given by integer inequalities `n · x <= c`, as an independent
/// membership oracle.
struct HalfSpaces(Vec<([i64; 3], i64)>);

impl HalfSpaces {
    fn side(&self, x: &[i128; 3], w: i128) -> Sign {
        let mut on = false;
        for (n, c) in &self.0 {
            let v = (0..3).map(|k| n[k] as i128 * x[k]).sum::<i128>() - *c as i128 * w;
            if v > 0 {
                return Sign::Positive;
            }
            on |= v == 0;
        }
        if on {
            Sign::Zero
        } else {
            Sign::Negative
        }
    }
}

#[test]
fn crossing_octahedron_and_box() {
    // An octahedron |x| + |y| + |z| <= 6 crossed by the box [-2, 9] x [-1, 1] x [-3, 2]:
    // slanted planes, rational vertices. Membership of sample points against the
    // inequalities; the volume by inclusion–exclusion over the two solids' own pieces.
    let mut m = Mesh::default();
    m.shell();
    let r = 6;
    for sx in [-1, 1] {
        for sy in [-1, 1] {
            for sz in [-1, 1] {
                m.poly(
                    &[[sx * r, 0, 0], [0, sy * r, 0], [0, 0, sz * r]],
                    [sx, sy, sz],
                );
            }
        }
    }
    m.cuboid([-2, -1, -3], [9, 1, 2], true);
    let d = run(&m);
    let mut oct = Vec::new();
    for sx in [-1, 1] {
        for sy in [-1, 1] {
            for sz in [-1, 1] {
                oct.push(([sx, sy, sz], r));
            }
        }
    }
    let oct = HalfSpaces(oct);
    let cube = HalfSpaces(vec![
        ([1, 0, 0], 9),
        ([-1, 0, 0], 2),
        ([0, 1, 0], 1),
        ([0, -1, 0], 1),
        ([0, 0, 1], 2),
        ([0, 0, -1], 3),
    ]);
    // Sample points on a grid of step 1/3 offset by 1/7 (on no plane of either solid:
    // checked below), inside iff in either.
    let mut tested = 0;
    for x in -25..30 {
        for y in -20..20 {
            for z in -20..20 {
                let p = [7 * x as i128 + 1, 7 * y as i128 + 2, 7 * z as i128 + 3];
                let w = 21;
                let (a, b) = (oct.side(&p, w), cube.side(&p, w));
                if a == Sign::Zero || b == Sign::Zero {
                    continue;
                }
                let inside = a == Sign::Negative || b == Sign::Negative;
                let loc: Vec<Containment> =
                    d.pieces.iter().map(|q| common::locate(q, &p, w)).collect();
                let interior = loc.iter().filter(|c| **c == Containment::Inside).count();
                let closed = loc.iter().filter(|c| **c != Containment::Outside).count();
                if inside {
                    assert!(closed >= 1 && interior <= 1, "{p:?}/{w}");
                } else {
                    assert_eq!(closed, 0, "{p:?}/{w}");
                }
                tested += 1;
            }
        }
    }
    assert!(tested > 50_000);
    // Volume: octahedron 4 r^3 / 3 = 288, box 11 * 2 * 5 = 110, minus the intersection,
    // computed as the octahedron clipped by |y| <= 1, -3 <= z <= 2, x >= -2 by hand:
    // see `octahedron_slab_volume`.
    let expected =
        &(&Rational::from_int(288) + &Rational::from_int(110)) - &octahedron_slab_volume();
    assert_eq!(volume(&d.pieces), expected);
}

/// The volume of {|x| + |y| + |z| <= 6} ∩ [-2, 9] x [-1, 1] x [-3, 2], by hand: for fixed
/// (y, z) the section is x in [-2, 6 - s] with s = |y| + |z| <= 4, of length 8 - s, and
/// ∫∫ (8 - |y| - |z|) dy dz = 80 - 5 * 1 - 2 * (9/2 + 2) = 62.
fn octahedron_slab_volume() -> Rational {
    Rational::from_int(62)
}

#[test]
fn large_coordinates() {
    // The octahedron and box of `crossing_octahedron_and_box`, scaled by 2^36 and moved
    // to near -2^39: coordinates close to the 2^40 limit, every exact fallback in play.
    let k = 1i64 << 36;
    let t = -(1i64 << 39) + 12345;
    let at = |p: [i64; 3]| [p[0] * k + t, p[1] * k - t, p[2] * k + 7];
    let mut m = Mesh::default();
    m.shell();
    for sx in [-1, 1] {
        for sy in [-1, 1] {
            for sz in [-1, 1] {
                m.poly(
                    &[at([sx * 6, 0, 0]), at([0, sy * 6, 0]), at([0, 0, sz * 6])],
                    [sx, sy, sz],
                );
            }
        }
    }
    m.cuboid(at([-2, -1, -3]), at([9, 1, 2]), true);
    let d = run(&m);
    let scale = Rational::from_int(Int::from(k) * Int::from(k) * Int::from(k));
    assert_eq!(
        volume(&d.pieces),
        &Rational::from_int(288 + 110 - 62) * &scale
    );
}

#[test]
fn valid_solids_agree_with_decompose() {
    for shape in shapes::all().iter().map(common::exact) {
        if shape.tris.len() > 600 {
            continue;
        }
        let a = decompose(&shape.points, &shape.tris, &Options::default()).unwrap();
        let b = decompose_union(&shape.points, &shape.tris, &Options::default())
            .unwrap_or_else(|e| panic!("{}: {e}", shape.name));
        assert_eq!(volume(&b.pieces), shape.volume, "{}", shape.name);
        assert_eq!(volume(&a.pieces), shape.volume, "{}", shape.name);
        assert_eq!(b.stats.winding, Some((0, 1)), "{}", shape.name);
        check_pieces(&b.pieces);
        common::check_samples(&shape, &b.pieces);
        eprintln!(
            "{}: {} pieces (decompose: {}), {} cells",
            shape.name,
            b.pieces.len(),
            a.pieces.len(),
            b.stats.cells
        );
    }
}

fn random_boxes(boxes: &[([i64; 3], [i64; 3])], weld: bool, flip_order: bool) {
    let signed: Vec<_> = boxes.iter().map(|&(lo, hi)| (lo, hi, true)).collect();
    random_signed_boxes(&signed, weld, flip_order);
}

/// Boxes, each outward or inward, in one surface: the winding number of a voxel is the
/// number of outward boxes holding it minus the number of inward ones (the oracle).
fn random_signed_boxes(boxes: &[([i64; 3], [i64; 3], bool)], weld: bool, flip_order: bool) {
    let mut m = if weld {
        Mesh::welded()
    } else {
        Mesh::default()
    };
    for &(lo, hi, out) in boxes {
        m.cuboid(lo, hi, out);
    }
    if flip_order {
        m.tris.reverse();
    }
    let w = |p: [i64; 3]| -> i64 {
        boxes
            .iter()
            .filter(|(lo, hi, _)| in_box(p, *lo, *hi))
            .map(|b| if b.2 { 1 } else { -1 })
            .sum()
    };
    let inside = |p: [i64; 3]| w(p) >= 1;
    let (mut count, mut lo, mut hi) = (0, 0, 0);
    for x in 0..6 {
        for y in 0..6 {
            for z in 0..6 {
                count += inside([x, y, z]) as i64;
                lo = lo.min(w([x, y, z]));
                hi = hi.max(w([x, y, z]));
            }
        }
    }
    if count == 0 {
        let err = decompose_union(&m.points, &m.tris, &Options::default()).unwrap_err();
        assert_eq!(err, DecomposeError::NotPositive);
        return;
    }
    let d = run(&m);
    assert_eq!(volume(&d.pieces), Rational::from_int(count));
    // The least winding number is exact; the greatest is the largest met (cells lying
    // entirely in the solid are kept whole).
    let (wl, wh) = d.stats.winding.unwrap();
    assert_eq!(wl, lo);
    assert!(1 <= wh && wh <= hi, "{wh} not in 1..={hi}");
    check_voxel_centres(&d.pieces, [-1; 3], [7; 3], inside);
}

fn interval() -> impl Strategy<Value = (i64, i64)> + Clone {
    // Intervals of [0, 6] with length 1 to 4.
    (0i64..6, 1i64..5).prop_map(|(a, l)| (a, (a + l).min(6)))
}

fn boxes_strategy() -> impl Strategy<Value = Vec<([i64; 3], [i64; 3])>> {
    proptest::collection::vec([interval(), interval(), interval()], 1..6).prop_map(|v| {
        v.into_iter()
            .map(|[x, y, z]| ([x.0, y.0, z.0], [x.1, y.1, z.1]))
            .collect()
    })
}

fn signed_boxes_strategy() -> impl Strategy<Value = Vec<([i64; 3], [i64; 3], bool)>> {
    proptest::collection::vec(([interval(), interval(), interval()], 0..3), 1..7).prop_map(|v| {
        v.into_iter()
            .map(|([x, y, z], o)| ([x.0, y.0, z.0], [x.1, y.1, z.1], o != 0))
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_box_unions(boxes in boxes_strategy(), weld in any::<bool>(), flip in any::<bool>()) {
        random_boxes(&boxes, weld, flip);
    }

    /// Inward boxes too: cavities, and negative winding where they stick out.
    #[test]
    fn random_signed_box_unions(boxes in signed_boxes_strategy(), weld in any::<bool>()) {
        random_signed_boxes(&boxes, weld, false);
    }

    /// Valid solids (unions of voxels welded into one manifold-or-touching surface): the
    /// same volume as the voxel count and as `decompose`.
    #[test]
    fn voxel_solids_agree_with_decompose(on in proptest::collection::vec(any::<bool>(), 27)) {
        prop_assume!(on.iter().any(|&b| b));
        let shape = common::exact(&shapes::voxels([3, 3, 3], &on));
        let a = decompose(&shape.points, &shape.tris, &Options::default()).unwrap();
        let b = decompose_union(&shape.points, &shape.tris, &Options::default()).unwrap();
        prop_assert_eq!(volume(&b.pieces), shape.volume.clone());
        prop_assert_eq!(volume(&a.pieces), shape.volume.clone());
        prop_assert_eq!(b.stats.winding, Some((0, 1)));
        check_pieces(&b.pieces);
        common::check_samples(&shape, &b.pieces);
    }

    /// Height fields (valid solids with generic planes and rational vertices).
    #[test]
    fn terrains_agree_with_decompose(h in proptest::collection::vec(1i64..60, 16)) {
        let shape = common::exact(&shapes::terrain(3, 20, &h));
        let b = decompose_union(&shape.points, &shape.tris, &Options::default()).unwrap();
        prop_assert_eq!(volume(&b.pieces), shape.volume.clone());
        check_pieces(&b.pieces);
        common::check_samples(&shape, &b.pieces);
    }

    /// Random crossing tetrahedra: slanted planes, rational vertices; membership of
    /// lattice points against the tetrahedra's own inequalities.
    #[test]
    fn random_tetrahedra_unions(pts in proptest::collection::vec([0i64..13, 0i64..13, 0i64..13], 8..17)) {
        tetrahedra(&pts);
    }
}

/// The tetrahedra of consecutive quadruples of `pts` (flat ones skipped), outward.
fn tetrahedra(pts: &[[i64; 3]]) {
    let mut m = Mesh::default();
    let mut solids = Vec::new();
    let mut total = Rational::zero();
    for q in pts.chunks_exact(4) {
        let sub = |a: [i64; 3], b: [i64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let cross = |u: [i64; 3], v: [i64; 3]| {
            [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ]
        };
        let dot = |u: [i64; 3], v: [i64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        let det = dot(cross(sub(q[1], q[0]), sub(q[2], q[0])), sub(q[3], q[0]));
        if det == 0 {
            continue;
        }
        total = &total + &Rational::new(Int::from(det.abs()), Int::from(6));
        m.shell();
        let mut faces = Vec::new();
        for k in 0..4 {
            let f: Vec<[i64; 3]> = (0..4).filter(|&j| j != k).map(|j| q[j]).collect();
            let mut n = cross(sub(f[1], f[0]), sub(f[2], f[0]));
            // Outward: away from the opposite corner.
            if dot(n, sub(q[k], f[0])) > 0 {
                n = n.map(|v| -v);
            }
            m.poly(&f, n);
            faces.push((n, dot(n, f[0])));
        }
        solids.push(HalfSpaces(faces));
    }
    if solids.is_empty() {
        return;
    }
    let d = run(&m);
    let v = volume(&d.pieces);
    assert!(v <= total);
    for x in 0..26 {
        for y in 0..26 {
            for z in 0..26 {
                let p = [7 * x as i128 + 1, 7 * y as i128 + 3, 7 * z as i128 + 2];
                let w = 14;
                let sides: Vec<Sign> = solids.iter().map(|h| h.side(&p, w)).collect();
                if sides.contains(&Sign::Zero) {
                    continue;
                }
                let inside = sides.contains(&Sign::Negative);
                let loc: Vec<Containment> =
                    d.pieces.iter().map(|q| common::locate(q, &p, w)).collect();
                let interior = loc.iter().filter(|c| **c == Containment::Inside).count();
                let closed = loc.iter().filter(|c| **c != Containment::Outside).count();
                if inside {
                    assert!(closed >= 1 && interior <= 1, "{p:?}/{w}");
                } else {
                    assert_eq!(closed, 0, "{p:?}/{w}");
                }
            }
        }
    }
}

/// A longer run of random signed boxes and tetrahedra: `cargo test --release -- --ignored`.
#[test]
#[ignore]
fn union_stress() {
    let mut seed = 0x5851f42d4c957f2du64;
    let mut next = move |n: u64| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % n) as i64
    };
    for case in 0..2000 {
        let k = 1 + next(8) as usize;
        let boxes: Vec<_> = (0..k)
            .map(|_| {
                let iv = |a: i64, l: i64| (a, (a + l).min(6));
                let [x, y, z] = [0; 3].map(|_| iv(next(6), 1 + next(4)));
                ([x.0, y.0, z.0], [x.1, y.1, z.1], next(4) != 0)
            })
            .collect();
        eprintln!("boxes {case}");
        random_signed_boxes(&boxes, next(2) == 0, next(2) == 0);
        let pts: Vec<[i64; 3]> = (0..4 * (2 + next(4)))
            .map(|_| [0; 3].map(|_| next(13)))
            .collect();
        eprintln!("tetrahedra {case}");
        tetrahedra(&pts);
    }
}

#[test]
fn sliver_triangle_closing_a_t_junction() {
    // The box [0, 2]^3 whose top face is split at the midpoint m of its edge a-b, the
    // T-junction closed by the zero-area triangle (a, b, m): a common CAD artefact.
    // decompose rejects the collinear triangle; the union counts it for closure only.
    let mut m = Mesh::welded();
    m.cuboid([0, 0, 0], [2, 2, 2], true);
    let (a, b) = ([0, 0, 2], [2, 0, 2]);
    let top: Vec<usize> = (0..m.tris.len())
        .filter(|&t| m.tris[t].iter().all(|&v| m.raw[v as usize][2] == 2))
        .collect();
    assert_eq!(top.len(), 2);
    // Replace the top face by a fan from the midpoint m = (1, 0, 2).
    let (ia, ib) = (m.id(a), m.id(b));
    let (ic, id) = (m.id([2, 2, 2]), m.id([0, 2, 2]));
    let im = m.id([1, 0, 2]);
    m.tris.remove(top[1]);
    m.tris.remove(top[0]);
    m.tris
        .extend([[im, ib, ic], [im, ic, id], [im, id, ia], [ia, ib, im]]);
    let err = decompose(&m.points, &m.tris, &Options::default()).unwrap_err();
    assert!(
        matches!(err, DecomposeError::DegenerateTriangle { .. }),
        "{err}"
    );
    let d = run(&m);
    assert_eq!(volume(&d.pieces), Rational::from_int(8));
    assert_eq!(d.pieces.len(), 1);
}
