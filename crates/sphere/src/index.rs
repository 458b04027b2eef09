//! A uniform-grid index of arcs for exact point queries (which arcs may contain a point).

use crate::arc::Arc;
use apart_kernel::spherical::ArcPosition;
use apart_kernel::Vec3;

/// Buckets arcs by the cells of a uniform grid over `[-1, 1]^3` that their conservative
/// boxes touch; a query tests exactly only the arcs in the point's cell.
#[derive(Clone, Debug)]
pub struct ArcIndex {
    g: usize,
    cells: Vec<Vec<u32>>,
}

impl ArcIndex {
    /// Indexes `arcs` (their positions in the slice are the ids returned by queries).
    pub fn new(arcs: &[Arc]) -> ArcIndex {
        let g = ((arcs.len() as f64 / 4.0).cbrt().ceil() as usize).clamp(1, 64);
        let mut cells = vec![Vec::new(); g * g * g];
        let cell = |v: f64| {
            (((v + 1.0) * 0.5 * g as f64).floor() as isize).clamp(0, g as isize - 1) as usize
        };
        for (i, a) in arcs.iter().enumerate() {
            let b = a.bbox();
            let (x0, x1) = (cell(b.min[0]), cell(b.max[0]));
            let (y0, y1) = (cell(b.min[1]), cell(b.max[1]));
            let (z0, z1) = (cell(b.min[2]), cell(b.max[2]));
            for x in x0..=x1 {
                for y in y0..=y1 {
                    for z in z0..=z1 {
                        cells[(x * g + y) * g + z].push(i as u32);
                    }
                }
            }
        }
        ArcIndex { g, cells }
    }

    /// Ids of arcs that may contain `p` (a superset of those that do).
    pub fn candidates(&self, p: &Vec3) -> &[u32] {
        let u = p.unit_f64();
        let g = self.g;
        let cell = |v: f64| {
            (((v + 1.0) * 0.5 * g as f64).floor() as isize).clamp(0, g as isize - 1) as usize
        };
        // A point on a cell boundary could belong to the neighbour: the boxes are padded
        // by more than the rounding of `unit_f64`, so the point's own cell suffices.
        &self.cells[(cell(u[0]) * g + cell(u[1])) * g + cell(u[2])]
    }

    /// The first arc (by id) whose closed arc contains `p`, exactly, with the position.
    pub fn locate(&self, arcs: &[Arc], p: &Vec3) -> Option<(u32, ArcPosition)> {
        self.candidates(p)
            .iter()
            .find_map(|&i| match arcs[i as usize].locate(p) {
                Some(ArcPosition::Outside) | None => None,
                Some(pos) => Some((i, pos)),
            })
    }
}
