//! The c-space obstacles of a pair of parts, and what a straight move meets in them.
//!
//! For parts `i` and `j` at offsets `p_i` and `p_j`, piece `a` of `i` overlaps piece `b`
//! of `j` exactly when `r = p_i − p_j` lies in the interior of the convex sum
//! `b ⊕ (−a)`. A move of `i` (not `j`) by `t d` moves `r` along the line `r + t d`,
//! which meets each sum's interior in an open interval of `t` computed from its facets
//! in exact rationals.

use crate::PlanError;
use apart_kernel::{Rational, Vec3};
use apart_minkowski::minkowski_difference;
use apart_pieces::Polytope;

/// A convex obstacle: the closed half-spaces `n · r <= c` of one sum `b ⊕ (−a)`.
#[derive(Clone, Debug)]
pub struct Obstacle {
    /// Each facet's outward normal (primitive integers) and offset.
    pub facets: Vec<([Rational; 3], Rational)>,
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
        Ok(Obstacle { facets })
    }
}

/// Every obstacle of part `i` (moving) against part `j` (fixed).
pub fn pair_obstacles(i: &[Polytope], j: &[Polytope]) -> Result<Vec<Obstacle>, PlanError> {
    let mut out = Vec::with_capacity(i.len() * j.len());
    for a in i {
        for b in j {
            out.push(Obstacle::of(a, b)?);
        }
    }
    Ok(out)
}

/// What the line `r + t d` meets in a pair's obstacles, on both sides of `t = 0`.
#[derive(Clone, Debug, Default)]
pub struct RayFacts {
    /// The first `t >= 0` at which the line enters an obstacle's interior (`Some(0)`:
    /// blocked at once; `None`: never).
    pub forward: Option<Rational>,
    /// The same for `t <= 0`, as a distance `−t`.
    pub backward: Option<Rational>,
    /// Distances `t > 0` at which the line crosses a facet plane of an obstacle.
    pub forward_events: Vec<Rational>,
    /// Distances `−t > 0` at which it crosses one for `t < 0`.
    pub backward_events: Vec<Rational>,
}

fn min_opt(a: &mut Option<Rational>, v: Rational) {
    if a.as_ref().is_none_or(|x| v < *x) {
        *a = Some(v);
    }
}

/// Meets the line `r + t d` (`d` an integer direction) with every obstacle.
pub fn ray_facts(obstacles: &[Obstacle], r: &[Rational; 3], d: &[Rational; 3]) -> RayFacts {
    let mut out = RayFacts::default();
    for o in obstacles {
        // The open interval (lo, hi) of t inside, or empty.
        let mut lo: Option<Rational> = None;
        let mut hi: Option<Rational> = None;
        let mut empty = false;
        for (n, c) in &o.facets {
            let s = apart_kernel::rational::dot(n, d);
            let v = c - &apart_kernel::rational::dot(n, r);
            if s.is_zero() {
                // Parallel: inside the open half-space for every t, or for none.
                empty |= v.sign() != apart_kernel::Sign::Positive;
                continue;
            }
            let t = &v / &s;
            if t.sign() == apart_kernel::Sign::Positive {
                out.forward_events.push(t.clone());
            } else if t.sign() == apart_kernel::Sign::Negative {
                out.backward_events.push(-&t);
            }
            if s.sign() == apart_kernel::Sign::Positive {
                // t s < v: t < v / s.
                if hi.as_ref().is_none_or(|h| t < *h) {
                    hi = Some(t);
                }
            } else if lo.as_ref().is_none_or(|l| t > *l) {
                lo = Some(t);
            }
        }
        if empty {
            continue;
        }
        match (&lo, &hi) {
            (Some(l), Some(h)) if l >= h => continue,
            _ => {}
        }
        // Forward: an interval reaching past 0 is entered at max(lo, 0).
        if hi
            .as_ref()
            .is_none_or(|h| h.sign() == apart_kernel::Sign::Positive)
        {
            let at = match &lo {
                Some(l) if l.sign() == apart_kernel::Sign::Positive => l.clone(),
                _ => Rational::zero(),
            };
            min_opt(&mut out.forward, at);
        }
        // Backward: an interval reaching below 0 is entered at min(hi, 0).
        if lo
            .as_ref()
            .is_none_or(|l| l.sign() == apart_kernel::Sign::Negative)
        {
            let at = match &hi {
                Some(h) if h.sign() == apart_kernel::Sign::Negative => -h,
                _ => Rational::zero(),
            };
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
pub fn contact_normals(obstacles: &[Obstacle], r: &[Rational; 3], out: &mut Vec<Vec3>) {
    for o in obstacles {
        let mut active = Vec::new();
        let mut inside = true;
        for (n, c) in &o.facets {
            let v = c - &apart_kernel::rational::dot(n, r);
            match v.sign() {
                apart_kernel::Sign::Negative => {
                    inside = false;
                    break;
                }
                apart_kernel::Sign::Zero => active.push(n),
                apart_kernel::Sign::Positive => {}
            }
        }
        if inside {
            for n in active {
                out.push(Vec3::from_ints(n.clone().map(|x| x.numer())));
            }
        }
    }
}
