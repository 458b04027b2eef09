//! Parametric sheet-metal parts of the stacking paper (paper 004, fig. 14 and fig. 2) as
//! closed integer meshes; in millimetres, sheet thickness a few units. The stacking
//! tests, benchmark and example generator turn them into placement models (the cube as
//! one convex piece, the others decomposed exactly).
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
//! Known answers: every mesh is closed and outward; a profile of horizontal run `r`
//! thickened by `t` and extruded by `l` encloses `t · r · l`.

use crate::solids::{area2, ear_clip, rectilinear, IntMesh};

/// A named part mesh.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SheetPart {
    /// The part's name (also its file stem in `examples/sheet-metal/`).
    pub name: &'static str,
    /// Its boundary.
    pub mesh: IntMesh,
    /// The part is convex (one piece: the hull of its points).
    pub convex: bool,
}

/// A unit-aligned cube `[0, size]³`, its points numbered `x + 2y + 4z` (bits of the
/// corner).
pub fn cube(size: i64) -> SheetPart {
    SheetPart {
        name: "cube",
        mesh: box_mesh([0, 0, 0], [size, size, size]),
        convex: true,
    }
}

fn box_mesh(lo: [i64; 3], hi: [i64; 3]) -> IntMesh {
    let points = crate::solids::cuboid_corners(lo, hi);
    let mut triangles = Vec::new();
    for q in crate::solids::CUBOID_QUADS {
        triangles.push([q[0], q[1], q[2]]);
        triangles.push([q[0], q[2], q[3]]);
    }
    IntMesh { points, triangles }
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
pub fn channel() -> SheetPart {
    channel_with(&ChannelParams::default())
}

/// A U-profile channel: web and two walls splayed outwards, extruded along y.
pub fn channel_with(c: &ChannelParams) -> SheetPart {
    let line = [
        [-c.splay, c.height],
        [0, 0],
        [c.width, 0],
        [c.width + c.splay, c.height],
    ];
    SheetPart {
        name: "channel",
        mesh: extrusion(&thickened(&line, c.thickness), c.length),
        convex: false,
    }
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
pub fn triangle_part() -> SheetPart {
    triangle_with(&TriangleParams::default())
}

/// A roof profile: hem, foot, slope up, slope down, foot, hem (six flanges).
pub fn triangle_with(t: &TriangleParams) -> SheetPart {
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
    SheetPart {
        name: "triangle",
        mesh: extrusion(&thickened(&line, t.thickness), t.length),
        convex: false,
    }
}

/// The polygon of a polyline (x, z) thickened upwards by `t`: the line, then the line
/// raised by `t` backwards.
fn thickened(line: &[[i64; 2]], t: i64) -> Vec<[i64; 2]> {
    let mut poly: Vec<[i64; 2]> = line.to_vec();
    poly.extend(line.iter().rev().map(|p| [p[0], p[1] + t]));
    poly
}

/// A prism over a simple polygon in the (x, z) plane, `y` in `[0, length]`, with
/// outward triangles.
pub fn extrusion(profile: &[[i64; 2]], length: i64) -> IntMesh {
    let mut poly = profile.to_vec();
    if area2(&poly) < 0 {
        poly.reverse();
    }
    let n = poly.len() as u32;
    let points: Vec<[i64; 3]> = poly
        .iter()
        .map(|p| [p[0], 0, p[1]])
        .chain(poly.iter().map(|p| [p[0], length, p[1]]))
        .collect();
    let mut triangles = Vec::new();
    // Counter-clockwise in (x, z) gives the −y normal for a triangle at y = 0.
    for t in ear_clip(&poly) {
        let t = t.map(|i| i as u32);
        triangles.push([t[0], t[1], t[2]]);
        triangles.push([t[0] + n, t[2] + n, t[1] + n]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        triangles.push([i, j + n, j]);
        triangles.push([i, i + n, j + n]);
    }
    IntMesh { points, triangles }
}

/// The complex part: a 240 x 160 plate (t = 2) with 50 holes of 10 x 10, two 102-high
/// flanges along its short edges with windows and notches, and a 60-high middle flange
/// with a slot (82 convex pieces after exact decomposition).
pub fn complex_part() -> SheetPart {
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
    let mesh = rectilinear([&xs, &ys, &zs], |c| {
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
    SheetPart {
        name: "complex",
        mesh,
        convex: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profiles_enclose_thickness_times_run_times_length() {
        let c = ChannelParams::default();
        let run = i128::from(2 * c.splay + c.width);
        let v = i128::from(c.thickness) * run * i128::from(c.length);
        assert_eq!(channel().mesh.volume6(), 6 * v);
        let t = TriangleParams::default();
        let run = i128::from(2 * (t.hem / 3 + t.foot + t.run));
        let v = i128::from(t.thickness) * run * i128::from(t.length);
        assert_eq!(triangle_part().mesh.volume6(), 6 * v);
        assert_eq!(cube(3).mesh.volume6(), 6 * 27);
        assert!(complex_part().mesh.volume6() > 0);
    }
}
