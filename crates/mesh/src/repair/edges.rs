//! Every use of every undirected edge, sorted so that the uses of one edge are
//! adjacent: the one table every repair step reads edge pairing from.

use crate::mesh::Mesh;
use rayon::prelude::*;

/// One triangle running along one edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Use {
    /// `lo << 32 | hi`, the edge's vertices with `lo < hi`.
    pub key: u64,
    /// The triangle.
    pub tri: u32,
    /// The triangle runs `lo → hi`.
    pub forward: bool,
}

impl Use {
    /// The smaller vertex of the edge.
    pub fn lo(&self) -> u32 {
        (self.key >> 32) as u32
    }

    /// The larger vertex of the edge.
    pub fn hi(&self) -> u32 {
        self.key as u32
    }
}

/// The key of edge `a b`, either direction.
pub(super) fn key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    (lo as u64) << 32 | hi as u64
}

/// All edge uses, sorted by edge and then triangle.
pub(super) fn uses(mesh: &Mesh) -> Vec<Use> {
    let mut out: Vec<Use> = mesh
        .triangles
        .par_iter()
        .enumerate()
        .with_min_len(4096)
        .flat_map_iter(|(t, tri)| {
            (0..3).map(move |k| {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                Use {
                    key: key(a, b),
                    tri: t as u32,
                    forward: a < b,
                }
            })
        })
        .collect();
    out.par_sort_unstable_by_key(|u| (u.key, u.tri, u.forward));
    out
}

/// The uses grouped by edge.
pub(super) fn runs(uses: &[Use]) -> impl Iterator<Item = &[Use]> {
    uses.chunk_by(|a, b| a.key == b.key)
}

/// Numbers of uses `lo → hi` and `hi → lo` in one run.
pub(super) fn balance(run: &[Use]) -> (usize, usize) {
    let f = run.iter().filter(|u| u.forward).count();
    (f, run.len() - f)
}
