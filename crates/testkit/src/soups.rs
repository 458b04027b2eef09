//! Triangle soups with the defects of real CAD exports that only the winding-number
//! rule makes into solids, each with its answer known by construction.
//!
//! The rule: close every boundary loop of the soup (the edges whose uses one way and
//! the other do not cancel, taken with their multiplicity) by a cap, when the loop is
//! planar or nearly so; the part is then the set of points whose winding number with
//! respect to the oriented triangles and caps is at least 1. Every generator here puts
//! its vertices on the integer grid and states the exact volume of that solid
//! ([`Case::volume`]), which [`crate::winding`] checks independently; each also comes as
//! a two-part assembly with a known plan.
//!
//! - [`folded_rim_box`]: a box whose rim carries a subdivided ring of faces doubled
//!   back inside it (rim edges of three faces that do not alternate, or of two faces
//!   the same way with the rim open; open planar loops).
//! - [`thread`]: a threaded rod of stacked crossing rings with open seams and
//!   zero-area slivers; [`nut_on_thread`] puts a nut on it (interlocked).
//! - [`gear`]: an extruded gear whose adjacent tooth flanks run past the root and cross.
//! - [`folded_fillet`]: a box with one edge rounded by a strip whose faces fold back
//!   over themselves (a region of winding −1).
//! - [`overlapping_shells`], [`bracket_shells`]: two closed boxes of one part that
//!   overlap.
//! - [`on_plate`]: any of them resting on a plain box; [`families`]: all of them at
//!   their usual parameters, with their assemblies.

use crate::winding::TriSoup;

/// A defective part and the exact volume of its winding-number solid.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Case {
    /// The triangles, as an exporter writes them.
    pub soup: TriSoup,
    /// Triangles closing the soup's boundary loops, as the rule closes them: the soup
    /// and its caps together are a closed chain (every edge used as often one way as
    /// the other). Not part of the export; the oracle counts winding numbers with them.
    pub caps: TriSoup,
    /// The volume of `{w >= 1}` after closing the boundary loops, exact, as
    /// `(numerator, denominator)` in lowest terms (denominator positive).
    pub volume: (i128, i128),
}

impl Case {
    /// The volume as a float.
    pub fn volume_f64(&self) -> f64 {
        self.volume.0 as f64 / self.volume.1 as f64
    }

    /// The soup with its caps: the closed chain whose winding numbers define the solid.
    pub fn closed(&self) -> TriSoup {
        let mut s = self.soup.clone();
        s.append(&self.caps);
        s
    }
}

/// A part: its name and its triangles.
pub type NamedTriSoup = (String, TriSoup);

fn gcd(a: i128, b: i128) -> i128 {
    if b == 0 {
        a.abs()
    } else {
        gcd(b, a % b)
    }
}

/// `n / d` in lowest terms, `d > 0`.
fn ratio(n: i128, d: i128) -> (i128, i128) {
    let g = gcd(n, d).max(1) * d.signum();
    (n / g, d / g)
}

/// The box `lo..hi` as 12 outward triangles.
pub fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> TriSoup {
    let c = crate::solids::cuboid_corners(lo, hi);
    let mut s = TriSoup::default();
    for q in crate::solids::CUBOID_QUADS {
        s.fan(&q.map(|i| c[i as usize]));
    }
    s
}

/// The volume of a union of boxes `(lo, hi)`, exactly (cells of the grid of their
/// coordinates, each counted once).
pub fn union_volume(boxes: &[([i64; 3], [i64; 3])]) -> i128 {
    let axis = |k: usize| {
        let mut v: Vec<i64> = boxes.iter().flat_map(|b| [b.0[k], b.1[k]]).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let (xs, ys, zs) = (axis(0), axis(1), axis(2));
    let mut total = 0i128;
    for x in xs.windows(2) {
        for y in ys.windows(2) {
            for z in zs.windows(2) {
                let c = [x[0] + x[1], y[0] + y[1], z[0] + z[1]];
                let inside = boxes
                    .iter()
                    .any(|(lo, hi)| (0..3).all(|k| 2 * lo[k] < c[k] && c[k] < 2 * hi[k]));
                if inside {
                    total += ((x[1] - x[0]) * (y[1] - y[0]) * (z[1] - z[0])) as i128;
                }
            }
        }
    }
    total
}

/// The corners of the rectangle `lo..hi` (in x, y) counter-clockwise seen from `+z`.
fn footprint(lo: [i64; 2], hi: [i64; 2]) -> [[i64; 2]; 4] {
    [
        [lo[0], lo[1]],
        [hi[0], lo[1]],
        [hi[0], hi[1]],
        [lo[0], hi[1]],
    ]
}

fn at(p: [i64; 2], z: i64) -> [i64; 3] {
    [p[0], p[1], z]
}

/// Appends the quad `a, b, c, d` (counter-clockwise from outside) as two triangles.
fn quad(s: &mut TriSoup, a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3]) {
    s.fan(&[a, b, c, d]);
}

/// A box `0..extent` whose rim carries a ring of faces doubled back inside it, as
/// exporters leave a socket's lip: the bottom (and with `lid` the top) is an
/// `segments × segments` grid, each side wall `segments` columns by two rows (z in
/// `0..Z − fold` and `Z − fold..Z`), and from each of the `4 · segments` rim edges a
/// flap goes down into the box to the rectangle inset by `inset` at `z = Z − fold`.
/// The flaps run along the rim edges the same way as the walls do (their normals face
/// out of the box like the walls'), so the faces at a rim edge do not alternate: with
/// `lid`, three faces (wall, lid, flap: non-manifold); without, two faces the same way
/// and the rim loop (`z = Z`, `4 · segments` edges) open. The inset loop (4 edges) is
/// open in both: every open loop is planar.
///
/// Known answer: the boundary (as a chain) is the rim loop (twice without the lid,
/// once with it) and the inset loop once; capped, the walls, bottom and lid enclose
/// the box (winding 1) and the flaps with their caps enclose the frustum between the
/// rim and the inset rectangle (winding 1 more). The solid is the box: volume
/// `X · Y · Z`. (Flipping the flaps to match the walls instead, as an orientation
/// repair would, turns the frustum's winding to 0 and carves it out: a different,
/// wrong answer.)
///
/// # Panics
/// Unless `segments` divides `X` and `Y`, `0 < fold < Z` and `0 < 2 · inset < min(X, Y)`.
pub fn folded_rim_box(extent: [i64; 3], segments: u32, fold: i64, inset: i64, lid: bool) -> Case {
    let [x, y, z] = extent;
    let s = segments as i64;
    assert!(s >= 1 && x % s == 0 && y % s == 0);
    assert!(0 < fold && fold < z && 0 < inset && 2 * inset < x.min(y));
    let mut soup = TriSoup::default();
    // Bottom, facing -z: cells (x_i, y_j) → (x_i, y_j+1) → (x_i+1, y_j+1) → (x_i+1, y_j).
    let (dx, dy) = (x / s, y / s);
    for i in 0..s {
        for j in 0..s {
            let (x0, x1, y0, y1) = (i * dx, (i + 1) * dx, j * dy, (j + 1) * dy);
            quad(
                &mut soup,
                [x0, y0, 0],
                [x0, y1, 0],
                [x1, y1, 0],
                [x1, y0, 0],
            );
            if lid {
                quad(
                    &mut soup,
                    [x0, y0, z],
                    [x1, y0, z],
                    [x1, y1, z],
                    [x0, y1, z],
                );
            }
        }
    }
    let rim = footprint([0, 0], [x, y]);
    let inner = footprint([inset, inset], [x - inset, y - inset]);
    let rows = [0, z - fold, z];
    for side in 0..4 {
        let (p, q) = (rim[side], rim[(side + 1) % 4]);
        let pt = |j: i64| [p[0] + (q[0] - p[0]) * j / s, p[1] + (q[1] - p[1]) * j / s];
        for j in 0..s {
            let (a, b) = (pt(j), pt(j + 1));
            for r in 0..2 {
                let (z0, z1) = (rows[r], rows[r + 1]);
                quad(&mut soup, at(a, z0), at(b, z0), at(b, z1), at(a, z1));
            }
        }
        // The flap: the wall uses its rim edges from q towards p; so does the flap,
        // the trapezoid (rim from q back to p, then the inset corners under p and q),
        // fanned from the inset corner under q.
        let (li, lq) = (
            at(inner[side], z - fold),
            at(inner[(side + 1) % 4], z - fold),
        );
        for j in (0..s).rev() {
            soup.fan(&[lq, at(pt(j + 1), z), at(pt(j), z)]);
        }
        soup.fan(&[lq, at(p, z), li]);
    }
    // Caps: the rim loop twice without the lid, once with it (facing +z, fanned from a
    // corner: the triangles along the two sides at that corner have zero area), the
    // inset loop once facing -z.
    let mut caps = TriSoup::default();
    let mut loop_pts = Vec::new();
    for side in 0..4 {
        let (p, q) = (rim[side], rim[(side + 1) % 4]);
        for j in 0..s {
            loop_pts.push(at(
                [p[0] + (q[0] - p[0]) * j / s, p[1] + (q[1] - p[1]) * j / s],
                z,
            ));
        }
    }
    caps.fan(&loop_pts);
    if !lid {
        caps.fan(&loop_pts);
    }
    caps.fan(
        &inner
            .map(|v| at(v, z - fold))
            .into_iter()
            .rev()
            .collect::<Vec<_>>(),
    );
    Case {
        soup,
        caps,
        volume: ratio(x as i128 * y as i128 * z as i128, 1),
    }
}

/// [`folded_rim_box`] with the lid, its inset loop made nearly planar: the inset
/// corner `(inset, inset)` raised one grid step (to `z = Z − fold + 1`), so the loop's
/// four points are no longer coplanar and how it is capped is the loader's choice.
///
/// Known answer: still the box, volume `X · Y · Z`: the loop lies inside the box, and
/// any cap spanning it there only moves the boundary between winding 2 and winding 1.
pub fn warped_rim_box(extent: [i64; 3], segments: u32, fold: i64, inset: i64) -> Case {
    assert!(fold >= 2, "the raised corner stays below the rim");
    let mut c = folded_rim_box(extent, segments, fold, inset, true);
    let corner = [inset, inset, extent[2] - fold];
    for p in c.soup.points.iter_mut().chain(c.caps.points.iter_mut()) {
        if *p == corner {
            p[2] += 1;
        }
    }
    c
}

/// The half-widths and core of [`thread`] for a horizontal `unit`: `(a, b, c)` =
/// `(5, 3, 2) · unit`.
pub fn thread_sizes(unit: i64) -> (i64, i64, i64) {
    (5 * unit, 3 * unit, 2 * unit)
}

/// The boxes whose union is [`thread`]`(layers, unit)`: the core, then the layers.
pub fn thread_boxes(layers: usize, unit: i64) -> Vec<([i64; 3], [i64; 3])> {
    let (a, b, c) = thread_sizes(unit);
    let top = 4 * layers as i64 + 4;
    let mut boxes = vec![([-c, -c, -2], [c, c, top])];
    for k in 0..layers as i64 {
        let (hx, hy) = if k % 2 == 0 { (a, b) } else { (b, a) };
        boxes.push(([-hx, -hy, 4 * k], [hx, hy, 4 * k + 6]));
    }
    boxes
}

/// A threaded rod as exporters approximate a thread by stacked rings: a square core
/// (half-width `c`, z from −2 to `4 · layers + 4`, a closed box) through `layers`
/// closed rectangular rings, ring `k` spanning z in `4k..4k + 6` (so consecutive rings
/// overlap by 2) with half-widths `(a, b)` in x and y, turned a quarter turn from one
/// ring to the next (`(b, a)` for odd `k`); `(a, b, c)` = [`thread_sizes`]`(unit)`. The
/// rings' walls cross the neighbouring rings' caps and the core's walls cross every
/// cap.
///
/// Each ring `k` has an open seam: side wall `k mod 4` (counted counter-clockwise from
/// the `−y` wall seen from `+z`) misses the strip between the horizontal coordinates 0
/// and 1 (one grid step; the caps keep vertices at both sides, so the hole is a planar
/// rectangle). Each ring also carries a zero-area sliver: three collinear points along
/// the bottom edge of the next wall.
///
/// Known answer: the union of [`thread_boxes`] (closing the seams restores the walls,
/// the slivers enclose nothing), volume [`union_volume`] of them.
pub fn thread(layers: usize, unit: i64) -> Case {
    assert!(layers >= 1 && unit >= 1);
    let boxes = thread_boxes(layers, unit);
    let mut soup = cuboid(boxes[0].0, boxes[0].1);
    let mut caps = TriSoup::default();
    for (k, &(lo, hi)) in boxes[1..].iter().enumerate() {
        let (ring, cap) = seamed_ring(lo, hi, k % 4);
        soup.append(&ring);
        caps.append(&cap);
    }
    Case {
        soup,
        caps,
        volume: ratio(union_volume(&boxes), 1),
    }
}

/// The box `lo..hi` with the strip between horizontal coordinates 0 and 1 missing
/// from side wall `seam` (0: `−y`, 1: `+x`, 2: `+y`, 3: `−x`), and a zero-area sliver
/// along the bottom edge of wall `seam + 1`; and the caps closing both (the strip, the
/// sliver reversed).
fn seamed_ring(lo: [i64; 3], hi: [i64; 3], seam: usize) -> (TriSoup, TriSoup) {
    let (z0, z1) = (lo[2], hi[2]);
    let corners = footprint([lo[0], lo[1]], [hi[0], hi[1]]);
    let mut s = TriSoup::default();
    let mut caps = TriSoup::default();
    // The footprint loop, with the seam's two vertices.
    let mut lp: Vec<[i64; 2]> = Vec::new();
    for side in 0..4 {
        let (p, q) = (corners[side], corners[(side + 1) % 4]);
        lp.push(p);
        let dir = [(q[0] - p[0]).signum(), (q[1] - p[1]).signum()];
        if side == seam {
            // The strip between coordinates 0 and 1 along the wall, in travel order.
            let along = if dir[0] != 0 { 0 } else { 1 };
            let (s0, s1) = if dir[along] > 0 { (0, 1) } else { (1, 0) };
            let mut a = p;
            let mut b = p;
            a[along] = s0;
            b[along] = s1;
            quad(&mut s, at(p, z0), at(a, z0), at(a, z1), at(p, z1));
            quad(&mut s, at(b, z0), at(q, z0), at(q, z1), at(b, z1));
            quad(&mut caps, at(a, z0), at(b, z0), at(b, z1), at(a, z1));
            lp.push(a);
            lp.push(b);
        } else {
            quad(&mut s, at(p, z0), at(q, z0), at(q, z1), at(p, z1));
        }
        if side == (seam + 1) % 4 {
            let m = [p[0] + dir[0], p[1] + dir[1]];
            s.triangle(at(p, z0), at(m, z0), at(q, z0));
            caps.triangle(at(p, z0), at(q, z0), at(m, z0));
        }
    }
    // The ring's top and bottom, fanned from a corner off the seam's wall (so that no
    // fan triangle is degenerate).
    let apex = corners[(seam + 2) % 4];
    let k = lp.iter().position(|&v| v == apex).expect("a corner");
    lp.rotate_left(k);
    s.fan(&lp.iter().map(|&v| at(v, z1)).collect::<Vec<_>>());
    let mut down: Vec<[i64; 3]> = lp.iter().rev().map(|&v| at(v, z0)).collect();
    down.rotate_right(1);
    s.fan(&down);
    (s, caps)
}

/// The nut of [`nut_on_thread`]: the box of half-width `a + 2 · unit` with z in
/// `1..4 · layers + 1`, less the rod (the union of [`thread_boxes`]), as a closed
/// integer mesh of grid rectangles (valid as is).
pub fn thread_nut(layers: usize, unit: i64) -> crate::solids::IntMesh {
    let (a, b, c) = thread_sizes(unit);
    let w = a + 2 * unit;
    let (zlo, zhi) = (1, 4 * layers as i64 + 1);
    let boxes = thread_boxes(layers, unit);
    let xs = [-w, -a, -b, -c, c, b, a, w];
    let mut zs: Vec<i64> = boxes
        .iter()
        .flat_map(|b| [b.0[2], b.1[2]])
        .chain([zlo, zhi])
        .filter(|z| (zlo..=zhi).contains(z))
        .collect();
    zs.sort_unstable();
    zs.dedup();
    crate::solids::rectilinear([&xs, &xs, &zs], |i| {
        let c = [
            xs[i[0]] + xs[i[0] + 1],
            xs[i[1]] + xs[i[1] + 1],
            zs[i[2]] + zs[i[2] + 1],
        ];
        !boxes
            .iter()
            .any(|(lo, hi)| (0..3).all(|k| 2 * lo[k] < c[k] && c[k] < 2 * hi[k]))
    })
}

/// A nut (`"nut"`, [`thread_nut`], a valid closed mesh) on the threaded rod
/// (`"bolt"`, [`thread`], defective), `layers >= 3`. The nut's hole is the rod's cross
/// section at every height, so the two touch all along.
///
/// Known answer: interlocked, no translation of either part separates them. Along
/// `±z` the nut's material in ring 1's quarter-turned zone (z in `6..8`) meets ring 0's
/// or ring 2's lobes; every direction with a horizontal component drives the nut's
/// hole wall into the rod. Nut volume: the box less the rod inside it.
pub fn nut_on_thread(layers: usize, unit: i64) -> Vec<NamedTriSoup> {
    assert!(layers >= 3, "the nut interlocks from three rings on");
    vec![
        ("bolt".into(), thread(layers, unit).soup),
        ("nut".into(), TriSoup::from(&thread_nut(layers, unit))),
    ]
}

/// Twice the signed area of a polygon.
fn area2(poly: &[[i64; 2]]) -> i128 {
    crate::solids::area2(poly)
}

fn prim(d: [i64; 2]) -> [i64; 2] {
    let g = gcd(d[0] as i128, d[1] as i128).max(1) as i64;
    [d[0] / g, d[1] / g]
}

/// The profile of [`gear`] (self-crossing) and its outline (simple): `(profile,
/// outline)`, both counter-clockwise.
pub fn gear_profiles(
    teeth: usize,
    root: i64,
    tip: i64,
    overshoot: i64,
) -> (Vec<[i64; 2]>, Vec<[i64; 2]>) {
    use std::f64::consts::PI;
    assert!(teeth >= 3 && 0 < root && root < tip && overshoot >= 1);
    let pol = |r: i64, t: f64| [r as f64 * t.cos(), r as f64 * t.sin()];
    let grid = |p: [f64; 2]| p.map(|c| c.round() as i64);
    let step = 2.0 * PI / teeth as f64;
    let half = 0.3 * step / 2.0;
    let roots: Vec<[i64; 2]> = (0..teeth)
        .map(|i| grid(pol(root, step * (i as f64 + 0.5))))
        .collect();
    // A flank from root `r` towards the tip `target`: a short primitive step `v`
    // (about 3 grid steps long) along it, and the tip `r + m v` nearest the target.
    let flank = |r: [i64; 2], target: [f64; 2]| {
        let d = [target[0] - r[0] as f64, target[1] - r[1] as f64];
        let len = d[0].hypot(d[1]);
        let v = prim(grid([3.0 * d[0] / len, 3.0 * d[1] / len]));
        let m = (len / (v[0] as f64).hypot(v[1] as f64)).round() as i64;
        ([r[0] + m * v[0], r[1] + m * v[1]], v)
    };
    let (mut profile, mut outline) = (Vec::new(), Vec::new());
    for i in 0..teeth {
        let t = step * i as f64;
        let (before, after) = (roots[(i + teeth - 1) % teeth], roots[i]);
        let (ta, _) = flank(before, pol(tip, t - half));
        let (tb, v) = flank(after, pol(tip, t + half));
        let (_, w) = flank(after, pol(tip, t + step - half));
        // Past the root along this tooth's flank, then back along the next one's.
        let r = after;
        let x1 = [r[0] - overshoot * v[0], r[1] - overshoot * v[1]];
        let x2 = [r[0] - overshoot * w[0], r[1] - overshoot * w[1]];
        profile.extend([ta, tb, x1, x2]);
        outline.extend([ta, tb, r]);
    }
    (profile, outline)
}

/// Extrudes the counter-clockwise (possibly self-crossing) profile along `+z` from
/// `z0` to `z1`: a quad per profile edge and two caps fanned from `centre` (a chain
/// whose winding number at height `z0 < z < z1` is the profile's).
fn extrude_z(profile: &[[i64; 2]], centre: [i64; 2], z0: i64, z1: i64) -> TriSoup {
    let mut s = TriSoup::default();
    let n = profile.len();
    for k in 0..n {
        let (p, q) = (profile[k], profile[(k + 1) % n]);
        quad(&mut s, at(p, z0), at(q, z0), at(q, z1), at(p, z1));
        s.triangle(at(centre, z1), at(p, z1), at(q, z1));
        s.triangle(at(centre, z0), at(q, z0), at(p, z0));
    }
    s
}

/// An extruded gear (z from 0 to `height`) of `teeth` teeth whose tessellated flanks
/// overlap: each flank runs on past the root, `overshoot` steps along its own line (a
/// step: the flank's primitive grid vector, about 3 units long; the tips are placed at
/// whole steps from the roots), before the profile turns back to the next flank, so the two flanks
/// at every root cross there (the profile crosses itself once per root). Tips at
/// radius `tip` (30% of the pitch wide), roots at radius `root`, rounded to the grid;
/// the caps are fanned from the axis; one closed, consistently oriented surface.
///
/// Known answer: the winding number is 1 inside the gear's outline (tip, tip, root,
/// ...: [`gear_profiles`]) and 2 in the small triangle each root's overshoot closes
/// (inside the hub), so the solid is the outline extruded: volume
/// `height · area(outline)`. Checked against [`crate::winding::monte_carlo_volume`]
/// for the sizes of [`families`]; for gears of hundreds of teeth (tips at `40·teeth/6`)
/// this closed form falls short of that estimate (by 1.3% at 300 teeth), so use the
/// estimate there.
pub fn gear(teeth: usize, root: i64, tip: i64, height: i64, overshoot: i64) -> Case {
    let (profile, outline) = gear_profiles(teeth, root, tip, overshoot);
    Case {
        soup: extrude_z(&profile, [0, 0], 0, height),
        caps: TriSoup::default(),
        volume: ratio(height as i128 * area2(&outline), 2),
    }
}

/// The profile of [`folded_fillet`] in the `(x, z)` plane, counter-clockwise, and the
/// four arc points `Q0..Q3` around the fold (`Q1, Q2` swapped in the profile).
pub fn fillet_profile(
    extent: [i64; 3],
    radius: i64,
    segments: usize,
    fold: usize,
) -> (Vec<[i64; 2]>, [[i64; 2]; 4]) {
    use std::f64::consts::PI;
    let [x, _, z] = extent;
    assert!(0 < radius && radius < x.min(z) && segments >= 3);
    assert!(
        fold >= 1 && fold + 2 <= segments,
        "the fold needs an arc point on each side"
    );
    let arc: Vec<[i64; 2]> = (0..=segments)
        .map(|j| {
            let t = PI / 2.0 * j as f64 / segments as f64;
            [
                x - radius + (radius as f64 * t.cos()).round() as i64,
                z - radius + (radius as f64 * t.sin()).round() as i64,
            ]
        })
        .collect();
    let mut profile = vec![[0, 0], [x, 0]];
    let mut a = arc.clone();
    a.swap(fold, fold + 1);
    profile.extend(a);
    profile.push([0, z]);
    let q = [arc[fold - 1], arc[fold], arc[fold + 1], arc[fold + 2]];
    (profile, q)
}

/// A box `0..extent` whose edge at `x = X, z = Z` (along y) is rounded by a fillet of
/// `radius` in `segments` facets, as a strip of faces whose facets `fold` and
/// `fold + 1` are exported in the wrong order: the strip runs to the second, back to
/// the first and on, so that it folds over itself and its faces cross. The profile is
/// extruded along `y` (caps fanned from the profile point `(1, 1)`): closed and
/// consistently oriented.
///
/// Known answer: with `Q0..Q3` the arc points around the fold and `X` the crossing of
/// `Q0Q2` with `Q1Q3`, the winding number is −1 in the triangle `Q1 Q2 X`, 0 in
/// `Q0 Q1 X` and `Q2 Q3 X`, 1 elsewhere inside: the solid is the profile with `Q1, Q2`
/// replaced by `X`, its volume `Y · area` (rational). Bounds: between `Y` times the
/// area of the rounded profile less the quadrilateral `Q0..Q3`, and `Y` times the area
/// of the rounded profile.
pub fn folded_fillet(extent: [i64; 3], radius: i64, segments: usize, fold: usize) -> Case {
    let (profile, q) = fillet_profile(extent, radius, segments, fold);
    // Map (x, z) to (u, v) = (z, x) with w = y: (z, x, y) is right-handed, and the
    // swap reverses the profile's turn, so reverse it.
    let uv: Vec<[i64; 2]> = profile.iter().rev().map(|p| [p[1], p[0]]).collect();
    let mut soup = extrude_z(&uv, [1, 1], 0, extent[1]);
    for p in &mut soup.points {
        *p = [p[1], p[2], p[0]];
    }
    let volume = fillet_volume(extent, &profile, q, fold);
    Case {
        soup,
        caps: TriSoup::default(),
        volume,
    }
}

/// The exact volume of [`folded_fillet`]: `Y ·` the area of the profile with
/// `Q1, Q2` (entries `fold + 2, fold + 3` of the profile, swapped) replaced by the
/// crossing `X`.
fn fillet_volume(
    extent: [i64; 3],
    profile: &[[i64; 2]],
    q: [[i64; 2]; 4],
    fold: usize,
) -> (i128, i128) {
    let c = |a: [i64; 2], b: [i64; 2]| a[0] as i128 * b[1] as i128 - a[1] as i128 * b[0] as i128;
    let d = |a: [i64; 2], b: [i64; 2]| [b[0] - a[0], b[1] - a[1]];
    // The profile is (0, 0), (X, 0), the arc, (0, Z): arc point j is entry j + 2.
    // X = Q0 + t (Q2 − Q0), t = ((Q1 − Q0) × (Q3 − Q1)) / ((Q2 − Q0) × (Q3 − Q1)).
    let (e, f) = (d(q[0], q[2]), d(q[1], q[3]));
    let den = c(e, f);
    let num = c(d(q[0], q[1]), f);
    assert!(den != 0 && 0 < num * den.signum() && num.abs() < den.abs());
    // Every vertex scaled by `den`.
    let scaled = |p: [i64; 2]| [p[0] as i128 * den, p[1] as i128 * den];
    let x = [
        q[0][0] as i128 * den + num * e[0] as i128,
        q[0][1] as i128 * den + num * e[1] as i128,
    ];
    let mut poly: Vec<[i128; 2]> = Vec::new();
    for (k, &p) in profile.iter().enumerate() {
        if k == fold + 2 {
            poly.push(x);
        } else if k != fold + 3 {
            poly.push(scaled(p));
        }
    }
    let a2: i128 = (0..poly.len())
        .map(|k| {
            let (p, r) = (poly[k], poly[(k + 1) % poly.len()]);
            p[0] * r[1] - p[1] * r[0]
        })
        .sum();
    ratio(a2 * extent[1] as i128, 2 * den * den)
}

/// Two closed boxes `a` and `b` (each `(lo, hi)`, 12 outward triangles) in one soup,
/// overlapping, as an export that writes two bodies of one part without their boolean
/// union. Known answer: the union, volume [`union_volume`]`([a, b])`.
pub fn overlapping_shells(a: ([i64; 3], [i64; 3]), b: ([i64; 3], [i64; 3])) -> Case {
    let mut soup = cuboid(a.0, a.1);
    soup.append(&cuboid(b.0, b.1));
    Case {
        soup,
        caps: TriSoup::default(),
        volume: ratio(union_volume(&[a, b]), 1),
    }
}

/// An L-bracket as [`overlapping_shells`]: the plate `0..(w, d, t)` and the upright
/// `0..(t, d, h)` sharing the block `0..(t, d, t)`.
pub fn bracket_shells(w: i64, d: i64, t: i64, h: i64) -> Case {
    overlapping_shells(([0, 0, 0], [w, d, t]), ([0, 0, 0], [t, d, h]))
}

/// `part` (named `name`) resting on a plain box (`"plate"`): the box under the part's
/// bounding box, from `z = lo_z − 2` to its bottom `lo_z` (the solid's lowest points
/// must lie on that plane, as in every generator here).
///
/// Known answer: the part leaves through the open upper hemisphere (and slides along
/// the plate), the plate through the lower; no solution moves the part downwards. A
/// plan with the plate as base: one step, the part upwards.
pub fn on_plate(name: &str, part: TriSoup) -> Vec<NamedTriSoup> {
    let (lo, hi) = part.bbox();
    let plate = cuboid([lo[0], lo[1], lo[2] - 2], [hi[0], hi[1], lo[2]]);
    vec![(name.into(), part), ("plate".into(), plate)]
}

/// One family at its usual parameters: the defective part, its name in the
/// assembly, and the two-part assembly.
#[derive(Clone, Debug)]
pub struct Family {
    /// The family's name (also a folder name).
    pub name: &'static str,
    /// The defective part's name in [`Family::assembly`].
    pub part: &'static str,
    /// The defective part with its known volume.
    pub case: Case,
    /// Two parts: the defective one and a plain partner ([`on_plate`]), or the nut of
    /// [`nut_on_thread`] for the thread.
    pub assembly: Vec<NamedTriSoup>,
}

/// Every family of this module at its usual parameters: `folded-rim` and
/// `folded-rim-open` ([`folded_rim_box`]`([12, 8, 10], 4, 3, 2, lid)` with and without
/// the lid, volume 960), `warped-rim` ([`warped_rim_box`]`([12, 8, 10], 4, 3, 2)`,
/// volume 960), `thread`
/// ([`thread`]`(4, 1)` with its nut, interlocked), `gear` ([`gear`]`(12, 30, 40, 6,
/// 1)`), `folded-fillet` ([`folded_fillet`]`([40, 10, 36], 20, 5, 2)`) and
/// `overlapping-shells` ([`bracket_shells`]`(10, 4, 2, 8)`, volume 128: the shells
/// share a corner edge and overlap in coplanar faces) and `crossing-shells`
/// ([`overlapping_shells`] of `0..6` and `(3, 2, 1)..(9, 4, 4)`, volume 234: faces in
/// general position).
pub fn families() -> Vec<Family> {
    let plated = |name: &'static str, part: &'static str, case: Case| Family {
        name,
        part,
        assembly: on_plate(part, case.soup.clone()),
        case,
    };
    vec![
        plated(
            "folded-rim",
            "rim",
            folded_rim_box([12, 8, 10], 4, 3, 2, true),
        ),
        plated("warped-rim", "rim", warped_rim_box([12, 8, 10], 4, 3, 2)),
        plated(
            "folded-rim-open",
            "rim",
            folded_rim_box([12, 8, 10], 4, 3, 2, false),
        ),
        Family {
            name: "thread",
            part: "bolt",
            case: thread(4, 1),
            assembly: nut_on_thread(4, 1),
        },
        plated("gear", "gear", gear(12, 30, 40, 6, 1)),
        plated(
            "folded-fillet",
            "fillet",
            folded_fillet([40, 10, 36], 20, 5, 2),
        ),
        plated("overlapping-shells", "shells", bracket_shells(10, 4, 2, 8)),
        plated(
            "crossing-shells",
            "shells",
            overlapping_shells(([0, 0, 0], [6, 6, 6]), ([3, 2, 1], [9, 4, 4])),
        ),
    ]
}

/// Writes each part as `<name>.off` into `dir` (created if needed).
pub fn write_off_dir(parts: &[NamedTriSoup], dir: &std::path::Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for (name, soup) in parts {
        std::fs::write(dir.join(format!("{name}.off")), soup.to_soup().to_off())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::winding::{cell_volume, monte_carlo_volume, WindingOracle};

    fn check_estimate(name: &str, c: &Case, samples: usize) {
        assert!(
            c.closed().edge_balance().values().all(|&n| n == 0),
            "{name}"
        );
        let e = monte_carlo_volume(&c.closed(), samples, 12345);
        assert!(e.agrees(c.volume_f64()), "{name}: {e:?} vs {:?}", c.volume);
        assert!(e.bound < 0.1 * e.box_volume, "{name}: {e:?}");
    }

    #[test]
    fn folded_rim_box_is_open_and_non_manifold_and_is_the_box() {
        let lidded = folded_rim_box([12, 8, 10], 4, 3, 2, true);
        assert_eq!(lidded.volume, (960, 1));
        // With the lid: the rim edges carry three faces, the boundary counts them once.
        let bal = lidded.soup.edge_balance();
        let rim = bal
            .iter()
            .filter(|(e, &n)| n.abs() == 1 && e.0[2] == 10 && e.1[2] == 10);
        assert_eq!(rim.count(), 16);
        assert_eq!(bal.values().filter(|&&n| n != 0).count(), 20);
        check_estimate("lidded rim", &lidded, 4000);
        let warped = warped_rim_box([12, 8, 10], 4, 3, 2);
        assert_eq!(warped.volume, (960, 1));
        check_estimate("warped rim", &warped, 4000);
        // The inset loop is not planar: its four points span a volume.
        let inset: Vec<[i64; 3]> = warped.caps.points[warped.caps.points.len() - 6..].to_vec();
        assert!(inset.iter().any(|p| p[2] == 8) && inset.iter().any(|p| p[2] == 7));
        let c = folded_rim_box([12, 8, 10], 4, 3, 2, false);
        assert_eq!(c.volume, (960, 1));
        let bal = c.soup.edge_balance();
        // Rim edges: two faces the same way (balance ±2); inset loop: ±1.
        let rim = bal
            .iter()
            .filter(|(e, &n)| n.abs() == 2 && e.0[2] == 10 && e.1[2] == 10);
        assert_eq!(rim.count(), 16);
        let inset = bal
            .iter()
            .filter(|(e, &n)| n.abs() == 1 && e.0[2] == 7 && e.1[2] == 7);
        assert_eq!(inset.count(), 4);
        assert_eq!(bal.values().filter(|&&n| n != 0).count(), 20);
        // Winding 2 in the frustum under the rim, 1 elsewhere in the box, 0 outside.
        let o = WindingOracle::new(&c.closed(), 2);
        assert_eq!(o.winding([11, 9, 19]), Some(2));
        assert_eq!(o.winding([1, 7, 15]), Some(1));
        assert_eq!(o.winding([11, 9, 11]), Some(1));
        assert_eq!(o.winding([11, 9, 21]), Some(0));
        check_estimate("rim", &c, 4000);
        for s in [2, 3, 5] {
            let c = folded_rim_box([6 * s, 3 * s, 7], s as u32, 2, 1, s % 2 == 0);
            assert_eq!(c.volume.0, 126 * (s * s) as i128);
        }
    }

    #[test]
    fn thread_is_the_union_of_its_rings() {
        for (layers, unit) in [(1, 1), (3, 1), (4, 2), (6, 1)] {
            let c = thread(layers, unit);
            let boxes = thread_boxes(layers, unit);
            let axis = |k: usize| {
                let mut v: Vec<i64> = boxes.iter().flat_map(|b| [b.0[k], b.1[k]]).collect();
                v.extend([0, 1]);
                v.sort_unstable();
                v.dedup();
                v
            };
            let (xs, ys, zs) = (axis(0), axis(1), axis(2));
            // Cell by cell, the seams' strips lie on the walls: closing them is what
            // the centres' winding numbers (taken off the walls) already say.
            assert_eq!(
                cell_volume(&c.closed(), [&xs, &ys, &zs]),
                Some(c.volume.0),
                "{layers} {unit}"
            );
            // Open seams: a 1-wide rectangle per ring; slivers: 3 edges per ring.
            let open = c.soup.edge_balance().values().filter(|&&n| n != 0).count();
            assert_eq!(open, layers * (4 + 3));
            let zero_area = c
                .soup
                .triangles
                .iter()
                .filter(|t| {
                    let [a, b, p] = t.map(|i| c.soup.points[i as usize].map(i128::from));
                    let (u, v) = (
                        [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                        [p[0] - a[0], p[1] - a[1], p[2] - a[2]],
                    );
                    u[1] * v[2] == u[2] * v[1]
                        && u[2] * v[0] == u[0] * v[2]
                        && u[0] * v[1] == u[1] * v[0]
                })
                .count();
            assert_eq!(zero_area, layers);
        }
        check_estimate("thread", &thread(4, 1), 4000);
        assert_eq!(thread(1, 1).volume.0, 10 * 6 * 6 + 4 * 4 * 2 * 2);
    }

    #[test]
    fn the_nut_fills_the_rest_of_its_box() {
        for (layers, unit) in [(3, 1), (5, 2)] {
            let nut = thread_nut(layers, unit);
            let (a, _, _) = thread_sizes(unit);
            let w = (a + 2 * unit) as i128;
            let h = 4 * layers as i128;
            let boxes = thread_boxes(layers, unit);
            let inside: Vec<_> = boxes
                .iter()
                .map(|&(lo, hi)| (lo, hi))
                .map(|(mut lo, mut hi)| {
                    lo[2] = lo[2].max(1);
                    hi[2] = hi[2].min(4 * layers as i64 + 1);
                    (lo, hi)
                })
                .collect();
            assert_eq!(nut.volume6(), 6 * (4 * w * w * h - union_volume(&inside)));
            // The nut and the bolt do not overlap: no point is in both.
            let bolt = thread(layers, unit).closed();
            let (ob, on) = (
                WindingOracle::new(&bolt, 2),
                WindingOracle::new(&TriSoup::from(&nut), 2),
            );
            let mut rng = crate::solids::Lcg(3);
            for _ in 0..2000 {
                let p = [
                    2 * rng.range(-(w as i64), w as i64) + 1,
                    2 * rng.range(-(w as i64), w as i64) + 1,
                    2 * rng.range(0, h as i64 + 2) + 1,
                ];
                let (b, n) = (ob.winding(p), on.winding(p));
                assert!(!(b >= Some(1) && n >= Some(1)), "{p:?}");
            }
        }
    }

    #[test]
    fn gear_flanks_cross_at_the_roots_and_the_solid_is_the_outline() {
        for (teeth, root, tip, over) in [(12, 30, 40, 1), (8, 20, 28, 2), (20, 60, 72, 1)] {
            let (profile, outline) = gear_profiles(teeth, root, tip, over);
            assert!(area2(&outline) > 0);
            // Each overshoot closes a counter-clockwise triangle (winding 2 there).
            for i in 0..teeth {
                let r = outline[3 * i + 2];
                let (x1, x2) = (profile[4 * i + 2], profile[4 * i + 3]);
                assert!(area2(&[r, x1, x2]) > 0, "{teeth} {i}");
            }
            let c = gear(teeth, root, tip, 6, over);
            // No cap triangle has zero area.
            assert!(c.soup.triangles.iter().all(|t| {
                let [a, b, p] = t.map(|i| c.soup.points[i as usize]);
                !(a[2] == b[2] && b[2] == p[2])
                    || area2(&[[a[0], a[1]], [b[0], b[1]], [p[0], p[1]]]) != 0
            }));
            // At mid-height, on a lattice of half-integer points, {w >= 1} is the
            // outline (exact crossing-number test on the outline).
            let o = WindingOracle::new(&c.soup, 2);
            for x in -tip - 1..=tip {
                for y in -tip - 1..=tip {
                    let p = [2 * x + 1, 2 * y + 1, 6];
                    let Some(w) = o.winding(p) else { continue };
                    assert_eq!(
                        w >= 1,
                        inside_polygon(&outline, [2 * x + 1, 2 * y + 1]),
                        "{teeth}: ({x}.5, {y}.5) w = {w}"
                    );
                    assert!((0..=2).contains(&w));
                }
            }
        }
        check_estimate("gear", &gear(12, 30, 40, 6, 1), 4000);
    }

    /// Crossing number of the doubled point `p` (odd coordinates) in the polygon
    /// scaled by 2: never on a vertex; a point on an edge counts as inside.
    fn inside_polygon(poly: &[[i64; 2]], p: [i64; 2]) -> bool {
        let n = poly.len();
        let mut inside = false;
        for k in 0..n {
            let (a, b) = (poly[k].map(|c| 2 * c), poly[(k + 1) % n].map(|c| 2 * c));
            if (a[1] > p[1]) != (b[1] > p[1]) {
                let lhs = (p[0] - a[0]) as i128 * (b[1] - a[1]) as i128;
                let rhs = (b[0] - a[0]) as i128 * (p[1] - a[1]) as i128;
                if (lhs < rhs) == (b[1] > a[1]) {
                    inside = !inside;
                }
            }
        }
        inside
    }

    #[test]
    fn folded_fillet_has_a_negative_pocket_and_the_known_volume() {
        for (radius, segments, fold) in [(20, 5, 2), (30, 6, 2), (30, 6, 3)] {
            let e = [40, 10, 36];
            let (profile, q) = fillet_profile(e, radius, segments, fold);
            // The arc is strictly convex around the fold.
            for k in 0..2 {
                assert!(area2(&[q[k], q[k + 1], q[k + 2]]) > 0);
            }
            let c = folded_fillet(e, radius, segments, fold);
            assert!(c.soup.edge_balance().values().all(|&n| n == 0));
            let v = c.volume_f64();
            let full = area2(&profile);
            let mut rounded = profile.clone();
            rounded.swap(fold + 2, fold + 3);
            let hi = (area2(&rounded) * e[1] as i128) as f64 / 2.0;
            let lo = hi - (area2(&q) * e[1] as i128) as f64 / 2.0;
            assert!(lo < v && v < hi, "{lo} {v} {hi}");
            // Against the box with a true quarter-round edge: the facets and the fold
            // only take material away, and never more than the corner square.
            let (xz, r2) = ((e[0] * e[2]) as f64, (radius * radius) as f64);
            let round = e[1] as f64 * (xz - (1.0 - std::f64::consts::FRAC_PI_4) * r2);
            assert!(v < round && v > e[1] as f64 * (xz - r2), "{v} {round}");
            // The folded profile's own signed area is smaller still (the pocket
            // counts −1, the two wings 0).
            assert!(((full * e[1] as i128) as f64 / 2.0) < v);
            let e_mc = monte_carlo_volume(&c.soup, 4000, 99);
            assert!(e_mc.agrees(v), "{e_mc:?} {v}");
            // The pocket's centroid has winding −1: (Q1 + Q2 + X) / 3 at mid-length,
            // X = Q0 + (num / den) (Q2 − Q0), all scaled by 6 · den.
            let cr = |a: [i64; 2], b: [i64; 2]| a[0] * b[1] - a[1] * b[0];
            let d = |a: [i64; 2], b: [i64; 2]| [b[0] - a[0], b[1] - a[1]];
            let (ev, fv) = (d(q[0], q[2]), d(q[1], q[3]));
            let (mut den, mut num) = (cr(ev, fv), cr(d(q[0], q[1]), fv));
            if den < 0 {
                (den, num) = (-den, -num);
            }
            let pocket = |k: usize| 2 * ((q[1][k] + q[2][k] + q[0][k]) * den + num * ev[k]);
            let o = WindingOracle::new(&c.soup, 6 * den);
            assert_eq!(o.winding([pocket(0), 3 * den * e[1], pocket(1)]), Some(-1));
        }
    }

    #[test]
    fn overlapping_shells_are_their_union() {
        let c = bracket_shells(10, 4, 2, 8);
        assert_eq!(c.volume, (10 * 4 * 2 + 2 * 4 * 8 - 2 * 4 * 2, 1));
        let g = [0, 2, 10];
        assert_eq!(
            cell_volume(&c.closed(), [&g, &[0, 4], &[0, 2, 8]]),
            Some(c.volume.0)
        );
        check_estimate("shells", &c, 4000);
        let c = overlapping_shells(([0, 0, 0], [5, 5, 5]), ([3, 2, 1], [9, 4, 4]));
        assert_eq!(c.volume.0, 125 + 6 * 2 * 3 - 2 * 2 * 3);
        check_estimate("shells2", &c, 4000);
    }

    #[test]
    fn every_family_is_sampled_to_its_volume() {
        for f in families() {
            check_estimate(f.name, &f.case, 4000);
            assert!(f
                .assembly
                .iter()
                .any(|(n, s)| n == f.part && *s == f.case.soup));
        }
    }

    #[test]
    fn plates_sit_under_their_parts() {
        let parts = on_plate("gear", gear(8, 20, 28, 4, 1).soup);
        let (lo, hi) = parts[1].1.bbox();
        assert_eq!((lo[2], hi[2]), (-2, 0));
        assert_eq!(parts[0].1.bbox().0[2], 0);
        assert_eq!(nut_on_thread(3, 1).len(), 2);
    }
}
