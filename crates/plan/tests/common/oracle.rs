//! The brute-force oracle (ARCHITECTURE.md, invariants): piece `a` of part `i` moving along `d`
//! hits piece `b` of part `j` iff for some `t > 0` the translate `a + t d` meets `b` in
//! an interior point, i.e. the open ray `{t d : t > 0}` meets the interior of
//! `b ⊕ (−a)`. Decided from the facet inequalities of the two pieces alone, without any
//! Minkowski sum: first the box of differences (which contains the sum, and is the sum
//! when both pieces are axis-aligned boxes), then the small exact linear program of
//! `apart_testkit::oracle` (`sweep_meets_interior`).

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

/// The facet inequalities of a piece as rationals.
fn rows(p: &Polytope) -> Vec<([Rational; 3], Rational)> {
    let normal = |f: &apart_pieces::Facet| [0, 1, 2].map(|k| Rational::from_int(f.normal.get(k)));
    p.facets()
        .iter()
        .map(|f| (normal(f), Rational::from_int(f.offset.clone())))
        .collect()
}

/// True when some `x` in the interior of `a` and some `t > 0` put `x + t d` in the
/// interior of `b`: `apart_testkit::oracle::sweep_meets_interior` on the two pieces'
/// facets, compared at a common denominator (then `t` absorbs the factor).
pub fn sweep_meets_interior(a: &Polytope, b: &Polytope, d: &Vec3) -> bool {
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return sweep_meets_interior(&a, &b, d);
    }
    let d = [0, 1, 2].map(|k| Rational::from_int(d.get(k)));
    apart_testkit::oracle::sweep_meets_interior(&rows(a), &rows(b), &d)
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
