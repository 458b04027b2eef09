//! Exact interference of two convex polytopes: do their interiors meet, and where.

use crate::polytope::{Containment, Polytope, Shadow};
use apart_kernel::int::{self, Int};
use apart_kernel::{Rational, Sign, Vec3};

/// True when some plane weakly separates `a` and `b` (their interiors are disjoint).
///
/// Separating-axis test over the exact candidate normals of two convex polytopes: the
/// facet normals of both and the cross products of their edge directions. Touching
/// polytopes (shared faces, edges, points) are separated.
pub fn interiors_disjoint(a: &Polytope, b: &Polytope) -> bool {
    separating_normal(a, b).is_some()
}

/// A normal `n` with `max_a n·x <= min_b n·y`, if any (the plane separates with `a` below).
///
/// The candidate normals are tried behind a floating-point filter: an axis along which
/// the shadows overlap by more than a proven bound of the rounding error cannot
/// separate and is skipped, facet normals are tried in the order of how far the other
/// polytope's centre lies beyond the facet, and the exact support values are taken over
/// only the vertices within the error bound of the floating-point extreme. Every
/// decision is exact; the filter only prunes.
pub fn separating_normal(a: &Polytope, b: &Polytope) -> Option<Vec3> {
    filtered_separating_normal(a, b).unwrap_or_else(|| exact_separating_normal(a, b))
}

/// [`separating_normal`] without a filter: every candidate axis, exact supports.
fn exact_separating_normal(a: &Polytope, b: &Polytope) -> Option<Vec3> {
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return exact_separating_normal(&a, &b);
    }
    let separates = |n: &Vec3| -> bool {
        let (ha, _) = a.support(n);
        let (hb, _) = b.support(&n.neg());
        // max_a n·x <= min_b n·y  <=>  ha + hb' <= 0 with hb' = max_b (-n)·y.
        ha + hb <= Int::ZERO
    };
    for f in a.facets() {
        if separates(&f.normal) {
            return Some(f.normal.clone());
        }
    }
    for f in b.facets() {
        let n = f.normal.neg();
        if separates(&n) {
            return Some(n);
        }
    }
    for da in a.edge_directions() {
        for db in b.edge_directions() {
            let n = da.cross(db);
            if n.is_zero() {
                continue;
            }
            let n = n.primitive();
            if separates(&n) {
                return Some(n);
            }
            let m = n.neg();
            if separates(&m) {
                return Some(m);
            }
        }
    }
    None
}

/// The unit vector along `n` in floating point (each component within 2^-49), `None` for
/// the zero vector.
fn unit(n: &Vec3) -> Option<[f64; 3]> {
    let u = n.unit_f64();
    (u != [0.0; 3] && u.iter().all(|c| c.is_finite())).then_some(u)
}

fn dot3(p: &[f64; 3], u: &[f64; 3]) -> f64 {
    p[0] * u[0] + p[1] * u[1] + p[2] * u[2]
}

fn neg3(u: &[f64; 3]) -> [f64; 3] {
    u.map(|c| -c)
}

/// The smallest and largest of `u · p` over the shadow's points.
fn float_range(s: &Shadow, u: &[f64; 3]) -> (f64, f64) {
    s.points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let t = dot3(p, u);
            (lo.min(t), hi.max(t))
        })
}

/// The exact `max n · v` over the stored vertices of `p` whose floating-point value
/// `u · v` is at least `floor` (which must keep every maximiser).
fn support_among(p: &Polytope, s: &Shadow, n: &Vec3, u: &[f64; 3], floor: f64) -> Int {
    let mut best: Option<Int> = None;
    for (v, q) in p.vertices().iter().zip(&s.points) {
        if dot3(q, u) < floor {
            continue;
        }
        let d = n.dot(v);
        if best.as_ref().is_none_or(|b| d > *b) {
            best = Some(d);
        }
    }
    best.expect("the floating-point maximum is among the candidates")
}

/// Two polytopes with their shadows, for exact comparisons along axes behind a
/// floating-point filter.
///
/// Every float dot product is within `err` ([`Shadow::error`] of the larger) of the
/// exact one. The filter only prunes: an axis along which the float ranges overlap by more
/// than `2 err` cannot separate, and a vertex whose float value falls short of the float
/// extreme by more than `2 err` is not extreme; every answer is exact.
struct FilteredPair<'p> {
    a: &'p Polytope,
    b: &'p Polytope,
    sa: &'p Shadow,
    sb: &'p Shadow,
    err: f64,
}

impl<'p> FilteredPair<'p> {
    fn new(a: &'p Polytope, b: &'p Polytope) -> Option<FilteredPair<'p>> {
        let (sa, sb) = (a.shadow()?, b.shadow()?);
        Some(FilteredPair {
            a,
            b,
            sa,
            sb,
            err: sa.error().max(sb.error()),
        })
    }

    /// The exact `min_b n·y` as `-hb` (stored integers of `b`), given `blo`, the float
    /// minimum along `u`.
    fn min_b(&self, n: &Vec3, u: &[f64; 3], blo: f64) -> Int {
        -support_among(self.b, self.sb, &n.neg(), &neg3(u), -blo - 2.0 * self.err)
    }

    /// Whether `a` lies weakly below `b` along `n` (`max_a n·x <= min_b n·y`), and
    /// whether strictly; `None` when not.
    fn below(&self, n: &Vec3, u: &[f64; 3]) -> Option<bool> {
        let ((_, ahi), (blo, _)) = (float_range(self.sa, u), float_range(self.sb, u));
        self.below_given(n, u, ahi, blo)
    }

    fn below_given(&self, n: &Vec3, u: &[f64; 3], ahi: f64, blo: f64) -> Option<bool> {
        if ahi - blo > 2.0 * self.err {
            return None;
        }
        let ha = support_among(self.a, self.sa, n, u, ahi - 2.0 * self.err);
        let mb = self.min_b(n, u, blo);
        compare(&ha, self.a.den(), &mb, self.b.den())
    }

    /// [`Self::below`] along the outward normal of facet `f` of `a` (whose support
    /// value is its offset).
    fn below_facet_of_a(&self, i: usize, u: &[f64; 3]) -> Option<bool> {
        let (f, c) = (&self.a.facets()[i], self.sa.facet_levels[i]);
        let (blo, _) = float_range(self.sb, u);
        if c - blo > 2.0 * self.err {
            return None;
        }
        let mb = self.min_b(&f.normal, u, blo);
        compare(&f.offset, self.a.den(), &mb, self.b.den())
    }

    /// [`Self::below`] along the inward normal of facet `f` of `b`: `min_a n·x` against
    /// `f`'s offset.
    fn below_facet_of_b(&self, i: usize, u: &[f64; 3]) -> Option<bool> {
        let (f, c) = (&self.b.facets()[i], self.sb.facet_levels[i]);
        let (alo, _) = float_range(self.sa, u);
        if c - alo > 2.0 * self.err {
            return None;
        }
        let ma = -support_among(
            self.a,
            self.sa,
            &f.normal.neg(),
            &neg3(u),
            -alo - 2.0 * self.err,
        );
        compare(&f.offset, self.b.den(), &ma, self.a.den())
    }

    /// Facet axes worth testing, most promising first: a facet of one can only be a
    /// separating plane when the mean of the other's vertices (a point of it) lies
    /// beyond it. Each entry: the score, whether the facet is `b`'s, its index, and its
    /// float unit normal.
    fn facet_candidates(&self) -> Vec<(f64, bool, usize, [f64; 3])> {
        let mut out = Vec::new();
        for (sp, so, of_b) in [(self.sa, self.sb, false), (self.sb, self.sa, true)] {
            // The mean carries the rounding of a sum of `len` terms: prune generously.
            let slack =
                sp.magnitude.max(so.magnitude) * (so.points.len() as f64 + 64.0) * 2f64.powi(-44);
            for (i, (u, level)) in sp.facet_units.iter().zip(&sp.facet_levels).enumerate() {
                let (u, score) = (*u, dot3(&so.mean, u) - level);
                if score >= -slack {
                    out.push((score, of_b, i, u));
                }
            }
        }
        out.sort_by(|x, y| y.0.total_cmp(&x.0));
        out
    }

    /// [`Self::below`] for a candidate of [`Self::facet_candidates`], with the axis
    /// oriented from `a` to `b`.
    fn below_candidate(&self, of_b: bool, i: usize, u: &[f64; 3]) -> Option<(Vec3, bool)> {
        if of_b {
            self.below_facet_of_b(i, u)
                .map(|s| (self.b.facets()[i].normal.neg(), s))
        } else {
            self.below_facet_of_a(i, u)
                .map(|s| (self.a.facets()[i].normal.clone(), s))
        }
    }
}

/// `x / dx` against `y / dy` (positive denominators): `Some(strict)` when at most.
fn compare(x: &Int, dx: &Int, y: &Int, dy: &Int) -> Option<bool> {
    match int::cmp_fractions(x, dx, y, dy) {
        std::cmp::Ordering::Greater => None,
        o => Some(o == std::cmp::Ordering::Less),
    }
}

/// Every facet normal of `a`, and negated facet normal of `b`, along which `a` lies
/// weakly below `b` (`max_a n·x <= min_b n·y`), with whether strictly: the facet
/// separating axes of a pair, exact, behind the floating-point filter.
pub fn facet_axes(a: &Polytope, b: &Polytope) -> Vec<(Vec3, bool)> {
    let Some(fp) = FilteredPair::new(a, b) else {
        return exact_facet_axes(a, b);
    };
    let mut out: Vec<(usize, bool, (Vec3, bool))> = fp
        .facet_candidates()
        .into_iter()
        .filter_map(|(_, of_b, i, u)| Some((i, of_b, fp.below_candidate(of_b, i, &u)?)))
        .collect();
    // The order of the facets, a's first, as the unfiltered version gives.
    out.sort_by_key(|&(i, of_b, _)| (of_b, i));
    out.into_iter().map(|x| x.2).collect()
}

fn exact_facet_axes(a: &Polytope, b: &Polytope) -> Vec<(Vec3, bool)> {
    let mut out = Vec::new();
    for f in a.facets() {
        let (hb, _) = b.support(&f.normal.neg());
        if let Some(s) = compare(&f.offset, a.den(), &-hb, b.den()) {
            out.push((f.normal.clone(), s));
        }
    }
    for f in b.facets() {
        let (ha, _) = a.support(&f.normal.neg());
        if let Some(s) = compare(&f.offset, b.den(), &-ha, a.den()) {
            out.push((f.normal.neg(), s));
        }
    }
    out
}

/// Whether `a` lies weakly below `b` along `n` (`max_a n·x <= min_b n·y`, true
/// coordinates), and whether strictly; `None` when not. Exact, behind the filter.
pub fn below_along(a: &Polytope, b: &Polytope, n: &Vec3) -> Option<bool> {
    match (FilteredPair::new(a, b), unit(n)) {
        (Some(fp), Some(u)) => fp.below(n, &u),
        _ => {
            let (ha, _) = a.support(n);
            let (hb, _) = b.support(&n.neg());
            compare(&ha, a.den(), &-hb, b.den())
        }
    }
}

fn filtered_separating_normal(a: &Polytope, b: &Polytope) -> Option<Option<Vec3>> {
    let fp = FilteredPair::new(a, b)?;
    for (_, of_b, i, u) in fp.facet_candidates() {
        if let Some((n, _)) = fp.below_candidate(of_b, i, &u) {
            return Some(Some(n));
        }
    }
    for da in a.edge_directions() {
        for db in b.edge_directions() {
            let n = da.cross(db);
            if n.is_zero() {
                continue;
            }
            let Some(u) = unit(&n) else {
                // No float axis: decide this one exactly.
                for m in [n.clone(), n.neg()] {
                    if below_along(a, b, &m).is_some() {
                        return Some(Some(m.primitive()));
                    }
                }
                continue;
            };
            let ((alo, ahi), (blo, bhi)) = (float_range(fp.sa, &u), float_range(fp.sb, &u));
            if fp.below_given(&n, &u, ahi, blo).is_some() {
                return Some(Some(n.primitive()));
            }
            let (m, mu) = (n.neg(), neg3(&u));
            if fp.below_given(&m, &mu, -alo, -bhi).is_some() {
                return Some(Some(m.primitive()));
            }
        }
    }
    Some(None)
}

/// When the interiors of `a` and `b` meet, a point in both interiors (exact rational
/// coordinates); `None` when they are disjoint or only touch.
///
/// The witness is the average of a superset of the vertices of `a ∩ b` (vertices of one
/// inside the other, and crossings of edges of one with facets of the other): a convex
/// combination giving every vertex of the full-dimensional intersection positive weight,
/// hence an interior point of it.
pub fn interior_witness(a: &Polytope, b: &Polytope) -> Option<[Rational; 3]> {
    if interiors_disjoint(a, b) {
        return None;
    }
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return interior_witness(&a, &b);
    }
    let pts = contact_points(a, b);
    debug_assert!(!pts.is_empty());
    // Average of x_i / w_i.
    let mut sum = [Rational::zero(), Rational::zero(), Rational::zero()];
    for (x, w) in &pts {
        for (k, s) in sum.iter_mut().enumerate() {
            *s = &*s + &Rational::new(x.get(k), w.clone());
        }
    }
    // The stored integers are den times the coordinates.
    let n = Rational::from_int(Int::from(pts.len()) * a.den());
    let inv = Rational::new(n.denom().clone(), n.numer().clone());
    Some(sum.map(|s| &s * &inv))
}

/// A superset of the vertices of `a ∩ b` for two closed convex polytopes at the same
/// denominator, as homogeneous points `(x, w)`, `w > 0` (coordinates `x / (w · den)`):
/// the vertices of one inside or on the other, and the crossings of the edges of one with
/// the facets of the other that lie in the other. Empty when `a` and `b` do not meet.
pub fn contact_points(a: &Polytope, b: &Polytope) -> Vec<(Vec3, Int)> {
    debug_assert_eq!(
        a.den(),
        b.den(),
        "contact_points needs a common denominator"
    );
    let mut pts: Vec<(Vec3, Int)> = Vec::new();
    for (p, q) in [(a, b), (b, a)] {
        for v in p.vertices() {
            if q.locate(v) != Containment::Outside {
                pts.push((v.clone(), Int::ONE));
            }
        }
        for e in p.edges() {
            let (s, t) = (
                &p.vertices()[e.ends[0] as usize],
                &p.vertices()[e.ends[1] as usize],
            );
            let d = t.sub(s);
            for f in q.facets() {
                // n·(s + λ d) = c  =>  λ = (c - n·s) / (n·d), strictly inside (0, 1).
                let den = f.normal.dot(&d);
                if den == Int::ZERO {
                    continue;
                }
                let num = &f.offset - f.normal.dot(s);
                let (num, den) = if den < Int::ZERO {
                    (-num, -den)
                } else {
                    (num, den)
                };
                if num <= Int::ZERO || num >= den {
                    continue;
                }
                // Point = (s * den + d * num) / den.
                let x = s.scale(&den).add(&d.scale(&num));
                if locate_homogeneous(q, &x, &den) != Containment::Outside {
                    pts.push((x, den));
                }
            }
        }
    }
    pts
}

fn locate_homogeneous(p: &Polytope, x: &Vec3, w: &Int) -> Containment {
    let mut on = false;
    for f in p.facets() {
        match int::sign_of(&(f.normal.dot(x) - &f.offset * w)) {
            Sign::Positive => return Containment::Outside,
            Sign::Zero => on = true,
            Sign::Negative => {}
        }
    }
    if on {
        Containment::Boundary
    } else {
        Containment::Inside
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxp(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    fn strictly_inside(p: &Polytope, w: &[Rational; 3]) -> bool {
        p.facets().iter().all(|f| {
            let mut s = Rational::from_int(-f.offset.clone());
            for (k, c) in w.iter().enumerate() {
                s = &s + &(&Rational::from_int(f.normal.get(k)) * c);
            }
            s.sign() == Sign::Negative
        })
    }

    #[test]
    fn touching_boxes_do_not_interfere() {
        let a = boxp([0, 0, 0], [2, 2, 2]);
        assert!(interiors_disjoint(&a, &boxp([2, 0, 0], [4, 2, 2]))); // shared face
        assert!(interiors_disjoint(&a, &boxp([2, 2, 0], [4, 4, 2]))); // shared edge
        assert!(interiors_disjoint(&a, &boxp([2, 2, 2], [4, 4, 4]))); // shared vertex
        assert!(interior_witness(&a, &boxp([2, 0, 0], [4, 2, 2])).is_none());
    }

    #[test]
    fn overlapping_boxes_have_a_witness() {
        let a = boxp([0, 0, 0], [2, 2, 2]);
        for b in [
            boxp([1, 1, 1], [3, 3, 3]),
            boxp([0, 0, 0], [2, 2, 2]),
            boxp([-1, 1, -1], [3, 2, 3]),
        ] {
            let w = interior_witness(&a, &b).expect("overlap");
            assert!(strictly_inside(&a, &w) && strictly_inside(&b, &w), "{w:?}");
        }
    }

    #[test]
    fn crossing_without_vertices_inside() {
        // Two long bars crossing like a plus sign: no vertex of either is inside the other.
        let a = boxp([-4, -1, 0], [4, 1, 1]);
        let b = boxp([-1, -4, 0], [1, 4, 1]);
        let w = interior_witness(&a, &b).expect("overlap");
        assert!(strictly_inside(&a, &w) && strictly_inside(&b, &w));
    }
}

#[cfg(test)]
mod den_tests {
    use super::*;
    use apart_kernel::Vec3;

    #[test]
    fn different_denominators() {
        // The cube [0, 1]^3 stored with denominator 2, and [1, 2] x [0, 1] x [0, 1].
        let pts = |lo: i64, s: i64| -> Vec<Vec3> {
            (0..8)
                .map(|i| Vec3::new(lo + (i & 1) * s, (i >> 1 & 1) * s, (i >> 2) * s))
                .collect()
        };
        let a = Polytope::hull_of_points(&pts(0, 2))
            .unwrap()
            .with_den(apart_kernel::Int::from(2));
        let b = Polytope::hull_of_points(&pts(1, 1)).unwrap();
        assert_eq!(a.volume(), Rational::from_int(1));
        assert!(interiors_disjoint(&a, &b));
        // Overlap: the unit cube itself, stored with denominator 3.
        let d = Polytope::hull_of_points(&pts(0, 3))
            .unwrap()
            .with_den(apart_kernel::Int::from(3));
        let w = interior_witness(&a, &d).expect("same cube");
        for c in &w {
            assert_eq!(
                *c,
                Rational::new(apart_kernel::Int::from(1), apart_kernel::Int::from(2))
            );
        }
    }
}

/// How deep the interiors of `a` and `b` overlap: the shortest translation that
/// separates them, in true coordinates, measured in floating point (a report for people,
/// never a decision). Taken over the candidate separating axes of [`separating_normal`]
/// (facet normals of both, and the cross products of edge directions while there are
/// at most 4096 of them), so it is the exact penetration depth up to rounding, or an
/// upper bound of it when the cross products were left out. Zero for touching or
/// disjoint polytopes.
pub fn overlap_depth(a: &Polytope, b: &Polytope) -> f64 {
    signed_depth(a, b).depth.max(0.0)
}

/// Whether the interiors of `a` and `b` overlap (exact), and how deep (measured, as
/// [`overlap_depth`]; 0 when they do not). A floating-point filter decides first: a
/// clear gap along one axis proves them apart, a clear overlap along every candidate
/// axis proves them overlapping, each beyond a proven bound of the rounding error; the
/// exact separating-axis test decides the rest.
pub fn overlap_with_depth(a: &Polytope, b: &Polytope) -> (bool, f64) {
    let s = signed_depth(a, b);
    let overlapping = if s.depth < -s.error {
        false
    } else if s.depth > s.error && s.all_axes {
        true
    } else {
        !interiors_disjoint(a, b)
    };
    (
        overlapping,
        if overlapping { s.depth.max(0.0) } else { 0.0 },
    )
}

/// The smallest signed overlap over the candidate axes (negative: a gap), whether every
/// candidate axis was tried, and a bound of the rounding error.
struct SignedDepth {
    depth: f64,
    all_axes: bool,
    error: f64,
}

fn signed_depth(a: &Polytope, b: &Polytope) -> SignedDepth {
    let pts = |p: &Polytope| -> Vec<[f64; 3]> {
        // Exact values divided once: `approx` is only proportional for big vectors.
        p.vertices()
            .iter()
            .map(|v| [0, 1, 2].map(|k| Rational::new(v.get(k), p.den().clone()).to_f64()))
            .collect()
    };
    let (pa, pb) = (pts(a), pts(b));
    // Every coordinate is below m in magnitude. Each vertex coordinate and each unit
    // axis component carries a relative error of at most 2^-52, so a dot product of a
    // vertex with a unit axis is off by less than 8 m 2^-52, and a signed overlap (a
    // difference of two extremes) by less than 16 m 2^-52; 2^-40 m leaves a margin.
    let m = pa
        .iter()
        .chain(&pb)
        .flatten()
        .fold(0f64, |x, c| x.max(c.abs()));
    let error = m * 2f64.powi(-40);
    let range = |ps: &[[f64; 3]], u: &[f64; 3]| {
        ps.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let t = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
                (lo.min(t), hi.max(t))
            })
    };
    let overlap_along = |n: [f64; 3]| -> f64 {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len == 0.0 || !len.is_finite() {
            return f64::INFINITY;
        }
        let u = n.map(|c| c / len);
        let ((alo, ahi), (blo, bhi)) = (range(&pa, &u), range(&pb, &u));
        (ahi - blo).min(bhi - alo)
    };
    let mut best = f64::INFINITY;
    for f in a.facets().iter().chain(b.facets()) {
        best = best.min(overlap_along(f.normal.approx()));
    }
    let (ea, eb) = (a.edge_directions(), b.edge_directions());
    let all_axes = ea.len() * eb.len() <= 4096;
    if all_axes {
        for da in ea {
            for db in eb {
                let n = da.cross(db);
                if !n.is_zero() {
                    best = best.min(overlap_along(n.approx()));
                }
            }
        }
    }
    SignedDepth {
        depth: if best.is_finite() { best } else { 0.0 },
        all_axes: all_axes && best.is_finite(),
        error: if m.is_finite() { error } else { f64::INFINITY },
    }
}

#[cfg(test)]
mod depth_tests {
    use super::*;

    #[test]
    fn depth_of_overlapping_boxes_is_the_smallest_push() {
        let a = Polytope::cuboid([0, 0, 0], [10, 10, 10]).unwrap();
        // Overlap 3 in x, 10 in y and z: the push is 3.
        let b = Polytope::cuboid([7, 0, 0], [20, 10, 10]).unwrap();
        assert_eq!(overlap_depth(&a, &b), 3.0);
        // Touching: zero. Apart: zero.
        let c = Polytope::cuboid([10, 0, 0], [20, 10, 10]).unwrap();
        assert_eq!(overlap_depth(&a, &c), 0.0);
        let d = Polytope::cuboid([12, 0, 0], [20, 10, 10]).unwrap();
        assert_eq!(overlap_depth(&a, &d), 0.0);
        // A corner poking in diagonally: the octahedron-like tip of a tetrahedron
        // reaching 1 unit past the plane x + y + z = 30 of the box corner region.
        let t = Polytope::hull_of_points(
            &[[9, 9, 9], [20, 9, 9], [9, 20, 9], [9, 9, 20]].map(Vec3::from_i64),
        )
        .unwrap();
        // The tetrahedron's corner (9,9,9) is 1 inside each of the box's faces x=10,
        // y=10, z=10: pushing it out along x by 1 suffices.
        assert!((overlap_depth(&a, &t) - 1.0).abs() < 1e-12);
        // Rational pieces: the same boxes with denominator 4 (coordinates / 4).
        let a4 = a.clone().with_den(Int::from(4));
        let b4 = b.clone().with_den(Int::from(4));
        assert_eq!(overlap_depth(&a4, &b4), 0.75);
    }

    #[test]
    fn the_filtered_decision_agrees_with_the_exact_test() {
        // Overlapping, touching (face, edge, corner), apart, and overlapping by much
        // less than a unit at a scale where the filter must step aside.
        let a = Polytope::cuboid([0, 0, 0], [10, 10, 10]).unwrap();
        let cases = [
            ([7, 0, 0], [20, 10, 10]),
            ([10, 0, 0], [20, 10, 10]),
            ([10, 10, 0], [20, 20, 10]),
            ([10, 10, 10], [20, 20, 20]),
            ([11, 0, 0], [20, 10, 10]),
            ([-5, -5, -5], [15, 15, 15]),
        ];
        for (lo, hi) in cases {
            let b = Polytope::cuboid(lo, hi).unwrap();
            let (o, d) = overlap_with_depth(&a, &b);
            assert_eq!(o, !interiors_disjoint(&a, &b), "{lo:?} {hi:?}");
            assert_eq!(d > 0.0, o);
        }
        // Far from the origin, overlapping by 1 / 2^20 (a denominator): the filter's
        // bound is larger than the overlap, so the exact test decides.
        let big = 1i64 << 40;
        let a = Polytope::cuboid([big, 0, 0], [big + 10, 10, 10])
            .unwrap()
            .rescaled(&Int::from(1u64 << 20));
        let b = Polytope::cuboid(
            [(big + 10) << 20, 0, 0],
            [(big + 20) << 20, 10 << 20, 10 << 20],
        )
        .unwrap()
        .with_den(Int::from(1u64 << 20))
        .translated(&Vec3::new(-1, 0, 0));
        let _ = b; // translated by whole units; build the sliver directly instead
        let c = Polytope::cuboid(
            [((big + 10) << 20) - 1, 0, 0],
            [(big + 20) << 20, 10 << 20, 10 << 20],
        )
        .unwrap()
        .with_den(Int::from(1u64 << 20));
        let (o, _) = overlap_with_depth(&a, &c);
        assert!(o);
        assert!(!interiors_disjoint(&a, &c));
    }
}
