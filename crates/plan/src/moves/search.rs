//! Breadth-first search over the states of one subassembly, to the first move that
//! separates it.
//!
//! A state holds every part's offset relative to the subassembly's first part (which
//! never moves: a move of a set `S` along `d` is the move of the rest along `−d`), as
//! exact rationals, so states are told apart exactly. From a state, every candidate
//! direction is met with every pair's obstacles once; a moving set must then contain
//! every part that a part of it pushes on at once, and goes as far as its first
//! blocking distance, stopping on the way where a contact begins or ends (and, along
//! an axis, at every grid step).

use super::directions::{axes, candidates};
use super::obstacles::{contact_normals, ray_facts, PairObstacles, RayFacts};
use crate::progress::Progress;
use apart_kernel::{Rational, Vec3};
use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};

/// Positions of a subassembly's parts, relative to its first part.
pub type State = Box<[[Rational; 3]]>;

/// A state as a node keeps it: integer offsets (on the grid, the usual case) as machine
/// words, three per part, else exactly.
#[derive(Clone, PartialEq, Eq)]
enum Packed {
    Ints(Box<[i64]>),
    Exact(State),
}

impl Packed {
    fn of(s: &[[Rational; 3]]) -> Packed {
        let mut words = Vec::with_capacity(s.len() * 3);
        for c in s.iter().flatten() {
            match c.as_small() {
                Some((n, 1)) => words.push(n),
                _ => return Packed::Exact(s.into()),
            }
        }
        Packed::Ints(words.into_boxed_slice())
    }

    fn unpack(&self) -> State {
        match self {
            Packed::Ints(w) => w
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]].map(Rational::from))
                .collect(),
            Packed::Exact(s) => s.clone(),
        }
    }
}

/// A state's identity: its [`Packed`] form with a well-mixed hash computed once (offsets
/// are multiples of large powers of two on the grid, which weak hashes bucket badly).
#[derive(PartialEq, Eq)]
struct Key(u64, Packed);

impl std::hash::Hash for Key {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        h.write_u64(self.0)
    }
}

/// splitmix64's finaliser.
fn mix(mut x: u64) -> u64 {
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

impl Key {
    fn of(packed: Packed) -> Key {
        let x = match &packed {
            Packed::Ints(w) => w
                .iter()
                .fold(0x9e37_79b9_7f4a_7c15u64, |h, &v| mix(h ^ v as u64)),
            Packed::Exact(s) => {
                let mut h = rustc_hash::FxHasher::default();
                std::hash::Hash::hash(s, &mut h);
                mix(std::hash::Hasher::finish(&h))
            }
        };
        Key(x, packed)
    }
}

/// A move within one subassembly: the parts of `moving` (bits of the subassembly's
/// local indices) translate by `distance × direction`, or to infinity.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LocalMove {
    /// Local indices as bits (never bit 0, the part that stays).
    pub moving: u64,
    /// A primitive integer direction.
    pub direction: Vec3,
    /// `None` for a move to infinity.
    pub distance: Option<Rational>,
}

/// How a search ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The moves up to and including the first move to infinity.
    Separated(Vec<LocalMove>),
    /// Every state reachable under the move model was explored: none separates.
    Exhausted,
    /// No separation within the move limit (every state within it explored).
    MoveLimit,
    /// The state limit was reached first.
    StateLimit,
    /// The stop flag was raised.
    Stopped,
}

/// What one search needs to know.
pub struct Search<'a> {
    /// Obstacles of local part `a` moving against `b` fixed, for `a < b` (index
    /// `a * m + b`); the offset difference they take is `p_a − p_b`.
    pub obstacles: Vec<Option<&'a PairObstacles>>,
    /// Parts in the subassembly.
    pub m: usize,
    /// Only the six axis directions.
    pub axes_only: bool,
    /// The grid step along each axis (moves along an axis stop at every one).
    pub steps: [Option<Rational>; 3],
    /// Groups of congruent parts (local indices, never part 0) and every part's anchor
    /// (a vertex that congruent parts share), for symmetric states.
    pub classes: Vec<Vec<usize>>,
    /// Each part's anchor.
    pub anchors: Vec<[Rational; 3]>,
    /// Moves allowed (the last one to infinity included).
    pub max_moves: usize,
    /// States allowed.
    pub max_states: usize,
}

/// Stopping distances allowed per move beyond the farthest one.
pub const MAX_STOPS: usize = 64;

/// Moving sets tried from each state are every subset up to this many parts, closures
/// of one part beyond.
pub const ALL_SUBSETS_UP_TO: usize = 13;

/// Takes each move from a state with the state it reaches (`None`: to infinity);
/// false stops the expansion.
type Visit<'a> = dyn FnMut(LocalMove, Option<&[[Rational; 3]]>) -> bool + 'a;

/// Nodes expanded in parallel at a time.
const BATCH: usize = 256;

/// What expanding one node gave.
enum Expansion {
    /// It is at the move limit.
    TooDeep,
    /// A move to infinity (the first found).
    Leaves(LocalMove),
    /// Every move to a finite position, with its state and key.
    Children(Vec<(LocalMove, Packed, Key)>),
}

struct Node {
    state: Packed,
    parent: u32,
    depth: u32,
    mv: Option<LocalMove>,
}

/// The facts of every ordered pair along one direction.
struct Table {
    m: usize,
    /// First blocking distance of `a` moving against `b` fixed, at `a * m + b`.
    tau: Vec<Option<Rational>>,
    events: Vec<Vec<Rational>>,
    /// Bits of the parts that block `a` at once.
    pushes: Vec<u64>,
}

impl<'a> Search<'a> {
    fn table(&self, s: &State, d: &[Rational; 3]) -> Table {
        let m = self.m;
        let mut tau = vec![None; m * m];
        let mut events = vec![Vec::new(); m * m];
        let mut pushes = vec![0u64; m];
        for a in 0..m {
            for b in a + 1..m {
                let r = apart_kernel::rational::sub(&s[a], &s[b]);
                let f: RayFacts = ray_facts(self.obstacles[a * m + b].expect("a pair"), &r, d);
                if f.forward.as_ref().is_some_and(|t| t.is_zero()) {
                    pushes[a] |= 1 << b;
                }
                if f.backward.as_ref().is_some_and(|t| t.is_zero()) {
                    pushes[b] |= 1 << a;
                }
                tau[a * m + b] = f.forward;
                tau[b * m + a] = f.backward;
                events[a * m + b] = f.forward_events;
                events[b * m + a] = f.backward_events;
            }
        }
        Table {
            m,
            tau,
            events,
            pushes,
        }
    }

    fn directions(&self, s: &State) -> Vec<Vec3> {
        if self.axes_only {
            return axes();
        }
        let m = self.m;
        let mut normals = Vec::new();
        for a in 0..m {
            for b in a + 1..m {
                let r = apart_kernel::rational::sub(&s[a], &s[b]);
                contact_normals(self.obstacles[a * m + b].expect("a pair"), &r, &mut normals);
            }
        }
        candidates(&normals)
    }

    /// The state as it is told apart from others: congruent parts sorted by where
    /// they are, packed into machine words when its numbers are small.
    fn key(&self, s: &[[Rational; 3]]) -> Key {
        let sorted;
        let s = if self.classes.is_empty() {
            s
        } else {
            sorted = self.canonical(s);
            &sorted
        };
        Key::of(Packed::of(s))
    }

    fn canonical(&self, s: &[[Rational; 3]]) -> State {
        let mut out: Vec<[Rational; 3]> = Vec::with_capacity(s.len());
        for (k, p) in s.iter().enumerate() {
            if !self.classes.iter().any(|c| c.contains(&k)) {
                out.push(p.clone());
            }
        }
        for c in &self.classes {
            let mut at: Vec<[Rational; 3]> = c
                .iter()
                .map(|&k| apart_kernel::rational::add(&self.anchors[k], &s[k]))
                .collect();
            at.sort();
            out.extend(at);
        }
        out.into_boxed_slice()
    }

    /// Searches from `start` (offsets relative to part 0). `extra` gives more moves to
    /// infinity to try at the start when its own candidates find none.
    pub fn run(
        &self,
        start: State,
        extra: &mut dyn FnMut() -> Vec<LocalMove>,
        progress: &Progress,
    ) -> (Outcome, usize) {
        let mut seen: FxHashSet<Key> = FxHashSet::default();
        seen.insert(self.key(&start));
        let mut nodes = vec![Node {
            state: Packed::of(&start),
            parent: u32::MAX,
            depth: 0,
            mv: None,
        }];
        let mut limited = false;
        let mut i = 0;
        while i < nodes.len() {
            if progress.stopped() {
                return (Outcome::Stopped, nodes.len());
            }
            progress.report(crate::progress::phases::MOVES, nodes.len(), self.max_states);
            // A batch of nodes expanded in parallel, then taken in order: the same
            // search, node for node, as one at a time.
            let end = nodes.len().min(i + BATCH);
            let seen_now = &seen;
            let results: Vec<Expansion> = nodes[i..end]
                .par_iter()
                .map(|n| {
                    if n.depth as usize + 1 > self.max_moves {
                        return Expansion::TooDeep;
                    }
                    let mut out = Expansion::Children(Vec::new());
                    self.expand(
                        &n.state.unpack(),
                        &mut |mv, state| match (state, &mut out) {
                            (None, _) => {
                                out = Expansion::Leaves(mv);
                                false
                            }
                            (Some(s), Expansion::Children(c)) => {
                                // States seen before this batch are dropped here, in parallel.
                                let key = self.key(s);
                                if !seen_now.contains(&key) {
                                    c.push((mv, Packed::of(s), key));
                                }
                                true
                            }
                            _ => false,
                        },
                    );
                    out
                })
                .collect();
            for (k, result) in results.into_iter().enumerate() {
                let at = i + k;
                let found = match result {
                    Expansion::TooDeep => {
                        limited = true;
                        continue;
                    }
                    Expansion::Leaves(mv) => Some(mv),
                    Expansion::Children(c) => {
                        let esc = if at == 0 {
                            extra().into_iter().next()
                        } else {
                            None
                        };
                        if esc.is_none() && !self.insert(&mut nodes, &mut seen, at, c) {
                            return (Outcome::StateLimit, nodes.len());
                        }
                        esc
                    }
                };
                if let Some(esc) = found {
                    let mut path = vec![esc];
                    let mut k = at;
                    while let Some(mv) = &nodes[k].mv {
                        path.push(mv.clone());
                        k = nodes[k].parent as usize;
                    }
                    path.reverse();
                    return (Outcome::Separated(path), nodes.len());
                }
            }
            i = end;
        }
        let outcome = if limited {
            Outcome::MoveLimit
        } else {
            Outcome::Exhausted
        };
        (outcome, nodes.len())
    }

    /// Adds the new states among `children` of node `at`; false at the state limit.
    fn insert(
        &self,
        nodes: &mut Vec<Node>,
        seen: &mut FxHashSet<Key>,
        at: usize,
        children: Vec<(LocalMove, Packed, Key)>,
    ) -> bool {
        let depth = nodes[at].depth + 1;
        for (mv, s, key) in children {
            if nodes.len() >= self.max_states {
                return false;
            }
            if seen.insert(key) {
                nodes.push(Node {
                    state: s,
                    parent: at as u32,
                    depth,
                    mv: Some(mv),
                });
            }
        }
        true
    }

    /// Hands every move from `s` to `each` (`None` as the state for a move to
    /// infinity); stops when `each` returns false.
    fn expand(&self, s: &State, each: &mut Visit<'_>) {
        let m = self.m;
        let mut next: Vec<[Rational; 3]> = s.to_vec();
        for d in self.directions(s) {
            let dr = [0, 1, 2].map(|k| Rational::from_int(d.get(k)));
            let t = self.table(s, &dr);
            let axis = match dr.iter().filter(|c| !c.is_zero()).count() {
                1 => (0..3).find(|&k| !dr[k].is_zero()),
                _ => None,
            };
            let step = axis.and_then(|k| self.steps[k].clone());
            let mut sets: Vec<u64> = Vec::new();
            moving_sets(m, &t.pushes, &mut sets);
            for set in sets {
                let Some(far) = farthest(&t, set) else {
                    let mv = LocalMove {
                        moving: set,
                        direction: d.clone(),
                        distance: None,
                    };
                    if !each(mv, None) {
                        return;
                    }
                    continue;
                };
                for dist in stops(&t, set, &far, step.as_ref()) {
                    next.clone_from_slice(s);
                    for (k, p) in next.iter_mut().enumerate() {
                        if set >> k & 1 == 1 {
                            *p = [0, 1, 2].map(|c| &p[c] + &(&dr[c] * &dist));
                        }
                    }
                    let mv = LocalMove {
                        moving: set,
                        direction: d.clone(),
                        distance: Some(dist),
                    };
                    if !each(mv, Some(&next)) {
                        return;
                    }
                }
            }
        }
    }
}

/// The bit set of all `m` parts of a subassembly.
pub(crate) fn all_parts(m: usize) -> u64 {
    if m == 64 {
        u64::MAX
    } else {
        (1u64 << m) - 1
    }
}

/// Moving sets (never holding part 0) closed under "pushes at once": every subset for
/// small subassemblies, the closures of one part and the complements of what one part
/// and part 0 push beyond.
fn moving_sets(m: usize, pushes: &[u64], out: &mut Vec<u64>) {
    let closed = |s: u64| (0..m).all(|a| s >> a & 1 == 0 || pushes[a] & !s == 0);
    if m <= ALL_SUBSETS_UP_TO {
        for half in 1u64..1 << (m - 1) {
            let s = half << 1;
            if closed(s) {
                out.push(s);
            }
        }
        return;
    }
    let closure = |seed: u64, next: &dyn Fn(usize) -> u64| {
        let mut s = seed;
        loop {
            let mut t = s;
            for a in 0..m {
                if s >> a & 1 == 1 {
                    t |= next(a);
                }
            }
            if t == s {
                return s;
            }
            s = t;
        }
    };
    let pulled = |b: usize| {
        (0..m)
            .filter(|&a| pushes[a] >> b & 1 == 1)
            .fold(0u64, |x, a| x | 1 << a)
    };
    let all = all_parts(m);
    let mut seen = FxHashMap::default();
    for a in 1..m {
        let s = closure(1 << a, &|k| pushes[k]);
        if s & 1 == 0 {
            seen.entry(s).or_insert(());
        }
        let rest = closure(1 | 1 << a, &pulled);
        let s = all & !rest;
        if s != 0 {
            seen.entry(s).or_insert(());
        }
    }
    let mut v: Vec<u64> = seen.into_keys().collect();
    v.sort_unstable();
    out.extend(v);
}

/// The distance `set` can go before a part of it enters a part outside it (`None`:
/// for ever).
fn farthest(t: &Table, set: u64) -> Option<Rational> {
    let m = t.m;
    let mut best: Option<Rational> = None;
    for a in (0..m).filter(|&a| set >> a & 1 == 1) {
        for b in (0..m).filter(|&b| set >> b & 1 == 0) {
            if let Some(x) = &t.tau[a * m + b] {
                if best.as_ref().is_none_or(|y| x < y) {
                    best = Some(x.clone());
                }
            }
        }
    }
    best
}

/// Where a move of `set` may stop: where contacts begin or end before `far` (at most
/// [`MAX_STOPS`], the nearest), every grid step before it (`step`, when there are at
/// most [`MAX_STOPS`]), and `far` itself.
fn stops(t: &Table, set: u64, far: &Rational, step: Option<&Rational>) -> Vec<Rational> {
    let m = t.m;
    let mut out: Vec<Rational> = Vec::new();
    for a in (0..m).filter(|&a| set >> a & 1 == 1) {
        for b in (0..m).filter(|&b| set >> b & 1 == 0) {
            out.extend(t.events[a * m + b].iter().filter(|e| *e < far).cloned());
        }
    }
    if let Some(g) = step {
        let n = (far / g).as_small().map_or(0, |(n, d)| n.div_euclid(d));
        if (1..=MAX_STOPS as i64).contains(&n) {
            out.extend((1..=n).map(|k| g * &Rational::from(k)));
        }
    }
    out.sort();
    out.dedup();
    out.retain(|e| e < far);
    out.truncate(MAX_STOPS);
    out.push(far.clone());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_states_round_trip_and_key_equal_states_alike() {
        let ints: Vec<[Rational; 3]> = vec![
            [0, 0, 0].map(Rational::from),
            [3, -4, 1 << 40].map(Rational::from),
        ];
        let half: Vec<[Rational; 3]> = vec![
            [0, 0, 0].map(Rational::from),
            [Rational::from_i128(1, 2), 0.into(), 0.into()],
        ];
        for s in [&ints, &half] {
            assert_eq!(&*Packed::of(s).unpack(), s.as_slice());
            assert!(Key::of(Packed::of(s)) == Key::of(Packed::of(&s.clone())));
        }
        assert!(matches!(Packed::of(&ints), Packed::Ints(_)));
        assert!(matches!(Packed::of(&half), Packed::Exact(_)));
        assert!(Key::of(Packed::of(&ints)) != Key::of(Packed::of(&half)));
    }
}
