//! The motion space of a (sub)assembly: the overlay of its pairs' blocked regions, with
//! the blocking statuses of every vertex, edge and face.

use crate::dbg::Dbg;
use crate::regions::BlockingRegions;
use apart_kernel::spherical::ArcPosition;
use apart_kernel::Vec3;
use apart_sphere::arrangement::BuildStats;
use apart_sphere::overlay::{cell_statuses, CellStatuses, RegionArrangement};
use apart_sphere::region::region_inputs;
use apart_sphere::{Arc, Arrangement, BitSet};
use rustc_hash::FxHashMap as HashMap;

/// The kind of a cell of the motion space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellKind {
    /// An open region of directions: robust solutions with positive clearance.
    Face,
    /// An open arc of directions: sliding motions.
    Edge,
    /// An isolated direction: zero clearance.
    Vertex,
}

impl CellKind {
    /// "face", "edge" or "vertex".
    pub fn name(self) -> &'static str {
        match self {
            CellKind::Face => "face",
            CellKind::Edge => "edge",
            CellKind::Vertex => "vertex",
        }
    }
}

/// The arrangement of the blocked regions of the parts of a subassembly, with the
/// directional blocking graph of every cell.
pub struct MotionSpace {
    parts: Vec<usize>,
    maps: Vec<(usize, usize)>,
    arr: RegionArrangement,
    st: CellStatuses,
    vertex_is_cell: Vec<bool>,
    edge_cell_of: Vec<u32>,
    edge_cells: Vec<Vec<u32>>,
    vertex_edge_cell: Vec<u32>,
    /// Arcs of the real edges (by edge index; structural edges get a dummy) and their index.
    edge_arcs: Vec<Arc>,
    edge_index: apart_sphere::index::ArcIndex,
    real_edge_ids: Vec<u32>,
    vertex_at: HashMap<Vec3, u32>,
    /// Arcs inserted into the overlay (from the simplified pair regions).
    pub input_arcs: usize,
    /// Statistics of the arrangement build.
    pub build_stats: BuildStats,
}

impl MotionSpace {
    /// Overlays the regions of every pair of parts in `subset` (global part indices);
    /// `Q_ji` is inserted as the antipode of `Q_ij`.
    pub fn build(regions: &BlockingRegions, subset: &[usize]) -> MotionSpace {
        MotionSpace::build_with_guides(regions, subset, &[])
    }

    /// Like [`MotionSpace::build`], with extra *guide* arcs that change no status but cut
    /// faces and edges (the equator, to draw each hemisphere separately). Guide arcs make
    /// vertices and edges of their own: use this arrangement for drawing, not for cells.
    pub fn build_with_guides(
        regions: &BlockingRegions,
        subset: &[usize],
        guides: &[Arc],
    ) -> MotionSpace {
        let mut parts = subset.to_vec();
        parts.sort_unstable();
        parts.dedup();
        let mut maps = Vec::new();
        let mut region_maps = Vec::new();
        let mut owned = Vec::new();
        for (li, &i) in parts.iter().enumerate() {
            for (lj, &j) in parts.iter().enumerate().skip(li + 1) {
                let r = regions.pair(i, j);
                maps.push((li, lj));
                maps.push((lj, li));
                owned.push(r.region.antipodal());
                region_maps.push((r, maps.len() - 2));
            }
        }
        let mut refs: Vec<&apart_sphere::region::RegionMap> = Vec::with_capacity(maps.len());
        for (k, (r, _)) in region_maps.iter().enumerate() {
            refs.push(&r.region);
            refs.push(&owned[k]);
        }
        let (mut arcs, points) = region_inputs(&refs);
        let input_arcs = arcs.len();
        let guide_map = maps.len() as u32;
        arcs.extend(guides.iter().map(|g| apart_sphere::InputArc {
            arc: g.clone(),
            label: Some(apart_sphere::overlay::SideLabel {
                map: guide_map,
                pos: false,
                on: false,
                neg: false,
            }),
        }));
        let (arr, build_stats) = Arrangement::build(arcs, points);
        let st = cell_statuses(&arr, maps.len() + 1, |x, y| {
            let mut s = BitSet::new(maps.len() + 1);
            for (k, (r, _)) in region_maps.iter().enumerate() {
                s.set(2 * k, r.blocks_perturbed(x, y));
                s.set(2 * k + 1, r.blocks_perturbed(&x.neg(), &y.neg()));
            }
            s
        });
        let Cells {
            vertex_is_cell,
            edge_cell_of,
            edge_cells,
            vertex_edge_cell,
        } = cells(&arr, &st);
        let edge_arcs: Vec<Arc> = (0..arr.edges().len() as u32)
            .map(|e| arr.edge_arc(e))
            .collect();
        let real_arcs: Vec<Arc> = edge_arcs
            .iter()
            .zip(arr.edges())
            .filter(|(_, e)| !e.structural)
            .map(|(a, _)| a.clone())
            .collect();
        let real_ids: Vec<u32> = (0..arr.edges().len() as u32)
            .filter(|&e| !arr.edges()[e as usize].structural)
            .collect();
        let edge_index = apart_sphere::index::ArcIndex::new(&real_arcs);
        let vertex_at = arr
            .vertices()
            .iter()
            .enumerate()
            .map(|(v, x)| (x.point.clone(), v as u32))
            .collect();
        MotionSpace {
            parts,
            maps,
            arr,
            st,
            vertex_is_cell,
            edge_cell_of,
            edge_cells,
            vertex_edge_cell,
            edge_arcs: real_arcs,
            edge_index,
            real_edge_ids: real_ids,
            vertex_at,
            input_arcs,
            build_stats,
        }
    }

    /// The parts (global indices, sorted); local index = position in this list.
    pub fn parts(&self) -> &[usize] {
        &self.parts
    }

    /// The arrangement.
    pub fn arrangement(&self) -> &RegionArrangement {
        &self.arr
    }

    /// Blocking statuses of all cells (bit `2k` / `2k+1` = the two orders of the `k`-th
    /// pair, see [`MotionSpace::map_pair`]).
    pub fn statuses(&self) -> &CellStatuses {
        &self.st
    }

    /// The (moving, fixed) local part indices of map `m`.
    pub fn map_pair(&self, m: usize) -> (usize, usize) {
        self.maps[m]
    }

    /// The directional blocking graph for a status set.
    pub fn dbg(&self, status: &BitSet) -> Dbg {
        Dbg::new(
            self.parts.len(),
            status
                .iter()
                .filter(|&m| m < self.maps.len())
                .map(|m| self.maps[m])
                .collect(),
        )
    }

    /// The blocking graph of a status set as bit masks, when there are at most 64 parts.
    pub fn masks(&self, status: &BitSet) -> Option<crate::dbg::Masks> {
        if self.parts.len() > 64 {
            return None;
        }
        let mut m = crate::dbg::Masks::new(self.parts.len());
        for k in status.iter().filter(|&k| k < self.maps.len()) {
            let (a, b) = self.maps[k];
            m.block(a, b);
        }
        Some(m)
    }

    /// Number of ordered pairs blocked in a status set.
    pub fn blocked_pairs(&self, status: &BitSet) -> usize {
        status.iter().filter(|&m| m < self.maps.len()).count()
    }

    /// Number of ordered pairs of parts (maps).
    pub fn pair_count(&self) -> usize {
        self.maps.len()
    }

    /// The vertices that are cells of the motion space: isolated cells whose blocking
    /// status differs from that of every face and edge around them.
    pub fn real_vertices(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.arr.vertices().len()).filter(|&v| self.vertex_is_cell[v])
    }

    /// The edge cells: maximal connected sets of arrangement edges (and the vertices
    /// between them) with one blocking status that differs from the status of the faces
    /// on both sides; each a list of arrangement edge indices.
    pub fn edge_cells(&self) -> &[Vec<u32>] {
        &self.edge_cells
    }

    /// The edge cell an arrangement edge belongs to (`None` for structural edges and for
    /// edges with the status of a face beside them, which belong to that face).
    pub fn edge_cell_of(&self, e: usize) -> Option<usize> {
        let c = self.edge_cell_of[e];
        (c != u32::MAX).then_some(c as usize)
    }

    /// The maximal cell direction `d` lies in: a vertex, an edge cell (cell index) or a
    /// face (`None` index: faces are not located, their DBG is evaluated directly). A
    /// direction on an arc or at a vertex with the status of a face beside it is in
    /// that face.
    pub fn locate(&self, d: &Vec3) -> (CellKind, Option<usize>) {
        let p = d.primitive();
        if let Some(&v) = self.vertex_at.get(&p) {
            if self.vertex_is_cell[v as usize] {
                return (CellKind::Vertex, Some(v as usize));
            }
            // A vertex that is no cell lies inside an edge cell or a face.
            return match self.vertex_edge_cell[v as usize] {
                u32::MAX => (CellKind::Face, None),
                c => (CellKind::Edge, Some(c as usize)),
            };
        }
        match self.edge_index.locate(&self.edge_arcs, &p) {
            Some((k, _)) => match self.edge_cell_of(self.real_edge_ids[k as usize] as usize) {
                Some(c) => (CellKind::Edge, Some(c)),
                None => (CellKind::Face, None),
            },
            None => (CellKind::Face, None),
        }
    }
}

impl MotionSpace {
    /// An exact point strictly inside face `f`, found without the blocking statuses:
    /// `k · m + n`, where `m` is an interior point of one of the face's boundary edges and
    /// `n` that edge's normal towards the face, for `k` large enough that the short arc
    /// from `m` to the point crosses no edge of the motion space.
    pub fn face_sample(&self, f: u32) -> Vec3 {
        let arr = &self.arr;
        let h = arr
            .boundary_loops(f)
            .into_iter()
            .flatten()
            .next()
            .or_else(|| {
                arr.faces()[f as usize]
                    .iter()
                    .map(|&c| arr.cycle_start(c))
                    .next()
            });
        let Some(h) = h else {
            // No edge at all: the sphere minus isolated points.
            return self.sample_away_from_vertices();
        };
        let arc = arr.half_edge_arc(h);
        let m = arc.interior_point();
        let mut k = apart_kernel::Int::from(16);
        loop {
            let x = m.scale(&k).add(&arc.normal).primitive();
            let probe = Arc::between(&m, &x).expect("distinct points");
            let clear = arr.edges().iter().enumerate().all(|(e, _)| {
                e as u32 == h / 2
                    || !apart_sphere::arc::arcs_intersect(&probe, &arr.edge_arc(e as u32))
            }) && arr.vertices().iter().all(|v| {
                probe
                    .locate(&v.point)
                    .is_none_or(|p| p == ArcPosition::Outside)
            });
            if clear {
                return x;
            }
            k = &k * apart_kernel::Int::from(256);
        }
    }

    fn sample_away_from_vertices(&self) -> Vec3 {
        let mut d = Vec3::new(1, 2, 3);
        while self.arr.vertices().iter().any(|v| v.point == d.primitive()) {
            d = d.add(&Vec3::new(1, 0, 0));
        }
        d
    }
}

/// Which vertices are genuine cells, and the grouping of arrangement edges into edge
/// cells: the cells are the *maximal* connected sets of one blocking status, so that a
/// direction is reported in the largest cell around it.
///
/// - An edge whose status equals that of a face on either side is no cell: it belongs to
///   that face (the boundary arc of an open blocked set, where nothing else changes, has
///   the status of the face outside the set; for cubes touching along an edge or at a
///   vertex, every arc of the motion space is such a boundary).
/// - A vertex is no cell when it is structural, or when its status equals that of a face
///   around it (it belongs to the face), or else that of a real edge through it that is a
///   cell (it joins that edge cell, and every such edge cell through it becomes one).
///
/// So a straight continuation of two edges with the vertex's own status (a point that
/// only splits a hemisphere's boundary into minor arcs) is one edge cell, and an isolated
/// point with its face's status is no cell.
fn cells(arr: &RegionArrangement, st: &CellStatuses) -> Cells {
    let n = arr.edges().len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    // Real edges that are cells: a status different from both faces beside them.
    let edge_is_cell: Vec<bool> = (0..n)
        .map(|e| {
            let s = &st.edges[e];
            !arr.edges()[e].structural
                && *s != st.cycles[arr.cycle_of(2 * e as u32) as usize]
                && *s != st.cycles[arr.cycle_of(2 * e as u32 + 1) as usize]
        })
        .collect();
    let mut is_cell = vec![false; arr.vertices().len()];
    // For a vertex that is no cell: one arrangement edge of the edge cell it joins.
    let mut joins = vec![u32::MAX; arr.vertices().len()];
    for (v, vert) in arr.vertices().iter().enumerate() {
        let s = &st.vertices[v];
        let real = || {
            vert.around
                .iter()
                .map(|&h| (h / 2) as usize)
                .filter(|&e| !arr.edges()[e].structural)
        };
        if vert.structural {
            // A structural vertex on a real arc joins the two halves of that arc.
            let r: Vec<usize> = real().filter(|&e| edge_is_cell[e]).collect();
            if let [a, b] = r[..] {
                if st.edges[a] == st.edges[b] {
                    let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                    parent[ra] = rb;
                    joins[v] = a as u32;
                }
            }
            continue;
        }
        if vert.around.is_empty() {
            // A point alone on the sphere (no arc at all): a cell when its status is not
            // the sphere's.
            is_cell[v] = st.faces.first().is_some_and(|f| f != s);
            continue;
        }
        if vert
            .around
            .iter()
            .any(|&h| st.cycles[arr.cycle_of(h) as usize] == *s)
        {
            continue;
        }
        let same: Vec<usize> = real()
            .filter(|&e| edge_is_cell[e] && st.edges[e] == *s)
            .collect();
        if let Some(&first) = same.first() {
            for &e in &same[1..] {
                let (ra, rb) = (find(&mut parent, first), find(&mut parent, e));
                parent[ra] = rb;
            }
            joins[v] = first as u32;
            continue;
        }
        is_cell[v] = true;
    }
    let mut ids: HashMap<usize, u32> = HashMap::default();
    let mut groups: Vec<Vec<u32>> = Vec::new();
    let mut of = vec![u32::MAX; n];
    for (e, slot) in of.iter_mut().enumerate() {
        if !edge_is_cell[e] {
            continue;
        }
        let root = find(&mut parent, e);
        let c = *ids.entry(root).or_insert_with(|| {
            groups.push(Vec::new());
            (groups.len() - 1) as u32
        });
        groups[c as usize].push(e as u32);
        *slot = c;
    }
    let vertex_edge_cell = joins
        .iter()
        .map(|&e| {
            if e == u32::MAX {
                u32::MAX
            } else {
                of[e as usize]
            }
        })
        .collect();
    Cells {
        vertex_is_cell: is_cell,
        edge_cell_of: of,
        edge_cells: groups,
        vertex_edge_cell,
    }
}

/// The cells of a motion space (see [`cells`]).
struct Cells {
    vertex_is_cell: Vec<bool>,
    edge_cell_of: Vec<u32>,
    edge_cells: Vec<Vec<u32>>,
    /// For a vertex that is no cell but lies in an edge cell, that cell (else `u32::MAX`).
    vertex_edge_cell: Vec<u32>,
}
