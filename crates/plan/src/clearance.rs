//! A direction deep inside a face of the motion space, and its angular clearance.
//!
//! Clearance is a measurement reported to the user, not a combinatorial decision, so it
//! is computed in floating point; the direction finally reported is an integer vector
//! checked exactly (it lies on no arc and has the face's blocking graph).
//!
//! Internally distances are compared as squared chord lengths `2 − 2 cos θ`, which grow
//! with the angle θ and need no trigonometry; [`to_angle`] converts back.

use apart_kernel::fvec::{self, cross, dot, normalize};
use apart_sphere::overlay::RegionArrangement;

type V3 = [f64; 3];

pub(crate) fn chord2(a: &V3, b: &V3) -> f64 {
    let d = fvec::sub(*a, *b);
    fvec::dot(d, d)
}

/// The angle (radians) of a squared chord length.
pub fn to_angle(c2: f64) -> f64 {
    2.0 * (c2.max(0.0).sqrt() / 2.0).min(1.0).asin()
}

/// A boundary arc in floating point: unit end points and unit normal (left = positive).
#[derive(Clone, Copy, Debug)]
pub struct FArc {
    a: V3,
    b: V3,
    n: V3,
}

impl FArc {
    /// The arc from unit `a` to unit `b` with unit normal `n` (counter-clockwise).
    pub fn new(a: V3, b: V3, n: V3) -> FArc {
        FArc { a, b, n }
    }

    /// The exact arc `arc` in floating point (its ends and normal as unit vectors).
    pub fn of(arc: &apart_sphere::Arc) -> FArc {
        FArc::new(
            arc.start.unit_f64(),
            arc.end.unit_f64(),
            arc.normal.unit_f64(),
        )
    }

    /// The unit end points.
    pub fn ends(&self) -> (V3, V3) {
        (self.a, self.b)
    }

    /// Squared chord distance from unit point `p` to the closed arc.
    pub fn distance2(&self, p: &V3) -> f64 {
        let s = dot(self.n, *p);
        let q = [
            p[0] - s * self.n[0],
            p[1] - s * self.n[1],
            p[2] - s * self.n[2],
        ];
        let within = dot(cross(self.a, q), self.n) >= 0.0 && dot(cross(q, self.b), self.n) >= 0.0;
        if within && dot(q, q) > 1e-30 {
            // Nearest point: the projection onto the circle, at angle asin|s|.
            2.0 - 2.0 * (1.0 - s * s).max(0.0).sqrt()
        } else {
            chord2(p, &self.a).min(chord2(p, &self.b))
        }
    }
}

/// Real isolated points (vertices with no real edge, e.g. a free direction inside a
/// blocked region) of every face, as unit vectors.
pub fn isolated_points(arr: &RegionArrangement) -> Vec<Vec<V3>> {
    let mut out = vec![Vec::new(); arr.faces().len()];
    for v in arr.vertices() {
        if v.structural || v.around.is_empty() {
            continue;
        }
        if v.around.iter().all(|&h| arr.edge(h.edge()).structural) {
            out[arr.face(v.around[0]).index()].push(v.point.unit_f64());
        }
    }
    out
}

/// Squared chord clearance of unit point `p`: to the nearest boundary arc or point.
pub fn clearance2(p: &V3, arcs: &[FArc], points: &[V3]) -> f64 {
    let mut c = 4.0;
    for a in arcs {
        c = a.distance2(p).min(c);
    }
    for q in points {
        c = chord2(p, q).min(c);
    }
    c
}

/// Angular clearance (radians) of unit point `p`.
pub fn clearance(p: &V3, arcs: &[FArc], points: &[V3]) -> f64 {
    to_angle(clearance2(p, arcs, points))
}

/// Points just inside the face next to some of its boundary arcs (at most `max`), each
/// with its squared chord clearance, best first (equal ones by their coordinates). The
/// arcs are sampled in an order of their own end points, so the points do not depend on
/// where the boundary's list starts.
pub fn starting_points(arcs: &[FArc], points: &[V3], max: usize) -> Vec<(V3, f64)> {
    let mut out = Vec::new();
    let stride = (arcs.len() / max.max(1)).max(1);
    let mut order: Vec<usize> = (0..arcs.len()).collect();
    if stride > 1 {
        order.sort_by(|&i, &j| {
            let (x, y) = (&arcs[i], &arcs[j]);
            fvec::lex_cmp(x.a, y.a).then_with(|| fvec::lex_cmp(x.b, y.b))
        });
    }
    for &k in order.iter().step_by(stride) {
        let arc = &arcs[k];
        let m = normalize([
            arc.a[0] + arc.b[0],
            arc.a[1] + arc.b[1],
            arc.a[2] + arc.b[2],
        ]);
        let others = arcs
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != k)
            .map(|(_, o)| o.distance2(&m))
            .chain(points.iter().map(|q| chord2(&m, q)))
            .fold(chord2(&arc.a, &arc.b) / 4.0, f64::min);
        // Half the angular room, roughly (chords are within a few per cent of angles here).
        let delta = 0.5 * others.sqrt();
        if delta <= 1e-12 {
            continue;
        }
        let p = normalize([
            m[0] + delta * arc.n[0],
            m[1] + delta * arc.n[1],
            m[2] + delta * arc.n[2],
        ]);
        out.push((p, clearance2(&p, arcs, points)));
    }
    out.sort_by(|a, b| b.1.total_cmp(&a.1).then_with(|| fvec::lex_cmp(a.0, b.0)));
    out
}

/// Unit directions for the search steps, in the plane of a tangent basis.
const DIRS: [(f64, f64); 8] = [
    (1.0, 0.0),
    (
        std::f64::consts::FRAC_1_SQRT_2,
        std::f64::consts::FRAC_1_SQRT_2,
    ),
    (0.0, 1.0),
    (
        -std::f64::consts::FRAC_1_SQRT_2,
        std::f64::consts::FRAC_1_SQRT_2,
    ),
    (-1.0, 0.0),
    (
        -std::f64::consts::FRAC_1_SQRT_2,
        -std::f64::consts::FRAC_1_SQRT_2,
    ),
    (0.0, -1.0),
    (
        std::f64::consts::FRAC_1_SQRT_2,
        -std::f64::consts::FRAC_1_SQRT_2,
    ),
];

/// The arcs and points of a boundary that can be nearest to some point within chord
/// distance `reach` of `p`, when `p` is at squared chord distance `c2` from the nearest.
///
/// For `q` with `|q - p| <= reach`, the nearest boundary element is at most
/// `sqrt(c2) + reach` from `q`, and an element at distance `t` from `p` is at least
/// `t - reach` from `q` (distance to a set is 1-Lipschitz): elements farther than
/// `sqrt(c2) + 2 reach` from `p` are never nearest to `q`. The margin keeps rounding
/// from dropping an element that ties, so a clearance over the kept elements is the
/// clearance over all of them, to the bit.
struct Near {
    arcs: Vec<FArc>,
    points: Vec<V3>,
}

impl Near {
    fn around(p: &V3, c2: f64, reach: f64, arcs: &[FArc], points: &[V3]) -> Near {
        let r = c2.max(0.0).sqrt() + 2.0 * reach + 1e-9;
        let r2 = r * r;
        Near {
            arcs: arcs
                .iter()
                .filter(|a| a.distance2(p) <= r2)
                .copied()
                .collect(),
            points: points
                .iter()
                .filter(|q| chord2(p, q) <= r2)
                .copied()
                .collect(),
        }
    }
}

/// Moves `p` uphill in clearance; returns the point and its angular clearance. Every
/// step is shorter than the current clearance, so the path never meets the boundary and
/// `p` stays in the face.
pub fn climb(mut p: V3, arcs: &[FArc], points: &[V3]) -> (V3, f64) {
    let mut c2 = clearance2(&p, arcs, points);
    let mut c = to_angle(c2);
    let mut step = 0.5 * c;
    let mut iterations = 0;
    // The boundary that can be nearest to a point within `step` of `p` (see `Near`),
    // found again only when `p` moves: a shorter step needs no more of it.
    let mut near = Near::around(&p, c2, step, arcs, points);
    while step > 1e-7 * c.max(1e-9) && iterations < 120 {
        iterations += 1;
        let helper = if p[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = normalize(cross(p, helper));
        let w = cross(p, u);
        let mut best: Option<(V3, f64)> = None;
        for (co, s) in DIRS {
            let d = [
                u[0] * co + w[0] * s,
                u[1] * co + w[1] * s,
                u[2] * co + w[2] * s,
            ];
            let q = normalize([p[0] + step * d[0], p[1] + step * d[1], p[2] + step * d[2]]);
            let cq = clearance2(&q, &near.arcs, &near.points);
            if cq > c2 && best.is_none_or(|(_, bc)| cq > bc) {
                best = Some((q, cq));
            }
        }
        match best {
            Some((q, cq)) => {
                p = q;
                c2 = cq;
                c = to_angle(c2);
                // Longer steps while they pay: a start next to a tiny boundary arc has a
                // tiny first step, and the room may be a hemisphere.
                step = (2.0 * step).min(0.9 * c);
                near = Near::around(&p, c2, step, arcs, points);
            }
            None => step *= 0.5,
        }
    }
    (p, c)
}

/// Candidates [`deep_direction`]'s [`simple_direction`] lets the exact check reject
/// before it gives up.
const MAX_REJECTED: usize = 128;

/// The simplest integer direction near the unit point `p` (smallest multiplier `k`, then
/// `round(k p)` or a neighbour of it) that lies well inside the cap of radius `target` (radians,
/// the clearance of `p`) around `p`, has a clearance of at least `fraction` of `target`,
/// and that `ok` accepts; `None` when no small one qualifies, or when `ok` rejected
/// `max_rejected` candidates. Staying inside the cap keeps
/// the direction in the region whose boundary `arcs` and `points` describe.
pub fn simple_direction(
    p: &V3,
    target: f64,
    fraction: f64,
    arcs: &[FArc],
    points: &[V3],
    ok: &dyn Fn(&apart_kernel::Vec3) -> bool,
    max_rejected: usize,
) -> Option<(apart_kernel::Vec3, f64)> {
    // round(k p) first, then its 26 neighbours (nearest first): the exact rounding may lie
    // on an arc of the motion space, a neighbour usually does not.
    let mut offsets: Vec<[i64; 3]> = (0..27)
        .map(|i| [i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1])
        .collect();
    offsets.sort_by_key(|o| o.iter().map(|x| x.abs()).sum::<i64>());
    // Candidates lie within the cap of radius `target` around `p`, whose own squared
    // chord clearance is at most that of the angle `target`.
    let cap = 2.0 * (0.5 * target.min(std::f64::consts::PI)).sin();
    let near = Near::around(p, cap * cap, cap, arcs, points);
    let mut rejected = 0;
    for k in 1..=64i64 {
        let c = p.map(|x| (x * k as f64).round() as i64);
        for o in &offsets {
            let d = apart_kernel::Vec3::new(c[0] + o[0], c[1] + o[1], c[2] + o[2]);
            if d.is_zero() {
                continue;
            }
            let u = d.unit_f64();
            if to_angle(chord2(&u, p)) >= 0.98 * target {
                continue;
            }
            let cl = clearance(&u, &near.arcs, &near.points);
            if cl >= fraction * target {
                if ok(&d) {
                    return Some((d.primitive(), cl));
                }
                // Deep candidates that fail the exact check mostly lie in a part of the
                // region where the check fails throughout (a smaller moving set is free
                // there): give up after a few rather than test every one.
                rejected += 1;
                if rejected >= max_rejected {
                    return None;
                }
            }
        }
    }
    None
}

/// Where the climbs of [`deep_direction`] start: next to the boundary.
fn starts(arcs: &[FArc], points: &[V3]) -> Vec<V3> {
    let mut starts: Vec<V3> = starting_points(arcs, points, 8)
        .into_iter()
        .take(2)
        .map(|(p, _)| p)
        .collect();
    if arcs.is_empty() {
        // Only isolated points bound the region: start opposite the first one.
        starts.push(points[0].map(|x| -x));
    }
    starts
}

/// The end of the highest clearance climb from `starts`, with its clearance.
fn deepest_climb(starts: Vec<V3>, arcs: &[FArc], points: &[V3]) -> Option<(V3, f64)> {
    let mut best: Option<(V3, f64)> = None;
    for p in starts {
        let (q, c) = climb(p, arcs, points);
        if best.is_none_or(|(_, bc)| c > bc) {
            best = Some((q, c));
        }
    }
    best
}

/// [`deep_direction`] on a boundary with arcs, with a [`simple_direction`] that gives up
/// after `max_rejected` candidates that `ok` rejects (then the climb's end rounded, as
/// there), else `None`.
pub fn quick_direction(
    arcs: &[FArc],
    ok: &dyn Fn(&apart_kernel::Vec3) -> bool,
    max_rejected: usize,
) -> Option<(apart_kernel::Vec3, f64)> {
    if arcs.is_empty() {
        return None;
    }
    let (p, c) = deepest_climb(starts(arcs, &[]), arcs, &[])?;
    simple_direction(&p, c, 0.9, arcs, &[], ok, max_rejected).or_else(|| rounded(&p, c, ok))
}

/// A direction deep inside the region bounded by `arcs` (region on their left) and
/// `points`, with its clearance (radians): the best of clearance climbs from points next
/// to the boundary, then the simplest integer direction with 90% of that clearance, else
/// the climb's end rounded to 20, 30 or 40 bits; every candidate must pass the exact
/// check `ok`. `None` when no candidate passes (callers fall back to an exact sample).
pub fn deep_direction(
    arcs: &[FArc],
    points: &[V3],
    ok: &dyn Fn(&apart_kernel::Vec3) -> bool,
) -> Option<(apart_kernel::Vec3, f64)> {
    use apart_kernel::Vec3;
    if arcs.is_empty() && points.is_empty() {
        // No boundary: the whole sphere; any accepted direction has half-turn clearance.
        return [[0, 0, 1], [1, 2, 3], [3, -5, 7], [-11, 13, 17]]
            .into_iter()
            .map(Vec3::from_i64)
            .find(|d| ok(d))
            .map(|d| (d, std::f64::consts::PI));
    }
    let starts = starts(arcs, points);
    let (p, c) = deepest_climb(starts, arcs, points)?;
    if let Some(found) = simple_direction(&p, c, 0.9, arcs, points, ok, MAX_REJECTED) {
        return Some(found);
    }
    rounded(&p, c, ok)
}

/// The unit point `p` rounded to 20, 30 or 40 bits, the first that `ok` accepts, with
/// the clearance `c` of `p`.
fn rounded(
    p: &V3,
    c: f64,
    ok: &dyn Fn(&apart_kernel::Vec3) -> bool,
) -> Option<(apart_kernel::Vec3, f64)> {
    use apart_kernel::Vec3;
    for bits in [20, 30, 40] {
        let scale = (1u64 << bits) as f64;
        let d = Vec3::new(
            (p[0] * scale).round() as i64,
            (p[1] * scale).round() as i64,
            (p[2] * scale).round() as i64,
        )
        .primitive();
        if !d.is_zero() && ok(&d) {
            return Some((d, c));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_match_angles() {
        let arc = FArc {
            a: [1.0, 0.0, 0.0],
            b: [0.0, 1.0, 0.0],
            n: [0.0, 0.0, 1.0],
        };
        // Above the middle of the arc at 30°: the distance is 30°.
        let t = 30f64.to_radians();
        let h = std::f64::consts::FRAC_1_SQRT_2 * t.cos();
        let p = [h, h, t.sin()];
        assert!((to_angle(arc.distance2(&p)) - t).abs() < 1e-12);
        // Beyond the end point b: the distance to b.
        let q = normalize([-1.0, 1.0, 0.0]);
        assert!((to_angle(arc.distance2(&q)) - 45f64.to_radians()).abs() < 1e-12);
    }

    #[test]
    fn a_hemisphere_bounded_by_many_short_arcs_is_climbed_to_its_pole() {
        // The lower hemisphere, its equator cut into n arcs (clockwise seen from +z, so
        // the face is on their left): every start lies next to an arc a few thousandths
        // of a radian long, and the deepest direction is the pole, 90° from the boundary.
        for n in [64usize, 1354, 5000] {
            let corner = |k: usize| {
                let t = -(k as f64) * std::f64::consts::TAU / n as f64;
                [t.cos(), t.sin(), 0.0]
            };
            let arcs: Vec<FArc> = (0..n)
                .map(|k| FArc::new(corner(k), corner(k + 1), [0.0, 0.0, -1.0]))
                .collect();
            let below = |d: &apart_kernel::Vec3| d.approx()[2] < 0.0;
            let (d, c) = deep_direction(&arcs, &[], &below).expect("a direction");
            let u = d.unit_f64();
            assert!(c.to_degrees() > 89.0, "{n} arcs: {}°", c.to_degrees());
            assert!(u[2] < -0.999, "{n} arcs: {u:?}");
        }
    }

    #[test]
    fn starting_points_do_not_depend_on_where_the_boundary_starts() {
        // A face bounded by a 40-gon of arcs (more than the 8 sampled), counter-clockwise
        // around +z (face on their left), and a square one (all sampled, clearances
        // equal by symmetry): every rotation of the list gives the same points.
        for n in [40usize, 4] {
            let corner = |k: usize| {
                let t = k as f64 * std::f64::consts::TAU / n as f64;
                normalize([0.5 * t.cos(), 0.5 * t.sin(), 1.0])
            };
            let arcs: Vec<FArc> = (0..n)
                .map(|k| {
                    let (a, b) = (corner(k), corner(k + 1));
                    FArc::new(a, b, normalize(cross(a, b)))
                })
                .collect();
            let first = starting_points(&arcs, &[], 8);
            assert_eq!(first.len(), n.min(8));
            for r in 1..n {
                let mut rotated = arcs.clone();
                rotated.rotate_left(r);
                assert_eq!(
                    starting_points(&rotated, &[], 8),
                    first,
                    "{n} arcs from {r}"
                );
            }
        }
    }
}
