//! Tessellated curved parts whose fits interpenetrate by a known depth.
//!
//! Every solid here is a *lathe*: a polygonal profile in the `(r, z)` half-plane swept
//! around the z axis in `n` straight segments (a regular `n`-gon cross-section), emitted
//! as triangles the way CAD exporters tessellate cylinders. Profiles are stair steps
//! (horizontal and vertical segments only), so every quad of the sweep is planar before
//! and after snapping, and each solid is a closed, outward-oriented 2-manifold.
//!
//! Two lathes with the same `n` and phase share their ring coordinates bit for bit, so a
//! pin in a hole of the same tessellation touches its walls exactly after snapping. With
//! different tessellations the pin pokes out of the hole by [`pin_in_hole_depth`].

use crate::Soup;
use std::f64::consts::PI;

/// A part: its name and its closed surface.
pub type NamedSoup = (String, Soup);

/// The solid swept by the profile `(r, z)` around the z axis in `n` segments, the ring
/// vertices at angles `phase + 2πk/n`.
///
/// The profile runs counter-clockwise in the `(r, z)` plane (solid on its left): either
/// from a point on the axis (`r = 0`) to another point on the axis (a solid without a
/// hole, capped by `n`-gons fanned into triangles), or as a closed loop with `r > 0`
/// everywhere (a sleeve; the last point joins the first). Each profile segment off the
/// axis sweeps `n` quads, each split into two triangles.
pub fn lathe(profile: &[[f64; 2]], n: usize, phase: f64) -> Soup {
    assert!(n >= 3 && profile.len() >= 2);
    let open = profile[0][0] == 0.0;
    assert_eq!(
        open,
        profile[profile.len() - 1][0] == 0.0,
        "a profile starts and ends on the axis, or never touches it"
    );
    let mut soup = Soup::default();
    // One ring of vertices per profile point off the axis, one vertex per axis point.
    let mut rings: Vec<Vec<u32>> = Vec::new();
    for &[r, z] in profile {
        let base = soup.vertices.len() as u32;
        if r == 0.0 {
            soup.vertices.push([0.0, 0.0, z]);
            rings.push(vec![base]);
        } else {
            for k in 0..n {
                let t = phase + 2.0 * PI * k as f64 / n as f64;
                soup.vertices.push([r * t.cos(), r * t.sin(), z]);
            }
            rings.push((base..base + n as u32).collect());
        }
    }
    let segments = if open {
        profile.len() - 1
    } else {
        profile.len()
    };
    for s in 0..segments {
        let (p, q) = (&rings[s], &rings[(s + 1) % profile.len()]);
        match (p.len(), q.len()) {
            (1, 1) => panic!("a profile segment along the axis"),
            // Leaving the axis: a cap facing backwards (decreasing angle).
            (1, _) => {
                for k in 1..n - 1 {
                    soup.faces.push(vec![q[0], q[n - k], q[n - k - 1]]);
                }
            }
            // Reaching the axis: a cap facing forwards (increasing angle).
            (_, 1) => {
                for k in 1..n - 1 {
                    soup.faces.push(vec![p[0], p[k], p[k + 1]]);
                }
            }
            _ => {
                for k in 0..n {
                    let k1 = (k + 1) % n;
                    // (p_k, p_k+1, q_k+1, q_k) is counter-clockwise seen from outside.
                    soup.faces.push(vec![p[k], p[k1], q[k1]]);
                    soup.faces.push(vec![p[k], q[k1], q[k]]);
                }
            }
        }
    }
    soup
}

/// The number of triangles [`lathe`] makes of `profile` in `n` segments.
pub fn lathe_triangles(profile: &[[f64; 2]], n: usize) -> usize {
    let open = profile[0][0] == 0.0;
    let axis = profile.iter().filter(|p| p[0] == 0.0).count();
    let segments = if open {
        profile.len() - 1
    } else {
        profile.len()
    };
    // Segments touching the axis are caps (n − 2 triangles), the others 2n.
    let caps = if open { 2.min(axis) } else { 0 };
    caps * (n - 2) + (segments - caps) * 2 * n
}

/// Pin radius of [`pin_in_hole`].
pub const PIN_RADIUS: f64 = 4.0;

/// A pin in a blind hole: the pin (`"pin"`, a prism of `n` segments, radius
/// [`PIN_RADIUS`], z from 0 to 10) stands on the floor of a hole of `m` segments and the
/// same radius (z from 0 to 6) in a block (`"block"`, a prism of `m` segments, radius 8,
/// z from −2 to 6). The pin's vertices lie at angles `phase + 2πk/n`, the hole's at
/// `2πk/m`.
///
/// Known answer: with `n == m` and `phase == 0` the pin touches the floor and every wall
/// and leaves along `+z` only (an isolated direction, a vertex of the motion space; the
/// block leaves along `−z`). Otherwise the pin pokes out of the hole by
/// [`pin_in_hole_depth`]`(n, m, phase, PIN_RADIUS)` (positive unless the pin's vertices
/// all sit at hole vertices), and loading reports the overlap.
pub fn pin_in_hole(n: usize, m: usize, phase: f64) -> Vec<NamedSoup> {
    let r = PIN_RADIUS;
    let pin = lathe(&[[0.0, 0.0], [r, 0.0], [r, 10.0], [0.0, 10.0]], n, phase);
    let block = lathe(
        &[
            [0.0, -2.0],
            [8.0, -2.0],
            [8.0, 6.0],
            [r, 6.0],
            [r, 0.0],
            [0.0, 0.0],
        ],
        m,
        0.0,
    );
    vec![("block".into(), block), ("pin".into(), pin)]
}

/// An `n` by `n` rack of [`pin_in_hole`] pairs (`m` segments, matching tessellations)
/// under a plate: block `(i, j)` stands at `(16 i, 16 j)`, so neighbouring blocks touch
/// along a vertical edge, and the plate (`"plate"`, z from 10 to 11) covers every pin and
/// touches its top. `2 n² + 1` parts of curved pieces, for many-part benchmarks.
///
/// Known answer: the plate leaves through the open upper hemisphere; each block alone
/// leaves its pin along `−z` only (the pin fills the hole, so that direction is
/// isolated); a block at a corner of the rack leaves with its pin outwards and
/// downwards; no pin moves alone (the plate is on it).
pub fn pin_rack(n: usize, m: usize) -> Vec<NamedSoup> {
    let mut parts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let at = [16.0 * i as f64, 16.0 * j as f64, 0.0];
            for (name, soup) in pin_in_hole(m, m, 0.0) {
                parts.push((format!("{name}_{i}_{j}"), soup.translated(at)));
            }
        }
    }
    let far = 16.0 * n.saturating_sub(1) as f64 + 8.0;
    parts.push((
        "plate".into(),
        crate::defects::box_soup([-8.0, -8.0, 10.0], [far, far, 11.0]),
    ));
    parts
}

/// How far a regular `n`-gon pin of circumradius `r` (vertices at `phase + 2πk/n`) pokes
/// out of a regular `m`-gon hole of the same circumradius (vertices at `2πj/m`): the
/// largest distance from a point of the pin's cross-section to the hole's.
///
/// Closed form: the hole's edges lie at distance `r cos(π/m)` from the axis, with their
/// midpoints at angles `π/m + 2πj/m`. A pin vertex at angular distance `δ ≤ π/m` from the
/// nearest midpoint lies at distance `r cos δ − r cos(π/m)` outside that edge's line, and
/// its foot falls within the edge (`r sin δ ≤ r sin(π/m)`, half the edge), so that is its
/// distance to the hole. The distance to a convex set is convex, so its maximum over the
/// pin is at a vertex:
///
/// `depth = r (cos δ_min − cos(π/m))`, `δ_min` the smallest such `δ` over the pin's
/// vertices. Matching tessellations (`n == m`, `phase == 0`) give `δ_min = π/m` and depth
/// 0; a pin of `m` segments turned by half a segment (`phase = π/m`) gives `δ_min = 0`
/// and the largest depth `r (1 − cos(π/m))`.
pub fn pin_in_hole_depth(n: usize, m: usize, phase: f64, r: f64) -> f64 {
    let period = 2.0 * PI / m as f64;
    let delta = (0..n)
        .map(|k| {
            let a = phase + 2.0 * PI * k as f64 / n as f64 - PI / m as f64;
            let x = a.rem_euclid(period);
            x.min(period - x)
        })
        .fold(f64::INFINITY, f64::min);
    (r * (delta.cos() - (PI / m as f64).cos())).max(0.0)
}

/// Segments per ring of [`plug_and_socket`] for about `triangles` triangles in total.
pub fn plug_and_socket_segments(triangles: usize) -> usize {
    // The plug has 8n − 4 triangles, the socket 12n − 4.
    ((triangles + 8) / 20).max(3)
}

/// A stepped cylindrical plug in a socket, about `triangles` triangles in total (exactly
/// `20n − 8` for `n` = [`plug_and_socket_segments`]`(triangles)` segments per ring).
///
/// The plug (`"plug"`) is a cylinder of radius 3 (z from 0 to 4) under one of radius 5
/// (z from 4 to 12); the socket (`"socket"`, outer radius 8, z from −2 to 8) has the
/// matching stepped blind hole, so the plug touches its floor, its step and its walls.
///
/// Known answer: the plug leaves along `+z` only and the socket along `−z` only, both
/// isolated directions (vertices of the motion space); nothing else separates them.
pub fn plug_and_socket(triangles: usize) -> Vec<NamedSoup> {
    let n = plug_and_socket_segments(triangles);
    let plug = lathe(
        &[
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 4.0],
            [5.0, 4.0],
            [5.0, 12.0],
            [0.0, 12.0],
        ],
        n,
        0.0,
    );
    let socket = lathe(
        &[
            [0.0, -2.0],
            [8.0, -2.0],
            [8.0, 8.0],
            [5.0, 8.0],
            [5.0, 4.0],
            [3.0, 4.0],
            [3.0, 0.0],
            [0.0, 0.0],
        ],
        n,
        0.0,
    );
    vec![("plug".into(), plug), ("socket".into(), socket)]
}

/// A nut on a bolt whose thread is approximated by `rings` stacked rings, all lathes of
/// `n` segments.
///
/// The bolt (`"bolt"`): a head of radius 6 (z from −2 to 0) and a shaft of radius 2 up to
/// `z = 4 rings + 4`, with rings of radius 3 at z in `[2 + 4k, 4 + 4k]`. The nut (`"nut"`,
/// outer radius 5, z from 1 to `4 rings + 1`) fills the grooves between the rings: its
/// hole has radius 3 along the rings and 2 between them, so it touches the bolt all
/// along.
///
/// Known answer (for `rings >= 1`): interlocked. Along `±z` a ring of the bolt meets a
/// tooth of the nut, and every other direction drives the shaft into the nut.
pub fn nut_on_bolt(n: usize, rings: usize) -> Vec<NamedSoup> {
    assert!(rings >= 1);
    let (r_in, r_out) = (2.0, 3.0);
    let top = 4.0 * rings as f64 + 4.0;
    let mut bolt = vec![[0.0, -2.0], [6.0, -2.0], [6.0, 0.0], [r_in, 0.0]];
    for k in 0..rings {
        let z = 2.0 + 4.0 * k as f64;
        bolt.extend([[r_in, z], [r_out, z], [r_out, z + 2.0], [r_in, z + 2.0]]);
    }
    bolt.extend([[r_in, top], [0.0, top]]);
    let z1 = 4.0 * rings as f64 + 1.0;
    let mut nut = vec![[r_in, 1.0], [5.0, 1.0], [5.0, z1], [r_in, z1]];
    for k in (0..rings).rev() {
        let z = 2.0 + 4.0 * k as f64;
        nut.extend([[r_in, z + 2.0], [r_out, z + 2.0], [r_out, z], [r_in, z]]);
    }
    vec![
        ("bolt".into(), lathe(&bolt, n, 0.0)),
        ("nut".into(), lathe(&nut, n, 0.0)),
    ]
}

/// Writes each part as `<name>.off` into `dir` (created if needed): a folder the
/// assembly loader reads.
pub fn write_off_dir(parts: &[NamedSoup], dir: &std::path::Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for (name, soup) in parts {
        std::fs::write(dir.join(format!("{name}.off")), soup.to_off())?;
    }
    Ok(())
}

/// Total triangles of some parts.
pub fn triangle_count(parts: &[NamedSoup]) -> usize {
    parts
        .iter()
        .flat_map(|(_, s)| &s.faces)
        .map(|f| f.len() - 2)
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Every edge used once in each direction (closed, consistently oriented), and a
    /// positive signed volume (outward).
    fn check_closed(s: &Soup) -> f64 {
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for f in &s.faces {
            for k in 0..f.len() {
                let (a, b) = (f[k], f[(k + 1) % f.len()]);
                *edges.entry((a, b)).or_default() += 1;
            }
        }
        for (&(a, b), &c) in &edges {
            assert_eq!(c, 1, "edge {a}-{b} used {c} times");
            assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}-{b} has no twin");
        }
        let mut v6 = 0.0;
        for f in &s.faces {
            let p = |i: u32| s.vertices[i as usize];
            let (a, b, c) = (p(f[0]), p(f[1]), p(f[2]));
            v6 += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
        v6 / 6.0
    }

    #[test]
    fn solids_are_closed_and_outward() {
        let n = 12;
        let area = |r: f64| 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin();
        let parts = plug_and_socket(20 * n - 8);
        let plug = check_closed(&parts[0].1);
        assert!((plug - (area(3.0) * 4.0 + area(5.0) * 8.0)).abs() < 1e-9);
        let socket = check_closed(&parts[1].1);
        let want = area(8.0) * 10.0 - area(3.0) * 4.0 - area(5.0) * 4.0;
        assert!((socket - want).abs() < 1e-9);
        assert_eq!(triangle_count(&parts), 20 * n - 8);
        for (_, s) in nut_on_bolt(10, 3).iter().chain(&pin_in_hole(7, 9, 0.3)) {
            assert!(check_closed(s) > 0.0);
        }
    }

    #[test]
    fn triangle_counts() {
        let p = [[0.0, 0.0], [3.0, 0.0], [3.0, 4.0], [0.0, 4.0]];
        assert_eq!(lathe(&p, 9, 0.0).faces.len(), lathe_triangles(&p, 9));
        assert_eq!(
            triangle_count(&plug_and_socket(14000)),
            20 * plug_and_socket_segments(14000) - 8
        );
    }

    #[test]
    fn depth_closed_form() {
        let r = PIN_RADIUS;
        assert!(pin_in_hole_depth(8, 8, 0.0, r).abs() < 1e-12);
        let half = pin_in_hole_depth(8, 8, PI / 8.0, r);
        assert!((half - r * (1.0 - (PI / 8.0).cos())).abs() < 1e-12);
        // A pin of 4 segments in a hole of 8 whose vertices are all hole vertices.
        assert!(pin_in_hole_depth(4, 8, 0.0, r).abs() < 1e-12);
        // Brute force: sample the pin's boundary and measure its distance to the hole.
        for (n, m, phase) in [(6, 8, 0.0), (9, 7, 0.2), (12, 12, 0.1)] {
            let hole: Vec<[f64; 2]> = (0..m)
                .map(|j| {
                    let t = 2.0 * PI * j as f64 / m as f64;
                    [r * t.cos(), r * t.sin()]
                })
                .collect();
            let outside = |p: [f64; 2]| -> f64 {
                (0..m)
                    .map(|j| {
                        let (a, b) = (hole[j], hole[(j + 1) % m]);
                        let e = [b[0] - a[0], b[1] - a[1]];
                        let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
                        ((p[0] - a[0]) * e[1] - (p[1] - a[1]) * e[0]) / len
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
                    .max(0.0)
            };
            let mut worst: f64 = 0.0;
            for k in 0..n {
                for s in 0..=100 {
                    let t0 = phase + 2.0 * PI * k as f64 / n as f64;
                    let t1 = phase + 2.0 * PI * (k + 1) as f64 / n as f64;
                    let u = s as f64 / 100.0;
                    let p = [
                        r * ((1.0 - u) * t0.cos() + u * t1.cos()),
                        r * ((1.0 - u) * t0.sin() + u * t1.sin()),
                    ];
                    worst = worst.max(outside(p));
                }
            }
            // Outside exactly one edge's line near a vertex: the signed distance to that
            // line is the distance to the polygon.
            assert!(
                (worst - pin_in_hole_depth(n, m, phase, r)).abs() < 1e-9,
                "{n} {m} {phase}: {worst}"
            );
        }
    }
}
