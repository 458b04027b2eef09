//! The brute-force oracle (ARCHITECTURE.md, invariants): piece `a` of part `i` moving along `d`
//! hits piece `b` of part `j` iff for some `t > 0` the translate `a + t d` meets `b` in
//! an interior point, i.e. the open ray `{t d : t > 0}` meets the interior of
//! `b ⊕ (−a)`. Decided from the facet inequalities of the two pieces alone, without any
//! Minkowski sum: first the box of differences (which contains the sum, and is the sum
//! when both pieces are axis-aligned boxes), then a small exact linear program
//! (`sweep_meets_interior`).

use apart_kernel::{Int, Rational, Vec3};
use apart_pieces::Polytope;
use apart_plan::{Dbg, Part};

fn bounds(p: &Polytope) -> ([Int; 3], [Int; 3]) {
    let lo = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).min().unwrap());
    let hi = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).max().unwrap());
    (lo, hi)
}

fn is_box(p: &Polytope) -> bool {
    let axis = |n: &Vec3| (0..3).filter(|&k| n.get(k) != Int::ZERO).count() == 1;
    p.vertices().len() == 8 && p.facets().len() == 6 && p.facets().iter().all(|f| axis(&f.normal))
}

/// The box of differences `[lo_b − hi_a, hi_b − lo_a]` as facet inequalities: it contains
/// `b ⊕ (−a)` and equals it when both pieces are axis-aligned boxes.
fn box_facets(a: &Polytope, b: &Polytope) -> Facets {
    let ((alo, ahi), (blo, bhi)) = (bounds(a), bounds(b));
    let mut out = Vec::new();
    for k in 0..3 {
        let mut e = [0i64; 3];
        e[k] = 1;
        out.push((Vec3::from_i64(e), &bhi[k] - &alo[k]));
        e[k] = -1;
        out.push((Vec3::from_i64(e), -(&blo[k] - &ahi[k])));
    }
    out
}

fn recip(r: &Rational) -> Rational {
    Rational::new(r.denom().clone(), r.numer().clone())
}

/// True when some `x` in the interior of `a` and some `t > 0` put `x + t d` in the
/// interior of `b`: the linear program over `(x, t, s)`
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
pub fn sweep_meets_interior(a: &Polytope, b: &Polytope, d: &Vec3) -> bool {
    // Facet offsets refer to the stored integers (den times the coordinates): compare
    // the two pieces at a common denominator (then t absorbs the factor).
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return sweep_meets_interior(&a, &b, d);
    }
    // Rows: coefficients of (x, y, z, t) and the right-hand side; every row has s with
    // coefficient 1.
    let mut rows: Vec<([Int; 4], Int)> = Vec::new();
    for f in a.facets() {
        let n = &f.normal;
        rows.push(([n.get(0), n.get(1), n.get(2), Int::ZERO], f.offset.clone()));
    }
    for f in b.facets() {
        let n = &f.normal;
        rows.push(([n.get(0), n.get(1), n.get(2), n.dot(d)], f.offset.clone()));
    }
    rows.push(([Int::ZERO, Int::ZERO, Int::ZERO, Int::from(-1)], Int::ZERO));
    rows.push(([Int::ZERO, Int::ZERO, Int::ZERO, Int::ZERO], Int::from(1)));
    let s0 = rows
        .iter()
        .map(|r| r.1.clone())
        .min()
        .unwrap()
        .min(Int::ZERO);
    // Columns: x+, y+, z+, t+, x-, y-, z-, t-, σ, one slack per row, right-hand side.
    let m = rows.len();
    let (nv, rhs) = (9 + m, 9 + m);
    let z = Rational::zero();
    let mut tab: Vec<Vec<Rational>> = rows
        .iter()
        .enumerate()
        .map(|(i, (c, b))| {
            let mut row = vec![z.clone(); nv + 1];
            for k in 0..4 {
                row[k] = Rational::from_int(c[k].clone());
                row[4 + k] = Rational::from_int(-c[k].clone());
            }
            row[8] = Rational::from_int(1);
            row[9 + i] = Rational::from_int(1);
            row[rhs] = Rational::from_int(b - &s0);
            row
        })
        .collect();
    let mut basis: Vec<usize> = (9..9 + m).collect();
    // Reduced costs of maximizing σ, and the current value of σ.
    let mut cost = vec![z.clone(); nv];
    cost[8] = Rational::from_int(1);
    let mut sigma = z.clone();
    let goal = Rational::from_int(-s0); // s > 0 iff σ > −s0
    loop {
        if sigma > goal {
            return true;
        }
        let Some(col) = (0..nv).find(|&j| cost[j] > z) else {
            return false; // optimal with s <= 0
        };
        let mut best: Option<(Rational, usize, usize)> = None;
        for (i, row) in tab.iter().enumerate() {
            if row[col] > z {
                let ratio = &row[rhs] * &recip(&row[col]);
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
        let inv = recip(&tab[r][col]);
        for v in tab[r].iter_mut() {
            *v = &*v * &inv;
        }
        let pivot = tab[r].clone();
        for (i, row) in tab.iter_mut().enumerate() {
            if i != r && !row[col].is_zero() {
                let f = row[col].clone();
                for (v, p) in row.iter_mut().zip(&pivot) {
                    if !p.is_zero() {
                        *v = &*v - &(&f * p);
                    }
                }
            }
        }
        let f = cost[col].clone();
        sigma = &sigma + &(&f * &ratio);
        for (v, p) in cost.iter_mut().zip(&pivot) {
            if !p.is_zero() {
                *v = &*v - &(&f * p);
            }
        }
        basis[r] = col;
    }
}

pub fn ray_meets_interior(facets: &[(Vec3, Int)], d: &Vec3) -> bool {
    let mut lo = Rational::zero();
    let mut hi: Option<Rational> = None;
    for (n, c) in facets {
        let nd = n.dot(d);
        if nd == Int::ZERO {
            if *c <= Int::ZERO {
                return false;
            }
        } else if nd > Int::ZERO {
            let b = Rational::new(c.clone(), nd);
            if hi.as_ref().is_none_or(|h| b < *h) {
                hi = Some(b);
            }
        } else {
            let b = Rational::new(c.clone(), nd);
            if b > lo {
                lo = b;
            }
        }
    }
    hi.is_none_or(|h| lo < h)
}

/// Facet inequalities `n · x <= c` of one convex set.
type Facets = Vec<(Vec3, Int)>;

/// One piece pair (a moving, b fixed), both at their common denominator (the test is
/// invariant under that positive scale), with the box of differences.
struct PiecePair {
    a: Polytope,
    b: Polytope,
    boxes: bool,
    bbox: Facets,
}

impl PiecePair {
    fn new(a: &Polytope, b: &Polytope) -> PiecePair {
        let (a, b) = Polytope::common(a, b);
        let bbox = box_facets(&a, &b);
        PiecePair {
            boxes: is_box(&a) && is_box(&b),
            a,
            b,
            bbox,
        }
    }

    fn blocks(&self, d: &Vec3) -> bool {
        if !ray_meets_interior(&self.bbox, d) {
            return false;
        }
        self.boxes || sweep_meets_interior(&self.a, &self.b, d)
    }
}

pub struct Oracle {
    n: usize,
    /// pairs[i][j]: every piece pair, a in part i, b in part j.
    pairs: Vec<Vec<Vec<PiecePair>>>,
}

impl Oracle {
    pub fn new(parts: &[Part]) -> Oracle {
        let n = parts.len();
        let pairs = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        if i == j {
                            return Vec::new();
                        }
                        let mut v = Vec::new();
                        for a in &parts[i].pieces {
                            for b in &parts[j].pieces {
                                v.push(PiecePair::new(a, b));
                            }
                        }
                        v
                    })
                    .collect()
            })
            .collect();
        Oracle { n, pairs }
    }

    fn blocks(&self, i: usize, j: usize, d: &Vec3) -> bool {
        self.pairs[i][j].iter().any(|p| p.blocks(d))
    }

    pub fn dbg(&self, d: &Vec3) -> Dbg {
        let mut arcs = Vec::new();
        for i in 0..self.n {
            for j in 0..self.n {
                if i != j && self.blocks(i, j, d) {
                    arcs.push((i, j));
                }
            }
        }
        Dbg::new(self.n, arcs)
    }

    /// True when `moving` can translate along `d` without hitting any part of `rest`.
    pub fn free(&self, moving: &[usize], rest: &[usize], d: &Vec3) -> bool {
        moving
            .iter()
            .all(|&i| rest.iter().all(|&j| !self.blocks(i, j, d)))
    }
}
