//! Placement by partial c-space obstacles over discrete orientations (paper 004 §V and
//! §VI-A).
//!
//! For each orientation the free space starts as the permissible region Ω (one cell).
//! A candidate is the lexicographic minimizer of the cost in a cell. Popped from one
//! priority queue over every orientation and cell (cheapest first), a candidate is
//! tested for interference with the fixed pieces (BVH broad phase, exact separating
//! axes, pairs of the largest pieces first); the obstacle of the first pair that
//! interferes is added to that orientation's obstacle list and subtracted from its cells
//! lazily (a cell is brought up to date when it is popped), and the queue goes on. A candidate without interference is yielded:
//! it is free, and no free configuration is cheaper, because every queued cost is a lower
//! bound of its cell (obstacles only remove positions). This is the two-stage priority
//! queue of §V-C with every free-space cell's optimum kept as a candidate (§VI-A.4):
//! successive calls yield the optima of further cells in increasing cost, for the
//! planner's stability and feasibility checks.

use crate::extrapolate::Template;
use crate::free_space::{subtract, Cell, Split, SplitStats};
use crate::obstacle::{Obstacle, ObstacleShape};
use crate::orientation::{Base, Orientation};
use crate::part::{distinct_orientations, OrientedPart, PartModel, StackError};
pub use crate::qp::Objective;
use crate::qp::{lexmin, lexmin_box};
use crate::scene::Scene;

/// A newly found interfering pair: its placed obstacle and (fixed piece, moving piece).
type Detected = (Obstacle, (usize, usize));
use apart_kernel::{rational, Aabb, Bvh, HPoint, Rational};
use apart_pieces::interference::interiors_meet_translated;
use apart_pieces::Polytope;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;
use std::time::Instant;

/// Where the part may go.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Region {
    /// The translations themselves lie in this box (Ω given directly; equal `lo` and
    /// `hi` on z make it a plane: 2-D positions).
    Translations(Aabb<Rational>),
    /// The whole part must lie inside this box (Σ: floor area times the maximum
    /// height); Ω(θ) follows from the part's extent in each orientation.
    Container(Aabb<Rational>),
}

impl Region {
    /// Ω for the part in one orientation: the allowed translations (empty when the
    /// part does not fit).
    pub(crate) fn omega(&self, part: &OrientedPart) -> Aabb<Rational> {
        match self {
            Region::Translations(b) => b.clone(),
            Region::Container(s) => Aabb {
                min: rational::sub(&s.min, &part.extent.min),
                max: rational::sub(&s.max, &part.extent.max),
            },
        }
    }
}

/// The cost to minimize, a convex quadratic in the translation for each orientation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Cost {
    /// `‖p − p_d‖²` for a desired translation `p_d`.
    Distance([Rational; 3]),
    /// Paper 004 eq. (1) for the new part: `w [(max X − x0)² + (min X − x0)²] +
    /// w [(max Y − y0)² + (min Y − y0)²] + 4 (1 − w) (z_cg − z0)²` over the placed
    /// part's vertices and centre of gravity, with `floor = (x0, y0, z0)`.
    Stacking {
        /// Weight of floor-space use against height, in `[0, 1]`.
        w: Rational,
        /// The floor point `(x0, y0, z0)`.
        floor: [Rational; 3],
    },
    /// The same quadratic in the translation for every orientation.
    Quadratic(Box<Objective>),
}

impl Cost {
    /// The objective in the translation `p` of the part turned as `part`.
    pub(crate) fn objective(&self, part: &OrientedPart) -> Objective {
        match self {
            Cost::Distance(t) => Objective::distance(t),
            Cost::Quadratic(o) => (**o).clone(),
            Cost::Stacking { w, floor } => {
                let one_w = &Rational::from(1) - w;
                let e = &part.extent;
                let z = Rational::zero;
                let mut h = [[z(), z(), z()], [z(), z(), z()], [z(), z(), z()]];
                let mut g = [z(), z(), z()];
                let mut c = Rational::zero();
                let mut anchor = [z(), z(), z()];
                for i in 0..2 {
                    // w[(p + u − x0)² + (p + l − x0)²] = 2w p² + 2w(u + l − 2x0) p + w[(u−x0)² + (l−x0)²]
                    let (u, l) = (&e.max[i] - &floor[i], &e.min[i] - &floor[i]);
                    h[i][i] = &Rational::from(2) * w;
                    g[i] = &(&Rational::from(2) * w) * &(&u + &l);
                    c = &c + &(w * &(&(&u * &u) + &(&l * &l)));
                    anchor[i] =
                        &floor[i] - &(&(&e.max[i] + &e.min[i]) * &Rational::from_i128(1, 2));
                }
                // 4(1 − w)(p + cz − z0)²
                let dz = &part.centroid[2] - &floor[2];
                let k = &Rational::from(4) * &one_w;
                h[2][2] = k.clone();
                g[2] = &(&Rational::from(2) * &k) * &dz;
                c = &c + &(&k * &(&dz * &dz));
                anchor[2] = -&dz;
                Objective { h, g, c, anchor }
            }
        }
    }

    /// Checks the cost's parameters.
    pub(crate) fn validate(&self) -> Result<(), StackError> {
        match self {
            Cost::Stacking { w, .. } => {
                if *w < Rational::zero() || *w > Rational::from(1) {
                    return Err(StackError::Invalid(format!("weight {w} is not in [0, 1]")));
                }
                Ok(())
            }
            Cost::Quadratic(o) => Ok(o.validate()?),
            Cost::Distance(_) => Ok(()),
        }
    }
}

/// Settings of a placement.
#[derive(Clone, Debug)]
pub struct PlaceOptions {
    /// Where the part may go.
    pub region: Region,
    /// What to minimize.
    pub cost: Cost,
    /// Horizontal clearance to keep from fixed parts (robot positioning error), if any.
    pub clearance: Option<Rational>,
    /// Reuse obstacle structures inside constant-topology intervals (§IV).
    pub extrapolate: bool,
}

/// An interference-free configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// Index into the orientations of the [`Moving`] part.
    pub orientation: usize,
    /// The translation applied after turning the part.
    pub translation: [Rational; 3],
    /// The cost.
    pub cost: Rational,
    /// The tie-breaker `‖p − anchor‖²`.
    pub tie: Rational,
}

/// The part to place with its orientations prepared (rotated pieces, boxes, extents).
#[derive(Clone, Debug)]
pub struct Moving {
    /// The part.
    pub part: PartModel,
    /// The orientations tried.
    pub orientations: Vec<Orientation>,
    /// The part in each orientation.
    pub oriented: Vec<OrientedPart>,
    base_pieces: HashMap<Base, Vec<Polytope>>,
}

impl Moving {
    /// Prepares `part` in the given orientations; with `dedupe`, orientations giving
    /// the same shape up to translation are kept once.
    pub fn new(part: PartModel, orientations: &[Orientation], dedupe: bool) -> Moving {
        let orientations = if dedupe {
            distinct_orientations(&part, orientations)
        } else {
            orientations.to_vec()
        };
        let oriented = orientations.iter().map(|o| part.orient(o)).collect();
        let mut base_pieces = HashMap::default();
        for o in &orientations {
            base_pieces
                .entry(o.base)
                .or_insert_with(|| part.base_pieces(o.base));
        }
        Moving {
            part,
            orientations,
            oriented,
            base_pieces,
        }
    }
}

/// Counters and timings of placements (accumulated over every call sharing a cache).
#[derive(Clone, Copy, Debug, Default)]
pub struct PlaceStats {
    /// Orientations whose desired position was tested at least once.
    pub orientations_considered: usize,
    /// `m_new · m_fixed` summed over the orientations considered (paper 004 Table II,
    /// column 3: the pairs a complete c-space obstacle would need).
    pub pairs_total: u64,
    /// Pairs whose obstacle was added (Table II, column 4).
    pub pairs_evaluated: u64,
    /// Exact interference tests (separating axes) after the broad phase.
    pub interference_tests: u64,
    /// Seconds in interference detection (broad and narrow phase).
    pub detect_seconds: f64,
    /// Seconds subtracting obstacles and minimizing in cells.
    pub cells_seconds: f64,
    /// Cells created.
    pub cells: u64,
    /// Quadratic programs solved for candidates.
    pub qps: u64,
    /// Linear programs and quick rejections of subtractions.
    pub split: (u64, u64),
    /// Subtractions past the quick rejections, and pieces they produced.
    pub subtractions: (u64, u64),
    /// Candidates yielded.
    pub candidates: u64,
    /// Cells dropped by the stacking planner's support test before being solved or
    /// split (no position in them can be stable).
    pub unsupported: u64,
}

/// Counters and timings of obstacle construction.
#[derive(Clone, Copy, Debug, Default)]
pub struct ObstacleStats {
    /// Obstacles computed from scratch (Minkowski sums).
    pub fresh: u64,
    /// Seconds in fresh construction.
    pub fresh_seconds: f64,
    /// Obstacles extrapolated from a template.
    pub extrapolated: u64,
    /// Seconds in extrapolation (validity test and recomputation).
    pub extrapolate_seconds: f64,
    /// Template validity tests that failed (a critical angle in between).
    pub extrapolation_misses: u64,
    /// Obstacles reused from the cache (the same pair of shapes and orientation).
    pub reused: u64,
}

/// Obstacles of (fixed shape, orientation, moving piece), with the extrapolation
/// templates; shared by every placement in a plan.
#[derive(Clone, Debug, Default)]
pub(crate) struct ObstacleCache {
    exact: HashMap<(usize, usize, usize), Arc<ObstacleShape>>,
    /// The latest templates of each (fixed shape, base, moving piece), newest first:
    /// several, one per constant-topology interval met (orientations are visited in cost
    /// order, not by angle, and a template made at a critical angle is valid there only).
    /// Each with its constant-topology interval in degrees (floating point: it only
    /// picks the templates worth the exact check).
    /// An untraced template keeps the obstacle it is traced from when first used.
    templates: HashMap<TemplateKey, Vec<TemplateSlot>>,
    /// Fresh obstacles not yet made templates, by the same key: a template is built
    /// only when another orientation asks for the same pair (most pairs are met in
    /// one orientation only, and a template costs more than the obstacle).
    seeds: HashMap<TemplateKey, Vec<(usize, Arc<ObstacleShape>)>>,
    /// Counters.
    pub(crate) stats: ObstacleStats,
}

/// (fixed shape, base orientation, moving piece).
type TemplateKey = (usize, Base, usize);

/// A template, its interval (degrees, floating point), and until it is first used the
/// obstacle to trace it from.
type TemplateSlot = ((f64, f64), Template, Option<(usize, Arc<ObstacleShape>)>);

/// Templates kept per (fixed shape, base, moving piece).
const MAX_TEMPLATES: usize = 4;

impl ObstacleCache {
    /// An empty cache.
    pub(crate) fn new() -> ObstacleCache {
        ObstacleCache::default()
    }

    /// The obstacle of fixed shape `s` for moving piece `a` in orientation `o`.
    pub(crate) fn get(
        &mut self,
        scene: &Scene,
        moving: &Moving,
        s: usize,
        o: usize,
        a: usize,
        extrapolate: bool,
    ) -> Result<Arc<ObstacleShape>, StackError> {
        if let Some(x) = self.exact.get(&(s, o, a)) {
            self.stats.reused += 1;
            return Ok(x.clone());
        }
        let orient = moving.orientations[o];
        let fixed = &scene.shapes()[s];
        let key = (s, orient.base, a);
        if extrapolate {
            let deg = orient.theta.angle_deg();
            let inside = |&(lo, hi): &(f64, f64)| {
                // θ or θ ± 360° within the interval, with a margin for rounding.
                [deg - 360.0, deg, deg + 360.0]
                    .iter()
                    .any(|d| lo - 1e-6 <= *d && *d <= hi + 1e-6)
            };
            // Seeds become templates now that a second orientation needs the pair.
            let t0 = Instant::now();
            let base = &moving.base_pieces[&orient.base][a];
            for (o0, shape) in self.seeds.remove(&key).into_iter().flatten() {
                // A template made at a critical angle is valid there only: not kept.
                let theta0 = moving.orientations[o0].theta;
                if let Some(t) = Template::untraced(fixed, base, theta0) {
                    let (lo, hi) = t.interval_deg();
                    if hi - lo > 1e-6 {
                        let list = self.templates.entry(key).or_default();
                        list.insert(0, ((lo, hi), t, Some((o0, shape))));
                        list.truncate(MAX_TEMPLATES);
                    }
                }
            }
            self.stats.extrapolate_seconds += t0.elapsed().as_secs_f64();
            let near = self.templates.get_mut(&key).into_iter().flatten();
            for (interval, t, source) in near.filter(|(i, _, _)| inside(i)) {
                let t0 = Instant::now();
                let mut ok = t.valid_at(orient.theta);
                if ok {
                    if let Some((o0, obstacle)) = source.take() {
                        ok = t.trace(&obstacle, &moving.oriented[o0].pieces[a]);
                        if !ok {
                            *interval = (f64::INFINITY, f64::NEG_INFINITY); // never again
                        }
                    }
                }
                let shape = ok.then(|| t.extrapolate(orient.theta));
                self.stats.extrapolate_seconds += t0.elapsed().as_secs_f64();
                if let Some(shape) = shape {
                    self.stats.extrapolated += 1;
                    let shape = Arc::new(shape);
                    self.exact.insert((s, o, a), shape.clone());
                    return Ok(shape);
                }
                self.stats.extrapolation_misses += 1;
            }
        }
        let t0 = Instant::now();
        let shape = ObstacleShape::compute(fixed, &moving.oriented[o].pieces[a])
            .map_err(|e| StackError::Internal(format!("Minkowski sum: {e}")))?;
        self.stats.fresh_seconds += t0.elapsed().as_secs_f64();
        self.stats.fresh += 1;
        let shape = Arc::new(shape);
        if extrapolate {
            self.seeds.entry(key).or_default().push((o, shape.clone()));
        }
        self.exact.insert((s, o, a), shape.clone());
        Ok(shape)
    }
}

struct Slot {
    cell: Cell,
    /// The support test ([`Placer::unsupported`]) has been applied to the cell.
    checked: bool,
    /// Obstacles `0..verified` do not contain the cell's optimum in their interior.
    verified: usize,
    alive: bool,
    /// The cell's optimum, once computed (children are queued with their parent's cost,
    /// a lower bound, and solved only when popped).
    point: Option<[Rational; 3]>,
}

struct OrientState {
    omega: Aabb<Rational>,
    objective: Objective,
    obstacles: Vec<Obstacle>,
    index: ObstacleIndex,
    added: HashSet<(usize, usize)>,
    slots: Vec<Slot>,
    considered: bool,
}

#[derive(Clone, Debug)]
struct Entry {
    cost: Rational,
    tie: Rational,
    o: usize,
    cell: usize,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    /// Reversed: the cheapest entry is the greatest (`BinaryHeap` is a max-heap).
    fn cmp(&self, o: &Self) -> Ordering {
        (&o.cost, &o.tie, o.o, o.cell).cmp(&(&self.cost, &self.tie, self.o, self.cell))
    }
}

/// The placement engine for one part among fixed parts: yields interference-free
/// candidates in increasing cost.
pub(crate) struct Placer<'a> {
    scene: &'a Scene,
    moving: &'a Moving,
    cache: &'a mut ObstacleCache,
    opts: &'a PlaceOptions,
    states: Vec<Option<OrientState>>,
    heap: BinaryHeap<Entry>,
    yielded: HashSet<(usize, HPoint)>,
    split_stats: SplitStats,
    /// Counters of this placer.
    pub(crate) stats: PlaceStats,
    /// Drop cells in which no position can be stable (stacking only).
    support: Option<SupportFilter>,
    /// For each orientation, the moving pieces by decreasing box volume.
    largest_first: Vec<Vec<usize>>,
    /// The box volume of each fixed piece (as a double: it only orders detection).
    scene_volume: Vec<f64>,
}

/// The volume of a box, as a double (an order of detection, never a decision).
fn box_volume(b: &Aabb<Rational>) -> f64 {
    (0..3).map(|i| (&b.max[i] - &b.min[i]).to_f64()).product()
}

/// The stacking planner's necessary condition of stability, applied to whole cells
/// before they are solved or split: a cell is dropped when no translation in it can be
/// stable, so that none of the candidates its pieces would yield (all of them in the
/// cell, all rejected by the planner as unstable) costs any work.
///
/// Sound for the planner's stability test (`stability::stable`): a translation `p` is
/// stable only if the centre of gravity projects strictly inside the convex hull of the
/// supporting contact points. Those are vertices on the floor (only when the part's
/// lowest point is at `floor_z`) and points of fixed pieces touching the part, whose
/// boxes therefore meet the part's box at `p`. For `p` in a cell with box `C`, the part's
/// box lies in `extent ⊕ C`; with no floor contact possible, the hull lies in the xy box
/// `U` of the fixed pieces whose boxes meet `extent ⊕ C`, so the centre of gravity must
/// lie in the open box `int U`. When the box of the centre's projections over `C`
/// misses `int U` (or no fixed piece is in reach), every position of the cell is unstable.
#[derive(Clone, Debug)]
pub(crate) struct SupportFilter {
    /// Height of the floor.
    pub(crate) floor_z: Rational,
}

impl<'a> Placer<'a> {
    /// Prepares every orientation: Ω(θ), the objective, the first candidate.
    pub(crate) fn new(
        scene: &'a Scene,
        moving: &'a Moving,
        cache: &'a mut ObstacleCache,
        opts: &'a PlaceOptions,
    ) -> Result<Placer<'a>, StackError> {
        opts.cost.validate()?;
        let mut placer = Placer {
            scene,
            moving,
            cache,
            opts,
            states: Vec::new(),
            heap: BinaryHeap::new(),
            yielded: HashSet::default(),
            split_stats: SplitStats::default(),
            stats: PlaceStats::default(),
            support: None,
            largest_first: moving
                .oriented
                .iter()
                .map(|part| {
                    let v: Vec<f64> = part.boxes.iter().map(box_volume).collect();
                    let mut order: Vec<usize> = (0..v.len()).collect();
                    order.sort_by(|&x, &y| v[y].total_cmp(&v[x]));
                    order
                })
                .collect(),
            scene_volume: scene.pieces().iter().map(|p| box_volume(&p.bbox)).collect(),
        };
        for (o, part) in moving.oriented.iter().enumerate() {
            let omega = opts.region.omega(part);
            if omega.is_empty() {
                placer.states.push(None);
                continue;
            }
            let objective = opts.cost.objective(part);
            let cell = Cell::of_box(&omega);
            placer.stats.qps += 1;
            let Some(p) = cell.lexmin(&objective) else {
                placer.states.push(None);
                continue;
            };
            let key = (objective.value(&p), objective.tie(&p));
            let mut st = OrientState {
                omega,
                objective,
                obstacles: Vec::new(),
                index: ObstacleIndex::default(),
                added: HashSet::default(),
                slots: Vec::new(),
                considered: false,
            };
            placer.push_cell(o, &mut st, cell, key, Some(p));
            placer.states.push(Some(st));
        }
        Ok(placer)
    }

    /// Queues a cell under a lower bound of its cost (its parent's), optionally with its
    /// optimum already known.
    fn push_cell(
        &mut self,
        o: usize,
        st: &mut OrientState,
        cell: Cell,
        key: (Rational, Rational),
        point: Option<[Rational; 3]>,
    ) {
        self.stats.cells += 1;
        let entry = Entry {
            cost: key.0,
            tie: key.1,
            o,
            cell: st.slots.len(),
        };
        st.slots.push(Slot {
            cell,
            checked: false,
            verified: 0,
            alive: true,
            point,
        });
        self.heap.push(entry);
    }

    /// The next interference-free candidate (cheapest first), or `None` when no free
    /// space is left in any orientation.
    pub(crate) fn next_candidate(&mut self) -> Result<Option<Candidate>, StackError> {
        while let Some(e) = self.heap.pop() {
            let mut st = self.states[e.o]
                .take()
                .expect("state of a queued orientation");
            let out = self.step(&mut st, &e);
            self.states[e.o] = Some(st);
            match out? {
                Step::Continue => continue,
                Step::Yield(c) => {
                    self.stats.candidates += 1;
                    return Ok(Some(c));
                }
            }
        }
        Ok(None)
    }

    /// Drops cells in which no position can be stable ([`SupportFilter`]).
    pub(crate) fn with_support_filter(mut self, filter: SupportFilter) -> Placer<'a> {
        self.support = Some(filter);
        self
    }

    /// True when no translation in `cell` can be stable for the part in orientation `o`
    /// ([`SupportFilter`]).
    fn unsupported(&self, o: usize, cell: &Cell, filter: &SupportFilter) -> bool {
        let e = &self.moving.oriented[o].extent;
        let c = &cell.bbox;
        // The floor is reachable: the part's lowest point can be at floor_z.
        if &c.min[2] + &e.min[2] <= filter.floor_z {
            return false;
        }
        let reach = Aabb {
            min: rational::add(&c.min, &e.min),
            max: rational::add(&c.max, &e.max),
        };
        let cg = &self.moving.oriented[o].centroid;
        // The centre's projections over the cell: [lo, hi] per axis.
        let lo = [0, 1].map(|i| &c.min[i] + &cg[i]);
        let hi = [0, 1].map(|i| &c.max[i] + &cg[i]);
        // Unstable throughout when every reachable piece lies on one side of the centre's
        // box (on or beyond its side, along x or y): a possible side is struck off by the
        // first piece that reaches past it.
        // [x: pieces all at or left of lo, all at or right of hi; y: the same]
        let mut open = [true; 4];
        let mut near = Vec::new();
        self.scene.near(&reach.enclosing_f64(), &mut near);
        for k in near {
            let b = &self.scene.pieces()[k].bbox;
            let kills = [
                b.max[0] > lo[0],
                b.min[0] < hi[0],
                b.max[1] > lo[1],
                b.min[1] < hi[1],
            ];
            if (0..4).all(|j| !open[j] || !kills[j]) || !b.overlaps(&reach) {
                continue;
            }
            for j in 0..4 {
                open[j] &= !kills[j];
            }
            if open.iter().all(|o| !o) {
                return false;
            }
        }
        // Also when no piece is in reach at all: nothing to rest on.
        true
    }

    fn step(&mut self, st: &mut OrientState, e: &Entry) -> Result<Step, StackError> {
        if !st.slots[e.cell].alive {
            return Ok(Step::Continue);
        }
        if !st.slots[e.cell].checked {
            st.slots[e.cell].checked = true;
            if let Some(f) = &self.support {
                if self.unsupported(e.o, &st.slots[e.cell].cell, f) {
                    st.slots[e.cell].alive = false;
                    self.stats.unsupported += 1;
                    return Ok(Step::Continue);
                }
            }
        }
        let Some(point) = st.slots[e.cell].point.clone() else {
            // Solve the cell now and queue it under its own cost.
            let t0 = Instant::now();
            self.stats.qps += 1;
            let p = st.slots[e.cell].cell.lexmin(&st.objective);
            self.stats.cells_seconds += t0.elapsed().as_secs_f64();
            match p {
                None => st.slots[e.cell].alive = false,
                Some(p) => {
                    let entry = Entry {
                        cost: st.objective.value(&p),
                        tie: st.objective.tie(&p),
                        o: e.o,
                        cell: e.cell,
                    };
                    st.slots[e.cell].point = Some(p);
                    self.heap.push(entry);
                }
            }
            return Ok(Step::Continue);
        };
        let n = st.obstacles.len();
        if st.slots[e.cell].verified < n {
            // Lazy subtraction: only an obstacle containing the cell's optimum in its
            // interior matters now; the cell is split by the first such one, and the
            // pieces are checked again against every obstacle when they come up.
            let t0 = Instant::now();
            let p = HPoint::from_rationals(&point);
            let from = st.slots[e.cell].verified;
            let mut near = st.index.containing(&point, from);
            near.sort_unstable();
            let hit = near
                .into_iter()
                .find(|&k| st.obstacles[k].contains_open(&p));
            match hit {
                None => st.slots[e.cell].verified = n,
                Some(k) => {
                    st.slots[e.cell].alive = false;
                    let cell = st.slots[e.cell].cell.clone();
                    let split = subtract(
                        &cell,
                        &st.obstacles[k],
                        &st.omega,
                        std::slice::from_ref(&p),
                        &mut self.split_stats,
                    );
                    let pieces = match split {
                        Split::Unchanged => vec![(cell, None)],
                        Split::Pieces(ps) => ps,
                    };
                    for (piece, cut) in pieces {
                        // A lower bound of the piece: its parent's, or the optimum over
                        // the half-space that cut it off when that is larger.
                        let mut key = (e.cost.clone(), e.tie.clone());
                        if let Some(h) = cut {
                            self.stats.qps += 1;
                            match half_space_lexmin(&h, &st.objective) {
                                Some(b) => {
                                    let b = (st.objective.value(&b), st.objective.tie(&b));
                                    if b > key {
                                        key = b;
                                    }
                                }
                                None => continue,
                            }
                        }
                        self.push_cell(e.o, st, piece, key, None);
                    }
                    self.stats.split = (
                        self.split_stats.linear_programs as u64,
                        self.split_stats.quick_rejects as u64,
                    );
                    self.stats.subtractions =
                        (self.split_stats.full as u64, self.split_stats.pieces as u64);
                    self.stats.cells_seconds += t0.elapsed().as_secs_f64();
                    return Ok(Step::Continue);
                }
            }
            self.stats.cells_seconds += t0.elapsed().as_secs_f64();
        }
        if !st.considered {
            st.considered = true;
            self.stats.orientations_considered += 1;
            let m = self.moving.oriented[e.o].pieces.len() as u64;
            self.stats.pairs_total += m * self.scene.pieces().len() as u64;
        }
        let p = HPoint::from_rationals(&point);
        let t0 = Instant::now();
        let pairs = self.detect(e.o, st, &point, &p)?;
        self.stats.detect_seconds += t0.elapsed().as_secs_f64();
        if pairs.is_empty() {
            st.slots[e.cell].alive = false;
            if !self.yielded.insert((e.o, p)) {
                return Ok(Step::Continue);
            }
            return Ok(Step::Yield(Candidate {
                orientation: e.o,
                translation: point,
                cost: e.cost.clone(),
                tie: e.tie.clone(),
            }));
        }
        for (obstacle, key) in pairs {
            st.index.push(obstacle.bbox.as_ref());
            st.obstacles.push(obstacle);
            st.added.insert(key);
            self.stats.pairs_evaluated += 1;
        }
        self.heap.push(e.clone());
        Ok(Step::Continue)
    }

    /// A pair (fixed piece, moving piece) interfering at `p` (or closer than the
    /// clearance) not yet among the orientation's obstacles, with its placed obstacle;
    /// empty when there is none (`p` is free).
    ///
    /// One pair, not all: the candidate leaves the first obstacle (the cell is split by
    /// it), and where it lands the other pairs interfering at `p` often no longer do, so
    /// their obstacles would only cut the free space into more cells. Pairs of the largest
    /// pieces come first (moving piece, then fixed piece, by box volume): their obstacles
    /// cover the most, so fewer are needed. Complex stack: 139,671 -> 6,616 pairs
    /// evaluated, 508k -> 61k cells.
    fn detect(
        &mut self,
        o: usize,
        st: &OrientState,
        pq: &[Rational; 3],
        p: &HPoint,
    ) -> Result<Vec<Detected>, StackError> {
        let part = &self.moving.oriented[o];
        let clearance = self.opts.clearance.as_ref().filter(|c| !c.is_zero());
        let mut out = Vec::new();
        let mut near = Vec::new();
        for &a in &self.largest_first[o] {
            let b = &part.boxes[a];
            let mut fb = b.translated(pq).enclosing_f64();
            if let Some(c) = clearance {
                let c = c.to_f64() * (1.0 + 1e-6);
                for v in fb.min.iter_mut().take(2) {
                    *v -= c;
                }
                for v in fb.max.iter_mut().take(2) {
                    *v += c;
                }
            }
            near.clear();
            self.scene.near(&fb, &mut near);
            let volume = &self.scene_volume;
            near.sort_by(|&x, &y| volume[y].total_cmp(&volume[x]));
            for &k in &near {
                if st.added.contains(&(k, a)) {
                    continue;
                }
                let sp = &self.scene.pieces()[k];
                self.stats.interference_tests += 1;
                let hit = match clearance {
                    None => interiors_meet_translated(
                        &part.pieces[a],
                        &p.sub(&sp.translation),
                        &self.scene.shapes()[sp.shape],
                    ),
                    Some(c) => {
                        let shape = self.cache.get(
                            self.scene,
                            self.moving,
                            sp.shape,
                            o,
                            a,
                            self.opts.extrapolate,
                        )?;
                        shape.placed(&sp.translation, Some(c)).contains_open(p)
                    }
                };
                if hit {
                    let shape = self.cache.get(
                        self.scene,
                        self.moving,
                        sp.shape,
                        o,
                        a,
                        self.opts.extrapolate,
                    )?;
                    out.push((shape.placed(&sp.translation, clearance), (k, a)));
                    // One pair is enough to move on (see `detect`).
                    return Ok(out);
                }
            }
        }
        Ok(out)
    }
}

/// The lexicographic minimizer of `obj` over one half-space ([`lexmin`]; in closed form
/// for an axis-aligned half-space and a diagonal objective, the same point).
fn half_space_lexmin(h: &apart_kernel::BigPlane, obj: &Objective) -> Option<[Rational; 3]> {
    let axis: Vec<usize> = (0..3).filter(|&i| !h.n[i].is_zero()).collect();
    if let [i] = axis[..] {
        let v = Rational::new(h.c.clone(), h.n[i].clone());
        let mut lo = [None, None, None];
        let mut hi = [None, None, None];
        if h.n[i] > apart_kernel::Int::ZERO {
            hi[i] = Some(&v);
        } else {
            lo[i] = Some(&v);
        }
        if let Some(p) = lexmin_box(lo, hi, obj) {
            return p;
        }
    }
    lexmin(std::slice::from_ref(h), obj)
}

/// The boxes of an orientation's obstacles, for finding those that may contain a point:
/// a hierarchy rebuilt whenever the list has doubled, and a list of the newer ones.
/// An obstacle without a box (grown by a clearance) may contain any point.
#[derive(Default)]
struct ObstacleIndex {
    /// Each obstacle's box (outward-rounded), if known.
    boxes: Vec<Option<Aabb<f64>>>,
    /// The hierarchy over the first `built` boxes (no box: the empty box).
    bvh: Bvh<f64>,
    /// The obstacles without a box among the first `built`.
    unbounded: Vec<usize>,
    built: usize,
}

impl ObstacleIndex {
    fn push(&mut self, b: Option<&Aabb<Rational>>) {
        self.boxes.push(b.map(Aabb::enclosing_f64));
        if self.boxes.len() >= 2 * self.built.max(16) {
            let boxes = self
                .boxes
                .iter()
                .map(|b| b.unwrap_or(Aabb::EMPTY))
                .collect();
            self.bvh = Bvh::new(boxes);
            self.unbounded = (0..self.boxes.len())
                .filter(|&k| self.boxes[k].is_none())
                .collect();
            self.built = self.boxes.len();
        }
    }

    /// Indices `>= from` of obstacles whose (outward-rounded) box contains `p`, or that
    /// have no box, in no particular order.
    fn containing(&self, p: &[Rational; 3], from: usize) -> Vec<usize> {
        let q = Aabb::point(&p.clone().map(|v| v.to_f64()));
        let mut out = Vec::new();
        if from < self.built {
            self.bvh.query(&q, |k| {
                if k as usize >= from {
                    out.push(k as usize);
                }
            });
            out.extend(self.unbounded.iter().filter(|&&k| k >= from));
        }
        for k in self.built.max(from)..self.boxes.len() {
            if self.boxes[k].is_none_or(|b| b.overlaps(&q)) {
                out.push(k);
            }
        }
        out
    }
}

enum Step {
    Continue,
    Yield(Candidate),
}

/// The result of [`place`].
#[derive(Clone, Debug)]
pub struct Placement {
    /// Interference-free candidates, cheapest first.
    pub candidates: Vec<Candidate>,
    /// Counters of the placement.
    pub stats: PlaceStats,
    /// Counters of obstacle construction.
    pub obstacles: ObstacleStats,
}

/// Up to `count` interference-free configurations of `moving` among the fixed parts of
/// `scene`, in increasing cost (one per free-space cell).
pub fn place(
    scene: &Scene,
    moving: &Moving,
    opts: &PlaceOptions,
    count: usize,
) -> Result<Placement, StackError> {
    let mut cache = ObstacleCache::new();
    let (candidates, stats) = {
        let mut placer = Placer::new(scene, moving, &mut cache, opts)?;
        let mut out = Vec::new();
        while out.len() < count {
            match placer.next_candidate()? {
                Some(c) => out.push(c),
                None => break,
            }
        }
        (out, placer.stats)
    };
    Ok(Placement {
        candidates,
        stats,
        obstacles: cache.stats,
    })
}

/// The best configuration for one orientation with the complete c-space obstacle (every
/// pair's obstacle subtracted): the reference partial c-space must agree with (§V-B).
pub fn best_full(
    scene: &Scene,
    moving: &Moving,
    opts: &PlaceOptions,
    o: usize,
) -> Result<Option<Candidate>, StackError> {
    let part = &moving.oriented[o];
    let omega = opts.region.omega(part);
    if omega.is_empty() {
        return Ok(None);
    }
    let mut cache = ObstacleCache::new();
    let clearance = opts.clearance.as_ref().filter(|c| !c.is_zero());
    let mut cells = vec![Cell::of_box(&omega)];
    let mut st = SplitStats::default();
    for sp in scene.pieces() {
        for a in 0..part.pieces.len() {
            let shape = cache.get(scene, moving, sp.shape, o, a, false)?;
            let ob = shape.placed(&sp.translation, clearance);
            let mut next = Vec::new();
            for c in cells {
                match subtract(&c, &ob, &omega, &[], &mut st) {
                    Split::Unchanged => next.push(c),
                    Split::Pieces(ps) => next.extend(ps.into_iter().map(|(p, _)| p)),
                }
            }
            cells = next;
        }
    }
    let obj = opts.cost.objective(part);
    let best = cells
        .iter()
        .filter_map(|c| c.lexmin(&obj))
        .map(|p| (obj.value(&p), obj.tie(&p), p))
        .min_by(|x, y| (&x.0, &x.1).cmp(&(&y.0, &y.1)));
    Ok(best.map(|(cost, tie, translation)| Candidate {
        orientation: o,
        translation,
        cost,
        tie,
    }))
}
