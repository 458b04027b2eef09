//! Partitioning: every direction and subset that separates a (sub)assembly by one
//! infinite translation.

use crate::clearance::{climb, face_boundary, isolated_points, starting_points};
use crate::dbg::Dbg;
use crate::motion_space::{CellKind, MotionSpace};
use crate::regions::{BlockingRegions, PartPieces};
use crate::PlanError;
use apart_kernel::Vec3;
use apart_sphere::BitSet;
use rayon::prelude::*;
use rustc_hash::FxHashMap as HashMap;
use std::time::Instant;

/// Choices for [`partition`].
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Stop at the first solution found (faces, then edges, then vertices).
    pub first: bool,
}

/// One way to separate: `moving` translates along `direction`, the rest stays.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The kind of motion-space cell the direction lies in.
    pub cell: CellKind,
    /// An exact integer direction in that cell (the vertex itself, an interior point of
    /// the edge, or a point deep inside the face).
    pub direction: Vec3,
    /// The same direction as a unit vector.
    pub unit: [f64; 3],
    /// The parts that move (global indices, sorted): a minimal movable subset.
    pub moving: Vec<usize>,
    /// For faces, the angular distance in degrees from `direction` to the face's
    /// boundary; 0 for edges and vertices.
    pub clearance_deg: f64,
}

/// Seconds spent in each phase.
#[derive(Clone, Copy, Debug, Default)]
pub struct PhaseSeconds {
    /// Minkowski sums.
    pub sums: f64,
    /// Central projections.
    pub projection: f64,
    /// Per-pair unions.
    pub unions: f64,
    /// Overlay of all pairs (the motion space).
    pub overlay: f64,
    /// Blocking graphs, components and solution directions.
    pub graphs: f64,
}

/// Sizes and timings of a partitioning run.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// Convex pieces.
    pub pieces: usize,
    /// Minkowski sums.
    pub sums: usize,
    /// Arcs inserted into the motion-space overlay.
    pub arcs: usize,
    /// Real vertices of the motion space.
    pub vertices: usize,
    /// Real edges of the motion space.
    pub edges: usize,
    /// Faces of the motion space.
    pub faces: usize,
    /// Phase timings.
    pub seconds: PhaseSeconds,
}

/// The result of partitioning.
#[derive(Clone, Debug)]
pub struct Partitioning {
    /// Part names (global order).
    pub names: Vec<String>,
    /// True when no proper subset can move along any direction.
    pub interlocked: bool,
    /// All solutions: faces by decreasing clearance, then edges, then vertices.
    pub solutions: Vec<Solution>,
    /// Sizes and timings.
    pub stats: Stats,
}

/// Partitions an assembly loaded by `apart-assembly` (parts without declared pieces must
/// be convex until automatic decomposition is available).
pub fn partition(
    assembly: &apart_assembly::Assembly,
    opts: &Options,
) -> Result<Partitioning, PlanError> {
    partition_pieces(&crate::regions::parts_of(assembly)?, opts)
}

/// Partitions an assembly given as convex pieces per part.
pub fn partition_pieces(parts: &[PartPieces], opts: &Options) -> Result<Partitioning, PlanError> {
    let regions = BlockingRegions::compute(parts)?;
    let all: Vec<usize> = (0..parts.len()).collect();
    Ok(partition_subset(&regions, &all, opts).0)
}

/// Partitions the subassembly `subset` (global part indices) from precomputed regions;
/// also returns its motion space (for drawing and direction queries).
pub fn partition_subset(
    regions: &BlockingRegions,
    subset: &[usize],
    opts: &Options,
) -> (Partitioning, MotionSpace) {
    let t = Instant::now();
    let ms = MotionSpace::build(regions, subset);
    let overlay = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let solutions = solutions(regions, &ms, opts);
    let graphs = t.elapsed().as_secs_f64();
    let arr = ms.arrangement();
    let rs = regions.stats;
    let stats = Stats {
        pieces: rs.pieces,
        sums: rs.sums,
        arcs: ms.input_arcs,
        vertices: ms.real_vertices().count(),
        edges: ms.edge_cells().len(),
        faces: arr.faces().len(),
        seconds: PhaseSeconds {
            sums: rs.sums_seconds,
            projection: rs.projection_seconds,
            unions: rs.unions_seconds,
            overlay,
            graphs,
        },
    };
    let p = Partitioning {
        names: regions.names().to_vec(),
        interlocked: solutions.is_empty(),
        solutions,
        stats,
    };
    (p, ms)
}

/// Every (cell, minimal moving subset) of the motion space, or the first one.
fn solutions(regions: &BlockingRegions, ms: &MotionSpace, opts: &Options) -> Vec<Solution> {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let mut memo: HashMap<BitSet, Vec<Vec<usize>>> = HashMap::default();
    let mut sets = |s: &BitSet| -> Vec<Vec<usize>> {
        memo.entry(s.clone())
            .or_insert_with(|| ms.dbg(s).minimal_moving_sets())
            .clone()
    };
    let global =
        |local: Vec<usize>| -> Vec<usize> { local.into_iter().map(|k| ms.parts()[k]).collect() };
    let mut out = Vec::new();

    // Faces with solutions; their deep directions are independent searches, run in parallel.
    let mut faces: Vec<(usize, Vec<Vec<usize>>)> = Vec::new();
    for f in 0..arr.faces().len() {
        let moving = sets(&st.faces[f]);
        if !moving.is_empty() {
            faces.push((f, moving));
            if opts.first {
                break;
            }
        }
    }
    let isolated = isolated_points(arr);
    let directions: Vec<(Vec3, f64)> = faces
        .par_iter()
        .map(|(f, _)| face_direction(regions, ms, *f as u32, &st.faces[*f], &isolated[*f]))
        .collect();
    for ((_, moving), (direction, clearance)) in faces.into_iter().zip(directions) {
        for m in moving {
            out.push(Solution {
                cell: CellKind::Face,
                unit: direction.unit_f64(),
                direction: direction.clone(),
                moving: global(m),
                clearance_deg: clearance.to_degrees(),
            });
        }
        if opts.first {
            out.truncate(1);
            return out;
        }
    }
    out.sort_by(|a, b| {
        b.clearance_deg
            .total_cmp(&a.clearance_deg)
            .then_with(|| a.moving.cmp(&b.moving))
    });

    for cell in ms.edge_cells() {
        let e = cell[0] as usize;
        let moving = sets(&st.edges[e]);
        if moving.is_empty() {
            continue;
        }
        let direction = arr.edge_arc(e as u32).interior_point().primitive();
        for m in moving {
            out.push(Solution {
                cell: CellKind::Edge,
                unit: direction.unit_f64(),
                direction: direction.clone(),
                moving: global(m),
                clearance_deg: 0.0,
            });
        }
        if opts.first {
            out.truncate(1);
            return out;
        }
    }
    for v in ms.real_vertices() {
        let moving = sets(&st.vertices[v]);
        if moving.is_empty() {
            continue;
        }
        let direction = arr.vertices()[v].point.clone();
        for m in moving {
            out.push(Solution {
                cell: CellKind::Vertex,
                unit: direction.unit_f64(),
                direction: direction.clone(),
                moving: global(m),
                clearance_deg: 0.0,
            });
        }
        if opts.first {
            out.truncate(1);
            return out;
        }
    }
    // Edges and vertices in a stable order: by kind, moving set, then direction.
    let faces = out.iter().take_while(|s| s.cell == CellKind::Face).count();
    out[faces..].sort_by(|a, b| {
        a.cell
            .cmp(&b.cell)
            .then_with(|| a.moving.cmp(&b.moving))
            .then_with(|| a.direction.to_strings().cmp(&b.direction.to_strings()))
    });
    out
}

/// The exact blocking graph at direction `d` for the parts of `ms`, from the pair
/// regions' polygons (independent of the overlay).
pub fn dbg_at(regions: &BlockingRegions, parts: &[usize], d: &Vec3) -> Dbg {
    let mut arcs = Vec::new();
    for (li, &i) in parts.iter().enumerate() {
        for (lj, &j) in parts.iter().enumerate() {
            if i != j && regions.blocks(i, j, d) {
                arcs.push((li, lj));
            }
        }
    }
    Dbg::new(parts.len(), arcs)
}

/// A direction deep inside face `f` with its clearance (radians): the best of a
/// clearance-climbing search from points next to the boundary, verified exactly (on no
/// arc of the motion space, with the face's blocking graph); falls back to an exact
/// point of the face found without floating point when verification fails.
fn face_direction(
    regions: &BlockingRegions,
    ms: &MotionSpace,
    f: u32,
    status: &BitSet,
    points: &[[f64; 3]],
) -> (Vec3, f64) {
    let arr = ms.arrangement();
    let want = ms.dbg(status);
    let arcs = face_boundary(arr, f);
    let verify = |d: &Vec3| -> bool {
        !d.is_zero() && ms.locate(d).0 == CellKind::Face && dbg_at(regions, ms.parts(), d) == want
    };
    if arcs.is_empty() && points.is_empty() {
        // The whole sphere is one face: any direction, with half-turn clearance.
        return (Vec3::new(0, 0, 1), std::f64::consts::PI);
    }
    let mut best: Option<([f64; 3], f64)> = None;
    let mut starts: Vec<[f64; 3]> = starting_points(&arcs, points, 8)
        .into_iter()
        .take(2)
        .map(|(p, _)| p)
        .collect();
    if arcs.is_empty() {
        // Only isolated points bound the face: start opposite the first one.
        starts.push(points[0].map(|x| -x));
    }
    for p in starts {
        let (q, c) = climb(p, &arcs, points);
        if best.is_none_or(|(_, bc)| c > bc) {
            best = Some((q, c));
        }
    }
    if let Some((p, c)) = best {
        // A small integer direction with nearly the best clearance reads better.
        if let Some(found) = crate::clearance::simple_direction(&p, c, 0.9, &arcs, points, &verify)
        {
            return found;
        }
        for bits in [20, 30, 40] {
            let scale = (1u64 << bits) as f64;
            let d = Vec3::new(
                (p[0] * scale).round() as i64,
                (p[1] * scale).round() as i64,
                (p[2] * scale).round() as i64,
            )
            .primitive();
            if verify(&d) {
                return (d, c);
            }
        }
    }
    let d = ms.face_sample(f);
    debug_assert!(
        verify(&d),
        "the exact face sample must have the face's graph"
    );
    let c = crate::clearance::clearance(&d.unit_f64(), &arcs, points);
    (d, c)
}
