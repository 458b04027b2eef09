//! A floating-point run of the same Seidel algorithm as [`crate::qp`], used only as a
//! guide: it proposes the active constraints of the optimum, which the exact code then
//! certifies (exact point on those planes, exact feasibility, exact sign of the
//! Lagrange multipliers). When the certificate fails (degenerate or badly conditioned
//! input) the exact algorithm runs instead, so floating point never decides anything.

use apart_kernel::fvec::dot;

/// A constraint `a · p <= b` in doubles, scaled to a unit normal.
pub(crate) type FHalf = ([f64; 3], f64);

/// A quadratic `pᵀHp + g·p` and tie-breaker anchor, in doubles.
#[derive(Clone, Debug)]
pub(crate) struct FObjective {
    /// The matrix.
    pub(crate) h: [[f64; 3]; 3],
    /// The linear part.
    pub(crate) g: [f64; 3],
    /// The anchor of `‖p − anchor‖²`.
    pub(crate) anchor: [f64; 3],
}

const EPS: f64 = 1e-9;

/// Solutions of `a x = b` (`k` unknowns): a particular solution and a null-space basis,
/// by Gauss–Jordan with partial pivoting; `None` when clearly inconsistent.
// Row reduction reads and writes two rows at once by index.
#[allow(clippy::needless_range_loop)]
fn solve(rows: &mut [[f64; 4]], k: usize) -> Option<([f64; 3], Vec<[f64; 3]>)> {
    let n = rows.len();
    let scale = rows
        .iter()
        .flat_map(|r| r[..k].iter().map(|v| v.abs()))
        .fold(0.0f64, f64::max)
        .max(1e-300);
    let mut pivots = Vec::new();
    let mut r = 0;
    for col in 0..k {
        if r == n {
            break;
        }
        let (pr, best) = (r..n)
            .map(|i| (i, rows[i][col].abs()))
            .fold((r, -1.0), |a, b| if b.1 > a.1 { b } else { a });
        if best <= EPS * scale {
            continue;
        }
        rows.swap(r, pr);
        let inv = 1.0 / rows[r][col];
        for j in 0..=3 {
            rows[r][j] *= inv;
        }
        for i in 0..n {
            if i != r {
                let f = rows[i][col];
                if f != 0.0 {
                    for j in 0..=3 {
                        rows[i][j] -= f * rows[r][j];
                    }
                }
            }
        }
        pivots.push(col);
        r += 1;
    }
    let rhs_scale = rows
        .iter()
        .map(|r| r[3].abs())
        .fold(0.0f64, f64::max)
        .max(1.0);
    if rows[r..].iter().any(|row| row[3].abs() > 1e-7 * rhs_scale) {
        return None;
    }
    let mut x = [0.0; 3];
    for (i, &c) in pivots.iter().enumerate() {
        x[c] = rows[i][3];
    }
    let null = (0..k)
        .filter(|c| !pivots.contains(c))
        .map(|f| {
            let mut v = [0.0; 3];
            v[f] = 1.0;
            for (i, &c) in pivots.iter().enumerate() {
                v[c] = -rows[i][f];
            }
            v
        })
        .collect();
    Some((x, null))
}

fn affine_min(eqs: &[&FHalf], obj: &FObjective) -> Option<[f64; 3]> {
    let (p0, basis) = if eqs.is_empty() {
        (
            [0.0; 3],
            vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        )
    } else {
        let mut rows: Vec<[f64; 4]> = eqs.iter().map(|(a, b)| [a[0], a[1], a[2], *b]).collect();
        solve(&mut rows, 3)?
    };
    if basis.is_empty() {
        return Some(p0);
    }
    let mv = |h: &[[f64; 3]; 3], p: &[f64; 3]| [dot(h[0], *p), dot(h[1], *p), dot(h[2], *p)];
    let hp0 = mv(&obj.h, &p0);
    let grad0 = [0, 1, 2].map(|i| 2.0 * hp0[i] + obj.g[i]);
    let d = basis.len();
    let mut rows: Vec<[f64; 4]> = (0..d)
        .map(|i| {
            let mut r = [0.0; 4];
            for (j, rj) in r.iter_mut().enumerate().take(d) {
                *rj = 2.0 * dot(basis[i], mv(&obj.h, &basis[j]));
            }
            r[3] = -dot(basis[i], grad0);
            r
        })
        .collect();
    let (u0, kern) = solve(&mut rows, d)?;
    let comb = |c: &[f64; 3], vs: &[[f64; 3]]| {
        let mut s = [0.0; 3];
        for (ci, v) in c.iter().zip(vs) {
            for k in 0..3 {
                s[k] += ci * v[k];
            }
        }
        s
    };
    let du = comb(&u0, &basis);
    let p1 = [0, 1, 2].map(|i| p0[i] + du[i]);
    if kern.is_empty() {
        return Some(p1);
    }
    let b1: Vec<[f64; 3]> = kern.iter().map(|k| comb(k, &basis)).collect();
    let diff = [0, 1, 2].map(|i| obj.anchor[i] - p1[i]);
    let n = b1.len();
    let mut rows: Vec<[f64; 4]> = (0..n)
        .map(|i| {
            let mut r = [0.0; 4];
            for (j, rj) in r.iter_mut().enumerate().take(n) {
                *rj = dot(b1[i], b1[j]);
            }
            r[3] = dot(b1[i], diff);
            r
        })
        .collect();
    let (v, _) = solve(&mut rows, n)?;
    let dv = comb(&v, &b1);
    Some([0, 1, 2].map(|i| p1[i] + dv[i]))
}

fn violates(h: &FHalf, p: &[f64; 3]) -> bool {
    let s = dot(h.0, *p) - h.1;
    s > 1e-9 * (1.0 + h.1.abs() + p.iter().map(|v| v.abs()).fold(0.0, f64::max))
}

fn seidel<'a>(
    cons: &[(usize, &'a FHalf)],
    eqs: &mut Vec<(usize, &'a FHalf)>,
    obj: &FObjective,
    depth: usize,
) -> Option<([f64; 3], Vec<usize>)> {
    let hs: Vec<&FHalf> = eqs.iter().map(|e| e.1).collect();
    let mut p = affine_min(&hs, obj)?;
    let mut active: Vec<usize> = eqs.iter().map(|e| e.0).collect();
    for k in 0..cons.len() {
        if violates(cons[k].1, &p) {
            if depth >= 3 {
                return None;
            }
            eqs.push(cons[k]);
            let r = seidel(&cons[..k], eqs, obj, depth + 1);
            eqs.pop();
            let (q, a) = r?;
            p = q;
            active = a;
        }
    }
    Some((p, active))
}

/// The (approximate) lexicographic minimizer over the constraints, in the given order,
/// with the indices of the constraints holding with equality there.
pub(crate) fn lexmin(
    constraints: &[FHalf],
    order: &[usize],
    obj: &FObjective,
) -> Option<([f64; 3], Vec<usize>)> {
    let cons: Vec<(usize, &FHalf)> = order.iter().map(|&i| (i, &constraints[i])).collect();
    seidel(&cons, &mut Vec::with_capacity(4), obj, 0)
}
