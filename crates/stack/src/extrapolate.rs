//! Obstacle extrapolation inside constant-topology orientation intervals (paper 004
//! §IV and Appendix C).
//!
//! As the moving piece turns about z, the obstacle `B ⊕ (−R_θ A)` keeps its
//! face-edge-vertex structure (which vertex pairs `(a_i, b_j)` are extreme, which form
//! each facet) until the overlay of the two Gaussian maps changes: a facet normal of one
//! piece crosses the great circle of an edge of the other (`m · R_θ u = 0`), or two
//! horizontal facet normals coincide on the equator, where every arc of either map runs.
//! Each such event is `mᵀ R_θ v = 0` for fixed integer vectors, i.e.
//! `α cos θ + β sin θ + γ = 0`, a quadratic in `t = tan(θ/2)`:
//! `(γ − α) t² + 2β t + (α + γ) = 0` (Appendix C's equation (16), here over the Gaussian
//! map events rather than the paper's conservative "interior point meets a face" test,
//! which misses in-plane changes such as a horizontal edge sweeping over a horizontal
//! facet).
//!
//! With exact rational rotations, "extrapolation" means: keep the structure computed at
//! `θ_0`, and for another discrete orientation `θ_1` decide exactly whether any event
//! quadratic has a root between `0` and `tan((θ_1 − θ_0)/2)` (a rational number); if
//! none does, the obstacle at `θ_1` is the same structure with its vertices recomputed
//! as `b_j − R_θ1 a_i` and its facet planes through them. Tests compare extrapolated
//! obstacles with freshly computed ones.

use crate::obstacle::{provenance, ObstacleShape};
use crate::orientation::ZRotation;
use apart_kernel::int::sign_of;
use apart_kernel::{Int, Sign, Vec3};
use apart_pieces::Polytope;

/// The structure of one obstacle at a reference orientation, ready to be re-evaluated
/// at other orientations about z.
#[derive(Clone, Debug)]
pub struct Template {
    fixed: Polytope,
    moving: Polytope,
    theta0: ZRotation,
    pairs: Vec<(u32, u32)>,
    cycles: Vec<Vec<u32>>,
    /// Each event's quadratic in `tan(δ/2)` (it depends on the reference only), with
    /// identically zero ones (never an event) dropped.
    quadratics: Quadratics,
}

/// The event quadratics: machine integers when every coefficient is below 2^62
/// (boxes and small turns: the usual case), else arbitrary precision.
#[derive(Clone, Debug)]
enum Quadratics {
    Small(Vec<[i64; 3]>),
    Big(Vec<[Int; 3]>),
}

impl Template {
    /// The template of `obstacle = fixed ⊕ (−R_θ0 moving)`, where `moving` is the moving
    /// piece before its turn about z; `None` if the obstacle's vertices cannot be traced
    /// back to vertex pairs (never for a correct Minkowski sum).
    pub fn new(
        fixed: &Polytope,
        moving: &Polytope,
        theta0: ZRotation,
        obstacle: &ObstacleShape,
    ) -> Option<Template> {
        let quadratics = Template::event_quadratics(fixed, moving, theta0, false)?;
        let turned = rotate_z(moving, theta0);
        let pairs = provenance(obstacle, fixed, &turned)?;
        Some(Template {
            fixed: fixed.clone(),
            moving: moving.clone(),
            theta0,
            pairs,
            cycles: obstacle.cycles.clone(),
            quadratics,
        })
    }

    /// The events of a template without the obstacle's structure: enough for
    /// [`Template::valid_at`] and the interval, at a fraction of the cost; `None` when
    /// the reference angle is critical (an event quadratic vanishes at `δ = 0`: such a template is valid at the reference
    /// only, where the obstacle is known). Complete it
    /// with [`Template::trace`] before extrapolating.
    pub(crate) fn untraced(
        fixed: &Polytope,
        moving: &Polytope,
        theta0: ZRotation,
    ) -> Option<Template> {
        let quadratics = Template::event_quadratics(fixed, moving, theta0, true)?;
        Some(Template {
            fixed: fixed.clone(),
            moving: moving.clone(),
            theta0,
            pairs: Vec::new(),
            cycles: Vec::new(),
            quadratics,
        })
    }

    /// Completes an [`Template::untraced`] template with the structure of its obstacle
    /// (the obstacle at the reference, `fixed ⊕ (−turned)` with `turned` the moving
    /// piece turned to the reference); false if it cannot be traced.
    pub(crate) fn trace(&mut self, obstacle: &ObstacleShape, turned: &Polytope) -> bool {
        match provenance(obstacle, &self.fixed, turned) {
            Some(pairs) => {
                self.pairs = pairs;
                self.cycles = obstacle.cycles.clone();
                true
            }
            None => false,
        }
    }

    /// The event quadratics (see [`Template::valid_at`]), sorted and without duplicates
    /// or identically zero ones; with `useful_only`, `None` when one vanishes at the
    /// reference.
    fn event_quadratics(
        fixed: &Polytope,
        moving: &Polytope,
        theta0: ZRotation,
        useful_only: bool,
    ) -> Option<Quadratics> {
        let mut events = Vec::new();
        for f in fixed.facets() {
            for u in moving.edge_directions() {
                events.push((f.normal.clone(), u.clone()));
            }
        }
        for e in fixed.edge_directions() {
            for f in moving.facets() {
                events.push((e.clone(), f.normal.clone()));
            }
        }
        let z = Vec3::new(0, 0, 1);
        for fb in fixed
            .facets()
            .iter()
            .filter(|f| f.normal.get(2) == Int::ZERO)
        {
            let m = fb.normal.cross(&z);
            for fa in moving
                .facets()
                .iter()
                .filter(|f| f.normal.get(2) == Int::ZERO)
            {
                events.push((m.clone(), fa.normal.clone()));
            }
        }
        // Each moving direction turned once (events share them).
        let mut turned_dirs: Vec<(&Vec3, Vec3)> = Vec::new();
        let mut small: Option<Vec<[i64; 3]>> = Some(Vec::with_capacity(events.len()));
        let mut quadratics: Vec<[Int; 3]> = Vec::new();
        for (m, v) in &events {
            let k = match turned_dirs.iter().position(|(u, _)| *u == v) {
                Some(k) => k,
                None => {
                    turned_dirs.push((v, theta0.apply_scaled(v)));
                    turned_dirs.len() - 1
                }
            };
            let v = &turned_dirs[k].1;
            if let Some(list) = &mut small {
                let q = Template::quadratic_small(m, v);
                match q {
                    Some(q) => {
                        if q != [0, 0, 0] {
                            if useful_only && q[2] == 0 {
                                return None;
                            }
                            list.push(q);
                        }
                        continue;
                    }
                    None => {
                        // Too large: every quadratic in arbitrary precision from here on.
                        quadratics = list.iter().map(|q| q.map(Int::from)).collect();
                        small = None;
                    }
                }
            }
            let q = Template::quadratic_turned(m, v);
            if q.iter().any(|c| *c != Int::ZERO) {
                if useful_only && q[2] == Int::ZERO {
                    return None;
                }
                quadratics.push(q);
            }
        }
        if let Some(mut list) = small {
            list.sort_unstable();
            list.dedup();
            return Some(Quadratics::Small(list));
        }
        quadratics.sort();
        quadratics.dedup();
        Some(Quadratics::Big(quadratics))
    }

    /// Exactly: is the obstacle's structure the same at `theta` as at the reference
    /// (no event between them, the turn shorter than half a turn)?
    pub fn valid_at(&self, theta: ZRotation) -> bool {
        if theta == self.theta0 {
            return true;
        }
        let d = theta.then(self.theta0.inverse());
        if d.a == -d.c {
            return false;
        }
        // t1 = tan(δ/2) = sin δ / (1 + cos δ) = b / (c + a).
        let (p, qd) = (d.b, d.c + d.a);
        match &self.quadratics {
            // |a| < 2^62 and |p|, |q| < 2^31 (see `root_free_i128`).
            Quadratics::Small(list)
                if p.unsigned_abs() < 1 << 31 && qd.unsigned_abs() < 1 << 31 =>
            {
                let (p, qd) = (i128::from(p), i128::from(qd));
                list.iter().all(|q| {
                    let [a2, a1, a0] = q.map(i128::from);
                    root_free_i128(a2, a1, a0, p, qd)
                })
            }
            Quadratics::Small(list) => {
                let (p, qd) = (Int::from(p), Int::from(qd));
                list.iter().all(|q| {
                    let [a2, a1, a0] = q.map(Int::from);
                    root_free(&a2, &a1, &a0, &p, &qd)
                })
            }
            Quadratics::Big(list) => {
                let (p, qd) = (Int::from(p), Int::from(qd));
                list.iter()
                    .all(|[a2, a1, a0]| root_free(a2, a1, a0, &p, &qd))
            }
        }
    }

    /// [`Template::quadratic_turned`] in machine integers, when the vectors are small and
    /// every coefficient is below 2^62 in magnitude.
    fn quadratic_small(m: &Vec3, v: &Vec3) -> Option<[i64; 3]> {
        let (m, v) = (m.as_small()?, v.as_small()?);
        let [m, v] = [m, v].map(|c| c.map(i128::from));
        let alpha = m[0] * v[0] + m[1] * v[1];
        let beta = m[1] * v[0] - m[0] * v[1];
        let gamma = m[2] * v[2];
        let q = [gamma - alpha, 2 * beta, alpha + gamma];
        if q.iter().any(|c| c.unsigned_abs() >= 1 << 62) {
            return None;
        }
        Some(q.map(|c| c as i64))
    }

    /// Coefficients `[t², t, 1]` of the event quadratic in `t = tan(δ/2)`, `δ = θ − θ0`,
    /// for the event `(m, v)` with `v` already turned by the reference rotation.
    fn quadratic_turned(m: &Vec3, v: &Vec3) -> [Int; 3] {
        if let (Some(m), Some(v)) = (m.as_small(), v.as_small()) {
            // Machine integers (below 2^62): every product and sum fits in i128.
            let [m, v] = [m, v].map(|c| c.map(i128::from));
            let alpha = m[0] * v[0] + m[1] * v[1];
            let beta = m[1] * v[0] - m[0] * v[1];
            let gamma = m[2] * v[2];
            return [gamma - alpha, 2 * beta, alpha + gamma].map(Int::from);
        }
        let (m, v) = (m.to_ints(), v.to_ints());
        let alpha = &m[0] * &v[0] + &m[1] * &v[1];
        let beta = &m[1] * &v[0] - &m[0] * &v[1];
        let gamma = &m[2] * &v[2];
        [&gamma - &alpha, Int::from(2) * beta, alpha + gamma]
    }

    /// The obstacle at `theta`, from the structure (call only when [`Self::valid_at`]).
    pub fn extrapolate(&self, theta: ZRotation) -> ObstacleShape {
        let turned_den = self.moving.den() * Int::from(theta.c);
        let den = apart_kernel::int::lcm(self.fixed.den(), &turned_den);
        let kf = &den / self.fixed.den();
        let km = &den / &turned_den;
        let fixed: Vec<Vec3> = self.fixed.vertices().iter().map(|v| v.scale(&kf)).collect();
        let moving: Vec<Vec3> = self
            .moving
            .vertices()
            .iter()
            .map(|v| theta.apply_scaled(v).scale(&km))
            .collect();
        let vertices: Vec<Vec3> = self
            .pairs
            .iter()
            .map(|&(i, j)| fixed[j as usize].sub(&moving[i as usize]))
            .collect();
        let halfspaces = self
            .cycles
            .iter()
            .map(|c| {
                let (v0, v1, v2) = (
                    &vertices[c[0] as usize],
                    &vertices[c[1] as usize],
                    &vertices[c[2] as usize],
                );
                let n = v1.sub(v0).cross(&v2.sub(v1)).primitive();
                let off = n.dot(v0);
                crate::obstacle::facet_plane(&n, &off, &den)
            })
            .collect();
        ObstacleShape {
            vertices,
            den,
            halfspaces,
            cycles: self.cycles.clone(),
        }
    }

    /// The critical angles (degrees in `[0, 360)`, sorted) where some event happens: the
    /// ends of the constant-topology intervals (floating point, for reports).
    pub(crate) fn critical_angles_deg(&self) -> Vec<f64> {
        let t0 = self.theta0.angle_deg();
        let mut out = Vec::new();
        let as_f64: Vec<[f64; 3]> = match &self.quadratics {
            Quadratics::Small(list) => list.iter().map(|q| q.map(|c| c as f64)).collect(),
            Quadratics::Big(list) => list
                .iter()
                .map(|q| q.clone().map(|c| apart_kernel::int::to_f64(&c)))
                .collect(),
        };
        for [a2, a1, a0] in as_f64 {
            if a2 == 0.0 && a1 == 0.0 {
                continue; // constant: never an event (or always, identically zero)
            }
            let mut ts = Vec::new();
            if a2 == 0.0 {
                ts.push(-a0 / a1);
                out.push((t0 + 180.0).rem_euclid(360.0)); // t = ∞
            } else {
                let disc = a1 * a1 - 4.0 * a2 * a0;
                if disc >= 0.0 {
                    ts.push((-a1 + disc.sqrt()) / (2.0 * a2));
                    ts.push((-a1 - disc.sqrt()) / (2.0 * a2));
                }
            }
            for t in ts {
                out.push((t0 + 2.0 * t.atan().to_degrees()).rem_euclid(360.0));
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        out
    }

    /// The constant-topology interval around the reference, in degrees `(lo, hi)` with
    /// `lo <= θ0 <= hi` (unwrapped), from the float critical angles.
    pub fn interval_deg(&self) -> (f64, f64) {
        let t0 = self.theta0.angle_deg();
        let crit = self.critical_angles_deg();
        if crit.is_empty() {
            return (t0 - 180.0, t0 + 180.0);
        }
        let mut lo = t0 - 360.0;
        let mut hi = t0 + 360.0;
        for c in crit {
            for c in [c - 360.0, c, c + 360.0] {
                if c > t0 + 1e-9 {
                    hi = hi.min(c);
                } else if c < t0 - 1e-9 {
                    lo = lo.max(c);
                } else {
                    return (t0, t0);
                }
            }
        }
        (lo, hi)
    }
}

/// The polytope turned about z by `r`.
pub fn rotate_z(p: &Polytope, r: ZRotation) -> Polytope {
    crate::orientation::rotate_polytope(p, |v| r.apply_scaled(v), r.c)
}

/// Sign of `a2 t² + a1 t + a0` at `t = p / q` (`q > 0`), times `q²`.
fn eval_sign(a2: &Int, a1: &Int, a0: &Int, p: &Int, q: &Int) -> Sign {
    sign_of(&(a2 * p * p + a1 * p * q + a0 * q * q))
}

/// True when the quadratic has no root on the closed interval between `0` and `p/q`
/// (or is identically zero).
fn root_free(a2: &Int, a1: &Int, a0: &Int, p: &Int, q: &Int) -> bool {
    let zero = Int::ZERO;
    if *a2 == zero && *a1 == zero && *a0 == zero {
        return true;
    }
    let s0 = sign_of(a0);
    let s1 = eval_sign(a2, a1, a0, p, q);
    if s0 == Sign::Zero || s1 == Sign::Zero || s0 != s1 {
        return false;
    }
    if *a2 == zero {
        return true; // linear and the same sign at both ends
    }
    // The vertex t* = −a1 / (2 a2) strictly between 0 and p/q?
    let (lo_p, hi_p) = if *p < zero {
        (p.clone(), zero.clone())
    } else {
        (zero.clone(), p.clone())
    };
    // Compare t* with lo_p/q and hi_p/q: t* > x/q  <=>  −a1 q > 2 a2 x (sign of a2 flips).
    let two_a2 = Int::from(2) * a2;
    let gt = |x: &Int| -> bool {
        let l = -(a1 * q);
        let r = &two_a2 * x;
        if *a2 > zero {
            l > r
        } else {
            l < r
        }
    };
    let lt = |x: &Int| -> bool {
        let l = -(a1 * q);
        let r = &two_a2 * x;
        if *a2 > zero {
            l < r
        } else {
            l > r
        }
    };
    if !(gt(&lo_p) && lt(&hi_p)) {
        return true; // monotone on the interval
    }
    // Value at the vertex: a0 − a1²/(4 a2); its sign is sign(4 a2 a0 − a1²)·sign(a2).
    let disc = Int::from(4) * a2 * a0 - a1 * a1;
    let sv = match (sign_of(&disc), sign_of(a2)) {
        (Sign::Zero, _) => Sign::Zero,
        (x, Sign::Positive) => x,
        (x, _) => -x,
    };
    sv == s0
}

/// [`root_free`] in `i128`, for `|a_i| < 2^62` and `|p|, |q| < 2^31`: `a p q` is under
/// 2^124 in magnitude, so the sum of three under 2^126, and `4 a2 a0 − a1²` under 2^127.
fn root_free_i128(a2: i128, a1: i128, a0: i128, p: i128, q: i128) -> bool {
    let sign = |v: i128| v.cmp(&0);
    if a2 == 0 && a1 == 0 && a0 == 0 {
        return true;
    }
    use std::cmp::Ordering::{Equal, Greater};
    let s0 = sign(a0);
    let s1 = sign(a2 * p * p + a1 * p * q + a0 * q * q);
    if s0 == Equal || s1 == Equal || s0 != s1 {
        return false;
    }
    if a2 == 0 {
        return true;
    }
    let (lo_p, hi_p) = if p < 0 { (p, 0) } else { (0, p) };
    // t* = −a1 / (2 a2) strictly between lo_p/q and hi_p/q (q > 0)?
    let l = -(a1 * q);
    let gt = |x: i128| {
        if a2 > 0 {
            l > 2 * a2 * x
        } else {
            l < 2 * a2 * x
        }
    };
    let lt = |x: i128| {
        if a2 > 0 {
            l < 2 * a2 * x
        } else {
            l > 2 * a2 * x
        }
    };
    if !(gt(lo_p) && lt(hi_p)) {
        return true;
    }
    let disc = 4 * a2 * a0 - a1 * a1;
    let sv = match (sign(disc), sign(a2)) {
        (Equal, _) => Equal,
        (x, Greater) => x,
        (x, _) => x.reverse(),
    };
    sv == s0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The machine-integer root test agrees with the arbitrary-precision one.
    #[test]
    fn root_free_in_i128_matches() {
        let mut state: u64 = 0x1234_5678_9abc_def1;
        let mut next = |m: i64| -> i64 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % (2 * m as u64 + 1)) as i64 - m
        };
        for k in 0..20000 {
            let big = if k % 2 == 0 { 6 } else { i64::MAX / 4 };
            let a = [next(big), next(big), next(big)];
            let (p, q) = (next(1 << 30), next(1 << 30).abs().max(1));
            let fast = root_free_i128(a[0].into(), a[1].into(), a[2].into(), p.into(), q.into());
            let slow = root_free(
                &Int::from(a[0]),
                &Int::from(a[1]),
                &Int::from(a[2]),
                &Int::from(p),
                &Int::from(q),
            );
            assert_eq!(fast, slow, "{a:?} {p} {q}");
        }
    }

    #[test]
    fn quadratic_roots_on_intervals() {
        let i = |v: i64| Int::from(v);
        // 4t² − 1: roots ±1/2; none on [0, 1/4], one on [0, 1].
        assert!(root_free(&i(4), &i(0), &i(-1), &i(1), &i(4)));
        assert!(!root_free(&i(4), &i(0), &i(-1), &i(1), &i(1)));
        // (t − 1)(t − 2) = t² − 3t + 2: no root on [0, 1/2], a root on [0, 1], none...
        assert!(root_free(&i(1), &i(-3), &i(2), &i(1), &i(2)));
        assert!(!root_free(&i(1), &i(-3), &i(2), &i(1), &i(1)));
        // Two roots inside [0, 3] with equal end signs: detected by the vertex.
        assert!(!root_free(&i(1), &i(-3), &i(2), &i(3), &i(1)));
        // (t + 1)(t + 2): nothing on [0, 5].
        assert!(root_free(&i(1), &i(3), &i(2), &i(5), &i(1)));
        // Negative interval [−3/2, 0] contains −1.
        assert!(!root_free(&i(1), &i(3), &i(2), &i(-3), &i(2)));
        // Double root at 1/2 inside [0, 1]: 4t² − 4t + 1.
        assert!(!root_free(&i(4), &i(-4), &i(1), &i(1), &i(1)));
        // Identically zero: no event.
        assert!(root_free(&i(0), &i(0), &i(0), &i(1), &i(1)));
    }
}
