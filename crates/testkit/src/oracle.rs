//! The brute-force blocking oracle as plain exact arithmetic: piece `a` moving along `d`
//! hits piece `b` iff for some `t > 0` the translate `a + t d` meets `b` in an interior
//! point. Decided from the facet inequalities of the two pieces alone, without any
//! Minkowski sum, by a small exact linear program.
//!
//! The arithmetic is generic: callers pass their exact rationals (any ordered field with
//! exact `+ − × ÷` on references), so the oracle shares no code with what it checks.

use std::ops::{Add, Div, Mul, Sub};

/// The facet inequalities `n · x <= c` of one convex piece, as `(n, c)`.
pub type Facets<T> = [([T; 3], T)];

/// True when some `x` in the interior of `a` and some `t > 0` put `x + t d` in the
/// interior of `b` (both given by their facet inequalities in the same units): the
/// linear program over `(x, t, s)`
///
/// ```text
/// maximize s  subject to  n_a · x + s <= c_a          (every facet of a)
///                         n_b · x + (n_b · d) t + s <= c_b   (every facet of b)
///                         s − t <= 0,  s <= 1
/// ```
///
/// has optimum `s > 0`. Solved exactly by the simplex method with Bland's rule on a
/// rational tableau: free variables split into two non-negative ones, `s = s0 + σ` with
/// `s0 <= 0` chosen so that the origin is feasible, and the search stops as soon as
/// `s > 0` is reached.
pub fn sweep_meets_interior<T>(a: &Facets<T>, b: &Facets<T>, d: &[T; 3]) -> bool
where
    T: Clone + Ord + From<i64>,
    for<'x> &'x T: Add<&'x T, Output = T>
        + Sub<&'x T, Output = T>
        + Mul<&'x T, Output = T>
        + Div<&'x T, Output = T>,
{
    let z = T::from(0);
    let one = T::from(1);
    let dot = |n: &[T; 3]| &(&(&n[0] * &d[0]) + &(&n[1] * &d[1])) + &(&n[2] * &d[2]);
    // Rows: coefficients of (x, y, z, t) and the right-hand side; every row has s with
    // coefficient 1.
    let mut rows: Vec<([T; 4], T)> = Vec::new();
    for (n, c) in a {
        rows.push((
            [n[0].clone(), n[1].clone(), n[2].clone(), z.clone()],
            c.clone(),
        ));
    }
    for (n, c) in b {
        rows.push((
            [n[0].clone(), n[1].clone(), n[2].clone(), dot(n)],
            c.clone(),
        ));
    }
    rows.push(([z.clone(), z.clone(), z.clone(), T::from(-1)], z.clone()));
    rows.push(([z.clone(), z.clone(), z.clone(), z.clone()], one.clone()));
    let s0 = rows
        .iter()
        .map(|r| r.1.clone())
        .min()
        .unwrap()
        .min(z.clone());
    // Columns: x+, y+, z+, t+, x-, y-, z-, t-, σ, one slack per row, right-hand side.
    let m = rows.len();
    let (nv, rhs) = (9 + m, 9 + m);
    let mut tab: Vec<Vec<T>> = rows
        .iter()
        .enumerate()
        .map(|(i, (c, b))| {
            let mut row = vec![z.clone(); nv + 1];
            for k in 0..4 {
                row[k] = c[k].clone();
                row[4 + k] = &z - &c[k];
            }
            row[8] = one.clone();
            row[9 + i] = one.clone();
            row[rhs] = b - &s0;
            row
        })
        .collect();
    let mut basis: Vec<usize> = (9..9 + m).collect();
    // Reduced costs of maximizing σ, and the current value of σ.
    let mut cost = vec![z.clone(); nv];
    cost[8] = one.clone();
    let mut sigma = z.clone();
    let goal = &z - &s0; // s > 0 iff σ > −s0
    loop {
        if sigma > goal {
            return true;
        }
        let Some(col) = (0..nv).find(|&j| cost[j] > z) else {
            return false; // optimal with s <= 0
        };
        let mut best: Option<(T, usize, usize)> = None;
        for (i, row) in tab.iter().enumerate() {
            if row[col] > z {
                let ratio = &row[rhs] / &row[col];
                let better = match &best {
                    None => true,
                    Some((r, _, bi)) => ratio < *r || (ratio == *r && basis[i] < *bi),
                };
                if better {
                    best = Some((ratio, i, basis[i]));
                }
            }
        }
        let (ratio, r, _) = best.expect("σ is bounded by s <= 1");
        let inv = &one / &tab[r][col];
        for v in tab[r].iter_mut() {
            *v = &*v * &inv;
        }
        let pivot = tab[r].clone();
        for (i, row) in tab.iter_mut().enumerate() {
            if i != r && row[col] != z {
                let f = row[col].clone();
                for (v, p) in row.iter_mut().zip(&pivot) {
                    if *p != z {
                        *v = &*v - &(&f * p);
                    }
                }
            }
        }
        let f = cost[col].clone();
        sigma = &sigma + &(&f * &ratio);
        for (v, p) in cost.iter_mut().zip(&pivot) {
            if *p != z {
                *v = &*v - &(&f * p);
            }
        }
        basis[r] = col;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cmp::Ordering;

    /// A fraction of small integers, reduced, positive denominator: enough exactness for
    /// the unit boxes below.
    #[derive(Clone, Debug)]
    struct Q(i128, i128);

    fn gcd(a: i128, b: i128) -> i128 {
        if b == 0 {
            a.abs()
        } else {
            gcd(b, a % b)
        }
    }

    impl Q {
        fn new(n: i128, d: i128) -> Q {
            let g = gcd(n, d).max(1) * d.signum();
            Q(n / g, d / g)
        }
    }

    impl From<i64> for Q {
        fn from(v: i64) -> Q {
            Q(v.into(), 1)
        }
    }

    impl PartialEq for Q {
        fn eq(&self, o: &Q) -> bool {
            self.cmp(o) == Ordering::Equal
        }
    }

    impl Eq for Q {}

    impl PartialOrd for Q {
        fn partial_cmp(&self, o: &Q) -> Option<Ordering> {
            Some(self.cmp(o))
        }
    }

    impl Ord for Q {
        fn cmp(&self, o: &Q) -> Ordering {
            (self.0 * o.1).cmp(&(o.0 * self.1))
        }
    }

    impl Add for &Q {
        type Output = Q;
        fn add(self, o: &Q) -> Q {
            Q::new(self.0 * o.1 + o.0 * self.1, self.1 * o.1)
        }
    }

    impl Sub for &Q {
        type Output = Q;
        fn sub(self, o: &Q) -> Q {
            Q::new(self.0 * o.1 - o.0 * self.1, self.1 * o.1)
        }
    }

    impl Mul for &Q {
        type Output = Q;
        fn mul(self, o: &Q) -> Q {
            Q::new(self.0 * o.0, self.1 * o.1)
        }
    }

    impl Div for &Q {
        type Output = Q;
        fn div(self, o: &Q) -> Q {
            Q::new(self.0 * o.1, self.1 * o.0)
        }
    }

    /// The facets of the box `[lo, hi]`.
    fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Vec<([Q; 3], Q)> {
        let mut out = Vec::new();
        for k in 0..3 {
            let mut n = [0i64; 3];
            n[k] = 1;
            out.push((n.map(Q::from), Q::from(hi[k])));
            n[k] = -1;
            out.push((n.map(Q::from), Q::from(-lo[k])));
        }
        out
    }

    #[test]
    fn a_cube_on_a_cube_is_blocked_downwards_only() {
        let top = cuboid([0, 0, 1], [1, 1, 2]);
        let bottom = cuboid([0, 0, 0], [1, 1, 1]);
        let dir = |d: [i64; 3]| d.map(Q::from);
        assert!(sweep_meets_interior(&top, &bottom, &dir([0, 0, -1])));
        assert!(sweep_meets_interior(&top, &bottom, &dir([1, 0, -1])));
        assert!(!sweep_meets_interior(&top, &bottom, &dir([0, 0, 1])));
        assert!(!sweep_meets_interior(&top, &bottom, &dir([1, 0, 0])));
        assert!(!sweep_meets_interior(&top, &bottom, &dir([5, 3, 0])));
    }

    #[test]
    fn a_far_box_is_hit_only_along_directions_towards_it() {
        let a = cuboid([0, 0, 0], [1, 1, 1]);
        let b = cuboid([5, 0, 0], [6, 1, 1]);
        let dir = |d: [i64; 3]| d.map(Q::from);
        assert!(sweep_meets_interior(&a, &b, &dir([1, 0, 0])));
        assert!(sweep_meets_interior(&a, &b, &dir([10, 1, 0])));
        assert!(!sweep_meets_interior(&a, &b, &dir([1, 1, 0])));
        assert!(!sweep_meets_interior(&a, &b, &dir([-1, 0, 0])));
    }
}
