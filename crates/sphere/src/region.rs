//! Region maps: an open-or-closed subset of the sphere described by the arcs and points
//! where its status changes.

use crate::arc::Arc;
use crate::arrangement::{Arrangement, EdgeId, HalfEdge, VertexId};
use crate::bitset::BitSet;
use crate::overlay::{CellStatuses, PointStatus, RegionArrangement, SideLabel};
use apart_kernel::predicates::det3_sign;
use apart_kernel::{Sign, Vec3};

/// A map's status on both sides of an arc and on the arc itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Sides {
    /// Status on the positive side of the arc's circle.
    pub pos: bool,
    /// Status on the (open) arc.
    pub on: bool,
    /// Status on the negative side.
    pub neg: bool,
}

impl Sides {
    /// The label of this arc for map `map`.
    pub fn label(self, map: u32) -> SideLabel {
        SideLabel {
            map,
            pos: self.pos,
            on: self.on,
            neg: self.neg,
        }
    }
}

/// A subset of the sphere given by the arcs where its status changes (with the status
/// on each side and on the arc) and the points whose status differs from their
/// surroundings or where such arcs end or meet. Away from these, the status is constant
/// on each connected region.
#[derive(Clone, Debug, Default)]
pub struct RegionMap {
    /// Boundary arcs, each counter-clockwise around its normal, with their sides.
    pub arcs: Vec<(Arc, Sides)>,
    /// Points with their status.
    pub points: Vec<(Vec3, bool)>,
}

impl RegionMap {
    /// The image under `x -> -x`: arcs map to antipodal arcs (positive and negative
    /// sides swap), points to antipodal points.
    pub fn antipodal(&self) -> RegionMap {
        RegionMap {
            arcs: self
                .arcs
                .iter()
                .map(|(a, s)| {
                    (
                        a.antipodal(),
                        Sides {
                            pos: s.neg,
                            on: s.on,
                            neg: s.pos,
                        },
                    )
                })
                .collect(),
            points: self.points.iter().map(|(p, b)| (p.neg(), *b)).collect(),
        }
    }

    /// True when the map has no arc and no point (its status is the same everywhere).
    pub fn is_uniform(&self) -> bool {
        self.arcs.is_empty() && self.points.is_empty()
    }
}

/// The union of the maps of `arr` (a cell is `true` when any map is `true` there),
/// simplified: edges whose status equals both neighbouring faces' are dropped, vertices
/// whose status equals their surroundings and that no remaining edge needs are dropped,
/// and remaining edges continuing straight through a dropped vertex are merged (as long
/// as the merged arc stays shorter than a half circle).
pub fn simplify_union(arr: &RegionArrangement, st: &CellStatuses) -> RegionMap {
    let any = |b: &BitSet| !b.is_empty();
    let face_status = |h: HalfEdge| any(&st.cycles[arr.cycle(h).index()]);
    if arr.edges().is_empty() {
        let face = any(&st.faces[0]);
        let points = arr
            .vertices()
            .iter()
            .zip(&st.vertices)
            .filter(|(_, s)| any(s) != face)
            .map(|(v, s)| (v.point.clone(), any(s)))
            .collect();
        return RegionMap {
            arcs: Vec::new(),
            points,
        };
    }
    let n_edges = arr.edges().len();
    let sides: Vec<Sides> = arr
        .edge_ids()
        .map(|e| Sides {
            pos: face_status(e.forward()),
            on: any(&st.edges[e.index()]),
            neg: face_status(e.backward()),
        })
        .collect();
    let kept: Vec<bool> = sides
        .iter()
        .map(|s| !(s.pos == s.on && s.on == s.neg))
        .collect();
    let vstatus: Vec<bool> = st.vertices.iter().map(any).collect();
    // A vertex can be skipped when exactly two kept edges meet there, on one circle,
    // continuing straight (one arrives, one leaves in circle order), with equal sides,
    // and the vertex has the arcs' status.
    let kept_around: Vec<Vec<HalfEdge>> = arr
        .vertices()
        .iter()
        .map(|v| {
            v.around
                .iter()
                .copied()
                .filter(|&h| kept[h.edge().index()])
                .collect()
        })
        .collect();
    let skippable: Vec<bool> = (0..arr.vertices().len())
        .map(|v| {
            let hs = &kept_around[v];
            if hs.len() != 2 {
                return false;
            }
            let (a, b) = (hs[0].edge().index(), hs[1].edge().index());
            let (ea, eb) = (&arr.edges()[a], &arr.edges()[b]);
            ea.circle == eb.circle
                && hs[0].is_forward() != hs[1].is_forward()
                && sides[a] == sides[b]
                && vstatus[v] == sides[a].on
        })
        .collect();
    let face_around = |v: usize| -> bool {
        match arr.vertices()[v].around.first() {
            Some(&h) => face_status(h),
            None => vstatus[v],
        }
    };
    let mut points = Vec::new();
    for (v, vert) in arr.vertices().iter().enumerate() {
        let needed = !kept_around[v].is_empty() || vstatus[v] != face_around(v);
        if needed && !skippable[v] {
            points.push((vert.point.clone(), vstatus[v]));
        }
    }
    // Merge chains of kept edges through skippable vertices.
    let mut arcs = Vec::new();
    let mut done = vec![false; n_edges];
    let out_forward = |v: VertexId, circle: u32| -> Option<EdgeId> {
        kept_around[v.index()]
            .iter()
            .copied()
            .find(|&h| h.is_forward() && arr.edge(h.edge()).circle == circle)
            .map(HalfEdge::edge)
    };
    let in_forward = |v: VertexId, circle: u32| -> Option<EdgeId> {
        kept_around[v.index()]
            .iter()
            .copied()
            .find(|&h| !h.is_forward() && arr.edge(h.edge()).circle == circle)
            .map(HalfEdge::edge)
    };
    for e0 in arr.edge_ids() {
        if !kept[e0.index()] || done[e0.index()] {
            continue;
        }
        let circle = arr.edge(e0).circle;
        // Walk back to the start of the chain (or around a full circle of skippable ones).
        let mut first = e0;
        loop {
            let v = arr.edge(first).from;
            if !skippable[v.index()] {
                break;
            }
            match in_forward(v, circle) {
                Some(p) if p != e0 => first = p,
                _ => break,
            }
        }
        // Walk forward, cutting where the arc would reach a half circle.
        let normal = &arr.circles()[circle as usize];
        let mut cur = first;
        let mut start = arr.edge(cur).from;
        loop {
            done[cur.index()] = true;
            let end = arr.edge(cur).to;
            let next = if skippable[end.index()] {
                out_forward(end, circle).filter(|&n| !done[n.index()])
            } else {
                None
            };
            let close = match next {
                Some(n) => {
                    let far = &arr.vertex(arr.edge(n).to).point;
                    det3_sign(normal, &arr.vertex(start).point, far) != Sign::Positive
                }
                None => true,
            };
            if close {
                arcs.push((
                    Arc {
                        normal: normal.clone(),
                        start: arr.vertex(start).point.clone(),
                        end: arr.vertex(end).point.clone(),
                    },
                    sides[cur.index()],
                ));
                if skippable[end.index()] && next.is_some() {
                    // Cut here: the skipped vertex becomes an end point after all.
                    points.push((arr.vertex(end).point.clone(), vstatus[end.index()]));
                }
                start = end;
            }
            match next {
                Some(n) => cur = n,
                None => break,
            }
        }
    }
    points.sort_by_cached_key(|a| a.0.to_strings());
    points.dedup_by(|a, b| a.0 == b.0);
    RegionMap { arcs, points }
}

/// Inserts region maps (map index = position in `maps`) as labelled arcs and points.
pub fn region_inputs(
    maps: &[&RegionMap],
) -> (
    Vec<crate::arrangement::InputArc<SideLabel>>,
    Vec<crate::arrangement::InputPoint<PointStatus>>,
) {
    let mut arcs = Vec::new();
    let mut points = Vec::new();
    for (m, map) in maps.iter().enumerate() {
        for (a, s) in &map.arcs {
            arcs.push(crate::arrangement::InputArc {
                arc: a.clone(),
                label: Some(s.label(m as u32)),
            });
        }
        for (p, b) in &map.points {
            points.push(crate::arrangement::InputPoint {
                point: p.clone(),
                label: PointStatus {
                    map: m as u32,
                    on: *b,
                },
            });
        }
    }
    (arcs, points)
}

/// Inserts every region map of `maps` and its antipodal image as labelled arcs and
/// points: `maps[k]` is map `2k`, its image under `x -> -x` map `2k + 1` (as
/// [`region_inputs`] of the maps interleaved with their [`RegionMap::antipodal`] images,
/// without building those images).
pub fn region_inputs_with_antipodes(
    maps: &[&RegionMap],
) -> (
    Vec<crate::arrangement::InputArc<SideLabel>>,
    Vec<crate::arrangement::InputPoint<PointStatus>>,
) {
    let arc_count: usize = maps.iter().map(|m| 2 * m.arcs.len()).sum();
    let mut arcs = Vec::with_capacity(arc_count);
    let mut points = Vec::new();
    for (k, map) in maps.iter().enumerate() {
        let (m, anti) = (2 * k as u32, 2 * k as u32 + 1);
        for (a, s) in &map.arcs {
            arcs.push(crate::arrangement::InputArc {
                arc: a.clone(),
                label: Some(s.label(m)),
            });
        }
        for (a, s) in &map.arcs {
            let flipped = Sides {
                pos: s.neg,
                on: s.on,
                neg: s.pos,
            };
            arcs.push(crate::arrangement::InputArc {
                arc: a.antipodal(),
                label: Some(flipped.label(anti)),
            });
        }
        for (p, b) in &map.points {
            points.push(crate::arrangement::InputPoint {
                point: p.clone(),
                label: PointStatus { map: m, on: *b },
            });
        }
        for (p, b) in &map.points {
            points.push(crate::arrangement::InputPoint {
                point: p.neg(),
                label: PointStatus { map: anti, on: *b },
            });
        }
    }
    (arcs, points)
}

/// Builds the arrangement of one region map alone (for inspection and drawing).
pub fn arrangement_of(map: &RegionMap) -> RegionArrangement {
    let (arcs, points) = region_inputs(&[map]);
    Arrangement::build(arcs, points).0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_with_antipodes_match_the_interleaved_maps() {
        let p = |x, y, z| Vec3::new(x, y, z);
        let a = RegionMap {
            arcs: vec![
                (
                    Arc::between(&p(1, 0, 0), &p(0, 1, 0)).unwrap(),
                    Sides {
                        pos: true,
                        on: false,
                        neg: false,
                    },
                ),
                (
                    Arc::between(&p(0, 1, 0), &p(0, 0, 1)).unwrap(),
                    Sides {
                        pos: false,
                        on: true,
                        neg: true,
                    },
                ),
            ],
            points: vec![(p(1, 2, 3), true)],
        };
        let b = RegionMap {
            arcs: Vec::new(),
            points: vec![(p(-1, 0, 5), false)],
        };
        let (anti_a, anti_b) = (a.antipodal(), b.antipodal());
        let (want_arcs, want_points) = region_inputs(&[&a, &anti_a, &b, &anti_b]);
        let (arcs, points) = region_inputs_with_antipodes(&[&a, &b]);
        let key = |x: &crate::arrangement::InputArc<SideLabel>| {
            (
                x.arc.start.clone(),
                x.arc.end.clone(),
                x.arc.normal.clone(),
                x.label,
            )
        };
        assert_eq!(
            arcs.iter().map(key).collect::<Vec<_>>(),
            want_arcs.iter().map(key).collect::<Vec<_>>()
        );
        let pkey = |x: &crate::arrangement::InputPoint<PointStatus>| (x.point.clone(), x.label);
        assert_eq!(
            points.iter().map(pkey).collect::<Vec<_>>(),
            want_points.iter().map(pkey).collect::<Vec<_>>()
        );
    }
}
