//! Exact interference of two convex polytopes: do their interiors meet, and where.

use crate::polytope::{Containment, Polytope, Shadow};
use apart_kernel::int::{self, Int};
use apart_kernel::{fvec, HPoint, Rational, Sign, Vec3};

/// True when some plane weakly separates `a` and `b` (their interiors are disjoint).
///
/// Separating-axis test over the exact candidate normals of two convex polytopes: the
/// facet normals of both and the cross products of their edge directions. Touching
/// polytopes (shared faces, edges, points) are separated.
pub fn interiors_disjoint(a: &Polytope, b: &Polytope) -> bool {
    separating_normal(a, b).is_some()
}

/// True when the interiors of `a + t` and `b` meet, for an exact translation `t`
/// (touching is not interference), without building the translated polytope: the
/// separating-axis test over the same candidate normals as [`interiors_disjoint`],
/// with `n · t` added to `a`'s support values, all cross-multiplied by the
/// denominators. For placement, where pieces are tested at many rational positions.
pub fn interiors_meet_translated(a: &Polytope, t: &HPoint, b: &Polytope) -> bool {
    let (da, db) = (a.den(), b.den());
    let (x, w) = (t.num(), t.den());
    // Separated along n when [la, ha]/da + n·t and [lb, hb]/db touch or are apart.
    let separated = |n: &Vec3| -> bool {
        let ha = a.support_value(n);
        let hb = b.support_value(n);
        let na = a.support_value(&n.neg());
        let nb = b.support_value(&n.neg());
        let (la, lb) = (-na, -nb);
        let nd = n.to_ints();
        let nd = &nd[0] * &x[0] + &nd[1] * &x[1] + &nd[2] * &x[2];
        let dadb = da * db;
        // a below b: ha/da + nd/w <= lb/db.
        let below = &(&ha * db) * w - &(&lb * da) * w + &nd * &dadb;
        if int::sign_of(&below) != Sign::Positive {
            return true;
        }
        // b below a: hb/db <= la/da + nd/w.
        let above = &(&hb * da) * w - &(&la * db) * w - &nd * &dadb;
        int::sign_of(&above) != Sign::Positive
    };
    for f in a.facets() {
        if separated(&f.normal) {
            return false;
        }
    }
    for f in b.facets() {
        if separated(&f.normal) {
            return false;
        }
    }
    for ea in a.edge_directions() {
        for eb in b.edge_directions() {
            let n = ea.cross(eb);
            if !n.is_zero() && separated(&n.primitive()) {
                return false;
            }
        }
    }
    true
}

/// True when the closed triangle `tri` (grid points) meets the interior of `p`: no
/// plane weakly separates them. The candidate normals are those of the facets of
/// `p − tri`: `p`'s facet normals, the triangle's normal, and the cross products of
/// `p`'s edge directions with the triangle's sides. A triangle lying on a facet of `p`,
/// or touching it at an edge or a point, does not meet it.
pub fn triangle_meets_interior(p: &Polytope, tri: &[[i64; 3]; 3]) -> bool {
    let den = p.den();
    let t = tri.map(|c| Vec3::from_i64(c).scale(den));
    // Separated along n when max_p n·x <= min_t n·y, or max_t n·y <= min_p n·x.
    let separated = |n: &Vec3| -> bool {
        let ht = t.iter().map(|y| n.dot(y)).max().expect("three corners");
        let lt = t.iter().map(|y| n.dot(y)).min().expect("three corners");
        p.support_value(n) <= lt || ht <= -p.support_value(&n.neg())
    };
    if p.facets().iter().any(|f| separated(&f.normal)) {
        return false;
    }
    let sides = [t[1].sub(&t[0]), t[2].sub(&t[1]), t[0].sub(&t[2])];
    let normal = sides[0].cross(&sides[1]);
    if !normal.is_zero() && separated(&normal.primitive()) {
        return false;
    }
    for e in p.edge_directions() {
        for s in &sides {
            let n = e.cross(s);
            if !n.is_zero() && separated(&n.primitive()) {
                return false;
            }
        }
    }
    true
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
    match filtered_relation(a, b) {
        Some(Relation::Apart(n)) => Some(n),
        Some(Relation::Overlapping(_)) => None,
        None => exact_separating_normal(a, b),
    }
}

/// What the filtered separating-axis test found.
enum Relation {
    /// A separating normal (`a` below).
    Apart(Vec3),
    /// No separating axis; with a common interior point `(X, W)` when one was found.
    Overlapping(Option<(Vec3, Int)>),
}

/// [`separating_normal`] without a filter: every candidate axis, exact supports.
fn exact_separating_normal(a: &Polytope, b: &Polytope) -> Option<Vec3> {
    if a.den() != b.den() {
        let (a, b) = Polytope::common(a, b);
        return exact_separating_normal(&a, &b);
    }
    let separates = |n: &Vec3| -> bool {
        let ha = a.support_value(n);
        let hb = b.support_value(&n.neg());
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

/// The smallest and largest of `u · p` over the shadow's points.
fn float_range(s: &Shadow, u: &[f64; 3]) -> (f64, f64) {
    range_of(&s.points, u)
}

/// Whether [`Polytope::support`] climbs `p`'s vertex graph (exact, a few steps) rather
/// than scanning every vertex: then it beats the float filter's scans too.
fn climbs(p: &Polytope) -> bool {
    p.vertices().len() >= crate::climb::CLIMB_MIN
}

/// The smallest and largest of `u · p` over `points`.
fn range_of(points: &[[f64; 3]], u: &[f64; 3]) -> (f64, f64) {
    points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let t = fvec::dot(*p, *u);
            (lo.min(t), hi.max(t))
        })
}

/// The exact `max n · v` over the stored vertices of `p` whose floating-point value
/// `u · v` is at least `floor` (which must keep every maximiser).
fn support_among(p: &Polytope, s: &Shadow, n: &Vec3, u: &[f64; 3], floor: f64) -> Int {
    let mut best: Option<Int> = None;
    for (v, q) in p.vertices().iter().zip(&s.points) {
        if fvec::dot(*q, *u) < floor {
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
        -support_among(
            self.b,
            self.sb,
            &n.neg(),
            &fvec::neg(*u),
            -blo - 2.0 * self.err,
        )
    }

    /// Whether `a` lies weakly below `b` along `n` (`max_a n·x <= min_b n·y`), and
    /// whether strictly; `None` when not.
    fn below(&self, n: &Vec3, u: &[f64; 3]) -> Option<bool> {
        if climbs(self.a) || climbs(self.b) {
            let ha = self.a.support_value(n);
            let hb = self.b.support_value(&n.neg());
            return compare(&ha, self.a.den(), &-hb, self.b.den());
        }
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
        if climbs(self.b) {
            let mb = -self.b.support_value(&f.normal.neg());
            return compare(&f.offset, self.a.den(), &mb, self.b.den());
        }
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
        if climbs(self.a) {
            let ma = -self.a.support_value(&f.normal.neg());
            return compare(&f.offset, self.b.den(), &ma, self.a.den());
        }
        let (alo, _) = float_range(self.sa, u);
        if c - alo > 2.0 * self.err {
            return None;
        }
        let ma = -support_among(
            self.a,
            self.sa,
            &f.normal.neg(),
            &fvec::neg(*u),
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
                let (u, score) = (*u, fvec::dot(so.mean, *u) - level);
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

impl FilteredPair<'_> {
    /// A point strictly inside both polytopes, as homogeneous integers `(X, W)` (true
    /// coordinates `X / W`, `W > 0`): the floating-point centroid of the vertices of
    /// `a ∩ b` (every edge of one clipped to the other), checked exactly; `None` when the
    /// centroid is not inside both (which proves nothing: the pair may only touch).
    fn common_interior_point(&self) -> Option<(Vec3, Int)> {
        let mut sum = [0f64; 3];
        let mut count = 0usize;
        for (p, sp, sq) in [(self.a, self.sa, self.sb), (self.b, self.sb, self.sa)] {
            for e in p.edges() {
                let (s, t) = (
                    &sp.points[e.ends[0] as usize],
                    &sp.points[e.ends[1] as usize],
                );
                if let Some((lo, hi)) = clip(s, t, sq) {
                    for l in [lo, hi] {
                        for k in 0..3 {
                            sum[k] += s[k] + l * (t[k] - s[k]);
                        }
                    }
                    count += 2;
                }
            }
        }
        if count == 0 {
            return None;
        }
        let c = sum.map(|x| x / count as f64);
        let (x, w) = dyadic_point(&c)?;
        (strictly_inside_homogeneous(self.a, &x, &w) && strictly_inside_homogeneous(self.b, &x, &w))
            .then_some((x, w))
    }
}

/// The part `[lo, hi]` of the segment `s + λ (t - s)`, `λ ∈ [0, 1]`, inside the shadow
/// polytope `q` (floating point: only a candidate for an exact check), if not empty.
fn clip(s: &[f64; 3], t: &[f64; 3], q: &Shadow) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (0f64, 1f64);
    for (u, l) in q.facet_units.iter().zip(&q.facet_levels) {
        let (ds, dt) = (fvec::dot(*s, *u) - l, fvec::dot(*t, *u) - l);
        if ds > 0.0 && dt > 0.0 {
            return None;
        }
        if ds > 0.0 {
            lo = lo.max(ds / (ds - dt));
        } else if dt > 0.0 {
            hi = hi.min(ds / (ds - dt));
        }
        if lo > hi {
            return None;
        }
    }
    Some((lo, hi))
}

/// The exact value of a finite float point as homogeneous integers `(X, W)`.
fn dyadic_point(c: &[f64; 3]) -> Option<(Vec3, Int)> {
    let q = [
        Rational::from_f64(c[0])?,
        Rational::from_f64(c[1])?,
        Rational::from_f64(c[2])?,
    ];
    // Denominators are powers of two: the largest is a multiple of the others.
    let w = q.iter().map(|r| r.denom()).max().expect("three").clone();
    let x = q.map(|r| r.numer() * &(&w / r.denom()));
    Some((Vec3::from_ints(x), w))
}

/// Whether the true point `x / w` (`w > 0`) lies in the interior of `p`: stored
/// coordinates `den x / w`, so `n · (den x) < offset w` for every facet.
fn strictly_inside_homogeneous(p: &Polytope, x: &Vec3, w: &Int) -> bool {
    let dx = x.scale(p.den());
    p.facets().iter().all(|f| f.normal.dot(&dx) < &f.offset * w)
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
        let hb = b.support_value(&f.normal.neg());
        if let Some(s) = compare(&f.offset, a.den(), &-hb, b.den()) {
            out.push((f.normal.clone(), s));
        }
    }
    for f in b.facets() {
        let ha = a.support_value(&f.normal.neg());
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
            let ha = a.support_value(n);
            let hb = b.support_value(&n.neg());
            compare(&ha, a.den(), &-hb, b.den())
        }
    }
}

fn filtered_relation(a: &Polytope, b: &Polytope) -> Option<Relation> {
    let fp = FilteredPair::new(a, b)?;
    for (_, of_b, i, u) in fp.facet_candidates() {
        if let Some((n, _)) = fp.below_candidate(of_b, i, &u) {
            return Some(Relation::Apart(n));
        }
    }
    // Before the edge axes (quadratic in the edge directions): a common interior point
    // proves that nothing separates.
    if let Some(p) = fp.common_interior_point() {
        return Some(Relation::Overlapping(Some(p)));
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
                        return Some(Relation::Apart(m.primitive()));
                    }
                }
                continue;
            };
            let ((alo, ahi), (blo, bhi)) = (float_range(fp.sa, &u), float_range(fp.sb, &u));
            if fp.below_given(&n, &u, ahi, blo).is_some() {
                return Some(Relation::Apart(n.primitive()));
            }
            let (m, mu) = (n.neg(), fvec::neg(u));
            if fp.below_given(&m, &mu, -alo, -bhi).is_some() {
                return Some(Relation::Apart(m.primitive()));
            }
        }
    }
    Some(Relation::Overlapping(None))
}

/// When the interiors of `a` and `b` meet, a point in both interiors (exact rational
/// coordinates); `None` when they are disjoint or only touch.
///
/// The witness is an average of vertices of each lying inside the other when the
/// floating-point filter finds one that checks exactly; otherwise the average of a
/// superset of the vertices of `a ∩ b` (vertices of one inside the other, and crossings
/// of edges of one with facets of the other): a convex combination giving every vertex
/// of the full-dimensional intersection positive weight, hence an interior point of it.
pub fn interior_witness(a: &Polytope, b: &Polytope) -> Option<[Rational; 3]> {
    match filtered_relation(a, b) {
        Some(Relation::Apart(_)) => return None,
        Some(Relation::Overlapping(Some((x, w)))) => {
            return Some([0, 1, 2].map(|k| Rational::new(x.get(k), w.clone())));
        }
        Some(Relation::Overlapping(None)) => {}
        None => {
            if exact_separating_normal(a, b).is_some() {
                return None;
            }
        }
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

    pub(super) fn strictly_inside(p: &Polytope, w: &[Rational; 3]) -> bool {
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
    signed_depth(a, b).max(0.0)
}

/// Whether the interiors of `a` and `b` overlap (exact, [`interiors_disjoint`]), and
/// how deep (measured, as [`overlap_depth`], only for overlapping pairs; 0 when they do
/// not).
pub fn overlap_with_depth(a: &Polytope, b: &Polytope) -> (bool, f64) {
    if interiors_disjoint(a, b) {
        (false, 0.0)
    } else {
        (true, overlap_depth(a, b))
    }
}

/// [`overlap_with_depth`] for a search of the deepest of many pairs: `None` when the
/// interiors do not overlap, or when the depth is at most `floor` (then the axes stop as
/// soon as one shows it, and the exact test is skipped). Otherwise the same depth as
/// [`overlap_with_depth`].
pub fn overlap_deeper_than(a: &Polytope, b: &Polytope, floor: f64) -> Option<f64> {
    let d = signed_depth_above(a, b, floor);
    (d > floor && !interiors_disjoint(a, b)).then_some(d.max(0.0))
}

/// The smallest signed overlap of `a` and `b` over the candidate axes (negative: a gap),
/// in floating point.
fn signed_depth(a: &Polytope, b: &Polytope) -> f64 {
    signed_depth_above(a, b, f64::NEG_INFINITY)
}

/// [`signed_depth`], stopping at the first axis whose overlap is at most `floor` (and
/// returning that overlap).
fn signed_depth_above(a: &Polytope, b: &Polytope, floor: f64) -> f64 {
    let (mut wa, mut wb) = (Extremes::new(a), Extremes::new(b));
    let overlap_along = |n: [f64; 3], wa: &mut Extremes, wb: &mut Extremes| -> f64 {
        let len = fvec::norm(n);
        if len == 0.0 || !len.is_finite() {
            return f64::INFINITY;
        }
        let u = n.map(|c| c / len);
        let ((alo, ahi), (blo, bhi)) = (wa.range(&u), wb.range(&u));
        (ahi - blo).min(bhi - alo)
    };
    let mut best = f64::INFINITY;
    // The smaller piece's facets first: with a floor, the axis that shows a shallow
    // overlap is most often the small piece's face against the big one.
    let (first, second) = if a.facets().len() <= b.facets().len() {
        (a, b)
    } else {
        (b, a)
    };
    for f in first.facets().iter().chain(second.facets()) {
        best = best.min(overlap_along(f.normal.approx(), &mut wa, &mut wb));
        if best <= floor {
            return best;
        }
    }
    let (ea, eb) = (a.edge_directions(), b.edge_directions());
    if ea.len() * eb.len() <= 4096 {
        for da in ea {
            for db in eb {
                let n = da.cross(db);
                if !n.is_zero() {
                    best = best.min(overlap_along(n.approx(), &mut wa, &mut wb));
                    if best <= floor {
                        return best;
                    }
                }
            }
        }
    }
    if best.is_finite() {
        best
    } else {
        0.0
    }
}

/// Floating-point extremes of a polytope's vertices along unit axes: a scan for small
/// polytopes and the first few axes, for big ones then a walk along the edges from the
/// last extreme found (on a convex polytope a vertex with no better neighbour is
/// extreme; in floating point the walk may stop within rounding of it, which a
/// measurement allows). The edge lists are built only when a walk is due: a search for
/// the deepest of many overlaps often needs one axis per pair.
struct Extremes<'a> {
    polytope: &'a Polytope,
    points: std::borrow::Cow<'a, [[f64; 3]]>,
    /// Neighbours of each vertex (empty for a scan).
    neighbours: Vec<Vec<u32>>,
    /// Axes asked so far.
    asked: usize,
    /// The last maximum and minimum found.
    hint: [usize; 2],
}

/// Vertices above which [`Extremes`] walks instead of scanning.
const WALK_ABOVE: usize = 64;

/// Axes [`Extremes`] scans before it builds the edge lists of a big polytope.
const SCANS_FIRST: usize = 8;

impl<'a> Extremes<'a> {
    fn new(p: &'a Polytope) -> Extremes<'a> {
        let points = match p.shadow() {
            Some(s) => std::borrow::Cow::Borrowed(&s.points[..]),
            // Exact values divided once: `approx` is only proportional for big vectors.
            None => std::borrow::Cow::Owned(
                p.vertices()
                    .iter()
                    .map(|v| [0, 1, 2].map(|k| Rational::new(v.get(k), p.den().clone()).to_f64()))
                    .collect(),
            ),
        };
        Extremes {
            polytope: p,
            points,
            neighbours: Vec::new(),
            asked: 0,
            hint: [0, 0],
        }
    }

    /// The smallest and largest `u · x` over the vertices.
    fn range(&mut self, u: &[f64; 3]) -> (f64, f64) {
        self.asked += 1;
        if self.points.len() <= WALK_ABOVE || self.asked <= SCANS_FIRST {
            return range_of(&self.points, u);
        }
        if self.neighbours.is_empty() {
            let mut neighbours = vec![Vec::new(); self.points.len()];
            for e in self.polytope.edges() {
                let [s, t] = e.ends;
                neighbours[s as usize].push(t);
                neighbours[t as usize].push(s);
            }
            self.neighbours = neighbours;
        }
        let hi = self.climb(0, u);
        let lo = -self.climb(1, &fvec::neg(*u));
        (lo, hi)
    }

    fn climb(&mut self, slot: usize, u: &[f64; 3]) -> f64 {
        let mut v = self.hint[slot];
        let mut best = fvec::dot(self.points[v], *u);
        loop {
            let next = self.neighbours[v]
                .iter()
                .map(|&w| (w as usize, fvec::dot(self.points[w as usize], *u)))
                .max_by(|x, y| x.1.total_cmp(&y.1));
            match next {
                Some((w, t)) if t > best => {
                    v = w;
                    best = t;
                }
                _ => break,
            }
        }
        self.hint[slot] = v;
        best
    }
}

#[cfg(test)]
mod depth_tests {
    use super::*;

    /// A prism over a `k`-gon of radius `r` (vertices rounded to integers, hull taken).
    fn prism(k: usize, r: f64, z: [i64; 2], phase: f64) -> Polytope {
        let mut pts = Vec::new();
        for i in 0..k {
            let t = phase + i as f64 * std::f64::consts::TAU / k as f64;
            let (x, y) = ((r * t.cos()).round() as i64, (r * t.sin()).round() as i64);
            pts.push(Vec3::new(x, y, z[0]));
            pts.push(Vec3::new(x, y, z[1]));
        }
        Polytope::hull_of_points(&pts).unwrap()
    }

    #[test]
    fn walking_extremes_agree_with_a_scan() {
        let p = prism(48, 1.0e6, [-50_000, 70_000], 0.1);
        assert!(p.vertices().len() > 64, "the walk is used");
        let mut walk = Extremes::new(&p);
        let pts = &p.shadow().unwrap().points;
        let mut rng = apart_testkit::solids::Lcg(12345);
        let mut next = || rng.unit() * 2.0 - 1.0;
        for _ in 0..500 {
            let n = [next(), next(), next() * 0.1];
            let len = fvec::norm(n);
            let u = n.map(|c| c / len);
            let (lo, hi) = walk.range(&u);
            let scan = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| {
                    (l.min(fvec::dot(*q, u)), h.max(fvec::dot(*q, u)))
                });
            assert!(
                (lo - scan.0).abs() <= 1e-6 && (hi - scan.1).abs() <= 1e-6,
                "{u:?}"
            );
        }
        assert!(!walk.neighbours.is_empty(), "the walk was used");
    }

    #[test]
    fn a_floor_skips_only_pairs_no_deeper_than_it() {
        // A 96-gon prism (walked) against boxes cutting into it by various depths, and
        // one apart from it: above the floor the depth is overlap_with_depth's, at or
        // below it (or with no overlap) there is none.
        let p = prism(96, 1.0e6, [0, 100_000], 0.0);
        for (x0, x1) in [
            (990_000, 1_200_000),
            (900_000, 1_100_000),
            (1_000_010, 1_100_000),
        ] {
            let b = Polytope::cuboid([x0, -20_000, 10_000], [x1, 20_000, 60_000]).unwrap();
            let (overlap, depth) = overlap_with_depth(&p, &b);
            assert_eq!(
                overlap_deeper_than(&p, &b, f64::NEG_INFINITY).is_some(),
                overlap
            );
            if !overlap {
                assert_eq!(overlap_deeper_than(&p, &b, 0.0), None);
                continue;
            }
            assert!(depth > 0.0);
            assert_eq!(overlap_deeper_than(&p, &b, depth * 0.5), Some(depth));
            assert_eq!(overlap_deeper_than(&p, &b, depth), None);
            assert_eq!(overlap_deeper_than(&p, &b, depth * 2.0), None);
        }
    }

    #[test]
    fn crossing_pieces_get_an_exact_common_interior_point() {
        // A 48-gon prism and a box cutting into its side, and a box whose corner
        // region overlaps it: a point strictly inside both is found without the edge
        // axes, and checked here independently with rationals.
        let p = prism(48, 1.0e6, [0, 100_000], 0.0);
        for b in [
            Polytope::cuboid([990_000, -30_000, -10], [1_200_000, 30_000, 50_000]).unwrap(),
            Polytope::cuboid([-500, -500, 99_000], [500, 500, 200_000]).unwrap(),
        ] {
            let fp = FilteredPair::new(&p, &b).unwrap();
            let (x, w) = fp.common_interior_point().expect("a certificate");
            let q = [0, 1, 2].map(|k| Rational::new(x.get(k), w.clone()));
            assert!(tests::strictly_inside(&p, &q) && tests::strictly_inside(&b, &q));
            assert!(separating_normal(&p, &b).is_none());
        }
        // Touching along the prism's top face: no certificate, a separating plane.
        let b = Polytope::cuboid([-500, -500, 100_000], [500, 500, 200_000]).unwrap();
        let fp = FilteredPair::new(&p, &b).unwrap();
        assert!(fp.common_interior_point().is_none());
        assert!(separating_normal(&p, &b).is_some());
    }

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

#[cfg(test)]
mod triangle_tests {
    use super::*;
    use apart_kernel::rational;

    /// The value `n · (den x) - offset` of facet `f` at an exact point `x`.
    fn level(p: &Polytope, f: &crate::Facet, x: &[Rational; 3]) -> Rational {
        let n = f
            .normal
            .to_ints()
            .map(|c| Rational::new(&c * p.den(), Int::from(1)));
        &rational::dot(&n, x) - &Rational::new(f.offset.clone(), Int::from(1))
    }

    /// Independent oracle: clip the triangle by every facet half-space (exact
    /// Sutherland-Hodgman); the clipped polygon meets the interior exactly when the mean
    /// of its vertices (a relative interior point) is strictly inside every facet.
    fn clipped_meets(p: &Polytope, tri: &[[i64; 3]; 3]) -> bool {
        let mut poly: Vec<[Rational; 3]> = tri.iter().map(|c| c.map(Rational::from)).collect();
        for f in p.facets() {
            let mut out = Vec::new();
            for k in 0..poly.len() {
                let (a, b) = (&poly[k], &poly[(k + 1) % poly.len()]);
                let (la, lb) = (level(p, f, a), level(p, f, b));
                if la.sign() != Sign::Positive {
                    out.push(a.clone());
                }
                let crosses = (la.sign() == Sign::Positive && lb.sign() == Sign::Negative)
                    || (la.sign() == Sign::Negative && lb.sign() == Sign::Positive);
                if crosses {
                    let t = &la / &(&la - &lb);
                    out.push(rational::add(a, &rational::sub(b, a).map(|c| &c * &t)));
                }
            }
            poly = out;
            if poly.is_empty() {
                return false;
            }
        }
        let k = Rational::from(poly.len() as i64);
        let mean = [0, 1, 2].map(|i| &poly.iter().fold(Rational::zero(), |s, q| &s + &q[i]) / &k);
        p.facets()
            .iter()
            .all(|f| level(p, f, &mean).sign() == Sign::Negative)
    }

    #[test]
    fn triangles_against_polytopes_agree_with_exact_clipping() {
        let cube = Polytope::cuboid([0, 0, 0], [4, 4, 4]).unwrap();
        let pts: Vec<Vec3> = [[0, 0, 0], [6, 1, 0], [1, 5, 1], [2, 2, 6], [5, 5, 4]]
            .map(Vec3::from_i64)
            .to_vec();
        let hull = Polytope::hull_of_points(&pts).unwrap();
        let halved = cube.clone().with_den(Int::from(2));
        let mut rng = apart_testkit::solids::Lcg(7);
        let (mut met, mut apart) = (0, 0);
        for p in [&cube, &hull, &halved] {
            for k in 0..3000 {
                // Small coordinates, so that touching, coplanar and shared-vertex cases
                // are frequent; every fifth triangle is flat on a line.
                let mut c = || (rng.unit() * 8.0).floor() as i64 - 1;
                let mut tri = [[c(), c(), c()], [c(), c(), c()], [c(), c(), c()]];
                if k % 5 == 0 {
                    tri[2] = [0, 1, 2].map(|i| 2 * tri[1][i] - tri[0][i]);
                }
                let got = triangle_meets_interior(p, &tri);
                assert_eq!(got, clipped_meets(p, &tri), "{tri:?}");
                if got {
                    met += 1;
                } else {
                    apart += 1;
                }
            }
        }
        assert!(met > 500 && apart > 500, "{met} {apart}");
        // On a facet, along an edge, at a corner: touching only.
        for tri in [
            [[0, 0, 4], [4, 0, 4], [0, 4, 4]],
            [[0, 0, 0], [4, 0, 0], [2, -3, 0]],
            [[4, 4, 4], [6, 5, 4], [5, 6, 7]],
        ] {
            assert!(!triangle_meets_interior(&cube, &tri));
        }
        // Through the middle, and just entering.
        assert!(triangle_meets_interior(
            &cube,
            &[[-1, 2, 2], [5, 2, 2], [2, 2, 5]]
        ));
        assert!(triangle_meets_interior(
            &cube,
            &[[3, 3, 3], [9, 9, 9], [9, 3, 9]]
        ));
    }
}
