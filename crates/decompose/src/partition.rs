//! The binary space partition: split cells until the solid is convex in each.
//!
//! A cell is a leaf when no reflex edge, non-manifold edge or non-manifold vertex meets
//! its open interior and its fragments form one group (connected across paired input
//! edges inside the open cell). Then the solid is locally convex inside the cell, so the
//! interior of solid ∩ cell is a union of convex components, each bounded inside the
//! cell by its own groups; one group means one component K, and K is convex and equal
//! to the cell cut by the inner half-spaces of the group's planes. (With two groups, one
//! component may still own both, e.g. a slab crossing the cell with its two faces not
//! connected inside it; two components may also overlap in their half-space regions: so
//! such cells are split further, by a fragment plane, until one group remains.)
//! Non-manifold edges and vertices are split away because two cones of the solid
//! touching there could belong to one component that is not convex.
//!
//! Termination: a split plane contains the element or fragment it was chosen for, which
//! then meets neither open part; parts only inherit elements and planes of their parent.

use crate::cell::Cell;
use crate::fragments::{split_by, Frag};
use crate::solid::Solid;
use crate::split::{for_groups, for_live, live, Choice};
use crate::DecomposeError;
use apart_kernel::plane::Plane;
use rustc_hash::FxHashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// Cells with fewer fragments than this in either part are processed sequentially.
const PARALLEL_MIN: usize = 48;

/// Counters of a partition run.
#[derive(Default)]
pub(crate) struct Counters {
    pub splits: AtomicUsize,
    pub cells: AtomicUsize,
}

pub(crate) struct Partition<'a> {
    solid: &'a Solid,
    parallel: bool,
    pub counters: Counters,
}

struct Task {
    cell: Cell,
    frags: Vec<Arc<Frag>>,
    /// Whether the cell is inside the solid, should it have no fragment.
    inside: bool,
}

enum Step {
    Piece(Cell),
    Nothing,
    Split(Task, Task),
}

impl<'a> Partition<'a> {
    pub fn new(solid: &'a Solid, parallel: bool) -> Partition<'a> {
        Partition {
            solid,
            parallel,
            counters: Counters::default(),
        }
    }

    /// The convex cells whose union is the solid.
    pub fn run(&self) -> Result<Vec<Cell>, DecomposeError> {
        let s = self.solid;
        let lo = s.bbox.min.map(|v| v - 1);
        let hi = s.bbox.max.map(|v| v + 1);
        let frags = Frag::all_whole(s);
        self.solve(Task {
            cell: Cell::boxed(lo, hi),
            frags,
            inside: false,
        })
    }

    fn solve(&self, task: Task) -> Result<Vec<Cell>, DecomposeError> {
        let mut out = Vec::new();
        let mut stack = vec![task];
        while let Some(t) = stack.pop() {
            match self.step(t)? {
                Step::Piece(c) => out.push(c),
                Step::Nothing => {}
                Step::Split(a, b) => {
                    if self.parallel && a.frags.len().min(b.frags.len()) >= PARALLEL_MIN {
                        let (ra, rb) = rayon::join(|| self.solve(a), || self.solve(b));
                        out.extend(ra?);
                        out.extend(rb?);
                    } else {
                        stack.push(b);
                        stack.push(a);
                    }
                }
            }
        }
        Ok(out)
    }

    fn step(&self, t: Task) -> Result<Step, DecomposeError> {
        self.counters.cells.fetch_add(1, Ordering::Relaxed);
        if t.frags.is_empty() {
            return Ok(if t.inside {
                Step::Piece(t.cell)
            } else {
                Step::Nothing
            });
        }
        let s = self.solid;
        let in_cell: FxHashMap<u32, u32> = t
            .frags
            .iter()
            .enumerate()
            .map(|(i, f)| (f.tri, i as u32))
            .collect();
        let l = live(s, &t.frags);
        if !l.is_empty() {
            let choice = for_live(s, &t.frags, &in_cell, &l);
            return self.divide(t, choice);
        }
        if groups(s, &t.frags, &in_cell) == 1 {
            return leaf(s, t);
        }
        let choice = for_groups(s, &t.frags);
        self.divide(t, choice)
    }

    fn divide(&self, t: Task, choice: Choice) -> Result<Step, DecomposeError> {
        self.counters.splits.fetch_add(1, Ordering::Relaxed);
        let h = choice.plane;
        let (below, above) = t.cell.split(&h, true);
        let (Some(below), Some(above)) = (below, above) else {
            return Err(DecomposeError::Internal(
                "a splitting plane missed the open cell".into(),
            ));
        };
        let (fb, fa) = split_by(&t.frags, &h, self.solid);
        Ok(Step::Split(
            Task {
                cell: below,
                frags: fb,
                inside: choice.below_inside,
            },
            Task {
                cell: above,
                frags: fa,
                inside: choice.above_inside,
            },
        ))
    }
}

/// Number of groups of fragments connected across paired input edges in the open cell.
fn groups(s: &Solid, frags: &[Arc<Frag>], in_cell: &FxHashMap<u32, u32>) -> usize {
    let mut parent: Vec<u32> = (0..frags.len() as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    let mut count = frags.len();
    for (i, f) in frags.iter().enumerate() {
        for e in &f.edges {
            if let (crate::fragments::Origin::Side(k), false) = (e.origin, e.bnd) {
                let other = s.partner[f.tri as usize][k as usize];
                if let Some(&j) = in_cell.get(&other) {
                    let (a, b) = (find(&mut parent, i as u32), find(&mut parent, j));
                    if a != b {
                        parent[a as usize] = b;
                        count -= 1;
                    }
                }
            }
        }
    }
    count
}

/// The leaf piece: the cell cut by the inner half-spaces of its fragments' planes.
fn leaf(s: &Solid, t: Task) -> Result<Step, DecomposeError> {
    let planes: Vec<Plane> = t.frags.iter().map(|f| s.planes[f.tri as usize]).collect();
    let pts = t
        .frags
        .iter()
        .map(|f| f.pts.iter().map(|p| (&*p.p, p.bnd)).collect::<Vec<_>>())
        .collect::<Vec<_>>();
    t.cell
        .carve(&planes, &pts)
        .map(Step::Piece)
        .ok_or_else(|| DecomposeError::Internal("a convex leaf lost its interior".into()))
}
