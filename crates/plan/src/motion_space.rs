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
        let (vertex_is_cell, edge_cell_of, edge_cells) = cells(&arr, &st);
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

    /// The vertices that are cells of the motion space (something changes there).
    pub fn real_vertices(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.arr.vertices().len()).filter(|&v| self.vertex_is_cell[v])
    }

    /// The edge cells: maximal runs of arrangement edges along one circle through vertices
    /// that are not cells; each a list of arrangement edge indices.
    pub fn edge_cells(&self) -> &[Vec<u32>] {
        &self.edge_cells
    }

    /// The real edge cell an arrangement edge belongs to (`None` for structural edges).
    pub fn edge_cell_of(&self, e: usize) -> Option<usize> {
        let c = self.edge_cell_of[e];
        (c != u32::MAX).then_some(c as usize)
    }

    /// Where direction `d` lies: a vertex, a real edge (cell index) or the inside of a
    /// face (`None` index: faces are not located, their DBG is evaluated directly).
    pub fn locate(&self, d: &Vec3) -> (CellKind, Option<usize>) {
        let p = d.primitive();
        if let Some(&v) = self.vertex_at.get(&p) {
            let vert = &self.arr.vertices()[v as usize];
            if self.vertex_is_cell[v as usize] {
                return (CellKind::Vertex, Some(v as usize));
            }
            // A vertex that is no cell lies inside an edge cell or a face.
            return match vert
                .around
                .iter()
                .find_map(|&h| self.edge_cell_of((h / 2) as usize))
            {
                Some(c) => (CellKind::Edge, Some(c)),
                None => (CellKind::Face, None),
            };
        }
        match self.edge_index.locate(&self.edge_arcs, &p) {
            Some((k, _)) => (
                CellKind::Edge,
                self.edge_cell_of(self.real_edge_ids[k as usize] as usize),
            ),
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
/// cells. A vertex is not a cell when nothing changes there: a structural vertex, a
/// vertex where exactly two real edges of one circle continue straight with the
/// vertex's own blocking status (for example a point that only splits a hemisphere's
/// boundary into minor arcs), or an isolated point with its face's status. Edges are
/// grouped across such vertices.
fn cells(arr: &RegionArrangement, st: &CellStatuses) -> (Vec<bool>, Vec<u32>, Vec<Vec<u32>>) {
    let n = arr.edges().len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut is_cell = vec![false; arr.vertices().len()];
    for (v, vert) in arr.vertices().iter().enumerate() {
        let real: Vec<u32> = vert
            .around
            .iter()
            .copied()
            .filter(|&h| !arr.edges()[(h / 2) as usize].structural)
            .collect();
        let straight = real.len() == 2 && {
            let (a, b) = ((real[0] / 2) as usize, (real[1] / 2) as usize);
            arr.edges()[a].circle == arr.edges()[b].circle && real[0] % 2 != real[1] % 2
        };
        if straight {
            let (a, b) = ((real[0] / 2) as usize, (real[1] / 2) as usize);
            let same = st.edges[a] == st.edges[b] && st.vertices[v] == st.edges[a];
            if vert.structural || same {
                let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                parent[ra] = rb;
                continue;
            }
        }
        is_cell[v] = if vert.structural {
            false
        } else if real.is_empty() {
            vert.around
                .first()
                .is_some_and(|&h| st.vertices[v] != st.cycles[arr.cycle_of(h) as usize])
        } else {
            true
        };
    }
    let mut ids: HashMap<usize, u32> = HashMap::default();
    let mut groups: Vec<Vec<u32>> = Vec::new();
    let mut of = vec![u32::MAX; n];
    for (e, slot) in of.iter_mut().enumerate() {
        if arr.edges()[e].structural {
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
    (is_cell, of, groups)
}
