//! The c-space obstacles of a pair of parts, and what a straight move meets in them.
//!
//! For parts `i` and `j` at offsets `p_i` and `p_j`, piece `a` of `i` overlaps piece `b`
//! of `j` exactly when `r = p_i − p_j` lies in the interior of the convex sum
//! `b ⊕ (−a)`. A move of `i` (not `j`) by `t d` moves `r` along the line `r + t d`,
//! which meets each sum in a closed interval of `t` (where the pieces touch or overlap)
//! and its interior in an open one, both from its facets in exact rationals; in machine
//! integers when the numbers are small, as they are on the grid.

use crate::PlanError;
use apart_kernel::{Rational, Sign, Vec3};
use apart_minkowski::minkowski_difference;
use apart_pieces::Polytope;

/// Bound on the absolute value of normal and direction components for the integer path.
const SMALL_NORMAL: i64 = 1 << 24;
/// Bound on offsets and positions for the integer path (products then fit in `i128`).
const SMALL_VALUE: i64 = 1 << 60;

/// A convex obstacle: the closed half-spaces `n · r <= c` of one sum `b ⊕ (−a)`.
#[derive(Clone, Debug)]
pub struct Obstacle {
    /// Each facet's outward normal (primitive integers) and offset.
    pub facets: Vec<([Rational; 3], Rational)>,
    /// The same in machine integers, when they are small.
    small: Option<Vec<([i64; 3], i64)>>,
}

impl Obstacle {
    /// The obstacle of a moving piece `a` against a fixed piece `b`.
    pub fn of(a: &Polytope, b: &Polytope) -> Result<Obstacle, PlanError> {
        let sum = minkowski_difference(b, a)
            .map_err(|e| PlanError::Internal(format!("Minkowski sum of two pieces: {e:?}")))?;
        let den = Rational::from_int(sum.den().clone());
        let facets = sum
            .facets()
            .iter()
            .map(|f| {
                let n = [0, 1, 2].map(|k| Rational::from_int(f.normal.get(k)));
                (n, &Rational::from_int(f.offset.clone()) / &den)
            })
            .collect();
        Ok(Obstacle::from_facets(facets))
    }

    fn from_facets(facets: Vec<([Rational; 3], Rational)>) -> Obstacle {
        let small = facets
            .iter()
            .map(|(n, c)| {
                let n = n.clone().map(|x| small_int(&x, SMALL_NORMAL));
                Some(([n[0]?, n[1]?, n[2]?], small_int(c, SMALL_VALUE)?))
            })
            .collect();
        Obstacle { facets, small }
    }

    /// The box around several obstacles, as an obstacle (`None` for none).
    fn bounding(list: &[Obstacle]) -> Option<Obstacle> {
        let mut facets = Vec::new();
        for k in 0..3 {
            for sign in [1i64, -1] {
                let mut n = [0i64; 3];
                n[k] = sign;
                let nr = n.map(Rational::from);
                // The box's side along n is the farthest of the obstacles' own facets
                // with normal n; an obstacle without one (not a box) gives no box.
                let mut best: Option<Rational> = None;
                for o in list {
                    let c = o.support(&nr)?;
                    if best.as_ref().is_none_or(|b| c > *b) {
                        best = Some(c);
                    }
                }
                facets.push((nr, best?));
            }
        }
        Some(Obstacle::from_facets(facets))
    }

    /// The offset of this obstacle's facet with normal `n`, if it has one.
    fn support(&self, n: &[Rational; 3]) -> Option<Rational> {
        self.facets
            .iter()
            .find(|(m, _)| m == n)
            .map(|(_, c)| c.clone())
    }
}

fn small_int(x: &Rational, bound: i64) -> Option<i64> {
    match x.as_small() {
        Some((n, 1)) if n.abs() < bound => Some(n),
        _ => None,
    }
}

/// Every obstacle of part `i` (moving) against part `j` (fixed), with their box when
/// every one of them has facets along the axes (boxes, on voxel puzzles), to skip the
/// pair at once when a line misses it.
#[derive(Clone, Debug)]
pub struct PairObstacles {
    /// The obstacles.
    pub list: Vec<Obstacle>,
    bounds: Option<Obstacle>,
}

/// Every obstacle of part `i` (moving) against part `j` (fixed).
pub fn pair_obstacles(i: &[Polytope], j: &[Polytope]) -> Result<PairObstacles, PlanError> {
    let mut list = Vec::with_capacity(i.len() * j.len());
    for a in i {
        for b in j {
            list.push(Obstacle::of(a, b)?);
        }
    }
    let bounds = Obstacle::bounding(&list);
    Ok(PairObstacles { list, bounds })
}

/// What the line `r + t d` meets in a pair's obstacles, on both sides of `t = 0`.
#[derive(Clone, Debug, Default)]
pub struct RayFacts {
    /// The first `t >= 0` at which the line enters an obstacle's interior (`Some(0)`:
    /// blocked at once; `None`: never).
    pub forward: Option<Rational>,
    /// The same for `t <= 0`, as a distance `−t`.
    pub backward: Option<Rational>,
    /// Distances `t > 0` at which a contact begins or ends (the line enters or leaves
    /// an obstacle's closed set).
    pub forward_events: Vec<Rational>,
    /// The same for `t < 0`, as distances `−t`.
    pub backward_events: Vec<Rational>,
}

/// The line's closed interval `[lo, hi]` in one obstacle (`None` ends: unbounded) and
/// whether its interior is met (an open interval, the same ends).
struct Interval<T> {
    lo: Option<T>,
    hi: Option<T>,
    interior: bool,
}

/// Meets the line with one obstacle in machine integers: `v / s` as `(v, s)`, `s > 0`.
fn interval_small(
    f: &[([i64; 3], i64)],
    r: &[i64; 3],
    d: &[i64; 3],
) -> Option<Interval<(i128, i128)>> {
    let dot =
        |n: &[i64; 3], x: &[i64; 3]| -> i128 { (0..3).map(|k| n[k] as i128 * x[k] as i128).sum() };
    let less = |a: &(i128, i128), b: &(i128, i128)| a.0 * b.1 < b.0 * a.1;
    let mut out = Interval {
        lo: None,
        hi: None,
        interior: true,
    };
    for (n, c) in f {
        let s = dot(n, d);
        let v = *c as i128 - dot(n, r);
        if s == 0 {
            if v < 0 {
                return None;
            }
            out.interior &= v > 0;
            continue;
        }
        let t = if s > 0 { (v, s) } else { (-v, -s) };
        if s > 0 {
            if out.hi.as_ref().is_none_or(|h| less(&t, h)) {
                out.hi = Some(t);
            }
        } else if out.lo.as_ref().is_none_or(|l| less(l, &t)) {
            out.lo = Some(t);
        }
    }
    if let (Some(l), Some(h)) = (&out.lo, &out.hi) {
        if less(h, l) {
            return None;
        }
        out.interior &= less(l, h);
    }
    Some(out)
}

/// The same in exact rationals.
fn interval_exact(
    f: &[([Rational; 3], Rational)],
    r: &[Rational; 3],
    d: &[Rational; 3],
) -> Option<Interval<Rational>> {
    use apart_kernel::rational::dot;
    let mut out = Interval {
        lo: None,
        hi: None,
        interior: true,
    };
    for (n, c) in f {
        let s = dot(n, d);
        let v = c - &dot(n, r);
        if s.is_zero() {
            match v.sign() {
                Sign::Negative => return None,
                Sign::Zero => out.interior = false,
                Sign::Positive => {}
            }
            continue;
        }
        let t = &v / &s;
        if s.sign() == Sign::Positive {
            if out.hi.as_ref().is_none_or(|h| t < *h) {
                out.hi = Some(t);
            }
        } else if out.lo.as_ref().is_none_or(|l| t > *l) {
            out.lo = Some(t);
        }
    }
    if let (Some(l), Some(h)) = (&out.lo, &out.hi) {
        if h < l {
            return None;
        }
        out.interior &= l < h;
    }
    Some(out)
}

/// The line's interval in `o`, in rationals.
fn interval(
    o: &Obstacle,
    small: Option<(&[i64; 3], &[i64; 3])>,
    r: &[Rational; 3],
    d: &[Rational; 3],
) -> Option<Interval<Rational>> {
    match (&o.small, small) {
        (Some(f), Some((rs, ds))) => {
            let i = interval_small(f, rs, ds)?;
            let q = |x: Option<(i128, i128)>| x.map(|(n, d)| Rational::from_i128(n, d));
            Some(Interval {
                lo: q(i.lo),
                hi: q(i.hi),
                interior: i.interior,
            })
        }
        _ => interval_exact(&o.facets, r, d),
    }
}

fn min_opt(a: &mut Option<Rational>, v: Rational) {
    if a.as_ref().is_none_or(|x| v < *x) {
        *a = Some(v);
    }
}

/// `x` as small integers, when every component is one.
fn small_vec(x: &[Rational; 3], bound: i64) -> Option<[i64; 3]> {
    let v = x.clone().map(|c| small_int(&c, bound));
    Some([v[0]?, v[1]?, v[2]?])
}

/// Meets the line `r + t d` (`d` an integer direction) with every obstacle of a pair.
pub fn ray_facts(pair: &PairObstacles, r: &[Rational; 3], d: &[Rational; 3]) -> RayFacts {
    let mut out = RayFacts::default();
    let rs = small_vec(r, SMALL_VALUE);
    let ds = small_vec(d, SMALL_NORMAL);
    let small = rs.as_ref().zip(ds.as_ref());
    if let Some(b) = &pair.bounds {
        if interval(b, small, r, d).is_none() {
            return out;
        }
    }
    let positive = |x: &Rational| x.sign() == Sign::Positive;
    let negative = |x: &Rational| x.sign() == Sign::Negative;
    for o in &pair.list {
        let Some(i) = interval(o, small, r, d) else {
            continue;
        };
        for e in i.lo.iter().chain(&i.hi) {
            if positive(e) {
                out.forward_events.push(e.clone());
            } else if negative(e) {
                out.backward_events.push(-e);
            }
        }
        if !i.interior {
            continue;
        }
        // Forward: an interval reaching past 0 is entered at max(lo, 0).
        if i.hi.as_ref().is_none_or(positive) {
            let at = i.lo.clone().filter(positive).unwrap_or_else(Rational::zero);
            min_opt(&mut out.forward, at);
        }
        // Backward: an interval reaching below 0 is entered at min(hi, 0).
        if i.lo.as_ref().is_none_or(negative) {
            let at =
                i.hi.as_ref()
                    .filter(|h| negative(h))
                    .map_or_else(Rational::zero, |h| -h);
            min_opt(&mut out.backward, at);
        }
    }
    for e in [&mut out.forward_events, &mut out.backward_events] {
        e.sort();
        e.dedup();
    }
    out
}

/// The outward normals of the obstacles' facets on which `r` lies, for obstacles whose
/// closed set holds `r` (contacts between the two parts).
pub fn contact_normals(pair: &PairObstacles, r: &[Rational; 3], out: &mut Vec<Vec3>) {
    let zero = [0, 1, 2].map(|_| Rational::zero());
    if let Some(b) = &pair.bounds {
        if interval_exact(&b.facets, r, &zero).is_none() {
            return;
        }
    }
    for o in &pair.list {
        let mut active = Vec::new();
        let mut inside = true;
        for (n, c) in &o.facets {
            let v = c - &apart_kernel::rational::dot(n, r);
            match v.sign() {
                Sign::Negative => {
                    inside = false;
                    break;
                }
                Sign::Zero => active.push(n),
                Sign::Positive => {}
            }
        }
        if inside {
            for n in active {
                out.push(Vec3::from_ints(n.clone().map(|x| x.numer())));
            }
        }
    }
}
