//! The floating-point filter of the separating-axis tests: float shadows of two
//! polytopes prune the axes and the vertices the exact comparisons look at, and find a
//! common interior point to check exactly. It only prunes: every answer is exact.

use crate::polytope::{Polytope, Shadow};
use apart_kernel::int::{self, Int};
use apart_kernel::{fvec, Rational, Vec3};

/// The unit vector along `n` in floating point (each component within 2^-49), `None` for
/// the zero vector.
pub(super) fn unit(n: &Vec3) -> Option<[f64; 3]> {
    let u = n.unit_f64();
    (u != [0.0; 3] && u.iter().all(|c| c.is_finite())).then_some(u)
}

/// The smallest and largest of `u · p` over the shadow's points.
pub(super) fn float_range(s: &Shadow, u: &[f64; 3]) -> (f64, f64) {
    range_of(&s.points, u)
}

/// Whether [`Polytope::support`] climbs `p`'s vertex graph (exact, a few steps) rather
/// than scanning every vertex: then it beats the float filter's scans too.
fn climbs(p: &Polytope) -> bool {
    p.vertices().len() >= crate::climb::CLIMB_MIN
}

/// The smallest and largest of `u · p` over `points`.
pub(super) fn range_of(points: &[[f64; 3]], u: &[f64; 3]) -> (f64, f64) {
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
pub(super) struct FilteredPair<'p> {
    a: &'p Polytope,
    b: &'p Polytope,
    pub(super) sa: &'p Shadow,
    pub(super) sb: &'p Shadow,
    err: f64,
}

impl<'p> FilteredPair<'p> {
    /// The pair with its shadows; `None` when either polytope has none.
    pub(super) fn new(a: &'p Polytope, b: &'p Polytope) -> Option<FilteredPair<'p>> {
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
    pub(super) fn below(&self, n: &Vec3, u: &[f64; 3]) -> Option<bool> {
        if climbs(self.a) || climbs(self.b) {
            let ha = self.a.support_value(n);
            let hb = self.b.support_value(&n.neg());
            return compare(&ha, self.a.den(), &-hb, self.b.den());
        }
        let ((_, ahi), (blo, _)) = (float_range(self.sa, u), float_range(self.sb, u));
        self.below_given(n, u, ahi, blo)
    }

    /// [`Self::below`] given `ahi` and `blo`, the float maximum of `a` and minimum of
    /// `b` along `u`.
    pub(super) fn below_given(&self, n: &Vec3, u: &[f64; 3], ahi: f64, blo: f64) -> Option<bool> {
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
    pub(super) fn facet_candidates(&self) -> Vec<(f64, bool, usize, [f64; 3])> {
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
    pub(super) fn below_candidate(
        &self,
        of_b: bool,
        i: usize,
        u: &[f64; 3],
    ) -> Option<(Vec3, bool)> {
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
    pub(super) fn common_interior_point(&self) -> Option<(Vec3, Int)> {
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
pub(super) fn compare(x: &Int, dx: &Int, y: &Int, dy: &Int) -> Option<bool> {
    match int::cmp_fractions(x, dx, y, dy) {
        std::cmp::Ordering::Greater => None,
        o => Some(o == std::cmp::Ordering::Less),
    }
}
