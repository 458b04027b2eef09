//! The brute-force oracle (ALGORITHMS.md §6): part `i` moving along `d` hits part `j`
//! iff for some piece pair the open ray `{k d : k > 0}` meets the interior of
//! `M = b ⊕ (−a)`, i.e. some `k > 0` satisfies every facet inequality of `M` strictly.
//! `M` is built independently of the Minkowski code (boxes: the box of differences;
//! other pieces: the hull of all vertex differences).

use apart_kernel::{Int, Rational, Vec3};
use apart_pieces::Polytope;
use apart_plan::{Dbg, PartPieces};

fn box_bounds(p: &Polytope) -> Option<([Int; 3], [Int; 3])> {
    if p.vertices().len() != 8 || p.facets().len() != 6 {
        return None;
    }
    let axis = |n: &Vec3| (0..3).filter(|&k| n.get(k) != Int::ZERO).count() == 1;
    if !p.facets().iter().all(|f| axis(&f.normal)) {
        return None;
    }
    let lo = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).min().unwrap());
    let hi = [0, 1, 2].map(|k| p.vertices().iter().map(|v| v.get(k)).max().unwrap());
    Some((lo, hi))
}

/// `b ⊕ (−a)` as facet inequalities `n · x <= c`.
fn difference_facets(b: &Polytope, a: &Polytope) -> Facets {
    if let (Some((alo, ahi)), Some((blo, bhi))) = (box_bounds(a), box_bounds(b)) {
        let mut out = Vec::new();
        for k in 0..3 {
            let mut e = [0i64; 3];
            e[k] = 1;
            out.push((Vec3::from_i64(e), &bhi[k] - &alo[k]));
            e[k] = -1;
            out.push((Vec3::from_i64(e), -(&blo[k] - &ahi[k])));
        }
        return out;
    }
    let mut s = Vec::new();
    for y in b.vertices() {
        for x in a.vertices() {
            s.push(y.sub(x));
        }
    }
    let m = Polytope::hull_of_points(&s).unwrap();
    m.facets()
        .iter()
        .map(|f| (f.normal.clone(), f.offset.clone()))
        .collect()
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

/// Facet inequalities `n · x <= c` of one convex sum.
type Facets = Vec<(Vec3, Int)>;

pub struct Oracle {
    n: usize,
    /// facets[i][j]: for each piece pair, the facets of b ⊕ (−a), a in part i, b in j.
    facets: Vec<Vec<Vec<Facets>>>,
}

impl Oracle {
    pub fn new(parts: &[PartPieces]) -> Oracle {
        let n = parts.len();
        let facets = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        if i == j {
                            return Vec::new();
                        }
                        let mut v = Vec::new();
                        for a in &parts[i].pieces {
                            for b in &parts[j].pieces {
                                v.push(difference_facets(b, a));
                            }
                        }
                        v
                    })
                    .collect()
            })
            .collect();
        Oracle { n, facets }
    }

    pub fn dbg(&self, d: &Vec3) -> Dbg {
        let mut arcs = Vec::new();
        for i in 0..self.n {
            for j in 0..self.n {
                if i != j && self.facets[i][j].iter().any(|f| ray_meets_interior(f, d)) {
                    arcs.push((i, j));
                }
            }
        }
        Dbg::new(self.n, arcs)
    }
}

impl Oracle {
    /// True when `moving` can translate along `d` without hitting any part of `rest`.
    pub fn free(&self, moving: &[usize], rest: &[usize], d: &Vec3) -> bool {
        moving.iter().all(|&i| {
            rest.iter()
                .all(|&j| !self.facets[i][j].iter().any(|f| ray_meets_interior(f, d)))
        })
    }
}
