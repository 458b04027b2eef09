//! The planner's checks beyond interference (paper 004 §II-B): contacts, static
//! stability, a face for the suction gripper, and lowering into place.
//!
//! - Contacts are found exactly: the intersection points of touching closed pieces, and
//!   the vertices lying on the floor. A contact *supports* the new part when some plane
//!   separating the two pieces has the new part above it (normal with positive z).
//! - Stable: the centre of gravity (exact rational centroid) projects strictly inside
//!   the convex hull of the supporting contact points (the support polygon). Marginal
//!   balance on the hull's boundary is rejected: a positioning error would tip it.
//! - Gripper: the turned part shows an upward horizontal face: facets with normal +z not
//!   covered by another piece of the same part, the largest plane's exposed area.
//! - Lowering: the part can come down along −z into place, i.e. it can leave along +z
//!   without its interior meeting any stack part, decided exactly per piece pair by
//!   the open blocked polygons of apart-minkowski (sliding contact stays free).

use crate::scene::{translated, Scene};
use apart_kernel::{Aabb, HPoint, Int, Rational, Sign, Vec3};
use apart_minkowski::{blocked_polygon, Blocking};
use apart_pieces::Polytope;

/// What the new part touches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum ContactWith {
    /// The floor plane.
    Floor,
    /// A part of the stack (by index).
    Part(usize),
}

/// The new part's contact with the floor or one stack part.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Contact {
    /// The other side.
    pub with: ContactWith,
    /// Points of the contact set (its vertices among them).
    pub points: Vec<[Rational; 3]>,
    /// The other side holds the new part up (a supporting contact).
    pub supports: bool,
}

/// The contacts of the placed pieces with the floor (`z = floor_z`) and the scene.
pub(crate) fn contacts(placed: &[Polytope], floor_z: &Rational, scene: &Scene) -> Vec<Contact> {
    let mut out: Vec<Contact> = Vec::new();
    let mut floor = Vec::new();
    for p in placed {
        for v in p.vertices() {
            let z = Rational::new(v.get(2), p.den().clone());
            if z == *floor_z {
                floor.push(HPoint::from_big(v.to_ints(), p.den().clone()).to_rationals());
            }
        }
    }
    if !floor.is_empty() {
        floor.sort();
        floor.dedup();
        out.push(Contact {
            with: ContactWith::Floor,
            points: floor,
            supports: true,
        });
    }
    let mut near = Vec::new();
    for p in placed {
        let b = Aabb::of_scaled(p.vertices(), p.den()).enclosing_f64();
        near.clear();
        scene.near(&b, &mut near);
        for &k in &near {
            let other = scene.placed(k);
            let Some(t) = touch(p, &other) else {
                continue;
            };
            let with = ContactWith::Part(scene.pieces()[k].part);
            match out.iter_mut().find(|c| c.with == with) {
                Some(c) => {
                    c.points.extend(t.points);
                    c.supports |= t.supports;
                }
                None => out.push(Contact {
                    with,
                    points: t.points,
                    supports: t.supports,
                }),
            }
        }
    }
    for c in &mut out {
        c.points.sort();
        c.points.dedup();
    }
    out.sort_by_key(|c| c.with);
    out
}

/// How two closed convex pieces with disjoint interiors touch.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Touch {
    /// The vertices (and more) of the contact set `a ∩ b`.
    pub(crate) points: Vec<[Rational; 3]>,
    /// Some plane separating them has `a` on its upper side (`b` supports `a`).
    pub(crate) supports: bool,
}

/// The contact of `a` and `b` (closed sets, interiors disjoint): `None` when they do not
/// touch. The points are a superset of the vertices of `a ∩ b`: vertices of one in the
/// other, and crossings of the edges of one with the facets of the other.
pub(crate) fn touch(a: &Polytope, b: &Polytope) -> Option<Touch> {
    let (a, b) = Polytope::common(a, b);
    let den = a.den().clone();
    let pts = apart_pieces::interference::contact_points(&a, &b);
    if pts.is_empty() {
        return None;
    }
    let mut points: Vec<[Rational; 3]> = pts
        .into_iter()
        .map(|(x, w)| HPoint::from_big(x.to_ints(), &w * &den).to_rationals())
        .collect();
    points.sort();
    points.dedup();
    // b supports a: a separating plane n with max_b n·x = min_a n·x and n_z > 0.
    let touching_up = |n: &Vec3| -> bool {
        if n.get(2) <= Int::ZERO {
            return false;
        }
        let (hb, _) = b.support(n);
        let (ha_neg, _) = a.support(&n.neg());
        hb + ha_neg == Int::ZERO
    };
    let mut supports = b.facets().iter().any(|f| touching_up(&f.normal))
        || a.facets().iter().any(|f| touching_up(&f.normal.neg()));
    if !supports {
        'outer: for ea in a.edge_directions() {
            for eb in b.edge_directions() {
                let n = ea.cross(eb);
                if n.is_zero() {
                    continue;
                }
                let n = n.primitive();
                if touching_up(&n) || touching_up(&n.neg()) {
                    supports = true;
                    break 'outer;
                }
            }
        }
    }
    Some(Touch { points, supports })
}

fn cross2(o: &[Rational; 2], a: &[Rational; 2], b: &[Rational; 2]) -> Rational {
    let l = &(&a[0] - &o[0]) * &(&b[1] - &o[1]);
    let r = &(&a[1] - &o[1]) * &(&b[0] - &o[0]);
    &l - &r
}

/// The strictly convex hull of 2-D points, counter-clockwise (monotone chain, exact).
pub(crate) fn convex_hull_2d(points: &[[Rational; 2]]) -> Vec<[Rational; 2]> {
    let mut pts = points.to_vec();
    pts.sort();
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut lower: Vec<[Rational; 2]> = Vec::new();
    for p in &pts {
        while lower.len() >= 2
            && cross2(&lower[lower.len() - 2], &lower[lower.len() - 1], p).sign() != Sign::Positive
        {
            lower.pop();
        }
        lower.push(p.clone());
    }
    let mut upper: Vec<[Rational; 2]> = Vec::new();
    for p in pts.iter().rev() {
        while upper.len() >= 2
            && cross2(&upper[upper.len() - 2], &upper[upper.len() - 1], p).sign() != Sign::Positive
        {
            upper.pop();
        }
        upper.push(p.clone());
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// True when the centre of gravity projects strictly inside the support polygon of the
/// supporting contacts.
pub(crate) fn stable(cg: &[Rational; 3], contacts: &[Contact]) -> bool {
    let pts: Vec<[Rational; 2]> = contacts
        .iter()
        .filter(|c| c.supports)
        .flat_map(|c| c.points.iter().map(|p| [p[0].clone(), p[1].clone()]))
        .collect();
    let hull = convex_hull_2d(&pts);
    if hull.len() < 3 {
        return false;
    }
    let c = [cg[0].clone(), cg[1].clone()];
    (0..hull.len())
        .all(|i| cross2(&hull[i], &hull[(i + 1) % hull.len()], &c).sign() == Sign::Positive)
}

/// Area of a simple polygon given counter-clockwise (shoelace).
fn area(poly: &[[Rational; 2]]) -> Rational {
    let mut s = Rational::zero();
    for i in 0..poly.len() {
        let (a, b) = (&poly[i], &poly[(i + 1) % poly.len()]);
        s = &s + &(&(&a[0] * &b[1]) - &(&a[1] * &b[0]));
    }
    &s * &Rational::from_i128(1, 2)
}

/// `subject` clipped to the convex counter-clockwise polygon `clip` (Sutherland–Hodgman).
fn clip(subject: &[[Rational; 2]], clip: &[[Rational; 2]]) -> Vec<[Rational; 2]> {
    let mut out = subject.to_vec();
    for i in 0..clip.len() {
        if out.is_empty() {
            break;
        }
        let (a, b) = (&clip[i], &clip[(i + 1) % clip.len()]);
        let input = std::mem::take(&mut out);
        for k in 0..input.len() {
            let (p, r) = (&input[k], &input[(k + 1) % input.len()]);
            let (sp, sr) = (cross2(a, b, p), cross2(a, b, r));
            let pin = sp.sign() != Sign::Negative;
            let rin = sr.sign() != Sign::Negative;
            if pin {
                out.push(p.clone());
            }
            if pin != rin {
                // p + (r − p) sp / (sp − sr)
                let t = &sp / &(&sp - &sr);
                out.push([
                    &p[0] + &(&(&r[0] - &p[0]) * &t),
                    &p[1] + &(&(&r[1] - &p[1]) * &t),
                ]);
            }
        }
    }
    out
}

/// The largest exposed area of an upward horizontal face of the part (facets with
/// normal +z minus the parts covered by other pieces' downward facets on the same
/// plane), exactly.
pub(crate) fn up_face_area(pieces: &[Polytope]) -> Rational {
    let up = Vec3::new(0, 0, 1);
    let down = Vec3::new(0, 0, -1);
    // (height, polygon counter-clockwise seen from above, is_up)
    let mut faces: Vec<(Rational, Vec<[Rational; 2]>, bool)> = Vec::new();
    for p in pieces {
        let den = p.den();
        for f in p.facets() {
            let is_up = f.normal == up;
            if !is_up && f.normal != down {
                continue;
            }
            let mut poly: Vec<[Rational; 2]> = f
                .cycle
                .iter()
                .map(|&i| {
                    let v = &p.vertices()[i as usize];
                    [
                        Rational::new(v.get(0), den.clone()),
                        Rational::new(v.get(1), den.clone()),
                    ]
                })
                .collect();
            if !is_up {
                poly.reverse();
            }
            let off = if is_up {
                f.offset.clone()
            } else {
                -f.offset.clone()
            };
            faces.push((Rational::new(off, den.clone()), poly, is_up));
        }
    }
    let mut best = Rational::zero();
    let mut heights: Vec<Rational> = faces.iter().filter(|f| f.2).map(|f| f.0.clone()).collect();
    heights.sort();
    heights.dedup();
    for h in heights {
        let ups: Vec<&Vec<[Rational; 2]>> = faces
            .iter()
            .filter(|f| f.2 && f.0 == h)
            .map(|f| &f.1)
            .collect();
        let downs: Vec<&Vec<[Rational; 2]>> = faces
            .iter()
            .filter(|f| !f.2 && f.0 == h)
            .map(|f| &f.1)
            .collect();
        let mut a = Rational::zero();
        for u in &ups {
            a = &a + &area(u);
            for d in &downs {
                let c = clip(u, d);
                if c.len() >= 3 {
                    a = &a - &area(&c);
                }
            }
        }
        if a > best {
            best = a;
        }
    }
    best
}

/// Exactly: can the pieces leave along +z without their interiors meeting the scene
/// (equivalently: be lowered into place along −z)?
///
/// Piece `a` moving along `d` meets the interior of piece `b` exactly when `d` lies in
/// the open central projection of `b ⊕ (−a)` ([`apart_minkowski::blocked_polygon`]), so
/// +z is blocked exactly when it lies inside one piece pair's open polygon: sliding
/// contact (+z on a polygon's boundary) stays free, as in apart-plan's blocked regions,
/// which are the unions of the same open polygons. Only pairs whose open footprints
/// meet and whose stack piece reaches above the new piece's bottom are summed: for any
/// other pair no translation along +z brings `a` into `b`'s interior. A pair whose
/// interiors already overlap is an error (the placement engine never proposes one).
pub(crate) fn lowerable(
    placed: &[Polytope],
    scene: &Scene,
) -> Result<bool, crate::part::StackError> {
    let boxes: Vec<Aabb<Rational>> = placed
        .iter()
        .map(|p| Aabb::of_scaled(p.vertices(), p.den()))
        .collect();
    let up = Vec3::new(0, 0, 1);
    for (k, sp) in scene.pieces().iter().enumerate() {
        let mut fixed = None;
        for (i, b) in boxes.iter().enumerate() {
            let meets = (0..2).all(|a| sp.bbox.min[a] < b.max[a] && b.min[a] < sp.bbox.max[a])
                && sp.bbox.max[2] > b.min[2];
            if !meets {
                continue;
            }
            let fixed = fixed.get_or_insert_with(|| scene.placed(k));
            match blocked_polygon(&placed[i], fixed) {
                Ok(Blocking::Polygon(q)) => {
                    if q.contains_open(&up) {
                        return Ok(false);
                    }
                }
                Ok(Blocking::Overlap) => {
                    return Err(crate::part::StackError::Internal(format!(
                        "lowering check: new piece {i} overlaps stack piece {k}"
                    )))
                }
                Err(e) => {
                    return Err(crate::part::StackError::Internal(format!(
                        "lowering check: {e}"
                    )))
                }
            }
        }
    }
    Ok(true)
}

/// The pieces of a part turned and translated into place.
pub fn placed_pieces(rotated: &[Polytope], t: &[Rational; 3]) -> Vec<Polytope> {
    let tp = HPoint::from_rationals(t);
    rotated.iter().map(|p| translated(p, &tp)).collect()
}

/// The exact height of the highest vertex of the pieces.
pub(crate) fn top(pieces: &[Polytope]) -> Option<Rational> {
    pieces
        .iter()
        .flat_map(|p| {
            p.vertices()
                .iter()
                .map(move |v| Rational::new(v.get(2), p.den().clone()))
        })
        .max()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{q, qfrac, unit};

    fn boxp(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    #[test]
    fn support_polygon_and_centre() {
        let mut scene = Scene::new();
        scene.add_fixed_part(&[boxp([0, 0, 0], [2, 2, 1])]);
        // A box on top, overhanging by less than half: stable.
        let top = [boxp([1, 0, 1], [4, 2, 2])];
        let c = contacts(&top, &q(0), &scene);
        assert_eq!(c.len(), 1);
        assert!(c[0].supports);
        assert!(!stable(&[qfrac(5, 2), q(1), qfrac(3, 2)], &c)); // cg at x = 2.5 > 2
        let top2 = [boxp([0, 0, 1], [3, 2, 2])];
        let c2 = contacts(&top2, &q(0), &scene);
        assert!(stable(&[qfrac(3, 2), q(1), qfrac(3, 2)], &c2));
        // On the floor.
        let fl = [boxp([5, 5, 0], [6, 6, 1])];
        let c3 = contacts(&fl, &q(0), &scene);
        assert_eq!(c3[0].with, ContactWith::Floor);
        assert!(stable(&[qfrac(11, 2), qfrac(11, 2), qfrac(1, 2)], &c3));
    }

    #[test]
    fn contacts_and_support() {
        let low = unit([0, 0, 0]);
        let high = translated(
            &unit([0, 0, 0]),
            &HPoint::from_rationals(&[qfrac(1, 2), q(0), q(1)]),
        );
        let t = touch(&high, &low).unwrap();
        assert!(t.supports);
        assert_eq!(t.points.len(), 4); // the rectangle [1/2, 1] x [0, 1] at z = 1
        let side = unit([1, 0, 0]);
        let t = touch(&side, &low).unwrap();
        assert!(!t.supports); // side by side
        assert!(touch(&unit([3, 0, 0]), &low).is_none());
    }

    #[test]
    fn upward_faces() {
        // Two stacked boxes: the lower top face is covered where the upper sits.
        let pieces = [boxp([0, 0, 0], [4, 4, 1]), boxp([0, 0, 1], [2, 4, 3])];
        assert_eq!(up_face_area(&pieces), q(8));
        let flat = [boxp([0, 0, 0], [4, 4, 1]), boxp([0, 0, 1], [1, 1, 3])];
        assert_eq!(up_face_area(&flat), q(15));
    }

    #[test]
    fn lowering() {
        let mut scene = Scene::new();
        // A bridge: two posts and a roof.
        scene.add_fixed_part(&[
            boxp([0, 0, 0], [1, 3, 3]),
            boxp([4, 0, 0], [5, 3, 3]),
            boxp([0, 0, 3], [5, 3, 4]),
        ]);
        let under = [boxp([2, 1, 0], [3, 2, 1])];
        assert!(!lowerable(&under, &scene).unwrap());
        let beside = [boxp([6, 1, 0], [7, 2, 1])];
        assert!(lowerable(&beside, &scene).unwrap());
    }

    /// The oracle's verdict on one piece pair: its interiors overlap, or `a` moving
    /// along +z meets `b`'s interior.
    #[derive(Debug, PartialEq)]
    enum Pair {
        Overlap,
        Blocked,
        Free,
    }

    /// Independent of apart-minkowski: `M = b ⊕ (−a)` as the hull of the vertex
    /// differences, then the open ray `{k·z : k > 0}` against `M`'s open facet
    /// inequalities `n·x < offset` (`k·n_z < offset` for every facet: facets with
    /// `n_z = 0` need a positive offset, the others bound `k` above or below).
    fn oracle(a: &Polytope, b: &Polytope) -> Pair {
        let (da, db) = (a.den(), b.den());
        let mut diffs = Vec::new();
        for vb in b.vertices() {
            for va in a.vertices() {
                diffs.push(vb.scale(da).sub(&va.scale(db)));
            }
        }
        let m = Polytope::hull_of_points(&diffs).expect("full-dimensional pieces");
        let zero = apart_kernel::Int::ZERO;
        if m.facets().iter().all(|f| f.offset > zero) {
            return Pair::Overlap;
        }
        let mut lower = q(0);
        let mut upper: Option<Rational> = None;
        for f in m.facets() {
            let nz = f.normal.get(2);
            if nz == zero {
                if f.offset <= zero {
                    return Pair::Free;
                }
                continue;
            }
            let bound = Rational::new(f.offset.clone(), nz.clone());
            if nz > zero {
                upper = Some(match upper {
                    Some(u) if u <= bound => u,
                    _ => bound,
                });
            } else if bound > lower {
                lower = bound;
            }
        }
        match upper {
            Some(u) if lower < u => Pair::Blocked,
            _ => Pair::Free,
        }
    }

    /// A random convex piece with small integer coordinates near `origin`: a box (many
    /// touching and coplanar faces) or the hull of a few points (slanted faces), or
    /// `None` when the points are flat.
    fn random_piece(rng: &mut apart_testkit::solids::Lcg, origin: [i64; 3]) -> Option<Polytope> {
        if rng.below(2) == 0 {
            let lo = origin.map(|o| o + rng.range(0, 3));
            let hi = [0, 1, 2].map(|i| lo[i] + rng.range(1, 3));
            return Some(boxp(lo, hi));
        }
        let pts: Vec<Vec3> = (0..rng.range(4, 7))
            .map(|_| {
                Vec3::new(
                    origin[0] + rng.range(0, 4),
                    origin[1] + rng.range(0, 4),
                    origin[2] + rng.range(0, 4),
                )
            })
            .collect();
        Polytope::hull_of_points(&pts).ok()
    }

    #[test]
    fn lowering_matches_a_brute_force_oracle() {
        // Random scenes of boxes and hulls on a small grid (so that faces touch, slide
        // along each other and share edges and vertices), the new part placed above,
        // beside or among them; +z is blocked exactly when some piece pair blocks it,
        // and sliding contact stays free.
        let mut rng = apart_testkit::solids::Lcg(20240917);
        let (mut blocked, mut free, mut overlapping) = (0, 0, 0);
        for _ in 0..400 {
            let mut scene = Scene::new();
            let mut stack = Vec::new();
            for _ in 0..rng.range(1, 3) {
                let pieces: Vec<Polytope> = (0..rng.range(1, 3))
                    .filter_map(|_| {
                        let origin = [0, 0, rng.range(0, 3)];
                        random_piece(&mut rng, origin)
                    })
                    .collect();
                if !pieces.is_empty() {
                    scene.add_fixed_part(&pieces);
                    stack.extend(pieces);
                }
            }
            let new: Vec<Polytope> = (0..rng.range(1, 3))
                .filter_map(|_| {
                    let origin = [rng.range(-1, 2), rng.range(-1, 2), 0];
                    random_piece(&mut rng, origin)
                })
                .collect();
            if new.is_empty() {
                continue;
            }
            let verdicts: Vec<Pair> = new
                .iter()
                .flat_map(|a| stack.iter().map(move |b| oracle(a, b)))
                .collect();
            let got = lowerable(&new, &scene);
            if verdicts.contains(&Pair::Overlap) {
                // The old blocked regions reported an overlap as an error; the pair
                // blocks every direction, so an early "blocked" is just as right.
                assert!(!matches!(got, Ok(true)), "{new:?} in {stack:?}");
                overlapping += 1;
                continue;
            }
            let want = !verdicts.contains(&Pair::Blocked);
            assert_eq!(got.unwrap(), want, "{new:?} in {stack:?}");
            if want {
                free += 1;
            } else {
                blocked += 1;
            }
        }
        assert!(blocked > 30 && free > 30, "{blocked} blocked, {free} free");
        assert!(overlapping > 0);
    }

    #[test]
    fn sliding_contact_stays_free() {
        // A box resting against a wall's side, under nothing: it slides up along the
        // wall. Under an overhang it is blocked, beside it free.
        let mut scene = Scene::new();
        scene.add_fixed_part(&[boxp([0, 0, 0], [1, 3, 4]), boxp([1, 0, 3], [3, 3, 4])]);
        assert!(lowerable(&[boxp([3, 0, 0], [4, 3, 1])], &scene).unwrap());
        assert!(!lowerable(&[boxp([1, 0, 0], [2, 3, 1])], &scene).unwrap());
        assert!(lowerable(&[boxp([1, 3, 0], [2, 4, 1])], &scene).unwrap());
        // Partly under the overhang, partly beside it: blocked.
        assert!(!lowerable(&[boxp([2, 0, 0], [4, 3, 1])], &scene).unwrap());
    }
}
