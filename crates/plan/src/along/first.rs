//! A quick first solution: the first likely direction that separates, before the
//! full motion space.

use super::DirectionQuery;
use crate::motion_space::CellKind;
use crate::partition::{Partitioning, PhaseSeconds, Solution, Stats};
use crate::regions::{BlockingRegions, Part};
use crate::PlanError;
use std::time::Instant;

impl DirectionQuery<'_> {
    /// The first solution of candidate directions ([`DirectionQuery::candidates`]): the
    /// first candidate with a minimal moving set, as a [`Solution`] of the exact kind of
    /// its cell (its direction is the candidate itself; a face solution's clearance is
    /// [`DirectionQuery::clearance`] there). `None` when no candidate separates.
    pub fn first_solution(&self) -> Result<Option<Solution>, PlanError> {
        for d in self.candidates() {
            let ans = self.answer(&d)?;
            if let Some(m) = ans.moving.first() {
                let clearance = if ans.cell == CellKind::Face {
                    self.clearance(&ans.direction, m)?.to_degrees()
                } else {
                    0.0
                };
                return Ok(Some(Solution {
                    cell: ans.cell,
                    unit: ans.direction.unit_f64(),
                    direction: ans.direction,
                    moving: m.clone(),
                    clearance_deg: clearance,
                }));
            }
        }
        Ok(None)
    }
}

/// `partition` with `first`: tries [`DirectionQuery::first_solution`] and falls back to
/// the full computation ([`crate::partition_subset`]) when no candidate separates. The
/// fast path's statistics count only the sums it computed.
pub fn partition_first(parts: &[Part]) -> Result<Partitioning, PlanError> {
    let t = Instant::now();
    let q = DirectionQuery::new(parts)?;
    if let Some(s) = q.first_solution()? {
        let st = q.stats();
        return Ok(Partitioning {
            names: parts.iter().map(|p| p.name.clone()).collect(),
            interlocked: false,
            sets: vec![crate::partition::MovingSet {
                moving: s.moving.clone(),
                counts: match s.cell {
                    crate::CellKind::Face => [1, 0, 0],
                    crate::CellKind::Edge => [0, 1, 0],
                    crate::CellKind::Vertex => [0, 0, 1],
                },
            }],
            solutions: vec![s],
            truncated: false,
            stopped: false,
            stats: Stats {
                pieces: parts.iter().map(|p| p.pieces.len()).sum(),
                sums: st.sums + st.contact_cones,
                seconds: PhaseSeconds {
                    graphs: t.elapsed().as_secs_f64(),
                    ..Default::default()
                },
                ..Default::default()
            },
        });
    }
    let regions = BlockingRegions::compute(parts)?;
    let all: Vec<usize> = (0..parts.len()).collect();
    Ok(crate::partition_subset(
        &regions,
        &all,
        &crate::Options {
            first: true,
            ..Default::default()
        },
    )
    .0)
}
