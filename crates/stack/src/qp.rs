//! Exact minimization of a convex quadratic over a convex cell of linear inequalities.
//!
//! The cell is `{p : n_k · p <= off_k}` in three variables (closed, possibly flat or a
//! single point). The objective is a convex quadratic `F(p) = pᵀHp + g·p + c` (`H`
//! positive semidefinite), and ties among minimizers of `F` (a zero weight, as in paper
//! 004 eq. (1) with `w = 0` or `w = 1`) are broken by the strictly convex
//! `G(p) = ‖p − anchor‖²`. The answer is the unique lexicographic minimizer of `(F, G)`.
//!
//! Method: Seidel's randomized incremental algorithm for LP-type problems, in exact
//! rational arithmetic. Constraints are added one at a time; when the current optimum
//! violates the new constraint, the new optimum lies on its plane, found recursively with
//! that plane as an equality (at most three levels deep in three variables). The base
//! case minimizes `(F, G)` over an affine subspace by exact linear algebra. Correctness
//! rests on the objective being convex with a unique lexicographic minimizer on every
//! closed convex set, which holds for `(F, G)` (see `DESIGN` in the crate docs). Linear
//! programs use the same machinery with `F = (n · p − L)²`, `L` a strict lower bound.

use apart_kernel::{int, rational, BigPlane, HPoint, Rational, Sign};

/// A convex quadratic `pᵀHp + g·p + c` with the anchor of its tie-breaker
/// `‖p − anchor‖²`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Objective {
    /// Symmetric positive semidefinite matrix.
    pub h: [[Rational; 3]; 3],
    /// Linear part.
    pub g: [Rational; 3],
    /// Constant.
    pub c: Rational,
    /// Ties between minimizers of the quadratic go to the point nearest this one.
    pub anchor: [Rational; 3],
}

/// Why an objective is not a bounded-below convex quadratic.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ObjectiveError {
    /// `H` is not symmetric.
    #[error("the quadratic form is not symmetric")]
    NotSymmetric,
    /// `H` is not positive semidefinite.
    #[error("the quadratic form is not convex (not positive semidefinite)")]
    NotConvex,
    /// The linear part has a component along a direction where `H` is zero: the
    /// objective decreases without bound.
    #[error("the objective is unbounded below (linear part outside the range of the form)")]
    Unbounded,
}

impl Objective {
    /// `‖p − target‖²`.
    pub(crate) fn distance(target: &[Rational; 3]) -> Objective {
        Objective::diagonal(
            &[Rational::from(1), Rational::from(1), Rational::from(1)],
            target,
            &Rational::zero(),
        )
    }

    /// `Σ weight_i (p_i − target_i)² + constant` (weights `>= 0`), ties to `target`.
    pub(crate) fn diagonal(
        weight: &[Rational; 3],
        target: &[Rational; 3],
        constant: &Rational,
    ) -> Objective {
        let z = Rational::zero;
        let mut h = [[z(), z(), z()], [z(), z(), z()], [z(), z(), z()]];
        let mut g = [z(), z(), z()];
        let mut c = constant.clone();
        for i in 0..3 {
            h[i][i] = weight[i].clone();
            g[i] = &(&Rational::from(-2) * &weight[i]) * &target[i];
            c = &c + &(&weight[i] * &(&target[i] * &target[i]));
        }
        Objective {
            h,
            g,
            c,
            anchor: target.clone(),
        }
    }

    /// `(n · p − lower)²` for integer `n`: minimizing it over a set where `n · p >= lower`
    /// minimizes `n · p`.
    pub(crate) fn linear(n: &[apart_kernel::Int; 3], lower: &Rational) -> Objective {
        let nq = n.clone().map(Rational::from_int);
        let h = [0, 1, 2].map(|i| [0, 1, 2].map(|j| &nq[i] * &nq[j]));
        let g = [0, 1, 2].map(|i| &(&Rational::from(-2) * lower) * &nq[i]);
        Objective {
            h,
            g,
            c: lower * lower,
            anchor: [Rational::zero(), Rational::zero(), Rational::zero()],
        }
    }

    /// Checks that the objective is a convex quadratic bounded below.
    pub(crate) fn validate(&self) -> Result<(), ObjectiveError> {
        for i in 0..3 {
            for j in 0..3 {
                if self.h[i][j] != self.h[j][i] {
                    return Err(ObjectiveError::NotSymmetric);
                }
            }
        }
        // Positive semidefinite: every principal minor >= 0.
        let h = &self.h;
        let m2 = |i: usize, j: usize| &(&h[i][i] * &h[j][j]) - &(&h[i][j] * &h[j][i]);
        let minors = [
            h[0][0].clone(),
            h[1][1].clone(),
            h[2][2].clone(),
            m2(0, 1),
            m2(0, 2),
            m2(1, 2),
            det3(h),
        ];
        if minors.iter().any(|m| m.sign() == Sign::Negative) {
            return Err(ObjectiveError::NotConvex);
        }
        // Bounded below: 2H x = -g solvable.
        let a: Vec<Vec<Rational>> = (0..3)
            .map(|i| (0..3).map(|j| &Rational::from(2) * &h[i][j]).collect())
            .collect();
        let b: Vec<Rational> = self.g.iter().map(|v| -v).collect();
        if affine_solutions(&a, &b, 3).is_none() {
            return Err(ObjectiveError::Unbounded);
        }
        Ok(())
    }

    /// `F(p)`.
    pub(crate) fn value(&self, p: &[Rational; 3]) -> Rational {
        let hp = mat_vec(&self.h, p);
        &(&rational::dot(p, &hp) + &rational::dot(&self.g, p)) + &self.c
    }

    /// The tie-breaker `‖p − anchor‖²`.
    pub(crate) fn tie(&self, p: &[Rational; 3]) -> Rational {
        let d = rational::sub(p, &self.anchor);
        rational::dot(&d, &d)
    }
}

fn det3(h: &[[Rational; 3]; 3]) -> Rational {
    let m = |a: &Rational, b: &Rational, c: &Rational, d: &Rational| &(a * d) - &(b * c);
    let t0 = &h[0][0] * &m(&h[1][1], &h[1][2], &h[2][1], &h[2][2]);
    let t1 = &h[0][1] * &m(&h[1][0], &h[1][2], &h[2][0], &h[2][2]);
    let t2 = &h[0][2] * &m(&h[1][0], &h[1][1], &h[2][0], &h[2][1]);
    &(&t0 - &t1) + &t2
}

fn mat_vec(h: &[[Rational; 3]; 3], p: &[Rational; 3]) -> [Rational; 3] {
    [0, 1, 2].map(|i| rational::dot(&h[i], p))
}

/// All solutions of `a x = b` (`a`: rows of length `k`): a particular solution and a
/// basis of the null space of `a`; `None` when inconsistent. Exact Gauss–Jordan.
// Row reduction reads and writes two rows at once by index.
#[allow(clippy::needless_range_loop)]
pub(crate) fn affine_solutions(
    a: &[Vec<Rational>],
    b: &[Rational],
    k: usize,
) -> Option<(Vec<Rational>, Vec<Vec<Rational>>)> {
    let mut rows: Vec<Vec<Rational>> = a
        .iter()
        .zip(b)
        .map(|(r, v)| {
            let mut row = r.clone();
            row.push(v.clone());
            row
        })
        .collect();
    let mut pivots: Vec<usize> = Vec::new();
    let mut r = 0;
    for col in 0..k {
        let Some(pr) = (r..rows.len()).find(|&i| !rows[i][col].is_zero()) else {
            continue;
        };
        rows.swap(r, pr);
        let inv = rows[r][col].recip();
        for j in col..=k {
            rows[r][j] = &rows[r][j] * &inv;
        }
        for i in 0..rows.len() {
            if i != r && !rows[i][col].is_zero() {
                let f = rows[i][col].clone();
                for j in col..=k {
                    let t = &f * &rows[r][j];
                    rows[i][j] = &rows[i][j] - &t;
                }
            }
        }
        pivots.push(col);
        r += 1;
        if r == rows.len() {
            break;
        }
    }
    // Inconsistent: a zero row with a non-zero right-hand side.
    if rows[r..].iter().any(|row| !row[k].is_zero()) {
        return None;
    }
    let mut x = vec![Rational::zero(); k];
    for (i, &c) in pivots.iter().enumerate() {
        x[c] = rows[i][k].clone();
    }
    let free: Vec<usize> = (0..k).filter(|c| !pivots.contains(c)).collect();
    let basis = free
        .iter()
        .map(|&f| {
            let mut v = vec![Rational::zero(); k];
            v[f] = Rational::from(1);
            for (i, &c) in pivots.iter().enumerate() {
                v[c] = -&rows[i][f];
            }
            v
        })
        .collect();
    Some((x, basis))
}

/// The lexicographic minimizer of `(F, G)` on the affine subspace where every `eqs`
/// holds with equality; `None` when the equalities are inconsistent (or `F` is
/// unbounded there, which a validated objective excludes).
fn affine_min(eqs: &[&BigPlane], obj: &Objective) -> Option<[Rational; 3]> {
    let a: Vec<Vec<Rational>> = eqs
        .iter()
        .map(|h| h.n.iter().map(|c| Rational::from_int(c.clone())).collect())
        .collect();
    let b: Vec<Rational> = eqs
        .iter()
        .map(|h| Rational::from_int(h.c.clone()))
        .collect();
    let (p0, basis) = if eqs.is_empty() {
        (
            vec![Rational::zero(), Rational::zero(), Rational::zero()],
            vec![
                vec![Rational::from(1), Rational::zero(), Rational::zero()],
                vec![Rational::zero(), Rational::from(1), Rational::zero()],
                vec![Rational::zero(), Rational::zero(), Rational::from(1)],
            ],
        )
    } else {
        affine_solutions(&a, &b, 3)?
    };
    let p0 = [p0[0].clone(), p0[1].clone(), p0[2].clone()];
    if basis.is_empty() {
        return Some(p0);
    }
    let basis: Vec<[Rational; 3]> = basis
        .into_iter()
        .map(|v| [v[0].clone(), v[1].clone(), v[2].clone()])
        .collect();
    let d = basis.len();
    // Stage F: 2 BᵀHB u = −Bᵀ(2Hp0 + g).
    let hp0 = mat_vec(&obj.h, &p0);
    let grad0 = [0, 1, 2].map(|i| &(&Rational::from(2) * &hp0[i]) + &obj.g[i]);
    let hb: Vec<[Rational; 3]> = basis.iter().map(|b| mat_vec(&obj.h, b)).collect();
    let m: Vec<Vec<Rational>> = (0..d)
        .map(|i| {
            (0..d)
                .map(|j| &Rational::from(2) * &rational::dot(&basis[i], &hb[j]))
                .collect()
        })
        .collect();
    let r: Vec<Rational> = (0..d).map(|i| -&rational::dot(&basis[i], &grad0)).collect();
    let (u0, kern) = affine_solutions(&m, &r, d)?;
    let combine = |coef: &[Rational], vecs: &[[Rational; 3]]| -> [Rational; 3] {
        let mut s = [Rational::zero(), Rational::zero(), Rational::zero()];
        for (c, v) in coef.iter().zip(vecs) {
            if c.is_zero() {
                continue;
            }
            for i in 0..3 {
                s[i] = &s[i] + &(c * &v[i]);
            }
        }
        s
    };
    let du = combine(&u0, &basis);
    let p1 = [0, 1, 2].map(|i| &p0[i] + &du[i]);
    if kern.is_empty() {
        return Some(p1);
    }
    let b1: Vec<[Rational; 3]> = kern.iter().map(|k| combine(k, &basis)).collect();
    // Stage G: (B1ᵀB1) v = B1ᵀ(anchor − p1), positive definite.
    let e = d - kern.len();
    let _ = e;
    let diff = rational::sub(&obj.anchor, &p1);
    let n = b1.len();
    let m: Vec<Vec<Rational>> = (0..n)
        .map(|i| (0..n).map(|j| rational::dot(&b1[i], &b1[j])).collect())
        .collect();
    let r: Vec<Rational> = (0..n).map(|i| rational::dot(&b1[i], &diff)).collect();
    let (v, _) = affine_solutions(&m, &r, n)?;
    let dv = combine(&v, &b1);
    Some([0, 1, 2].map(|i| &p1[i] + &dv[i]))
}

fn seidel<'a>(
    cons: &[&'a BigPlane],
    eqs: &mut Vec<&'a BigPlane>,
    obj: &Objective,
) -> Option<[Rational; 3]> {
    let mut p = affine_min(eqs, obj)?;
    let mut hp = HPoint::from_rationals(&p);
    for k in 0..cons.len() {
        if cons[k].side(&hp) == Sign::Positive {
            eqs.push(cons[k]);
            let r = seidel(&cons[..k], eqs, obj);
            eqs.pop();
            p = r?;
            hp = HPoint::from_rationals(&p);
        }
    }
    Some(p)
}

/// A fixed pseudo-random order of `0..n` (Seidel's expected linear time wants a random
/// insertion order; a fixed one keeps results reproducible).
fn shuffled(n: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15 ^ n as u64;
    for i in (1..n).rev() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let j = (state % (i as u64 + 1)) as usize;
        order.swap(i, j);
    }
    order
}

/// The lexicographic minimizer of `(F, G)` over `{p : every constraint}`, or `None`
/// when the cell is empty.
///
/// When `F` is strictly convex, a floating-point run proposes the active constraints and
/// the answer is certified exactly (the point on those planes is feasible and its
/// Lagrange multipliers are non-negative: the KKT conditions, sufficient for a convex
/// program); otherwise, or when the certificate fails, exact Seidel decides.
pub(crate) fn lexmin(constraints: &[BigPlane], obj: &Objective) -> Option<[Rational; 3]> {
    let order = shuffled(constraints.len());
    if obj.definite() {
        if let Some(p) = guided(constraints, &order, obj, &obj.gradient_at_neg()) {
            return Some(p);
        }
    }
    let cons: Vec<&BigPlane> = order.iter().map(|&i| &constraints[i]).collect();
    seidel(&cons, &mut Vec::with_capacity(4), obj)
}

/// The lexicographic minimizer of `(F, G)` over the box `lo <= p <= hi` (a missing
/// bound is unbounded on that side), in closed form when `H` is diagonal; `None` when
/// `H` is not diagonal (callers then solve the constraints in general).
/// `Some(None)`: the box is empty.
///
/// Both `F` and `G` are then sums of one-variable functions, so the lexicographic
/// minimizer is found coordinate by coordinate: with `h_ii > 0` the clamped vertex of
/// the parabola, with `h_ii = 0` the bound `g_i` points to (a validated objective has
/// `g_i = 0` there, but a bounded side is used either way) or, for `g_i = 0`, the anchor
/// clamped (the tie-breaker). This is the unique answer [`lexmin`] computes for the same
/// box written as half-spaces.
pub(crate) fn lexmin_box(
    lo: [Option<&Rational>; 3],
    hi: [Option<&Rational>; 3],
    obj: &Objective,
) -> Option<Option<[Rational; 3]>> {
    let h = &obj.h;
    if !(h[0][1].is_zero()
        && h[0][2].is_zero()
        && h[1][2].is_zero()
        && h[1][0].is_zero()
        && h[2][0].is_zero()
        && h[2][1].is_zero())
    {
        return None;
    }
    let mut p = [Rational::zero(), Rational::zero(), Rational::zero()];
    for i in 0..3 {
        if let (Some(l), Some(u)) = (lo[i], hi[i]) {
            if l > u {
                return Some(None);
            }
        }
        let free = if h[i][i].sign() == Sign::Positive {
            // −g / 2h
            -&(&obj.g[i] / &(&Rational::from(2) * &h[i][i]))
        } else {
            match obj.g[i].sign() {
                Sign::Positive => match lo[i] {
                    Some(l) => l.clone(),
                    None => return None,
                },
                Sign::Negative => match hi[i] {
                    Some(u) => u.clone(),
                    None => return None,
                },
                Sign::Zero => obj.anchor[i].clone(),
            }
        };
        let mut v = free;
        if let Some(l) = lo[i] {
            if v < *l {
                v = l.clone();
            }
        }
        if let Some(u) = hi[i] {
            if v > *u {
                v = u.clone();
            }
        }
        p[i] = v;
    }
    Some(Some(p))
}

/// The minimum of `n · p` over the box `[lo, hi]` and a corner attaining it; `None`
/// when the box is empty.
pub(crate) fn min_linear_box(
    b: &apart_kernel::Aabb<Rational>,
    n: &[apart_kernel::Int; 3],
) -> Option<(Rational, [Rational; 3])> {
    if (0..3).any(|i| b.min[i] > b.max[i]) {
        return None;
    }
    let p = [0, 1, 2].map(|i| {
        if n[i] < apart_kernel::Int::ZERO {
            b.max[i].clone()
        } else {
            b.min[i].clone()
        }
    });
    let nq = n.clone().map(Rational::from_int);
    Some((rational::dot(&nq, &p), p))
}

/// Certified guided solve: the float guide's active set, the exact point on it, exact
/// feasibility, and multipliers `λ >= 0` with `Σ λ_i n_i = r(p)` (for the quadratic,
/// `r = −∇F(p)`; for a linear objective `c · p`, `r = −c`).
fn guided(
    constraints: &[BigPlane],
    order: &[usize],
    obj: &Objective,
    rhs: &dyn Fn(&[Rational; 3]) -> [Rational; 3],
) -> Option<[Rational; 3]> {
    let fc: Vec<crate::guide::FHalf> = constraints.iter().map(to_float).collect::<Option<_>>()?;
    let (_, active) = crate::guide::lexmin(&fc, order, &obj.to_float())?;
    let eqs: Vec<&BigPlane> = active.iter().map(|&i| &constraints[i]).collect();
    let p = affine_min(&eqs, obj)?;
    let hp = HPoint::from_rationals(&p);
    if constraints.iter().any(|h| h.side(&hp) == Sign::Positive) {
        return None;
    }
    let r = rhs(&p);
    if eqs.is_empty() {
        return r.iter().all(Rational::is_zero).then_some(p);
    }
    // Σ λ_i n_i = r: three equations in |S| unknowns; a unique solution with λ >= 0.
    let a: Vec<Vec<Rational>> = (0..3)
        .map(|j| {
            eqs.iter()
                .map(|h| Rational::from_int(h.n[j].clone()))
                .collect()
        })
        .collect();
    let (lambda, null) = affine_solutions(&a, &r, eqs.len())?;
    if !null.is_empty() || lambda.iter().any(|l| l.sign() == Sign::Negative) {
        return None;
    }
    Some(p)
}

/// The half-space as doubles: unit normal and offset (`None` beyond the range).
fn to_float(h: &BigPlane) -> Option<crate::guide::FHalf> {
    let a = [0, 1, 2].map(|i| int::to_f64(&h.n[i]));
    let b = int::to_f64(&h.c);
    let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if !norm.is_finite() || !b.is_finite() || norm == 0.0 {
        return None;
    }
    Some((a.map(|v| v / norm), b / norm))
}

impl Objective {
    /// True when `H` is positive definite (then the minimizer is unique without the
    /// tie-breaker).
    pub(crate) fn definite(&self) -> bool {
        let h = &self.h;
        let m2 = &(&h[0][0] * &h[1][1]) - &(&h[0][1] * &h[1][0]);
        h[0][0].sign() == Sign::Positive
            && m2.sign() == Sign::Positive
            && det3(h).sign() == Sign::Positive
    }

    /// `p -> −∇F(p) = −(2Hp + g)`.
    fn gradient_at_neg(&self) -> impl Fn(&[Rational; 3]) -> [Rational; 3] + '_ {
        move |p: &[Rational; 3]| {
            let hp = mat_vec(&self.h, p);
            [0, 1, 2].map(|i| -&(&(&Rational::from(2) * &hp[i]) + &self.g[i]))
        }
    }

    fn to_float(&self) -> crate::guide::FObjective {
        crate::guide::FObjective {
            h: self.h.clone().map(|r| r.map(|v| v.to_f64())),
            g: self.g.clone().map(|v| v.to_f64()),
            anchor: self.anchor.clone().map(|v| v.to_f64()),
        }
    }
}

/// The minimum of `n · p` over the cell and a point attaining it, given a strict lower
/// bound `lower` of `n · p` on the cell (e.g. from a box containing it); `None` when
/// the cell is empty. A float guide proposes the optimal face; an exact dual certificate
/// (`n = −Σ λ_i n_i`, `λ >= 0` over its planes) confirms it, else exact Seidel decides.
pub(crate) fn min_linear(
    constraints: &[BigPlane],
    n: &[apart_kernel::Int; 3],
    lower: &Rational,
) -> Option<(Rational, [Rational; 3])> {
    let obj = Objective::linear(n, lower);
    let nq = n.clone().map(Rational::from_int);
    let order = shuffled(constraints.len());
    let neg_n = [-&nq[0], -&nq[1], -&nq[2]];
    let p = match guided(constraints, &order, &obj, &|_| neg_n.clone()) {
        Some(p) => p,
        None => {
            let cons: Vec<&BigPlane> = order.iter().map(|&i| &constraints[i]).collect();
            seidel(&cons, &mut Vec::with_capacity(4), &obj)?
        }
    };
    Some((rational::dot(&nq, &p), p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{q, qfrac};
    use apart_kernel::{Aabb, Int};

    fn unit_box() -> Vec<BigPlane> {
        Aabb {
            min: [q(0), q(0), q(0)],
            max: [q(1), q(1), q(1)],
        }
        .halfspaces()
    }

    #[test]
    fn projection_onto_a_box() {
        let obj = Objective::distance(&[q(3), qfrac(1, 2), q(-2)]);
        let p = lexmin(&unit_box(), &obj).unwrap();
        assert_eq!(p, [q(1), qfrac(1, 2), q(0)]);
        let inside = Objective::distance(&[qfrac(1, 3), qfrac(1, 2), qfrac(2, 3)]);
        assert_eq!(lexmin(&unit_box(), &inside).unwrap(), inside.anchor);
    }

    #[test]
    fn slanted_plane_and_ties() {
        // x + y + z <= 1 inside the unit box; nearest point to (1, 1, 1) is (1/3, 1/3, 1/3).
        let mut c = unit_box();
        c.push(BigPlane::reduced([1, 1, 1].map(Int::from), Int::from(1)));
        let p = lexmin(&c, &Objective::distance(&[q(1), q(1), q(1)])).unwrap();
        assert_eq!(p, [qfrac(1, 3), qfrac(1, 3), qfrac(1, 3)]);
        // Weight only on z: every point with z minimal ties; the anchor decides.
        let obj = Objective::diagonal(
            &[q(0), q(0), q(1)],
            &[qfrac(1, 2), qfrac(1, 4), q(-3)],
            &q(0),
        );
        assert_eq!(lexmin(&c, &obj).unwrap(), [qfrac(1, 2), qfrac(1, 4), q(0)]);
        // Far anchor: the nearest point of the bottom triangle is its corner (1, 0, 0).
        let obj = Objective::diagonal(&[q(0), q(0), q(1)], &[q(5), qfrac(1, 4), q(-3)], &q(0));
        assert_eq!(lexmin(&c, &obj).unwrap(), [q(1), q(0), q(0)]);
    }

    #[test]
    fn empty_and_flat_cells() {
        let mut c = unit_box();
        c.push(BigPlane::reduced([-1, 0, 0].map(Int::from), Int::from(-2))); // x >= 2
        assert!(lexmin(&c, &Objective::distance(&[q(0), q(0), q(0)])).is_none());
        let mut f = unit_box();
        f.push(BigPlane::reduced([-1, 0, 0].map(Int::from), Int::from(-1))); // x >= 1: a face
        let p = lexmin(&f, &Objective::distance(&[q(0), qfrac(1, 2), q(7)])).unwrap();
        assert_eq!(p, [q(1), qfrac(1, 2), q(1)]);
    }

    #[test]
    fn linear_programs() {
        let mut c = unit_box();
        c.push(BigPlane::reduced([1, 1, 0].map(Int::from), Int::from(1)));
        let (v, _) = min_linear(&c, &[-1, -2, 0].map(Int::from), &q(-10)).unwrap();
        assert_eq!(v, q(-2)); // max x + 2y on the triangle is 2 at (0, 1)
    }

    /// The closed forms for boxes agree with the general solvers on the same box written
    /// as half-spaces: random boxes (some flat or empty), diagonal objectives with zero
    /// weights (ties to the anchor), single half-spaces.
    #[test]
    fn box_closed_forms_match_the_solvers() {
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = |m: i64| -> i64 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % (2 * m as u64 + 1)) as i64 - m
        };
        for _ in 0..400 {
            let lo = [0; 3].map(|_| qfrac(next(8), 2));
            let hi = [0, 1, 2].map(|i| &lo[i] + &qfrac(next(8) + 6, 3));
            let b = Aabb {
                min: lo.clone(),
                max: hi.clone(),
            };
            let w = [0; 3].map(|_| q(next(2).max(0)));
            let obj = Objective::diagonal(&w, &[0; 3].map(|_| qfrac(next(20), 3)), &q(0));
            let got = lexmin_box(
                [0, 1, 2].map(|i| Some(&lo[i])),
                [0, 1, 2].map(|i| Some(&hi[i])),
                &obj,
            )
            .unwrap();
            assert_eq!(got, lexmin(&b.halfspaces(), &obj), "{b:?} {obj:?}");
            let n = [0; 3].map(|_| Int::from(next(3)));
            let lower = &b.min_dot(&n) - &q(1);
            let fast = min_linear_box(&b, &n).map(|(v, _)| v);
            let slow = min_linear(&b.halfspaces(), &n, &lower).map(|(v, _)| v);
            assert_eq!(fast, slow);
            // One axis-aligned half-space x_i <= v or x_i >= v.
            let i = next(1).unsigned_abs() as usize;
            let (lo1, hi1) = if next(1) >= 0 {
                (
                    [None, None, None],
                    [0, 1, 2].map(|k| (k == i).then_some(&hi[i])),
                )
            } else {
                (
                    [0, 1, 2].map(|k| (k == i).then_some(&lo[i])),
                    [None, None, None],
                )
            };
            let mut nrm = [Int::ZERO, Int::ZERO, Int::ZERO];
            let h = if hi1[i].is_some() {
                nrm[i] = hi[i].denom();
                BigPlane::reduced(nrm, hi[i].numer())
            } else {
                nrm[i] = -lo[i].denom();
                BigPlane::reduced(nrm, -lo[i].numer())
            };
            if let Some(fast) = lexmin_box(lo1, hi1, &obj) {
                assert_eq!(fast, lexmin(std::slice::from_ref(&h), &obj));
            }
        }
    }

    #[test]
    fn objective_checks() {
        assert!(Objective::distance(&[q(1), q(2), q(3)]).validate().is_ok());
        let mut o = Objective::distance(&[q(0), q(0), q(0)]);
        o.h[0][0] = q(-1);
        assert_eq!(o.validate(), Err(ObjectiveError::NotConvex));
        let mut o = Objective::diagonal(&[q(1), q(1), q(0)], &[q(0), q(0), q(0)], &q(0));
        o.g[2] = q(1);
        assert_eq!(o.validate(), Err(ObjectiveError::Unbounded));
    }
}
