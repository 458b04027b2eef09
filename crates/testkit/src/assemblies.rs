//! Assemblies of convex pieces built in code, independent of the loaders: each piece an
//! axis-aligned box or the convex hull of integer points, each part a name and its
//! pieces. The shared inputs of the planner's and the drawing's tests, examples and
//! benchmarks, which turn them into their own part types; and [`cap_directions`], the
//! integer directions the planner's tests probe around a direction found free.

/// A convex piece.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Piece {
    /// The axis-aligned box `[lo, hi]` (`lo < hi` on every axis).
    Box([i64; 3], [i64; 3]),
    /// The convex hull of the points (not all in one plane).
    Hull(Vec<[i64; 3]>),
}

/// A part: its name and its convex pieces, in order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Part {
    /// The part's name.
    pub name: String,
    /// The part's convex pieces.
    pub pieces: Vec<Piece>,
}

fn part(name: &str, pieces: Vec<Piece>) -> Part {
    Part {
        name: name.to_string(),
        pieces,
    }
}

/// Unit cubes on an `n × n × n` lattice spaced `1 + gap` (0: a touching block; 1:
/// channels exactly one cube wide, so many sliding arcs and isolated directions), named
/// `c{x}{y}{z}` in the order x, then y, then z.
pub fn lattice(n: i64, gap: i64) -> Vec<Part> {
    let s = 1 + gap;
    let mut parts = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                let o = [x * s, y * s, z * s];
                parts.push(part(
                    &format!("c{x}{y}{z}"),
                    vec![Piece::Box(o, [o[0] + 1, o[1] + 1, o[2] + 1])],
                ));
            }
        }
    }
    parts
}

/// `n` random disjoint boxes linked into `k` parts ([`crate::solids::random_boxes`]),
/// named `p0`, `p1`, ...
pub fn random_boxes(n: usize, k: usize, seed: u64) -> Vec<Part> {
    crate::solids::random_boxes(n, k, seed)
        .into_iter()
        .enumerate()
        .map(|(i, boxes)| {
            let pieces = boxes.into_iter().map(|(lo, hi)| Piece::Box(lo, hi));
            part(&format!("p{i}"), pieces.collect())
        })
        .collect()
}

/// The Split Star (Coffin), each part two square pyramids and an octahedron: red has
/// vertices (±2,0,0) (±2,0,2) (±1,±1,1) (0,0,0) (0,0,2); green = red with z -> -z; blue
/// = red under (x,y,z) -> (z,x,y); purple = blue with x -> -x; yellow = red under
/// (x,y,z) -> (y,z,x); turquoise = yellow with y -> -y.
pub fn split_star() -> Vec<Part> {
    let red: Vec<Vec<[i64; 3]>> = vec![
        vec![[-1, -1, 1], [-2, 0, 2], [-2, 0, 0], [-1, 1, 1], [0, 0, 2]],
        vec![[1, -1, 1], [2, 0, 0], [2, 0, 2], [1, 1, 1], [0, 0, 2]],
        vec![
            [-1, -1, 1],
            [0, 0, 0],
            [1, -1, 1],
            [-1, 1, 1],
            [1, 1, 1],
            [0, 0, 2],
        ],
    ];
    let map = |f: &dyn Fn([i64; 3]) -> [i64; 3]| -> Vec<Piece> {
        red.iter()
            .map(|pc| Piece::Hull(pc.iter().map(|&p| f(p)).collect()))
            .collect()
    };
    let blue = |p: [i64; 3]| [p[2], p[0], p[1]];
    let yellow = |p: [i64; 3]| [p[1], p[2], p[0]];
    vec![
        part("red", map(&|p| p)),
        part("green", map(&|p| [p[0], p[1], -p[2]])),
        part("blue", map(&blue)),
        part(
            "purple",
            map(&|p| {
                let q = blue(p);
                [-q[0], q[1], q[2]]
            }),
        ),
        part("yellow", map(&yellow)),
        part(
            "turquoise",
            map(&|p| {
                let q = yellow(p);
                [q[0], -q[1], q[2]]
            }),
        ),
    ]
}

/// Two unit cubes, `bottom` under `top`.
pub fn stacked_cubes() -> Vec<Part> {
    vec![
        part("bottom", vec![Piece::Box([0, 0, 0], [1, 1, 1])]),
        part("top", vec![Piece::Box([0, 0, 1], [1, 1, 2])]),
    ]
}

/// `n` unit cubes in a row along x, each touching the next, named `c0`, `c1`, ...
pub fn cubes_in_a_row(n: i64) -> Vec<Part> {
    (0..n)
        .map(|i| part(&format!("c{i}"), vec![Piece::Box([i, 0, 0], [i + 1, 1, 1])]))
        .collect()
}

/// A dovetail: a slot part (base, two overhanging sides, an end wall at x = -1..0) and a
/// trapezoidal tenon, wider at the bottom, sliding along x out of the open end x = 10.
pub fn dovetail() -> Vec<Part> {
    let prism = |yz: &[[i64; 2]], x0: i64, x1: i64| -> Piece {
        Piece::Hull(
            yz.iter()
                .flat_map(|&[y, z]| [[x0, y, z], [x1, y, z]])
                .collect(),
        )
    };
    let slot = vec![
        Piece::Box([0, -4, 0], [10, 4, 1]),
        prism(&[[-4, 1], [-3, 1], [-2, 3], [-4, 3]], 0, 10),
        prism(&[[4, 1], [3, 1], [2, 3], [4, 3]], 0, 10),
        Piece::Box([-1, -4, 0], [0, 4, 3]),
    ];
    let tenon = vec![prism(&[[-3, 1], [3, 1], [2, 3], [-2, 3]], 0, 10)];
    vec![part("slot", slot), part("tenon", tenon)]
}

/// A peg in a blind hole whose floor and four walls are separate pieces.
pub fn peg_in_hole() -> Vec<Part> {
    let block = vec![
        Piece::Box([-3, -3, 0], [3, 3, 1]),  // floor
        Piece::Box([-3, -3, 1], [-1, 3, 4]), // wall x-
        Piece::Box([1, -3, 1], [3, 3, 4]),   // wall x+
        Piece::Box([-1, -3, 1], [1, -1, 4]), // wall y-
        Piece::Box([-1, 1, 1], [1, 3, 4]),   // wall y+
    ];
    let peg = vec![Piece::Box([-1, -1, 1], [1, 1, 6])];
    vec![part("block", block), part("peg", peg)]
}

/// Two square rings of four bars each, linked like chain links.
pub fn linked_rings() -> Vec<Part> {
    let a = vec![
        Piece::Box([0, 0, 0], [6, 1, 1]),
        Piece::Box([0, 0, 5], [6, 1, 6]),
        Piece::Box([0, 0, 1], [1, 1, 5]),
        Piece::Box([5, 0, 1], [6, 1, 5]),
    ];
    let b = vec![
        Piece::Box([2, -2, 2], [3, 3, 3]),
        Piece::Box([2, -2, -2], [3, 3, -1]),
        Piece::Box([2, -2, -1], [3, -1, 2]),
        Piece::Box([2, 2, -1], [3, 3, 2]),
    ];
    vec![part("ring_a", a), part("ring_b", b)]
}

/// Four rows of five stepped bricks (each brick a slab with a second slab on top,
/// shifted by half a brick, so that neighbours in a row interlock), the rows side by
/// side along y: 20 parts named `brick-{row}-{i}`.
pub fn brick_rows() -> Vec<Part> {
    let mut parts = Vec::new();
    for row in 0..4i64 {
        for i in 0..5i64 {
            let y = 2 * row;
            parts.push(part(
                &format!("brick-{row}-{i}"),
                vec![
                    Piece::Box([2 * i, y, 0], [2 * i + 2, y + 2, 1]),
                    Piece::Box([2 * i + 1, y, 1], [2 * i + 3, y + 2, 2]),
                ],
            ));
        }
    }
    parts
}

/// Integer directions at angle `r` (and `r / 2`) around the unit vector `u`: twelve on
/// each circle, rounded at a scale of 2^20.
pub fn cap_directions(u: &[f64; 3], r: f64) -> Vec<[i64; 3]> {
    let helper = if u[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |a: &[f64; 3], b: &[f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let v = cross(u, &helper);
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let v = v.map(|x| x / n);
    let w = cross(u, &v);
    let mut out = Vec::new();
    for radius in [r, r / 2.0] {
        for k in 0..12 {
            let t = k as f64 * std::f64::consts::PI / 6.0;
            out.push([0, 1, 2].map(|i| {
                let x = u[i] * radius.cos() + (v[i] * t.cos() + w[i] * t.sin()) * radius.sin();
                (x * (1u64 << 20) as f64).round() as i64
            }));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_box_is_proper_and_every_name_distinct() {
        for parts in [
            lattice(2, 1),
            random_boxes(24, 5, 7),
            split_star(),
            stacked_cubes(),
            cubes_in_a_row(4),
            dovetail(),
            peg_in_hole(),
            linked_rings(),
            brick_rows(),
        ] {
            let mut names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
            names.sort_unstable();
            names.dedup();
            assert_eq!(names.len(), parts.len());
            for p in &parts {
                assert!(!p.pieces.is_empty());
                for piece in &p.pieces {
                    match piece {
                        Piece::Box(lo, hi) => assert!((0..3).all(|k| lo[k] < hi[k])),
                        Piece::Hull(points) => assert!(points.len() >= 4),
                    }
                }
            }
        }
    }

    #[test]
    fn cap_directions_lie_at_the_angle() {
        let u = [0.0, 0.6, 0.8];
        let d = cap_directions(&u, 0.3);
        assert_eq!(d.len(), 24);
        for (k, q) in d.iter().enumerate() {
            let q = q.map(|c| c as f64);
            let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            let cos = (q[0] * u[0] + q[1] * u[1] + q[2] * u[2]) / n;
            let want = if k < 12 { 0.3f64 } else { 0.15 };
            assert!((cos.acos() - want).abs() < 1e-5, "{k}: {}", cos.acos());
        }
    }
}
