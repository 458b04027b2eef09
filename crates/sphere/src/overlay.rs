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

use crate::arrangement::{ArcLabel, Arrangement};
use crate::bitset::BitSet;
use crate::polygon::perpendicular;
use apart_kernel::Vec3;
use std::collections::VecDeque;

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

/// For every cell, the set of maps whose status there is `true`.
#[derive(Clone, Debug)]
pub struct CellStatuses {
    /// Per vertex.
    pub vertices: Vec<BitSet>,
    /// Per edge.
    pub edges: Vec<BitSet>,
    /// Per face.
    pub faces: Vec<BitSet>,
    /// Per boundary cycle (equal to its face's).
    pub cycles: Vec<BitSet>,
}

/// Computes the statuses of `maps` maps on every cell of `arr`.
///
/// `oracle(x, y)` must return the exact statuses of all maps at the points `x + εy` for
/// every small enough `ε > 0` (a symbolic perturbation); it is called once.
pub fn cell_statuses(
    arr: &RegionArrangement,
    maps: usize,
    oracle: impl Fn(&Vec3, &Vec3) -> BitSet,
) -> CellStatuses {
    let point_override = |v: usize, s: &mut BitSet| {
        for l in &arr.vertices()[v].labels {
            s.set(l.map as usize, l.on);
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
    let e0 = arr.edge_arc(0);
    let start = oracle(&e0.interior_point(), &e0.normal);
    let mut cycles: Vec<Option<BitSet>> = vec![None; arr.cycle_count()];
    let c0 = arr.cycle_of(0);
    cycles[c0 as usize] = Some(start);
    let mut queue = VecDeque::from([c0]);
    while let Some(c) = queue.pop_front() {
        let status = cycles[c as usize].clone().unwrap();
        for h in arr.cycle_half_edges(c) {
            let twin = h ^ 1;
            let d = arr.cycle_of(twin);
            let mut s = status.clone();
            let forward = Arrangement::<SideLabel, PointStatus>::is_forward(twin);
            for l in &arr.edges()[(h / 2) as usize].labels {
                s.set(l.map as usize, if forward { l.pos } else { l.neg });
            }
            match &cycles[d as usize] {
                None => {
                    cycles[d as usize] = Some(s);
                    queue.push_back(d);
                }
                Some(existing) => {
                    debug_assert_eq!(existing, &s, "inconsistent labels around cycle {d}")
                }
            }
        }
    }
    let cycles: Vec<BitSet> = cycles
        .into_iter()
        .map(|s| s.expect("unreached cycle"))
        .collect();
    let faces = arr
        .faces()
        .iter()
        .map(|f| cycles[f[0] as usize].clone())
        .collect();
    let edges = arr
        .edges()
        .iter()
        .enumerate()
        .map(|(e, edge)| {
            let mut s = cycles[arr.cycle_of(2 * e as u32) as usize].clone();
            for l in &edge.labels {
                s.set(l.map as usize, l.on);
            }
            s
        })
        .collect();
    let vertices = arr
        .vertices()
        .iter()
        .enumerate()
        .map(|(v, vert)| {
            let mut s = match vert.around.first() {
                Some(&h) => cycles[arr.cycle_of(h) as usize].clone(),
                None => BitSet::new(maps),
            };
            for &h in &vert.around {
                for l in &arr.edges()[(h / 2) as usize].labels {
                    s.set(l.map as usize, l.on);
                }
            }
            point_override(v, &mut s);
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
