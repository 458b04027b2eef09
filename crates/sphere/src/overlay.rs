//! Overlay of region maps: which maps cover each vertex, edge and face.
//!
//! Each input arc belongs to one *map* (a region of the sphere, e.g. an open polygon or
//! the blocked set of a pair of parts) and carries that map's status on its positive
//! side, on the arc itself, and on its negative side. Input points carry a map's status
//! at a point. From one exactly evaluated face, statuses spread face to face across
//! edges: crossing an edge only changes the maps that have an arc on it, and to the
//! value that arc gives for the side entered (the Wilson–Schweikard crossing rule with
//! coinciding arcs handled label by label). An edge has the statuses of its faces except
//! for maps with an arc on it; a vertex those of its faces except for maps with an arc
//! through it or a point at it.

use crate::arrangement::{ArcLabel, Arrangement, EdgeId};
use crate::bitset::{BitSet, MapSet};
use crate::polygon::perpendicular;
use apart_kernel::Vec3;
use rayon::prelude::*;
use std::collections::VecDeque;

/// Cells per parallel task when the statuses of edges and vertices are derived (an
/// arrangement of fewer cells stays on the calling thread).
const CELLS_PER_TASK: usize = 1 << 14;

/// A map's status around an arc: on its positive side (`normal · x > 0`), on the arc,
/// and on its negative side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SideLabel {
    /// Map index.
    pub map: u32,
    /// Status on the positive side.
    pub pos: bool,
    /// Status on the arc.
    pub on: bool,
    /// Status on the negative side.
    pub neg: bool,
}

impl ArcLabel for SideLabel {
    fn flipped(&self) -> SideLabel {
        SideLabel {
            pos: self.neg,
            neg: self.pos,
            ..*self
        }
    }
}

/// A map's status at a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PointStatus {
    /// Map index.
    pub map: u32,
    /// Status at the point.
    pub on: bool,
}

/// An arrangement of region-map arcs and points.
pub type RegionArrangement = Arrangement<SideLabel, PointStatus>;

/// The set of maps whose status is `true` at a cell: dense bits ([`BitSet`]) for few maps,
/// a sorted list ([`MapSet`]) when there are many and few cover any one cell.
pub trait Status: Clone + PartialEq + std::fmt::Debug + Send + Sync {
    /// The empty set for `maps` maps.
    fn empty(maps: usize) -> Self;
    /// Sets map `map` to `on`.
    fn assign(&mut self, map: usize, on: bool);
    /// Applies `changes` in order (a later change of a map wins); may reorder them.
    fn assign_all(&mut self, changes: &mut [(u32, bool)]) {
        for &(m, on) in changes.iter() {
            self.assign(m as usize, on);
        }
    }
}

impl Status for BitSet {
    fn empty(maps: usize) -> Self {
        BitSet::new(maps)
    }
    fn assign(&mut self, map: usize, on: bool) {
        self.set(map, on);
    }
}

impl Status for MapSet {
    fn empty(_maps: usize) -> Self {
        MapSet::new()
    }
    fn assign(&mut self, map: usize, on: bool) {
        self.set(map, on);
    }
    fn assign_all(&mut self, changes: &mut [(u32, bool)]) {
        if changes.len() <= 4 || self.is_inline() {
            for &(m, on) in changes.iter() {
                self.set(m as usize, on);
            }
        } else {
            // One merge instead of an insertion per change (an edge where many pairs'
            // arcs coincide carries many labels).
            changes.sort_by_key(|c| c.0); // stable: the last change of a map stays last
            self.merge(changes);
        }
    }
}

/// For every cell, the set of maps whose status there is `true`.
#[derive(Clone, Debug)]
pub struct CellStatuses<S = BitSet> {
    /// Per vertex.
    pub vertices: Vec<S>,
    /// Per edge.
    pub edges: Vec<S>,
    /// Per face.
    pub faces: Vec<S>,
    /// Per boundary cycle (equal to its face's).
    pub cycles: Vec<S>,
}

/// Computes the statuses of `maps` maps on every cell of `arr`.
///
/// `oracle(x, y)` must return the exact statuses of all maps at the points `x + εy` for
/// every small enough `ε > 0` (a symbolic perturbation); it is called once.
pub fn cell_statuses<S: Status>(
    arr: &RegionArrangement,
    maps: usize,
    oracle: impl Fn(&Vec3, &Vec3) -> S,
) -> CellStatuses<S> {
    let point_override = |v: usize, s: &mut S| {
        for l in &arr.vertices()[v].labels {
            s.assign(l.map as usize, l.on);
        }
    };
    if arr.edges().is_empty() {
        // One face: the sphere minus isolated points.
        let x = arr
            .vertices()
            .first()
            .map_or(Vec3::new(0, 0, 1), |v| v.point.clone());
        let face = oracle(&x, &perpendicular(&x));
        let vertices = (0..arr.vertices().len())
            .map(|v| {
                let mut s = face.clone();
                point_override(v, &mut s);
                s
            })
            .collect();
        return CellStatuses {
            vertices,
            edges: Vec::new(),
            faces: vec![face],
            cycles: Vec::new(),
        };
    }

    // Exact statuses just left of edge 0 (its positive side), then breadth-first.
    let e0 = EdgeId::new(0);
    let a0 = arr.edge_arc(e0);
    let start = oracle(&a0.interior_point(), &a0.normal);
    let mut cycles: Vec<Option<S>> = vec![None; arr.cycle_count()];
    let c0 = arr.cycle(e0.forward());
    cycles[c0.index()] = Some(start);
    let mut queue = VecDeque::from([c0]);
    let mut changes: Vec<(u32, bool)> = Vec::new();
    while let Some(c) = queue.pop_front() {
        let status = cycles[c.index()].clone().unwrap();
        for h in arr.cycle_half_edges(c) {
            let twin = h.twin();
            let d = arr.cycle(twin);
            if cycles[d.index()].is_some() && !cfg!(debug_assertions) {
                continue;
            }
            let mut s = status.clone();
            let forward = twin.is_forward();
            changes.clear();
            changes.extend(
                arr.edge(h.edge())
                    .labels
                    .iter()
                    .map(|l| (l.map, if forward { l.pos } else { l.neg })),
            );
            s.assign_all(&mut changes);
            match &cycles[d.index()] {
                None => {
                    cycles[d.index()] = Some(s);
                    queue.push_back(d);
                }
                Some(existing) => {
                    debug_assert_eq!(existing, &s, "inconsistent labels around cycle {d:?}")
                }
            }
        }
    }
    let cycles: Vec<S> = cycles
        .into_iter()
        .map(|s| s.expect("unreached cycle"))
        .collect();
    let faces = arr
        .faces()
        .iter()
        .map(|f| cycles[f[0].index()].clone())
        .collect();
    // Edges and vertices from the cycles beside them: independent, so in parallel.
    let edges = (0..arr.edges().len())
        .into_par_iter()
        .with_min_len(CELLS_PER_TASK)
        .map_init(Vec::new, |changes, e| {
            let edge = &arr.edges()[e];
            let mut s = cycles[arr.cycle(EdgeId::new(e).forward()).index()].clone();
            changes.clear();
            changes.extend(edge.labels.iter().map(|l| (l.map, l.on)));
            s.assign_all(changes);
            s
        })
        .collect();
    let vertices = (0..arr.vertices().len())
        .into_par_iter()
        .with_min_len(CELLS_PER_TASK)
        .map_init(Vec::new, |changes, v| {
            let vert = &arr.vertices()[v];
            let mut s = match vert.around.first() {
                Some(&h) => cycles[arr.cycle(h).index()].clone(),
                None => S::empty(maps),
            };
            changes.clear();
            for &h in &vert.around {
                changes.extend(arr.edge(h.edge()).labels.iter().map(|l| (l.map, l.on)));
            }
            changes.extend(vert.labels.iter().map(|l| (l.map, l.on)));
            s.assign_all(changes);
            s
        })
        .collect();
    CellStatuses {
        vertices,
        edges,
        faces,
        cycles,
    }
}
