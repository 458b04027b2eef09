//! Independent truths for the stacking tests: exact pairwise interference, face
//! contacts and centres of gravity computed here without the crate's own code.
#![allow(dead_code)]

pub mod parts;

use apart_kernel::{Int, Rational, Sign, Vec3};
use apart_pieces::interference::interiors_disjoint;
use apart_pieces::Polytope;
use apart_stack::part::PartModel;
use apart_stack::planner::StackPlan;

/// The integer `v` as a rational.
pub fn q(v: i64) -> Rational {
    Rational::from(v)
}

/// `n / d` as a rational.
pub fn qfrac(n: i64, d: i64) -> Rational {
    Rational::from_i128(n.into(), d.into())
}

/// A floor region `factor` times the part's footprint in each direction, centred on the
/// footprint of the part as given.
pub fn floor_around(part: &PartModel, factor_num: i64, factor_den: i64) -> [Rational; 4] {
    let e = part
        .orient(&apart_stack::orientation::Orientation::IDENTITY)
        .extent;
    let half = |i: usize| {
        let w = &e.max[i] - &e.min[i];
        let c = &(&e.max[i] + &e.min[i]) * &qfrac(1, 2);
        let r = &(&w * &qfrac(factor_num, factor_den)) * &qfrac(1, 2);
        (&c - &r, &c + &r)
    };
    let (x0, x1) = half(0);
    let (y0, y1) = half(1);
    [x0, y0, x1, y1]
}

/// Exact pairwise check over every piece of every pair of parts (apart-pieces'
/// separating-axis test, not the planner's).
pub fn assert_no_interference(plan: &StackPlan) {
    let parts: Vec<Vec<Polytope>> = (0..plan.placements.len())
        .map(|k| plan.pieces_of(k))
        .collect();
    for i in 0..parts.len() {
        for j in i + 1..parts.len() {
            for a in &parts[i] {
                for b in &parts[j] {
                    assert!(interiors_disjoint(a, b), "parts {i} and {j} interfere");
                }
            }
        }
    }
}

/// The centre of gravity of convex pieces: Σ det(a, b, c)·(a + b + c)/4 over the
/// facet fans seen from the origin, divided by Σ det (volumes times 6).
pub fn centre_of_gravity(pieces: &[Polytope]) -> [Rational; 3] {
    let mut vol = Rational::zero();
    let mut m = [Rational::zero(), Rational::zero(), Rational::zero()];
    for p in pieces {
        let d = p.den();
        let d4 = d * d * d * d;
        for f in p.facets() {
            let c = &f.cycle;
            for k in 1..c.len() - 1 {
                let (a, b, e) = (
                    &p.vertices()[c[0] as usize],
                    &p.vertices()[c[k] as usize],
                    &p.vertices()[c[k + 1] as usize],
                );
                let det = a.dot(&b.cross(e));
                vol = &vol + &Rational::new(det.clone(), d * d * d);
                let s = a.add(b).add(e);
                for (i, mi) in m.iter_mut().enumerate() {
                    *mi = &*mi + &Rational::new(&det * s.get(i), d4.clone() * Int::from(4));
                }
            }
        }
    }
    let inv = Rational::new(vol.denom().clone(), vol.numer().clone());
    m.map(|x| &x * &inv)
}

fn xy(v: &Vec3, den: &Int) -> [Rational; 2] {
    [
        Rational::new(v.get(0), den.clone()),
        Rational::new(v.get(1), den.clone()),
    ]
}

fn cross(o: &[Rational; 2], a: &[Rational; 2], b: &[Rational; 2]) -> Rational {
    &(&(&a[0] - &o[0]) * &(&b[1] - &o[1])) - &(&(&a[1] - &o[1]) * &(&b[0] - &o[0]))
}

/// `poly` (counter-clockwise seen from above) clipped to the convex counter-clockwise
/// `clip`.
fn clip(poly: Vec<[Rational; 2]>, clip: &[[Rational; 2]]) -> Vec<[Rational; 2]> {
    let mut out = poly;
    for i in 0..clip.len() {
        let (a, b) = (&clip[i], &clip[(i + 1) % clip.len()]);
        let inp = std::mem::take(&mut out);
        for k in 0..inp.len() {
            let (p, r) = (&inp[k], &inp[(k + 1) % inp.len()]);
            let (sp, sr) = (cross(a, b, p), cross(a, b, r));
            if sp.sign() != Sign::Negative {
                out.push(p.clone());
            }
            if (sp.sign() == Sign::Negative) != (sr.sign() == Sign::Negative)
                && sp.sign() != Sign::Zero
                && sr.sign() != Sign::Zero
            {
                let den = &sp - &sr;
                let t = &sp * &Rational::new(den.denom().clone(), den.numer().clone());
                out.push([
                    &p[0] + &(&(&r[0] - &p[0]) * &t),
                    &p[1] + &(&(&r[1] - &p[1]) * &t),
                ]);
            }
        }
    }
    out
}

/// Facet polygon of a polytope in xy, counter-clockwise seen from above.
fn facet_xy(p: &Polytope, f: &apart_pieces::Facet) -> Vec<[Rational; 2]> {
    let mut v: Vec<[Rational; 2]> = f
        .cycle
        .iter()
        .map(|&i| xy(&p.vertices()[i as usize], p.den()))
        .collect();
    if f.normal.get(2) < Int::ZERO {
        v.reverse();
    }
    v
}

/// Support points of part `k` of a plan: its vertices on the floor, and the corners of
/// the overlaps of its downward facets with coplanar upward facets of earlier parts
/// (face contacts only).
pub fn support_points(plan: &StackPlan, k: usize, floor_z: &Rational) -> Vec<[Rational; 2]> {
    let mine = plan.pieces_of(k);
    let fz = floor_z.clone();
    let mut pts = Vec::new();
    for p in &mine {
        for v in p.vertices() {
            if Rational::new(v.get(2), p.den().clone()) == fz {
                pts.push(xy(v, p.den()));
            }
        }
    }
    for j in 0..k {
        for b in &plan.pieces_of(j) {
            for a in &mine {
                for fb in b.facets().iter().filter(|f| f.normal.get(2) > Int::ZERO) {
                    for fa in a.facets().iter().filter(|f| f.normal == fb.normal.neg()) {
                        // Same plane: n·x = off_b/den_b and −n·x = off_a/den_a.
                        let ob = Rational::new(fb.offset.clone(), b.den().clone());
                        let oa = Rational::new(-fa.offset.clone(), a.den().clone());
                        if ob != oa {
                            continue;
                        }
                        let poly = clip(facet_xy(a, fa), &facet_xy(b, fb));
                        if poly.len() >= 3 {
                            pts.extend(poly);
                        }
                    }
                }
            }
        }
    }
    pts
}

/// True when `c` lies strictly inside the convex hull of `pts` (gift wrapping).
pub fn strictly_inside_hull(pts: &[[Rational; 2]], c: &[Rational; 2]) -> bool {
    let mut pts = pts.to_vec();
    pts.sort();
    pts.dedup();
    if pts.len() < 3 {
        return false;
    }
    // Andrew's monotone chain.
    let mut hull: Vec<[Rational; 2]> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Vec<&[Rational; 2]> = if pass == 0 {
            pts.iter().collect()
        } else {
            pts.iter().rev().collect()
        };
        for p in iter {
            while hull.len() >= start + 2
                && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p).sign() != Sign::Positive
            {
                hull.pop();
            }
            hull.push(p.clone());
        }
        hull.pop();
    }
    hull.len() >= 3
        && (0..hull.len())
            .all(|i| cross(&hull[i], &hull[(i + 1) % hull.len()], c).sign() == Sign::Positive)
}

/// Every part's centre of gravity projects strictly inside its face-contact support
/// polygon (independent of the planner's contact code).
pub fn assert_stable(plan: &StackPlan, floor_z: &Rational) {
    for k in 0..plan.placements.len() {
        let cg = centre_of_gravity(&plan.pieces_of(k));
        let pts = support_points(plan, k, floor_z);
        assert!(
            strictly_inside_hull(&pts, &[cg[0].clone(), cg[1].clone()]),
            "part {k} is not stable: cg {cg:?}, {} support points",
            pts.len()
        );
    }
}

/// The height of the plan's stack, recomputed from the placed pieces.
pub fn height(plan: &StackPlan, floor_z: &Rational) -> Rational {
    let mut top = floor_z.clone();
    for k in 0..plan.placements.len() {
        for p in plan.pieces_of(k) {
            for v in p.vertices() {
                let z = Rational::new(v.get(2), p.den().clone());
                if z > top {
                    top = z;
                }
            }
        }
    }
    &top - floor_z
}
