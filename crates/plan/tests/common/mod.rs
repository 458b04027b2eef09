//! Assemblies built in code for the planner tests (independent of the loaders).

#![allow(dead_code)]

pub mod oracle;

use apart_kernel::Vec3;
use apart_pieces::Polytope;
use apart_plan::{Part, Sequence};

/// Unit cubes on an `n × n × n` lattice spaced `1 + gap` (0: a touching block; 1:
/// channels exactly one cube wide, so many sliding arcs and isolated directions).
pub fn lattice(n: i64, gap: i64) -> Vec<Part> {
    let s = 1 + gap;
    let mut parts = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                let o = [x * s, y * s, z * s];
                parts.push(part(
                    &format!("c{x}{y}{z}"),
                    vec![cuboid(o, [o[0] + 1, o[1] + 1, o[2] + 1])],
                ));
            }
        }
    }
    parts
}

/// A convex piece: the hull of integer points.
pub fn hull(pts: &[[i64; 3]]) -> Polytope {
    let v: Vec<Vec3> = pts.iter().map(|&p| Vec3::from(p)).collect();
    Polytope::hull_of_points(&v).unwrap()
}

/// An axis-aligned box [lo, hi].
pub fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
    Polytope::cuboid(lo, hi).unwrap()
}

pub fn part(name: &str, pieces: Vec<Polytope>) -> Part {
    Part::from_pieces(name, pieces)
}

/// `n` random disjoint boxes linked into `k` parts (paper 003, section 5.2; apart-testkit's
/// generator), as parts of box pieces named `p0`, `p1`, ...
pub fn random_box_parts(n: usize, k: usize, seed: u64) -> Vec<Part> {
    apart_testkit::solids::random_boxes(n, k, seed)
        .into_iter()
        .enumerate()
        .map(|(i, boxes)| {
            let pieces = boxes.into_iter().map(|(lo, hi)| cuboid(lo, hi));
            part(&format!("p{i}"), pieces.collect())
        })
        .collect()
}

/// The Split Star (Coffin), decomposed into two square pyramids and an octahedron per
/// part, in the frame of the issue: red has vertices (±2,0,0) (±2,0,2) (±1,±1,1)
/// (0,0,0) (0,0,2); green = red with z -> -z; blue = red under (x,y,z) -> (z,x,y);
/// purple = blue with x -> -x; yellow = red under (x,y,z) -> (y,z,x); turquoise = yellow
/// with y -> -y.
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
    let map = |f: &dyn Fn([i64; 3]) -> [i64; 3]| -> Vec<Polytope> {
        red.iter()
            .map(|pc| hull(&pc.iter().map(|&p| f(p)).collect::<Vec<_>>()))
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
        part("bottom", vec![cuboid([0, 0, 0], [1, 1, 1])]),
        part("top", vec![cuboid([0, 0, 1], [1, 1, 2])]),
    ]
}

/// Four unit cubes in a row along x, each touching the next (paper 003, fig. 2).
pub fn cubes_in_a_row(n: i64) -> Vec<Part> {
    (0..n)
        .map(|i| part(&format!("c{i}"), vec![cuboid([i, 0, 0], [i + 1, 1, 1])]))
        .collect()
}

/// A dovetail: a slot part (base, two overhanging sides, an end wall at x = -1..0) and a
/// trapezoidal tenon, wider at the bottom, sliding along x out of the open end x = 10.
pub fn dovetail() -> Vec<Part> {
    let prism = |yz: &[[i64; 2]], x0: i64, x1: i64| -> Polytope {
        let pts: Vec<[i64; 3]> = yz
            .iter()
            .flat_map(|&[y, z]| [[x0, y, z], [x1, y, z]])
            .collect();
        hull(&pts)
    };
    let slot = vec![
        cuboid([0, -4, 0], [10, 4, 1]),
        prism(&[[-4, 1], [-3, 1], [-2, 3], [-4, 3]], 0, 10),
        prism(&[[4, 1], [3, 1], [2, 3], [4, 3]], 0, 10),
        cuboid([-1, -4, 0], [0, 4, 3]),
    ];
    let tenon = vec![prism(&[[-3, 1], [3, 1], [2, 3], [-2, 3]], 0, 10)];
    vec![part("slot", slot), part("tenon", tenon)]
}

/// A peg in a blind hole whose floor and four walls are separate pieces.
pub fn peg_in_hole() -> Vec<Part> {
    let block = vec![
        cuboid([-3, -3, 0], [3, 3, 1]),  // floor
        cuboid([-3, -3, 1], [-1, 3, 4]), // wall x-
        cuboid([1, -3, 1], [3, 3, 4]),   // wall x+
        cuboid([-1, -3, 1], [1, -1, 4]), // wall y-
        cuboid([-1, 1, 1], [1, 3, 4]),   // wall y+
    ];
    let peg = vec![cuboid([-1, -1, 1], [1, 1, 6])];
    vec![part("block", block), part("peg", peg)]
}

/// Two square rings of four bars each, linked like chain links.
pub fn linked_rings() -> Vec<Part> {
    let a = vec![
        cuboid([0, 0, 0], [6, 1, 1]),
        cuboid([0, 0, 5], [6, 1, 6]),
        cuboid([0, 0, 1], [1, 1, 5]),
        cuboid([5, 0, 1], [6, 1, 5]),
    ];
    let b = vec![
        cuboid([2, -2, 2], [3, 3, 3]),
        cuboid([2, -2, -2], [3, 3, -1]),
        cuboid([2, -2, -1], [3, -1, 2]),
        cuboid([2, 2, -1], [3, 3, 2]),
    ];
    vec![part("ring_a", a), part("ring_b", b)]
}

/// Integer directions at angle `r` (and `r / 2`) around unit `u`: twelve on each circle,
/// rounded at a scale of 2^20 (far below the 3% margin the callers leave).
pub fn cap_directions(u: &[f64; 3], r: f64) -> Vec<Vec3> {
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
            let q: Vec<i64> = (0..3)
                .map(|i| {
                    let x = u[i] * radius.cos() + (v[i] * t.cos() + w[i] * t.sin()) * radius.sin();
                    (x * (1u64 << 20) as f64).round() as i64
                })
                .collect();
            out.push(Vec3::new(q[0], q[1], q[2]));
        }
    }
    out
}

/// Checks every step: the moving side is free along the direction against the rest of
/// its subassembly (oracle), it is a proper non-empty subset, the steps split exactly the
/// subassemblies the tree produces, and a complete plan ends with single parts.
pub fn check_plan(parts: &[Part], plan: &Sequence) {
    let oracle = oracle::Oracle::new(parts);
    let mut open: Vec<Vec<usize>> = vec![(0..parts.len()).collect()];
    for step in &plan.steps {
        assert!(
            !step.moving.is_empty() && step.moving.len() < step.subassembly.len(),
            "{step:?}"
        );
        let rest: Vec<usize> = step.staying();
        assert!(
            oracle.free(&step.moving, &rest, &step.direction),
            "step blocked: {step:?}"
        );
        // The subassembly is one still waiting to be split.
        let k = open
            .iter()
            .position(|s| s == &step.subassembly)
            .expect("step splits an open subassembly");
        open.remove(k);
        open.push(step.moving.clone());
        open.push(rest);
    }
    if plan.complete() {
        assert!(open.iter().all(|s| s.len() == 1), "{open:?}");
    }
    for s in plan.stuck.iter().chain(&plan.unsplit) {
        assert!(open.contains(s));
    }
}

/// The angular clearance at `d` of `moving` by brute force: the smallest angle from `d`
/// to the closed projection of `b ⊕ −a` over every piece `a` of a moving part and `b`
/// of a part of `rest` (floating point).
pub fn exhaustive_clearance(parts: &[Part], moving: &[usize], rest: &[usize], d: &Vec3) -> f64 {
    use apart_kernel::fvec;
    use apart_minkowski::{minkowski_difference, project, Projection};
    let u = d.unit_f64();
    let angle = |a: [f64; 3], b: [f64; 3]| fvec::norm(fvec::cross(a, b)).atan2(fvec::dot(a, b));
    let mut best = std::f64::consts::PI;
    for i in moving.iter().copied() {
        for j in rest.iter().copied() {
            for a in &parts[i].pieces {
                for b in &parts[j].pieces {
                    let m = minkowski_difference(b, a).unwrap();
                    let Projection::Polygon(p) = project(&m).unwrap() else {
                        return 0.0;
                    };
                    if p.contains_closed(d) {
                        return 0.0;
                    }
                    for arc in p.boundary() {
                        let (s, e) = (arc.start.unit_f64(), arc.end.unit_f64());
                        let n = fvec::normalize(arc.normal.unit_f64());
                        // The nearest point of the arc's circle, if it is on the arc.
                        let q = fvec::sub(u, fvec::scale(n, fvec::dot(u, n)));
                        let on = fvec::norm(q) > 1e-12
                            && fvec::dot(fvec::cross(s, q), n) >= 0.0
                            && fvec::dot(fvec::cross(q, e), n) >= 0.0;
                        let dist = if on {
                            angle(u, fvec::normalize(q))
                        } else {
                            angle(u, s).min(angle(u, e))
                        };
                        best = best.min(dist);
                    }
                }
            }
        }
    }
    best
}
