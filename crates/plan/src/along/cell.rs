//! The exact answer at one direction: the blocking graph from the pairs of parts the
//! line along it meets, and the kind of motion-space cell it lies in from the tangent
//! cones of the pairs free there ([`Cover`]), made only while they may add to it.

use super::cover::Cover;
use super::{DirectionAnswer, DirectionQuery};
use crate::dbg::Dbg;
use crate::pairs::{box_graze_normal, classify_boxes, ray_meets_box, ray_meets_int_box, Sep};
use crate::PlanError;
use apart_kernel::predicates::dot_sign;
use apart_kernel::{Sign, Vec3};
use rayon::prelude::*;

impl DirectionQuery<'_> {
    /// For a pair of parts at `x = σ d` (its smaller part moving along `x`): whether `x`
    /// is blocked and, when it is not, what the pair adds near `d` to the union of the
    /// tangent cones of the maps free at `d` ([`Cover`]): the cones of the polygons
    /// already made (those the blocking test summed) whose closure holds `x`, and the
    /// piece pairs left ([`Pending`]: `x` on the boundary of a separating axis'
    /// hemisphere, or a pair of boxes not blocking), made only if their cone may add
    /// something. Cones are given in the frame of `d` (normals times `σ`).
    fn near_cones(&self, i: usize, j: usize, x: &Vec3, flip: bool) -> Result<NearCones, PlanError> {
        let near = self.along_ray(i, j, x);
        match self.boxes_block(i, j, &near, x) {
            Some(true) => return Ok((true, Vec::new(), Vec::new())),
            Some(false) => {
                // Pairs of boxes, none blocking: each whose closed polygon may hold x is
                // left to decide (classified by its coordinate axes, which are all its
                // axes), without the pair's caches.
                let nb = self.parts[j].pieces.len();
                let pending = near
                    .into_iter()
                    .filter_map(|k| {
                        let (a, b) = (k / nb, k % nb);
                        let (pa, pb) = (&self.parts[i].pieces[a], &self.parts[j].pieces[b]);
                        let (ia, ib) = (&self.info[i][a], &self.info[j][b]);
                        if !ray_meets_box(ia, pa.den(), ib, pb.den(), x) {
                            return None;
                        }
                        let (s, touching) = classify_boxes(pa, ia, pb, ib, x);
                        (s != Sep::Outside).then_some(Pending {
                            i,
                            j,
                            k,
                            flip,
                            touching,
                        })
                    })
                    .collect();
                return Ok((false, Vec::new(), pending));
            }
            None => {}
        }
        let p = self.pair(i, j);
        let sep = self.classify_near(p, near, x);
        if self.blocker(p, &sep, x)?.is_some() {
            return Ok((true, Vec::new(), Vec::new()));
        }
        let orient = |q: &Vec3| if flip { q.neg() } else { q.clone() };
        let mut cones = Vec::new();
        let mut pending = Vec::new();
        for &(k, s) in &sep {
            if s == Sep::Unknown && p.cell(k).polygon.get().is_some() {
                // Summed by the blocking test (it tries every undecided pair when none
                // blocks, except pairs of boxes).
                let poly = self.polygon(p, k)?;
                if poly.contains_closed(x) {
                    cones.push(active(poly.normals(), x).map(orient).collect());
                }
                continue;
            }
            pending.push(Pending {
                i: p.i,
                j: p.j,
                k,
                flip,
                touching: self.axes(p, k).iter().any(|a| !a.strict),
            });
        }
        Ok((false, cones, pending))
    }

    /// What the parts' exact boxes say of the pair of parts `i < j` at `x` (the smaller
    /// part moving along `x`): nothing near `x` when the ray misses their box of sums
    /// `S`; not blocked, with its tangent cones at `x` inside `{n · y > 0}`, for every
    /// coordinate axis `n` square to `x` along which `S` lies weakly above the origin
    /// (then every piece pair's sum does too); else undecided.
    fn part_level(&self, i: usize, j: usize, x: &Vec3) -> Level {
        let Some(xs) = x.as_small() else {
            return Level::Open;
        };
        let (a, b) = (&self.boxes[i], &self.boxes[j]);
        let lo: [i128; 3] = std::array::from_fn(|k| i128::from(b.min[k] - a.max[k]));
        let hi: [i128; 3] = std::array::from_fn(|k| i128::from(b.max[k] - a.min[k]));
        if !ray_meets_int_box(lo, hi, xs) {
            return Level::Miss;
        }
        let mut mask = 0u8;
        for k in (0..3).filter(|&k| xs[k] == 0) {
            if lo[k] >= 0 {
                mask |= 1 << (2 * k);
            }
            if hi[k] <= 0 {
                mask |= 1 << (2 * k + 1);
            }
        }
        if mask == 0 {
            return Level::Open;
        }
        Level::Free {
            mask,
            touching: (0..3).all(|k| lo[k] <= 0 && 0 <= hi[k]),
        }
    }

    /// The cones an [`Item`] adds to the cover near `d` (none when the cover holds it).
    fn item_cones(
        &self,
        item: &Item,
        d: &Vec3,
        cover: &Cover,
    ) -> Result<Vec<Vec<Vec3>>, PlanError> {
        match item {
            Item::Piece(p) => Ok(self.pending_cone(p, d, cover)?.into_iter().collect()),
            &Item::Pair { i, j, flip, mask } => {
                // The coordinate axes of the parts' boxes, in the frame of d.
                let bound: Vec<Vec3> = (0..6)
                    .filter(|b| mask >> b & 1 == 1)
                    .map(|b| {
                        let mut e = [0i64; 3];
                        e[b / 2] = if (b % 2 == 1) != flip { -1 } else { 1 };
                        Vec3::from_i64(e)
                    })
                    .collect();
                if cover.holds(&bound) {
                    return Ok(Vec::new());
                }
                let x = if flip { d.neg() } else { d.clone() };
                let (blocked, mut cones, pending) = self.near_cones(i, j, &x, flip)?;
                debug_assert!(!blocked, "the parts' boxes leave the pair free");
                for p in &pending {
                    cones.extend(self.pending_cone(p, d, cover)?);
                }
                Ok(cones)
            }
        }
    }

    /// The cone of a [`Pending`] piece pair unless the cover already holds it: `None`
    /// when a cone holding its own lies in the cover (from its axes through the
    /// direction, or, for a pair of boxes, from where the ray grazes their box of
    /// differences), or (for pairs not touching) when the pair lies weakly below along
    /// the normal of one of the cover's half-planes; else the polygon is made, and its
    /// cone returned when its closure holds the direction.
    fn pending_cone(
        &self,
        p: &Pending,
        d: &Vec3,
        cover: &Cover,
    ) -> Result<Option<Vec<Vec3>>, PlanError> {
        let pair = self.pair(p.i, p.j);
        let x = if p.flip { d.neg() } else { d.clone() };
        let orient = |n: &Vec3| if p.flip { n.neg() } else { n.clone() };
        let nb = self.parts[p.j].pieces.len();
        let (a, b) = (p.k / nb, p.k % nb);
        // Free: weakly below along the axes through x, so its cone lies in theirs.
        let mut bound: Vec<Vec3> = self
            .axes(pair, p.k)
            .iter()
            .filter(|a| !a.strict && dot_sign(&a.n, &x) == Sign::Zero)
            .map(|a| orient(&a.n))
            .collect();
        if bound.is_empty() && self.boxy[p.i][a] && self.boxy[p.j][b] {
            // A pair of boxes the ray grazes at an edge or corner of their box of
            // differences.
            let (pa, pb) = (&self.parts[p.i].pieces[a], &self.parts[p.j].pieces[b]);
            let (ia, ib) = (&self.info[p.i][a], &self.info[p.j][b]);
            bound.extend(box_graze_normal(ia, pa.den(), ib, pb.den(), &x).map(|c| orient(&c)));
        }
        if cover.holds(&bound) {
            return Ok(None);
        }
        if !p.touching && !cover.halves.is_empty() {
            // Below along n, the open polygon lies in {n · y > 0}: in the frame of d
            // that half-plane's normal is σ n.
            let h: rustc_hash::FxHashSet<Vec3> = cover
                .halves
                .iter()
                .map(|n| if p.flip { n.neg() } else { n.clone() })
                .collect();
            let (pa, pb) = (&self.parts[p.i].pieces[a], &self.parts[p.j].pieces[b]);
            if crate::pairs::below_along_any(pa, pb, &h) {
                return Ok(None);
            }
        }
        let poly = self.polygon(pair, p.k)?;
        Ok(poly
            .contains_closed(&x)
            .then(|| active(poly.normals(), &x).map(orient).collect()))
    }

    /// The exact blocking graph at `d`, its minimal moving sets and the cell kind.
    pub fn answer(&self, d: &Vec3) -> Result<DirectionAnswer, PlanError> {
        let all: Vec<usize> = (0..self.parts.len()).collect();
        self.answer_in(&all, d)
    }

    /// [`DirectionQuery::answer`] within the subassembly `sub` (global part indices,
    /// increasing): the blocking graph among its parts (vertex `k` of [`Dbg`] stands for
    /// part `sub[k]`), its minimal moving sets in global indices, and the cell kind of `d`
    /// in the subassembly's motion space. Only the pairs of parts whose box of sums the
    /// line along `±d` meets are looked at (found in the part boxes' hierarchy): no other
    /// piece pair has `±d` in its closed projection.
    pub fn answer_in(&self, sub: &[usize], d: &Vec3) -> Result<DirectionAnswer, PlanError> {
        let d = d.primitive();
        let nd = d.neg();
        let n = sub.len();
        let near = self.pairs_along(sub, &d);
        // Each pair's arcs at d, its cones there and what is left to decide near d; in
        // pair order, so that the first error is the one a sequential loop would meet.
        // (A pair that its parts' boxes leave free, most of them, allocates nothing.)
        #[derive(Default)]
        struct Found {
            blocked: [bool; 2],
            free: [Option<(u8, bool)>; 2],
            cones: Vec<Vec<Vec3>>,
            pending: Vec<Pending>,
        }
        let found: Vec<Result<Found, PlanError>> = near
            .par_iter()
            .map(|&(li, lj)| {
                let (i, j) = (sub[li], sub[lj]);
                let mut f = Found::default();
                for (x, flip) in [(&d, false), (&nd, true)] {
                    match self.part_level(i, j, x) {
                        Level::Miss => {}
                        Level::Free { mask, touching } => {
                            f.free[usize::from(flip)] = Some((mask, touching));
                        }
                        Level::Open => {
                            let (b, c, pending) = self.near_cones(i, j, x, flip)?;
                            f.blocked[usize::from(flip)] = b;
                            f.cones.extend(c);
                            f.pending.extend(pending);
                        }
                    }
                }
                Ok(f)
            })
            .collect();
        let mut arcs = Vec::new();
        let mut cover = Cover::new(&d);
        // Touching ones first (contact cones: cheap, and their half-planes hold most
        // others), each in pair order.
        let (mut first, mut later) = (Vec::new(), Vec::new());
        for (&(li, lj), f) in near.iter().zip(found) {
            let f = f?;
            if f.blocked[0] {
                arcs.push((li, lj));
            }
            if f.blocked[1] {
                arcs.push((lj, li));
            }
            for c in &f.cones {
                cover.add(c);
            }
            let (i, j) = (sub[li], sub[lj]);
            for (flip, free) in [false, true].into_iter().zip(f.free) {
                if let Some((mask, touching)) = free {
                    let item = Item::Pair { i, j, flip, mask };
                    if touching { &mut first } else { &mut later }.push(item);
                }
            }
            for p in f.pending {
                if p.touching { &mut first } else { &mut later }.push(Item::Piece(p));
            }
        }
        first.extend(later);
        let items = first;
        // What is left, in chunks growing from 8 to 1024, each tested against the cover
        // so far: once it holds every direction around d, nothing more is made.
        let (mut start, mut size) = (0, 8);
        while start < items.len() && !cover.is_everything() {
            let end = (start + size).min(items.len());
            let cones: Vec<Result<Vec<Vec<Vec3>>, PlanError>> = items[start..end]
                .par_iter()
                .map(|item| self.item_cones(item, &d, &cover))
                .collect();
            for c in cones {
                for c in c? {
                    cover.add(&c);
                }
            }
            (start, size) = (end, (size * 2).min(1024));
        }
        let dbg = Dbg::new(n, arcs);
        let moving = dbg
            .minimal_moving_sets()
            .into_iter()
            .map(|s| s.into_iter().map(|k| sub[k]).collect())
            .collect();
        Ok(DirectionAnswer {
            cell: cover.kind(),
            direction: d,
            dbg,
            moving,
        })
    }
}

/// A piece pair `k` of parts `i < j` that a direction does not enter but whose closed
/// polygon may hold it (on the boundary of a separating axis' hemisphere, or a pair of
/// boxes), whose polygon is made only when needed.
struct Pending {
    i: usize,
    j: usize,
    k: usize,
    /// At `−d` (the pair's cone is then given with negated normals).
    flip: bool,
    /// Some axis is not strict (the pieces may touch).
    touching: bool,
}

/// What the parts' boxes say of a pair of parts at a direction ([`DirectionQuery::part_level`]).
enum Level {
    /// No piece pair's closed polygon holds it.
    Miss,
    /// Free, with every tangent cone inside the half-planes of the coordinate axes in
    /// `mask` (bit `2k`: `+e_k`, bit `2k + 1`: `−e_k`); `touching`: the boxes meet.
    Free { mask: u8, touching: bool },
    /// Undecided: the piece pairs are asked.
    Open,
}

/// What is left to decide near `d` after the blocking tests: a piece pair, or a pair
/// of parts free at `±d` by their boxes (its piece pairs asked only if its bound may
/// add something to the cover).
enum Item {
    Piece(Pending),
    Pair {
        i: usize,
        j: usize,
        flip: bool,
        mask: u8,
    },
}

/// What [`DirectionQuery::near_cones`] finds of a pair of parts at a direction: whether
/// it is blocked, the cones it adds, and its piece pairs left to decide.
type NearCones = (bool, Vec<Vec<Vec3>>, Vec<Pending>);

/// The normals of `normals` square to `x` (the sides of a polygon through `x`).
fn active<'n>(normals: &'n [Vec3], x: &'n Vec3) -> impl Iterator<Item = &'n Vec3> + 'n {
    normals.iter().filter(move |q| dot_sign(q, x) == Sign::Zero)
}
