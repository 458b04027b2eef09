//! Slabs: floating-point bounds on a group of triangles (or polygon sides) across
//! their common direction, a filter that skips pairs of nearly parallel neighbours.

use crate::mesh::Mesh;
use apart_kernel::fvec;
use apart_kernel::orient;

/// A bound on a node's triangles: their box, and the interval `[lo, hi]` of `u · x`
/// over their vertices for the unit normal `u` of the first of them (floating point).
/// Triangles that are nearly parallel and close together (the deep teeth of a star,
/// the flanks of a thread) have boxes that meet in quadratically many pairs, but thin
/// slabs: two nodes whose slabs are apart by more than the rounding error are skipped.
/// It is only a filter: a pair it cannot separate is left to the boxes and the exact
/// tests.
#[derive(Clone, Copy, Debug)]
pub(super) struct Slab {
    u: [f64; 3],
    lo: f64,
    hi: f64,
    min: [f64; 3],
    max: [f64; 3],
    ok: bool,
}

impl Slab {
    pub(super) const NONE: Slab = Slab {
        u: [0.0; 3],
        lo: 0.0,
        hi: 0.0,
        min: [0.0; 3],
        max: [0.0; 3],
        ok: false,
    };

    /// The slab of the triangles `ts` along the normal of the first one; none when
    /// one of them has no area (the exact test's answer on such a triangle is not a
    /// question of where it lies, so nothing is skipped for it).
    pub(super) fn of_triangles(mesh: &Mesh, ts: impl Iterator<Item = u32> + Clone) -> Slab {
        let corners = |t: u32| mesh.corners(t as usize).map(|p| p.map(|c| c as f64));
        let flat = |t: u32| {
            let [a, b, c] = mesh.corners(t as usize);
            orient::normal(a, b, c) == [0; 3]
        };
        if ts.clone().any(flat) {
            return Slab::NONE;
        }
        let Some(u) = ts.clone().find_map(|t| {
            let [a, b, c] = corners(t);
            let n = fvec::cross(fvec::sub(b, a), fvec::sub(c, a));
            let len = fvec::norm(n);
            (len > 0.0 && len.is_finite()).then(|| n.map(|x| x / len))
        }) else {
            return Slab::NONE;
        };
        Slab::of_points(u, ts.flat_map(corners))
    }

    /// The slab of the polygon sides `ks` of `q` (in the plane `z = 0`) along the
    /// normal of the first one with a length.
    pub(super) fn of_sides(q: &[[i64; 2]], ks: &[u32]) -> Slab {
        let ends = |k: u32| {
            let (a, b) = (q[k as usize], q[(k as usize + 1) % q.len()]);
            [a, b].map(|p| [p[0] as f64, p[1] as f64, 0.0])
        };
        let Some(u) = ks.iter().find_map(|&k| {
            let [a, b] = ends(k);
            let n = [a[1] - b[1], b[0] - a[0], 0.0];
            let len = fvec::norm(n);
            (len > 0.0 && len.is_finite()).then(|| n.map(|x| x / len))
        }) else {
            return Slab::NONE;
        };
        Slab::of_points(u, ks.iter().flat_map(|&k| ends(k)))
    }

    /// The slab of `points` along the unit vector `u`, with their box.
    fn of_points(u: [f64; 3], points: impl Iterator<Item = [f64; 3]>) -> Slab {
        let mut s = Slab {
            u,
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            min: [f64::INFINITY; 3],
            max: [f64::NEG_INFINITY; 3],
            ok: true,
        };
        for p in points {
            let d = fvec::dot(u, p);
            s.lo = s.lo.min(d);
            s.hi = s.hi.max(d);
            s.min = [0, 1, 2].map(|k| s.min[k].min(p[k]));
            s.max = [0, 1, 2].map(|k| s.max[k].max(p[k]));
        }
        s
    }

    /// An interval holding `v · x` for every point `x` the slab bounds (in its box and
    /// its slab), `v` a unit vector: through the box alone, and through the slab with
    /// `v · x = w · x + (v − w) · x` for `w = ±u`; the tighter of the two ends.
    fn along(&self, v: &[f64; 3]) -> (f64, f64) {
        let c = [0, 1, 2].map(|k| 0.5 * (self.min[k] + self.max[k]));
        let e = [0, 1, 2].map(|k| 0.5 * (self.max[k] - self.min[k]));
        let spread = |w: &[f64; 3]| (0..3).map(|k| w[k].abs() * e[k]).sum::<f64>();
        let (bc, bs) = (fvec::dot(*v, c), spread(v));
        // The slab along `u` or `−u`, whichever is nearer `v` (the two sides of a thin
        // tooth face opposite ways).
        let (w, lo, hi) = match fvec::dot(*v, self.u) < 0.0 {
            false => (self.u, self.lo, self.hi),
            true => (self.u.map(|x| -x), -self.hi, -self.lo),
        };
        let d = fvec::sub(*v, w);
        let (dc, ds) = (fvec::dot(d, c), spread(&d));
        ((bc - bs).max(lo + dc - ds), (bc + bs).min(hi + dc + ds))
    }

    /// A bound on the rounding errors of the slab's sums: far above them (about 2^-52
    /// of the coordinates' magnitude per operation), far below any real gap.
    fn margin(&self) -> f64 {
        let m = (0..3)
            .map(|k| self.min[k].abs().max(self.max[k].abs()))
            .fold(0.0, f64::max);
        1e-9 * (1.0 + m)
    }

    /// The slab of two nodes: along `a`'s normal, covering `b` through [`Slab::along`].
    pub(super) fn join(a: &Slab, b: &Slab) -> Slab {
        if !a.ok || !b.ok {
            return Slab::NONE;
        }
        let (lo, hi) = b.along(&a.u);
        Slab {
            u: a.u,
            lo: a.lo.min(lo),
            hi: a.hi.max(hi),
            min: [0, 1, 2].map(|k| a.min[k].min(b.min[k])),
            max: [0, 1, 2].map(|k| a.max[k].max(b.max[k])),
            ok: true,
        }
    }

    /// True when a plane along one of the two normals separates the nodes by more than
    /// the rounding margin (so no triangle of one meets a triangle of the other).
    pub(super) fn apart(a: &Slab, b: &Slab) -> bool {
        if !a.ok || !b.ok {
            return false;
        }
        let m = a.margin().max(b.margin());
        let off = |s: &Slab, o: &Slab| {
            let (lo, hi) = o.along(&s.u);
            hi < s.lo - m || lo > s.hi + m
        };
        off(a, b) || off(b, a)
    }
}
