//! Parametric test parts (paper 004 fig. 14 and fig. 2), as closed integer meshes
//! decomposed exactly into convex pieces; in millimetres, sheet thickness a few units.
//!
//! - [`cube`]: a cube (the 121 cubes of fig. 2).
//! - [`channel`]: a U-profile channel with three flanges (two splayed walls and the
//!   web), extruded; identical channels nest in the same orientation.
//! - [`triangle_part`]: a roof (Λ, triangular) profile with six flanges: two up-turned
//!   hems, two feet and the two slopes; identical parts nest in the same orientation.
//! - [`complex_part`]: a plate with a grid of holes and two tall flanges with windows
//!   (about 80 convex pieces), like fig. 14(c).
//!
//! The bent profiles are thickened vertically (the top line is the bottom line raised by
//! the thickness), so a part raised by the thickness rests exactly on an identical one.

use crate::part::{PartModel, StackError};
use apart_kernel::Vec3;
use std::collections::HashMap;
use std::fmt::Write as _;

/// A unit-aligned cube `[0, size]³`.
pub fn cube(size: i64) -> PartModel {
    let pts: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new((i & 1) * size, (i >> 1 & 1) * size, (i >> 2 & 1) * size))
        .collect();
    let p = apart_pieces::Polytope::hull_of_points(&pts).expect("a cube");
    let mut part = PartModel::from_pieces("cube", vec![p]).expect("pieces");
    part.mesh = Some(box_mesh([0, 0, 0], [size, size, size]));
    part
}

fn box_mesh(lo: [i64; 3], hi: [i64; 3]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let pts: Vec<Vec3> = (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 == 1 { hi[0] } else { lo[0] },
                if i & 2 == 2 { hi[1] } else { lo[1] },
                if i & 4 == 4 { hi[2] } else { lo[2] },
            )
        })
        .collect();
    let quads = [
        [0, 2, 3, 1], // z = lo, normal −z
        [4, 5, 7, 6], // z = hi
        [0, 1, 5, 4], // y = lo
        [2, 6, 7, 3], // y = hi
        [0, 4, 6, 2], // x = lo
        [1, 3, 7, 5], // x = hi
    ];
    let mut tris = Vec::new();
    for q in quads {
        tris.push([q[0], q[1], q[2]]);
        tris.push([q[0], q[2], q[3]]);
    }
    (pts, tris)
}

/// Dimensions of the channel part.
#[derive(Clone, Copy, Debug)]
pub struct ChannelParams {
    /// Width of the web (outside, at the bottom).
    pub width: i64,
    /// Height of the walls.
    pub height: i64,
    /// Horizontal run of each splayed wall.
    pub splay: i64,
    /// Sheet thickness (vertical).
    pub thickness: i64,
    /// Length of the extrusion (along y).
    pub length: i64,
}

impl Default for ChannelParams {
    fn default() -> Self {
        ChannelParams {
            width: 60,
            height: 30,
            splay: 15,
            thickness: 3,
            length: 80,
        }
    }
}

/// The channel part with default dimensions (60 wide, 30 high, 80 long, t = 3).
pub fn channel() -> PartModel {
    channel_with(&ChannelParams::default()).expect("the default channel decomposes")
}

/// A U-profile channel: web and two walls splayed outwards, extruded along y.
pub fn channel_with(c: &ChannelParams) -> Result<PartModel, StackError> {
    let line = [
        [-c.splay, c.height],
        [0, 0],
        [c.width, 0],
        [c.width + c.splay, c.height],
    ];
    let (pts, tris) = extrusion(&thickened(&line, c.thickness), c.length);
    PartModel::from_mesh("channel", pts, tris)
}

/// Dimensions of the triangle part.
#[derive(Clone, Copy, Debug)]
pub struct TriangleParams {
    /// Half the span of the triangle's base (horizontal run of each slope).
    pub run: i64,
    /// Height of the apex.
    pub rise: i64,
    /// Length of each foot.
    pub foot: i64,
    /// Height of the up-turned hems (run a third of it).
    pub hem: i64,
    /// Sheet thickness (vertical).
    pub thickness: i64,
    /// Length of the extrusion (along y).
    pub length: i64,
}

impl Default for TriangleParams {
    fn default() -> Self {
        TriangleParams {
            run: 30,
            rise: 24,
            foot: 15,
            hem: 9,
            thickness: 3,
            length: 60,
        }
    }
}

/// The triangle part with default dimensions.
pub fn triangle_part() -> PartModel {
    triangle_with(&TriangleParams::default()).expect("the default triangle part decomposes")
}

/// A roof profile: hem, foot, slope up, slope down, foot, hem (six flanges).
pub fn triangle_with(t: &TriangleParams) -> Result<PartModel, StackError> {
    let h = t.hem / 3;
    let x0 = 0;
    let x1 = x0 + h;
    let x2 = x1 + t.foot;
    let x3 = x2 + t.run;
    let x4 = x3 + t.run;
    let x5 = x4 + t.foot;
    let x6 = x5 + h;
    let line = [
        [x0, t.hem],
        [x1, 0],
        [x2, 0],
        [x3, t.rise],
        [x4, 0],
        [x5, 0],
        [x6, t.hem],
    ];
    let (pts, tris) = extrusion(&thickened(&line, t.thickness), t.length);
    PartModel::from_mesh("triangle", pts, tris)
}

/// The polygon of a polyline (x, z) thickened upwards by `t`: the line, then the line
/// raised by `t` backwards.
fn thickened(line: &[[i64; 2]], t: i64) -> Vec<[i64; 2]> {
    let mut poly: Vec<[i64; 2]> = line.to_vec();
    poly.extend(line.iter().rev().map(|p| [p[0], p[1] + t]));
    poly
}

/// Twice the signed area of a polygon.
fn area2(poly: &[[i64; 2]]) -> i128 {
    (0..poly.len())
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            p[0] as i128 * q[1] as i128 - p[1] as i128 * q[0] as i128
        })
        .sum()
}

fn orient2(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i128 {
    (b[0] - a[0]) as i128 * (c[1] - a[1]) as i128 - (b[1] - a[1]) as i128 * (c[0] - a[0]) as i128
}

/// Triangles of a simple counter-clockwise polygon (ear clipping, exact).
fn ear_clip(poly: &[[i64; 2]]) -> Vec<[usize; 3]> {
    let mut idx: Vec<usize> = (0..poly.len()).collect();
    let mut out = Vec::new();
    while idx.len() > 3 {
        let n = idx.len();
        let ear = (0..n)
            .find(|&k| {
                let (a, b, c) = (
                    poly[idx[(k + n - 1) % n]],
                    poly[idx[k]],
                    poly[idx[(k + 1) % n]],
                );
                if orient2(a, b, c) <= 0 {
                    return false;
                }
                idx.iter().all(|&j| {
                    let p = poly[j];
                    if p == a || p == b || p == c {
                        return true;
                    }
                    !(orient2(a, b, p) >= 0 && orient2(b, c, p) >= 0 && orient2(c, a, p) >= 0)
                })
            })
            .expect("a simple polygon has an ear");
        out.push([idx[(ear + n - 1) % n], idx[ear], idx[(ear + 1) % n]]);
        idx.remove(ear);
    }
    out.push([idx[0], idx[1], idx[2]]);
    out
}

/// A prism over a simple polygon in the (x, z) plane, `y` in `[0, length]`, with
/// outward triangles.
pub fn extrusion(profile: &[[i64; 2]], length: i64) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut poly = profile.to_vec();
    if area2(&poly) < 0 {
        poly.reverse();
    }
    let n = poly.len() as u32;
    let points: Vec<Vec3> = poly
        .iter()
        .map(|p| Vec3::new(p[0], 0, p[1]))
        .chain(poly.iter().map(|p| Vec3::new(p[0], length, p[1])))
        .collect();
    let mut tris = Vec::new();
    // Counter-clockwise in (x, z) gives the −y normal for a triangle at y = 0.
    for t in ear_clip(&poly) {
        let t = t.map(|i| i as u32);
        tris.push([t[0], t[1], t[2]]);
        tris.push([t[0] + n, t[2] + n, t[1] + n]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        tris.push([i, j + n, j]);
        tris.push([i, i + n, j + n]);
    }
    (points, tris)
}

/// The union of the filled cells of the rectilinear grid `xs × ys × zs`: its boundary,
/// two outward triangles per grid rectangle between a filled and an empty cell.
pub fn rectilinear(
    g: [&[i64]; 3],
    filled: impl Fn([usize; 3]) -> bool,
) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let n = [g[0].len() - 1, g[1].len() - 1, g[2].len() - 1];
    let full = |c: [i64; 3]| -> bool {
        (0..3).all(|a| c[a] >= 0 && (c[a] as usize) < n[a])
            && filled([c[0] as usize, c[1] as usize, c[2] as usize])
    };
    let mut ids: HashMap<[i64; 3], u32> = HashMap::new();
    let mut points = Vec::new();
    let mut id = |p: [i64; 3]| -> u32 {
        *ids.entry(p).or_insert_with(|| {
            points.push(Vec3::from_i64(p));
            (points.len() - 1) as u32
        })
    };
    let mut tris = Vec::new();
    let coord = |i: [usize; 3]| [g[0][i[0]], g[1][i[1]], g[2][i[2]]];
    for a in 0..3 {
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        for p in 0..=n[a] {
            for iu in 0..n[u] {
                for iv in 0..n[v] {
                    let mut lo = [0i64; 3];
                    lo[a] = p as i64 - 1;
                    lo[u] = iu as i64;
                    lo[v] = iv as i64;
                    let mut hi = lo;
                    hi[a] += 1;
                    let (fl, fh) = (full(lo), full(hi));
                    if fl == fh {
                        continue;
                    }
                    let mut base = [0usize; 3];
                    base[a] = p;
                    base[u] = iu;
                    base[v] = iv;
                    let mut c1 = base;
                    c1[u] += 1;
                    let mut c2 = c1;
                    c2[v] += 1;
                    let mut c3 = base;
                    c3[v] += 1;
                    let q = [base, c1, c2, c3].map(|c| id(coord(c)));
                    if fl {
                        tris.push([q[0], q[1], q[2]]);
                        tris.push([q[0], q[2], q[3]]);
                    } else {
                        tris.push([q[0], q[2], q[1]]);
                        tris.push([q[0], q[3], q[2]]);
                    }
                }
            }
        }
    }
    (points, tris)
}

/// The complex part: a 240 x 160 plate (t = 2) with 50 holes of 10 x 10, two 102-high
/// flanges along its short edges with windows and notches, and a 60-high middle flange
/// with a slot (82 convex pieces after exact decomposition).
pub fn complex_part() -> PartModel {
    const ROWS: usize = 9;
    let xs: Vec<i64> = [0, 2]
        .into_iter()
        .chain((1..12).map(|k| 10 * k))
        .chain([118, 122])
        .chain((13..24).map(|k| 10 * k))
        .chain([238, 240])
        .collect();
    let ys: Vec<i64> = (0..=16).map(|k| 10 * k).collect();
    let zs = [0i64, 2, 30, 60, 80, 102];
    let last = xs.len() - 2;
    let mid = xs.iter().position(|&x| x == 118).expect("middle flange");
    let (pts, tris) = rectilinear([&xs, &ys, &zs], |c| {
        let [i, j, k] = c;
        if k == 0 {
            // 10 x 10 holes: ten columns, five rows (y 10–20, 30–40, ..., 90–100).
            let x0 = xs[i];
            let hole = j % 2 == 1 && j <= ROWS && x0 % 20 == 10 && x0 != 110 && x0 != 230;
            !hole
        } else if i == 0 || i == last {
            // Tall flanges: windows at z 30–60 in y 20–40, 60–80, 100–120; notches at the
            // top in y 40–50 and 120–130.
            let window = k == 2 && matches!(j, 2 | 3 | 6 | 7 | 10 | 11);
            let notch = k == 4 && (j == 4 || j == 12);
            !(window || notch)
        } else if i == mid {
            // Middle flange, 60 high over y 20–140, with a slot at z 30–60, y 70–90.
            (2..=13).contains(&j) && k <= 2 && !(k == 2 && (j == 7 || j == 8))
        } else {
            false
        }
    });
    PartModel::from_mesh("complex", pts, tris).expect("the complex part decomposes")
}

/// The mesh of a part as OFF text (integer coordinates).
pub fn off_text(points: &[Vec3], triangles: &[[u32; 3]]) -> String {
    let mut s = String::from("OFF\n");
    let _ = writeln!(s, "{} {} 0", points.len(), triangles.len());
    for p in points {
        let c = p.to_strings();
        let _ = writeln!(s, "{} {} {}", c[0], c[1], c[2]);
    }
    for t in triangles {
        let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
    }
    s
}

/// Writes a part's mesh as an OFF file.
pub fn write_off(part: &PartModel, path: &std::path::Path) -> std::io::Result<()> {
    let Some((pts, tris)) = &part.mesh else {
        return Err(std::io::Error::other("the part has no mesh"));
    };
    std::fs::write(path, off_text(pts, tris))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::q;

    fn mesh_volume6(points: &[Vec3], tris: &[[u32; 3]]) -> apart_kernel::Int {
        let mut v = apart_kernel::Int::ZERO;
        for t in tris {
            let [a, b, c] = t.map(|i| points[i as usize].clone());
            v += a.dot(&b.cross(&c));
        }
        v
    }

    #[test]
    fn generated_parts_are_closed_and_decompose() {
        for part in [cube(2), channel(), triangle_part()] {
            let (pts, tris) = part.mesh.as_ref().unwrap();
            let v6 = mesh_volume6(pts, tris);
            assert!(v6 > apart_kernel::Int::ZERO, "{}", part.name);
            // The pieces' volume equals the mesh's (divergence theorem).
            assert_eq!(
                *part.volume(),
                crate::exact::Q::new(v6, apart_kernel::Int::from(6)),
                "{}",
                part.name
            );
            apart_decompose::verify(pts, tris, &part.pieces).unwrap();
        }
        // A profile thickened vertically by t has area t times its horizontal run.
        let c = ChannelParams::default();
        let run = 2 * c.splay + c.width;
        assert_eq!(*channel().volume(), q(c.thickness * run * c.length));
        let t = TriangleParams::default();
        let run = 2 * (t.hem / 3 + t.foot + t.run);
        assert_eq!(*triangle_part().volume(), q(t.thickness * run * t.length));
        assert_eq!(*cube(3).volume(), q(27));
    }
}
