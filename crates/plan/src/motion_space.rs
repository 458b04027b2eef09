//! The motion space of a (sub)assembly: the overlay of its pairs' blocked regions, with
//! the blocking statuses of every vertex, edge and face.

use crate::dbg::Dbg;
use crate::regions::BlockingRegions;
use apart_kernel::spherical::ArcPosition;
use apart_kernel::Vec3;
use apart_sphere::arrangement::BuildStats;
use apart_sphere::overlay::{cell_statuses, CellStatuses, RegionArrangement};
use apart_sphere::region::region_inputs_with_antipodes;
use apart_sphere::{Arc, Arrangement, BitSet, EdgeId, FaceId, MapSet};
use rayon::prelude::*;
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
    st: CellStatuses<MapSet>,
    vertex_is_cell: Vec<bool>,
    edge_cell_of: Vec<u32>,
    edge_cells: Vec<Vec<EdgeId>>,
    vertex_edge_cell: Vec<u32>,
    /// Arcs of the real edges (by edge index; structural edges get a dummy) and their index.
    edge_arcs: Vec<Arc>,
    edge_index: apart_sphere::index::ArcIndex,
    real_edge_ids: Vec<EdgeId>,
    vertex_at: HashMap<Vec3, u32>,
    /// Arcs inserted into the overlay (from the simplified pair regions).
    pub input_arcs: usize,
    /// Statistics of the arrangement build.
    pub build_stats: BuildStats,
}

/// What overlaying the pair regions of a subassembly would cost, estimated from the pair
/// regions alone before anything is built (see [`MotionSpace::estimate`]): enough for a
/// caller to warn or refuse before the arrangement takes the memory.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OverlayEstimate {
    /// Parts in the subassembly.
    pub parts: usize,
    /// Ordered pairs of parts (maps of the overlay).
    pub maps: usize,
    /// Arcs the overlay would insert (exact): every pair region's arcs and their antipodes.
    pub arcs: usize,
    /// Distinct end points of those arcs (exact): the arrangement has at least this many
    /// vertices, plus one per crossing of arcs.
    pub endpoints: usize,
    /// Estimated vertices of the arrangement: the end points and, for the crossings, as
    /// many again (on lattices of separated or touching cubes the crossings add 10% to
    /// 120% of the end points).
    pub vertices: usize,
    /// Blocked ordered pairs at a direction, on average over a few fixed directions: the
    /// size of a cell's blocking status.
    pub blocked_per_cell: f64,
    /// Estimated peak memory of building the motion space, in bytes: the input arcs and
    /// their sorted copies while the arrangement is built, and the vertices, edges and
    /// faces with their blocking statuses after.
    pub bytes: u64,
}

/// Edges of an arrangement from which the motion space derives its parts in parallel.
const PAR_EDGES: usize = 1 << 14;

/// Bytes per inserted arc while the arrangement is built (input arc, canonical copy,
/// sort keys), measured on 200 to 1000 separated or touching cubes.
const BYTES_PER_ARC: u64 = 300;
/// Cells (vertices, edges, faces and their boundary cycles) per vertex of the arrangement,
/// and bytes per cell besides the members of a blocking status held as a list (topology,
/// and the status itself: inline below [`MapSet::INLINE_MAPS`] maps).
const CELLS_PER_VERTEX: u64 = 6;
const BYTES_PER_CELL: u64 = 152;

impl MotionSpace {
    /// Estimates what [`MotionSpace::build`] of `subset` would cost, in time linear in the
    /// pair regions' arcs and without building anything.
    pub fn estimate(regions: &BlockingRegions, subset: &[usize]) -> OverlayEstimate {
        let mut parts = subset.to_vec();
        parts.sort_unstable();
        parts.dedup();
        let mut arcs = 0usize;
        let mut points: rustc_hash::FxHashSet<Vec3> = Default::default();
        for (li, &i) in parts.iter().enumerate() {
            for &j in &parts[li + 1..] {
                let r = &regions.pair(i, j).region;
                arcs += 2 * r.arcs.len();
                for (a, _) in &r.arcs {
                    for p in [&a.start, &a.end] {
                        if points.insert(p.primitive()) {
                            points.insert(p.neg().primitive());
                        }
                    }
                }
                for (p, _) in &r.points {
                    if points.insert(p.primitive()) {
                        points.insert(p.neg().primitive());
                    }
                }
            }
        }
        let n = parts.len();
        let endpoints = points.len();
        let vertices = 2 * endpoints;
        // Blocked pairs at a few generic directions (exact tests on the pair polygons).
        let probes = [[1, 2, 3], [-3, 1, 2], [2, -3, 1], [-1, -2, 3]].map(Vec3::from_i64);
        let mut blocked = 0usize;
        for (li, &i) in parts.iter().enumerate() {
            for &j in &parts[li + 1..] {
                let r = regions.pair(i, j);
                for d in &probes {
                    blocked += usize::from(r.blocks(d)) + usize::from(r.blocks(&d.neg()));
                }
            }
        }
        let blocked_per_cell = blocked as f64 / probes.len() as f64;
        let cells = vertices as u64 * CELLS_PER_VERTEX;
        let maps = n * n.saturating_sub(1);
        let status = if maps < MapSet::INLINE_MAPS {
            0
        } else {
            (4.0 * blocked_per_cell) as u64
        };
        OverlayEstimate {
            parts: n,
            maps,
            arcs,
            endpoints,
            vertices,
            blocked_per_cell,
            bytes: arcs as u64 * BYTES_PER_ARC + cells * (BYTES_PER_CELL + status),
        }
    }

    /// Overlays the regions of every pair of parts in `subset` (global part indices);
    /// `Q_ji` is inserted as the antipode of `Q_ij`.
    pub fn build(regions: &BlockingRegions, subset: &[usize]) -> MotionSpace {
        MotionSpace::build_with_guides(regions, subset, &[])
    }

    /// [`MotionSpace::build_with_guides`] with the equator as guide arcs, so that every
    /// face lies in one closed hemisphere: the space the sphere pictures draw.
    pub fn build_split_at_equator(regions: &BlockingRegions, subset: &[usize]) -> MotionSpace {
        let eq = [[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]].map(Vec3::from);
        let guides: Vec<Arc> = (0..4)
            .map(|k| Arc::between(&eq[k], &eq[(k + 1) % 4]).expect("a quarter of the equator"))
            .collect();
        MotionSpace::build_with_guides(regions, subset, &guides)
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
        for (li, &i) in parts.iter().enumerate() {
            for (lj, &j) in parts.iter().enumerate().skip(li + 1) {
                maps.push((li, lj));
                maps.push((lj, li));
                debug_assert_eq!(
                    maps.len(),
                    2 * (li * parts.len() - li * (li + 1) / 2 + (lj - li - 1)) + 2
                );
                region_maps.push(regions.pair(i, j));
            }
        }
        // Map 2k is the k-th pair's region, map 2k + 1 its antipode (the reversed pair).
        let refs: Vec<&apart_sphere::region::RegionMap> =
            region_maps.iter().map(|r| &r.region).collect();
        let (mut arcs, points) = region_inputs_with_antipodes(&refs);
        drop(refs);
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
        // Sparse statuses: a cell is covered by few of the n (n − 1) maps.
        let st = cell_statuses(&arr, maps.len() + 1, |x, y| {
            let mut s = Vec::new();
            for (k, r) in region_maps.iter().enumerate() {
                if r.blocks_perturbed(x, y) {
                    s.push(2 * k as u32);
                }
                if r.blocks_perturbed(&x.neg(), &y.neg()) {
                    s.push(2 * k as u32 + 1);
                }
            }
            MapSet::from_sorted(s)
        });
        // The cells, and the arcs of the real edges with their index: independent, so
        // side by side on a large arrangement.
        let cells_of = || cells(&arr, &st);
        let arcs_of = || {
            let real_ids: Vec<EdgeId> = arr
                .edge_ids()
                .filter(|&e| !arr.edge(e).structural)
                .collect();
            let real_arcs: Vec<Arc> = real_ids
                .par_iter()
                .with_min_len(PAR_EDGES)
                .map(|&e| arr.edge_arc(e))
                .collect();
            let edge_index = apart_sphere::index::ArcIndex::new(&real_arcs);
            let vertex_at: HashMap<Vec3, u32> = arr
                .vertices()
                .iter()
                .enumerate()
                .map(|(v, x)| (x.point.clone(), v as u32))
                .collect();
            (real_ids, real_arcs, edge_index, vertex_at)
        };
        let (
            Cells {
                vertex_is_cell,
                edge_cell_of,
                edge_cells,
                vertex_edge_cell,
            },
            (real_ids, real_arcs, edge_index, vertex_at),
        ) = if arr.edges().len() >= PAR_EDGES {
            rayon::join(cells_of, arcs_of)
        } else {
            (cells_of(), arcs_of())
        };
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
    pub fn statuses(&self) -> &CellStatuses<MapSet> {
        &self.st
    }

    /// The (moving, fixed) local part indices of map `m`.
    pub fn map_pair(&self, m: usize) -> (usize, usize) {
        self.maps[m]
    }

    /// The directional blocking graph for a status set.
    pub fn dbg(&self, status: &MapSet) -> Dbg {
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
    pub fn masks(&self, status: &MapSet) -> Option<crate::dbg::Masks> {
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

    /// The minimal moving sets (local indices) of a cell of status `status`: by bit masks
    /// up to 64 parts, else by a [`crate::dbg::BitGraph`].
    pub fn minimal_moving_sets(&self, status: &MapSet) -> Vec<Vec<usize>> {
        match self.masks(status) {
            Some(m) => m.minimal_moving_set_lists(),
            None => self.bit_graph(status).minimal_moving_sets(),
        }
    }

    /// The blocking graph of a status set as adjacency bits (any number of parts).
    pub fn bit_graph(&self, status: &MapSet) -> crate::dbg::BitGraph {
        let mut g = crate::dbg::BitGraph::new(self.parts.len());
        for k in status.iter().take_while(|&k| k < self.maps.len()) {
            let (a, b) = self.maps[k];
            g.block(a, b);
        }
        g
    }

    /// The map of "local part `a`, moving, hits local part `b`" (`a != b`): maps come in
    /// the order of the pairs `(a, b)`, `a < b`, each followed by its reverse.
    pub fn map_of(&self, a: usize, b: usize) -> usize {
        let n = self.parts.len();
        let (i, j) = (a.min(b), a.max(b));
        let k = i * n - i * (i + 1) / 2 + (j - i - 1);
        2 * k + usize::from(a > b)
    }

    /// True when the local set `set` (sorted, distinct) can move in a cell of status
    /// `status`: not empty, not everything, and no member hits a part outside it. Reads
    /// the blocked pairs or looks up the pairs leaving the set, whichever are fewer,
    /// without building a graph.
    pub fn can_move(&self, status: &MapSet, set: &[usize]) -> bool {
        let n = self.parts.len();
        if set.is_empty() || set.len() >= n {
            return false;
        }
        if status.count() <= set.len() * (n - set.len()) {
            let inside = |p: usize| set.binary_search(&p).is_ok();
            return status.iter().take_while(|&k| k < self.maps.len()).all(|k| {
                let (a, b) = self.maps[k];
                !inside(a) || inside(b)
            });
        }
        set.iter().all(|&a| {
            let mut inside = set.iter().copied().peekable();
            (0..n).all(|b| {
                if inside.peek() == Some(&b) {
                    inside.next();
                    return true;
                }
                !status.get(self.map_of(a, b))
            })
        })
    }

    /// True when the local set `set` (sorted, distinct) is a minimal moving set in a cell
    /// of status `status`: it can move, and its own blocking graph is strongly connected
    /// (no smaller set inside it can).
    pub fn is_minimal_moving_set(&self, status: &MapSet, set: &[usize]) -> bool {
        if !self.can_move(status, set) {
            return false;
        }
        if set.len() == 1 {
            return true;
        }
        // Every member reaches the first one and is reached from it inside the set.
        let reach = |forward: bool| -> bool {
            let mut seen = vec![false; set.len()];
            seen[0] = true;
            let mut todo = vec![0usize];
            while let Some(x) = todo.pop() {
                for (y, done) in seen.iter_mut().enumerate() {
                    let (a, b) = if forward { (x, y) } else { (y, x) };
                    if !*done && status.get(self.map_of(set[a], set[b])) {
                        *done = true;
                        todo.push(y);
                    }
                }
            }
            seen.iter().all(|&s| s)
        };
        reach(true) && reach(false)
    }

    /// The local parts that can move alone in a cell of status `status` (no blocked pair
    /// leaves them), in one pass over the status.
    pub fn free_alone(&self, status: &MapSet) -> BitSet {
        let n = self.parts.len();
        let mut free = BitSet::new(n);
        for p in 0..n {
            free.set(p, true);
        }
        for k in status.iter().take_while(|&k| k < self.maps.len()) {
            free.set(self.maps[k].0, false);
        }
        free
    }

    /// Number of ordered pairs blocked in a status set.
    pub fn blocked_pairs(&self, status: &MapSet) -> usize {
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
    pub fn edge_cells(&self) -> &[Vec<EdgeId>] {
        &self.edge_cells
    }

    /// The edge cell an arrangement edge belongs to (`None` for structural edges and for
    /// edges with the status of a face beside them, which belong to that face).
    pub fn edge_cell_of(&self, e: EdgeId) -> Option<usize> {
        let c = self.edge_cell_of[e.index()];
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
            Some((k, _)) => match self.edge_cell_of(self.real_edge_ids[k as usize]) {
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
    pub fn face_sample(&self, f: FaceId) -> Vec3 {
        let arr = &self.arr;
        let h = arr
            .boundary_loops(f)
            .into_iter()
            .flatten()
            .next()
            .or_else(|| {
                arr.face_cycles(f)
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
        // A path from `m` into `f` that leaves `f` crosses its boundary first: the edges
        // of its cycles (structural ones too: the graph is connected, so they reach every
        // isolated vertex) and their end points. A probe clear of those lies in `f` and
        // is clear of every other edge and vertex of the motion space as well.
        let mut edges: Vec<_> = arr
            .face_cycles(f)
            .iter()
            .flat_map(|&c| arr.cycle_half_edges(c))
            .map(|g| g.edge())
            .filter(|&e| e != h.edge())
            .collect();
        edges.sort_unstable_by_key(|e| e.index());
        edges.dedup();
        let arcs: Vec<Arc> = edges.iter().map(|&e| arr.edge_arc(e)).collect();
        let mut k = apart_kernel::Int::from(16);
        loop {
            let x = m.scale(&k).add(&arc.normal).primitive();
            let probe = Arc::between(&m, &x).expect("distinct points");
            let clear = arcs.iter().all(|a| {
                !apart_sphere::arc::arcs_intersect(&probe, a)
                    && [&a.start, &a.end]
                        .into_iter()
                        .all(|v| probe.locate(v).is_none_or(|p| p == ArcPosition::Outside))
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
fn cells(arr: &RegionArrangement, st: &CellStatuses<MapSet>) -> Cells {
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
    let edge_is_cell: Vec<bool> = arr
        .edge_ids()
        .map(|e| {
            let s = &st.edges[e.index()];
            !arr.edge(e).structural
                && *s != st.cycles[arr.cycle(e.forward()).index()]
                && *s != st.cycles[arr.cycle(e.backward()).index()]
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
                .map(|&h| h.edge().index())
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
            .any(|&h| st.cycles[arr.cycle(h).index()] == *s)
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
    let mut groups: Vec<Vec<EdgeId>> = Vec::new();
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
        groups[c as usize].push(EdgeId::new(e));
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
    edge_cells: Vec<Vec<EdgeId>>,
    /// For a vertex that is no cell but lies in an edge cell, that cell (else `u32::MAX`).
    vertex_edge_cell: Vec<u32>,
}
