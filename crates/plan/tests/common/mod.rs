//! The assemblies of `apart_testkit::assemblies` as planner parts, and the planner
//! tests' checks: every step of a plan against the brute-force oracle, and the angular
//! clearance by brute force.

#![allow(dead_code)]

pub mod oracle;

use apart_kernel::Vec3;
use apart_pieces::Polytope;
use apart_plan::{Part, Sequence};
use apart_testkit::assemblies::{self, Piece};

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

/// A piece of `apart_testkit::assemblies` as a polytope.
pub fn piece(p: &Piece) -> Polytope {
    match p {
        Piece::Box(lo, hi) => cuboid(*lo, *hi),
        Piece::Hull(points) => hull(points),
    }
}

/// The parts of an assembly of `apart_testkit::assemblies`.
pub fn parts(parts: Vec<assemblies::Part>) -> Vec<Part> {
    parts
        .iter()
        .map(|p| part(&p.name, p.pieces.iter().map(piece).collect()))
        .collect()
}

/// `assemblies::lattice`.
pub fn lattice(n: i64, gap: i64) -> Vec<Part> {
    parts(assemblies::lattice(n, gap))
}

/// `assemblies::random_boxes`.
pub fn random_box_parts(n: usize, k: usize, seed: u64) -> Vec<Part> {
    parts(assemblies::random_boxes(n, k, seed))
}

/// `assemblies::split_star`.
pub fn split_star() -> Vec<Part> {
    parts(assemblies::split_star())
}

/// `assemblies::stacked_cubes`.
pub fn stacked_cubes() -> Vec<Part> {
    parts(assemblies::stacked_cubes())
}

/// `assemblies::cubes_in_a_row`.
pub fn cubes_in_a_row(n: i64) -> Vec<Part> {
    parts(assemblies::cubes_in_a_row(n))
}

/// `assemblies::dovetail`.
pub fn dovetail() -> Vec<Part> {
    parts(assemblies::dovetail())
}

/// `assemblies::peg_in_hole`.
pub fn peg_in_hole() -> Vec<Part> {
    parts(assemblies::peg_in_hole())
}

/// `assemblies::linked_rings`.
pub fn linked_rings() -> Vec<Part> {
    parts(assemblies::linked_rings())
}

/// `assemblies::cap_directions` as `Vec3`.
pub fn cap_directions(u: &[f64; 3], r: f64) -> Vec<Vec3> {
    assemblies::cap_directions(u, r)
        .into_iter()
        .map(Vec3::from_i64)
        .collect()
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
