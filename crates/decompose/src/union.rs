//! The union solid of a closed, possibly self-crossing surface: `{x : w(x) >= 1}` for the
//! winding number `w`, cut into convex cells.
//!
//! Method: an autopartition. A box around the surface is split by planes through input
//! elements meeting the open cell (see below), carrying the triangles' fragments (exact convex
//! polygons, see `fragments`), until no fragment meets a cell's open interior. A fragment
//! lying in a splitting plane lies on the boundary of both parts and is dropped; every
//! other one goes to the part(s) it meets. A leaf's open interior therefore meets no
//! triangle, so `w` is constant on it; it is evaluated exactly at one interior point (the
//! vertex average) by counting signed crossings of a ray, and the leaf is kept when
//! `w >= 1`. The kept closed cells have disjoint interiors, and their union is the
//! closure of `{w >= 1}`: the leaves cover the box, the surface has measure zero, and a
//! leaf is kept exactly when its open interior lies in `{w >= 1}`.
//!
//! (Exactly: the union of the kept cells is closed and contains `{w >= 1}` off the surface,
//! hence its closure; conversely each kept cell is the closure of its open interior,
//! which lies in `{w >= 1}` off the surface, a set of measure zero that cannot hold an
//! open set.)
//!
//! The planes are chosen as by `decompose` while a reflex or non-manifold input edge or a
//! non-manifold vertex meets the open cell (through such an element, see `split`), then
//! among the fragments' planes (cutting few fragments). The first kind only serves the
//! quality of the pieces: on a valid solid, once the elements are resolved, each cell
//! holds one convex part of the solid, which the fragment planes carve out without
//! cutting it. Correctness rests on the leaves alone.
//!
//! A cell that still holds fragments is also a leaf, kept whole, when it provably lies
//! in the solid (fragments of interior layers, e.g. where shells overlap; see
//! `UnionPartition::whole`): this only saves cuts.
//!
//! Termination: a plane of the first kind contains a live element, which then meets
//! neither open part; one of the second kind contains a fragment, likewise. Parts only
//! inherit elements and fragments of their parent.
//!
//! The ray: from `q` along `+x`, with `q` moved to `q + (0, ε, ε²)` for an infinitesimal
//! `ε` (simulation of simplicity). `q` lies on no triangle, so the moved point has the
//! same `w`, and the moved ray passes through no triangle edge or vertex and lies in no
//! triangle plane parallel to `x`: every crossing is proper. A crossed triangle with
//! outward normal `n` adds `sign(n_x)` (leaving through the outer side counts +1, since
//! `w = 0` far away). Exactness: the point-in-triangle test is three 2D orientations in
//! `(y, z)`, each `D0 + ε (a_z - b_z) + ε² (b_y - a_y)`, decided by the first non-zero
//! coefficient (`D0` by a floating-point filter with a proven margin, else exactly); the
//! ray crosses in front when `sign(c - n·q) = sign(n_x)` (never zero there: `q` would lie
//! on the triangle).

use crate::cell::Cell;
use crate::fragments::{split_by, Frag};
use crate::partition::Counters;
use crate::solid::Solid;
use crate::split::{for_live, live};
use crate::DecomposeError;
use apart_kernel::plane::{HPoint, Plane};
use apart_kernel::{int, Int, Rational, Sign};
use rustc_hash::FxHashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Cells with fewer fragments than this in either part are processed sequentially.
const PARALLEL_MIN: usize = 48;
/// Cells with more fragments than this are never kept whole (see `whole`).
const WHOLE_MAX: usize = 64;
/// Nor those with more fragments facing an interior point than this: `w` would have to
/// exceed it.
const WHOLE_MAX_INNER: i64 = 2;
/// Candidate planes evaluated per split.
const CANDIDATES: usize = 24;

/// A leaf cell and the winding number at its interior point (on the whole interior for
/// a cell without fragments; at least 1 on all of it otherwise).
pub(crate) struct Leaf {
    pub cell: Cell,
    pub w: i64,
}

pub(crate) struct UnionPartition<'a> {
    solid: &'a Solid,
    rays: RayIndex,
    parallel: bool,
    stop: Option<Arc<AtomicBool>>,
    pub counters: Counters,
}

struct Task {
    cell: Cell,
    frags: Vec<Arc<Frag>>,
}

enum Step {
    Leaf(Leaf),
    Split(Task, Task),
}

impl<'a> UnionPartition<'a> {
    pub fn new(
        solid: &'a Solid,
        parallel: bool,
        stop: Option<Arc<AtomicBool>>,
    ) -> UnionPartition<'a> {
        UnionPartition {
            solid,
            rays: RayIndex::new(solid),
            parallel,
            stop,
            counters: Counters::default(),
        }
    }

    /// Every leaf cell of the partition of a box around the surface, with its winding
    /// number.
    pub fn run(&self) -> Result<Vec<Leaf>, DecomposeError> {
        let s = self.solid;
        let (lo, hi) = partition_box(s);
        let frags = Frag::all_whole(s);
        self.solve(Task {
            cell: Cell::boxed(lo, hi),
            frags,
        })
    }

    fn solve(&self, task: Task) -> Result<Vec<Leaf>, DecomposeError> {
        let mut out = Vec::new();
        let mut stack = vec![task];
        while let Some(t) = stack.pop() {
            match self.step(t)? {
                Step::Leaf(l) => out.push(l),
                Step::Split(a, b) => {
                    if self.parallel && a.frags.len().min(b.frags.len()) >= PARALLEL_MIN {
                        let (ra, rb) = rayon::join(|| self.solve(a), || self.solve(b));
                        out.extend(ra?);
                        out.extend(rb?);
                    } else {
                        stack.push(b);
                        stack.push(a);
                    }
                }
            }
        }
        Ok(out)
    }

    /// The winding number at an interior point when the whole cell lies in the solid
    /// although fragments cross it (interior layers, e.g. where shells overlap).
    ///
    /// For `x` and `q` in the open cell, off the surface, the segment from `q` to `x`
    /// stays in the open cell and meets each fragment at most once (generically): `w`
    /// drops by one exactly where it leaves a fragment's inner side. So
    /// `w(x) >= w(q) - k`, `k` the number of fragments with `q` strictly on their inner
    /// side, and the cell lies in the solid (up to the surface) when `w(q) - k >= 1`.
    /// `q` must lie on no fragment's plane (else the cell is just split).
    fn whole(&self, t: &Task) -> Result<Option<i64>, DecomposeError> {
        if t.frags.len() > WHOLE_MAX {
            return Ok(None);
        }
        let q = interior_point(&t.cell);
        let mut inner = 0;
        for f in &t.frags {
            match self.solid.planes[f.tri as usize].side(&q) {
                Sign::Zero => return Ok(None),
                Sign::Negative => inner += 1,
                Sign::Positive => {}
            }
        }
        if inner > WHOLE_MAX_INNER {
            return Ok(None);
        }
        let w = self.rays.winding(self.solid, &q)?;
        Ok((w - inner >= 1).then_some(w))
    }

    fn step(&self, t: Task) -> Result<Step, DecomposeError> {
        let cells = self.counters.cells.fetch_add(1, Ordering::Relaxed);
        if cells % 1024 == 0
            && self
                .stop
                .as_ref()
                .is_some_and(|s| s.load(Ordering::Relaxed))
        {
            return Err(DecomposeError::Stopped);
        }
        if t.frags.is_empty() {
            let q = interior_point(&t.cell);
            let w = self.rays.winding(self.solid, &q)?;
            return Ok(Step::Leaf(Leaf { cell: t.cell, w }));
        }
        if let Some(w) = self.whole(&t)? {
            return Ok(Step::Leaf(Leaf { cell: t.cell, w }));
        }
        self.counters.splits.fetch_add(1, Ordering::Relaxed);
        let l = live(self.solid, &t.frags);
        let h = if l.is_empty() {
            choose(self.solid, &t.frags)
        } else {
            let in_cell: FxHashMap<u32, u32> = t
                .frags
                .iter()
                .enumerate()
                .map(|(i, f)| (f.tri, i as u32))
                .collect();
            for_live(self.solid, &t.frags, &in_cell, &l).plane
        };
        let (below, above) = t.cell.split(&h, true);
        let (Some(below), Some(above)) = (below, above) else {
            return Err(DecomposeError::Internal(
                "a fragment's plane missed the open cell".into(),
            ));
        };
        let (fb, fa) = split_by(&t.frags, &h, self.solid);
        Ok(Step::Split(
            Task {
                cell: below,
                frags: fb,
            },
            Task {
                cell: above,
                frags: fa,
            },
        ))
    }
}

/// The plane of a fragment that cuts the fewest other fragments, then holds the most,
/// then leaves the smaller side largest (among evenly spread candidates).
fn choose(solid: &Solid, frags: &[Arc<Frag>]) -> Plane {
    let mut planes: Vec<Plane> = Vec::new();
    let mut seen = rustc_hash::FxHashSet::default();
    let step = frags.len().div_ceil(CANDIDATES).max(1);
    for f in frags.iter().step_by(step) {
        let p = solid.planes[f.tri as usize];
        if seen.insert(p.unoriented()) {
            planes.push(p);
        }
    }
    let mut best: Option<((i64, i64, i64), Plane)> = None;
    for p in planes {
        let (mut cut, mut on, mut below, mut above) = (0i64, 0i64, 0i64, 0i64);
        for f in frags {
            match f.straddle(&p, solid) {
                (true, true) => {
                    cut += 1;
                    below += 1;
                    above += 1;
                }
                (true, false) => below += 1,
                (false, true) => above += 1,
                (false, false) => on += 1,
            }
        }
        let key = (-cut, on, below.min(above));
        if best.as_ref().is_none_or(|b| key > b.0) {
            best = Some((key, p));
        }
    }
    best.expect("a cell with fragments").1
}

/// The average of the cell's vertices: a point of its open interior.
fn interior_point(cell: &Cell) -> HPoint {
    let mut l = Int::ONE;
    for v in &cell.verts {
        let d = v.p.den();
        let g = int::gcd(&l, d);
        l = &l / &g * d;
    }
    let mut x = [Int::ZERO, Int::ZERO, Int::ZERO];
    for v in &cell.verts {
        let k = &l / v.p.den();
        for (xi, ni) in x.iter_mut().zip(v.p.num()) {
            *xi += ni * &k;
        }
    }
    HPoint::from_big(x, l * Int::from(cell.verts.len()))
}

/// Triangles binned by their `(y, z)` bounding boxes, widened by one unit (far more than
/// The box the partition starts from: the surface's box grown by one grid step.
pub(crate) fn partition_box(s: &Solid) -> ([i64; 3], [i64; 3]) {
    (s.bbox.min.map(|v| v - 1), s.bbox.max.map(|v| v + 1))
}

/// the error of a point's floating-point shadow), for rays along `x`.
struct RayIndex {
    lo: [i64; 2],
    step: [i64; 2],
    n: [usize; 2],
    bins: Vec<Vec<u32>>,
    max_x: Vec<i64>,
}

impl RayIndex {
    fn new(s: &Solid) -> RayIndex {
        let side = ((s.tris.len() as f64 / 2.0).sqrt().ceil() as usize).clamp(1, 64);
        let (slo, shi) = (s.bbox.min, s.bbox.max);
        let lo = [slo[1] - 1, slo[2] - 1];
        let span = [shi[1] - slo[1] + 3, shi[2] - slo[2] + 3];
        let step = span.map(|d| (d + side as i64 - 1) / side as i64);
        let n = [0, 1].map(|a| ((span[a] + step[a] - 1) / step[a]) as usize);
        let mut bins = vec![Vec::new(); n[0] * n[1]];
        let mut max_x = Vec::with_capacity(s.tris.len());
        for (t, tri) in s.tris.iter().enumerate() {
            let mut b = [[i64::MAX; 2], [i64::MIN; 2]];
            let mut mx = i64::MIN;
            for &v in tri {
                let p = s.pts[v as usize];
                mx = mx.max(p[0]);
                for a in 0..2 {
                    b[0][a] = b[0][a].min(p[a + 1]);
                    b[1][a] = b[1][a].max(p[a + 1]);
                }
            }
            max_x.push(mx);
            let r = [0, 1].map(|a| {
                let i0 = ((b[0][a] - 1 - lo[a]) / step[a]).max(0) as usize;
                let i1 = (((b[1][a] + 1 - lo[a]) / step[a]) as usize).min(n[a] - 1);
                (i0, i1)
            });
            for i in r[0].0..=r[0].1 {
                for j in r[1].0..=r[1].1 {
                    bins[i * n[1] + j].push(t as u32);
                }
            }
        }
        RayIndex {
            lo,
            step,
            n,
            bins,
            max_x,
        }
    }

    /// The winding number of the surface around `q`, a point on no triangle.
    fn winding(&self, s: &Solid, q: &HPoint) -> Result<i64, DecomposeError> {
        let f = shadow(q);
        let bin = |a: usize| -> usize {
            let i = ((f[a + 1] - self.lo[a] as f64) / self.step[a] as f64).floor();
            (i.max(0.0) as usize).min(self.n[a] - 1)
        };
        let mut w = 0i64;
        for &t in &self.bins[bin(0) * self.n[1] + bin(1)] {
            if (self.max_x[t as usize] as f64) < f[0] - 1.0 {
                continue;
            }
            let pl = &s.planes[t as usize];
            let nx = Sign::of_i128(pl.n[0]);
            if nx == Sign::Zero {
                continue;
            }
            let [a, b, c] = s.tris[t as usize].map(|v| &s.pts[v as usize]);
            if orient(a, b, q) != nx || orient(b, c, q) != nx || orient(c, a, q) != nx {
                continue;
            }
            match pl.side(q) {
                Sign::Zero => {
                    return Err(DecomposeError::Internal(
                        "a leaf's interior point lies on a triangle".into(),
                    ))
                }
                side if side == -nx => w += if nx == Sign::Positive { 1 } else { -1 },
                _ => {}
            }
        }
        Ok(w)
    }
}

/// Floating-point coordinates of `q` within a few ulps (for binning only).
fn shadow(q: &HPoint) -> [f64; 3] {
    let f = q.approx();
    if f.iter().all(|v| v.is_finite()) {
        return f;
    }
    [0, 1, 2].map(|k| Rational::new(q.num()[k].clone(), q.den().clone()).to_f64())
}

/// Sign of the 2D orientation of `(a, b, q + (0, ε, ε²))` in the `(y, z)` projection.
fn orient(a: &[i64; 3], b: &[i64; 3], q: &HPoint) -> Sign {
    let (dy, dz) = (b[1] - a[1], b[2] - a[2]);
    let f = q.approx();
    let filter = f.iter().all(|v| v.is_finite());
    // Filter: differences of input coordinates are exact in f64; q's shadow is within
    // a relative 5u per coordinate, each subtraction and product adds u, the final
    // difference u: far below the 1e-12 margin.
    let (ty, tz) = (f[1] - a[1] as f64, f[2] - a[2] as f64);
    let v = dy as f64 * tz - dz as f64 * ty;
    let bound = 1e-12
        * ((dy as f64).abs() * (f[2].abs() + (a[2] as f64).abs())
            + (dz as f64).abs() * (f[1].abs() + (a[1] as f64).abs()));
    if filter && v > bound {
        return Sign::Positive;
    }
    if filter && v < -bound {
        return Sign::Negative;
    }
    let x = q.num();
    let w = q.den();
    let d0 = Int::from(dy) * (&x[2] - w * Int::from(a[2]))
        - Int::from(dz) * (&x[1] - w * Int::from(a[1]));
    let s = int::sign_of(&d0);
    if s != Sign::Zero {
        return s;
    }
    if dz != 0 {
        return Sign::of_i128(-(dz as i128));
    }
    Sign::of_i128(dy as i128)
}
