//! Loading: read every file once (in parallel), apply transforms, choose one grid for
//! all coordinates, then snap and validate every part and piece (in parallel), then
//! check the parts against each other.

mod build;
mod winding;

pub(crate) use build::fmt_len;

use crate::description::Description;
use crate::error::LoadError;
use crate::inputs::{self, Names, Origin, PartSpec, Plan, Root, SourceRef};
use crate::model::{Assembly, LoadSeconds, Loaded, Part, Repairs, WindingReport};
use crate::options::{check_stop, Decompose, LoadOptions};
use crate::overlap;
use crate::snapping;
use crate::tolerance::{self, Tolerance};
use apart_formats::{read_file_with, RawObject, ReadOptions};
use apart_kernel::grid::{GridError, MAX_BITS, MIN_BITS};
use apart_kernel::progress::phases;
use apart_kernel::Grid;
use apart_mesh::{Problem, ProblemKind};
use apart_pieces::Polytope;
use build::{build_parts, unique_name, Built, Ctx, InputPoints, Largest};
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

/// Loads an assembly from a folder, a mesh file or a manifest (see the crate docs).
/// Fails only when nothing can be loaded; every problem with parts, pieces or their
/// relations is collected in [`Loaded::problems`].
pub fn load(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    check_bits(opts)?;
    let plan = inputs::plan(path, &read_options(opts))?;
    load_plan(plan, opts)
}

/// Loads an assembly described in memory (see [`crate::description`]): exactly as the
/// manifest it stands for, except that the files it names are read wherever they lie
/// (the caller named them) and meshes given as arrays are named by their part and
/// element only. Fails when the description breaks a manifest's rules (no parts, a
/// part without a name or without a mesh or pieces, two parts of one name) or nothing
/// can be loaded; every other problem is collected in [`Loaded::problems`].
pub fn load_description(description: Description, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    check_bits(opts)?;
    description.check().map_err(LoadError::Description)?;
    let plan = inputs::from_description(description, None, Path::new(""));
    load_plan(plan, opts)
}

/// Fails before reading anything when the grid bits are out of the range the snapper
/// can honour (see `apart_kernel::grid`).
fn check_bits(opts: &LoadOptions) -> Result<(), LoadError> {
    if !(MIN_BITS..=MAX_BITS).contains(&opts.grid_bits) {
        return Err(GridError::BitsOutOfRange(opts.grid_bits).into());
    }
    Ok(())
}

/// The readers' options: glTF buffers outside the file's folder follow the same rule
/// as mesh files.
fn read_options(opts: &LoadOptions) -> ReadOptions {
    ReadOptions::default().allow_outside(opts.allow_outside)
}

/// Loads the parts a plan lists: reads every file once, chooses one grid, builds and
/// validates the parts, decomposes them, and checks them against each other.
fn load_plan(plan: Plan, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let mut seconds = LoadSeconds::default();
    let mut clock = Instant::now();
    let mut lap = || {
        let now = Instant::now();
        let s = now.duration_since(clock).as_secs_f64();
        clock = now;
        s
    };
    let Plan {
        name,
        root,
        parts: specs,
        mut problems,
        preloaded,
        skipped,
    } = plan;
    let read = read_files(&specs, root.as_deref(), preloaded, opts);
    check_stop(opts, phases::READING)?;
    seconds.read = lap();
    let raw = raw_parts(&specs, read);
    let scan = GridScan::of(&raw, opts)?;
    let ctx = Ctx {
        grid: &scan.grid,
        opts,
        largest: scan.largest.as_ref(),
    };
    let (mut parts, raw_points, repairs) = build_all(raw, &ctx, &mut problems);
    check_stop(opts, phases::VALIDATING)?;
    seconds.validate = lap();
    if needs_pieces(opts, parts.len()) {
        problems.extend(decompose_parts(&mut parts, opts));
        check_stop(opts, phases::DECOMPOSING)?;
    }
    seconds.decompose = lap();
    // Relations between parts that snapping changed (needs the pieces, for the exact
    // overlap test of the few pairs it asks about). When snapping moved no coordinate
    // (integer inputs, or values already on the grid), no relation can have changed:
    // the search, most of loading a small integer assembly, is skipped.
    // Pairs of parts whose interiors that check found disjoint: the overlap check
    // below skips them.
    let mut disjoint = Vec::new();
    if scan.max_snap_displacement > 0.0 {
        let (warnings, apart) =
            snapping::changed_relations(&parts, &raw_points, &scan.grid, &opts.progress);
        problems.extend(warnings);
        disjoint = apart;
        check_stop(opts, phases::OVERLAPS)?;
    }
    drop(raw_points);
    seconds.snapping = lap();
    let mut assembly = Assembly {
        name,
        grid: scan.grid,
        max_snap_displacement: scan.max_snap_displacement,
        parts,
        tolerance: None,
    };
    if opts.tolerance == Tolerance::None {
        problems.extend(overlap::check_parts(&assembly, opts, &disjoint));
    } else {
        problems.extend(tolerance::apply(
            &mut assembly,
            opts.tolerance,
            opts,
            &disjoint,
        ));
    }
    check_stop(opts, phases::OVERLAPS)?;
    seconds.overlaps = lap();
    Ok(Loaded {
        assembly,
        problems,
        repairs,
        skipped,
        seconds,
    })
}

/// What reading each file gave (its objects, or why it could not be read), and the
/// meshes given as arrays.
type ReadFiles = HashMap<Origin, Result<Vec<RawObject>, String>>;

/// Reads every file the parts name once, in parallel, with the meshes already in
/// memory (`preloaded`). A file outside `root` (unless [`LoadOptions::allow_outside`])
/// or that is not a regular file is never opened; once the stop flag is raised, no
/// file is. Meshes given as arrays count as read at once.
fn read_files(
    specs: &[PartSpec],
    root: Option<&Path>,
    preloaded: HashMap<Origin, Vec<RawObject>>,
    opts: &LoadOptions,
) -> ReadFiles {
    let read_opts = read_options(opts);
    let mut files: Vec<&Path> = specs
        .iter()
        .flat_map(|p| p.mesh.iter().chain(&p.pieces))
        .filter(|s| !preloaded.contains_key(&s.origin))
        .filter_map(|s| s.origin.file())
        .collect();
    files.sort();
    files.dedup();
    let root = match opts.allow_outside {
        false => root.map(Root::new),
        true => None,
    };
    let arrays = preloaded
        .keys()
        .filter(|o| matches!(o, Origin::Arrays(_)))
        .count();
    let counter = opts.progress.counter(phases::READING, arrays + files.len());
    // One by one, as files are counted.
    for _ in 0..arrays {
        counter.add(1);
    }
    let mut read: ReadFiles = files
        .par_iter()
        .map(|p| {
            let origin = Origin::File(p.to_path_buf());
            if opts.progress.stopped() {
                return (origin, Err("loading was stopped".to_string()));
            }
            let r = root
                .as_ref()
                .map_or(Ok(()), |root| root.inside(p))
                .and_then(|()| inputs::regular_file(p))
                .and_then(|()| read_file_with(p, &read_opts).map_err(|e| e.to_string()));
            counter.add(1);
            (origin, r)
        })
        .collect();
    read.extend(preloaded.into_iter().map(|(p, o)| (p, Ok(o))));
    read
}

/// The raw solids of every part, transformed: each object of a file is taken out at
/// its last use rather than copied.
fn raw_parts<'a>(specs: &'a [PartSpec], mut read: ReadFiles) -> Vec<RawPart<'a>> {
    // How often each object is used: the last use takes it instead of copying it.
    let mut uses: HashMap<(&Origin, Option<usize>), usize> = HashMap::new();
    for s in specs.iter().flat_map(|p| p.mesh.iter().chain(&p.pieces)) {
        *uses.entry((&s.origin, s.object)).or_default() += 1;
    }
    specs
        .iter()
        .map(|spec| {
            let mut probs = Vec::new();
            let mut get = |s: &'a SourceRef| {
                let left = uses.get_mut(&(&s.origin, s.object)).map(|n| {
                    *n -= 1;
                    *n
                });
                let objects = match read.get_mut(&s.origin) {
                    Some(Ok(o)) => Ok(o),
                    Some(Err(e)) => Err(&*e),
                    None => unreachable!("every source of the plan was read"),
                };
                match resolve(s, objects, left == Some(0)) {
                    Ok(o) => Some(o),
                    Err(p) => {
                        probs.push(s.locate(p).in_part(&spec.name));
                        None
                    }
                }
            };
            let mesh = spec.mesh.as_ref().and_then(&mut get);
            let pieces = spec.pieces.iter().map(|s| (s, get(s))).collect();
            RawPart {
                spec,
                mesh,
                pieces,
                problems: probs,
            }
        })
        .collect()
}

/// The grid chosen for every coordinate, with the part whose coordinates set its step
/// and how far snapping moves a coordinate at most.
struct GridScan {
    grid: Grid,
    largest: Option<Largest>,
    max_snap_displacement: f64,
}

impl GridScan {
    /// One grid for everything. `Grid::choose` depends only on the largest magnitude
    /// and on whether some value is not an integer, so both are found in parallel (per
    /// part, to name the part that sets the step) and the grid is chosen from that
    /// value and one non-integer witness.
    fn of(raw: &[RawPart], opts: &LoadOptions) -> Result<GridScan, LoadError> {
        let scan = |o: &RawObject| {
            o.vertices
                .par_iter()
                .with_min_len(8192)
                .fold(
                    || (0f64, None),
                    |(m, f): (f64, Option<f64>), v| {
                        v.iter()
                            .filter(|c| c.is_finite())
                            .fold((m, f), |(m, f), &c| {
                                (m.max(c.abs()), f.or((c.fract() != 0.0).then_some(c)))
                            })
                    },
                )
                .reduce(|| (0f64, None), |(m, f), (n, g)| (m.max(n), f.or(g)))
        };
        let per_part: Vec<(f64, Option<f64>)> = raw
            .iter()
            .map(|r| {
                r.solids()
                    .map(scan)
                    .fold((0f64, None), |(m, f), (n, g)| (m.max(n), f.or(g)))
            })
            .collect();
        let (max_abs, non_integer) = per_part
            .iter()
            .fold((0f64, None), |(m, f), &(n, g)| (m.max(n), f.or(g)));
        let grid = Grid::choose(std::iter::once(max_abs).chain(non_integer), opts.grid_bits)?;
        let grid = finer_for_tolerance(grid, max_abs, opts)?;
        let largest = per_part
            .iter()
            .position(|&(m, _)| m == max_abs)
            .map(|k| Largest {
                part: raw[k].spec.name.clone(),
                magnitude: max_abs,
            });
        let max_snap_displacement = raw
            .iter()
            .flat_map(RawPart::solids)
            .map(|o| {
                o.vertices
                    .par_iter()
                    .with_min_len(8192)
                    .map(|v| {
                        v.iter()
                            .filter(|c| c.is_finite())
                            .map(|&c| grid.displacement(c))
                            .fold(0.0, f64::max)
                    })
                    .reduce(|| 0.0, f64::max)
            })
            .fold(0.0, f64::max);
        Ok(GridScan {
            grid,
            largest,
            max_snap_displacement,
        })
    }
}

/// The parts, built and validated in parallel, with the input coordinates of each
/// part's mesh vertices (for the snapping check) and the repairs made. Part names are
/// made unique (files split into bodies may collide with other names) before their
/// problems join `problems`, so that a renamed part's problems name it. Once the stop
/// flag is raised, no part is begun (and the parts are incomplete).
fn build_all(
    raw: Vec<RawPart>,
    ctx: &Ctx,
    problems: &mut Vec<Problem>,
) -> (Vec<Part>, Vec<InputPoints>, Vec<Repairs>) {
    let progress = &ctx.opts.progress;
    let counter = progress.counter(phases::VALIDATING, raw.len());
    let built: Vec<Built> = raw
        .into_par_iter()
        .filter_map(|r| {
            if progress.stopped() {
                return None;
            }
            let out = build_parts(r, ctx);
            counter.add(1);
            Some(out)
        })
        .collect();
    let mut parts = Vec::with_capacity(built.len());
    let mut raw_points = Vec::with_capacity(built.len());
    let mut repairs = Vec::new();
    let mut names = Names::default();
    for mut b in built {
        for (part, probs, _) in &mut b.parts {
            unique_name(&mut names, part, probs);
        }
        let wound: Vec<WindingReport> = b
            .parts
            .iter_mut()
            .filter_map(|(p, _, _)| {
                let w = p.winding.as_mut()?;
                w.part = p.name.clone();
                Some(w.clone())
            })
            .collect();
        let record = match (b.repairs, wound.is_empty()) {
            (Some(r), _) => Some(r),
            (None, false) => Some(Repairs {
                file: b.parts[0].0.source.clone(),
                parts: Vec::new(),
                report: Default::default(),
                winding: Vec::new(),
            }),
            (None, true) => None,
        };
        if let Some(mut record) = record {
            record.parts = b.parts.iter().map(|(p, _, _)| p.name.clone()).collect();
            record.winding = wound;
            repairs.push(record);
        }
        for (part, probs, points) in b.parts {
            parts.push(part);
            raw_points.push(points);
            problems.extend(probs);
        }
    }
    (parts, raw_points, repairs)
}

/// Whether every part needs convex pieces: a tolerance shrinks them, and the overlap
/// check between two parts or more is complete on them.
fn needs_pieces(opts: &LoadOptions, parts: usize) -> bool {
    match opts.decompose {
        _ if opts.tolerance != Tolerance::None => true,
        Decompose::Never => false,
        Decompose::WhenNeeded => parts >= 2,
        Decompose::Always => true,
    }
}

/// Decomposes every valid non-convex part without pieces, in parallel; once the stop
/// flag is raised, no decomposition is begun.
fn decompose_parts(parts: &mut [Part], opts: &LoadOptions) -> Vec<Problem> {
    let todo: Vec<usize> = (0..parts.len())
        .filter(|&k| {
            let p = &parts[k];
            p.pieces.is_empty()
                && !p.convex
                && p.mesh.is_some()
                && p.info
                    .as_ref()
                    .is_some_and(|i| i.closed && i.volume6.is_some() && i.self_intersections == 0)
        })
        .collect();
    let counter = opts.progress.counter(phases::DECOMPOSING, todo.len());
    let results: Vec<(usize, Result<Vec<Polytope>, Problem>)> = todo
        .par_iter()
        .filter_map(|&k| {
            if opts.progress.stopped() {
                return None;
            }
            let p = &parts[k];
            let mesh = p.mesh.as_ref().expect("filtered");
            let points = mesh.points();
            let r = apart_decompose::decompose(&points, &mesh.triangles, &Default::default())
                .map_err(|e| {
                    Problem::error(format!("exact convex decomposition failed: {e}"))
                        .with_kind(ProblemKind::Decomposition)
                })
                .and_then(|d| {
                    if opts.verify {
                        apart_decompose::verify(&points, &mesh.triangles, &d.pieces).map_err(
                            |e| {
                                Problem::error(format!(
                                    "the convex decomposition did not verify: {e}"
                                ))
                                .with_kind(ProblemKind::Decomposition)
                            },
                        )?;
                    }
                    Ok(d.pieces)
                });
            counter.add(1);
            Some((k, r.map_err(|e| e.in_part(p.name.clone()))))
        })
        .collect();
    let mut problems = Vec::new();
    for (k, r) in results {
        match r {
            Ok(pieces) => {
                parts[k].pieces = pieces;
                parts[k].decomposed = true;
            }
            Err(p) => problems.push(p),
        }
    }
    problems
}

/// One specification's solids as read and transformed, before snapping.
struct RawPart<'a> {
    spec: &'a PartSpec,
    mesh: Option<RawObject>,
    /// Each declared piece's source, and its solid when it could be read.
    pieces: Vec<(&'a SourceRef, Option<RawObject>)>,
    problems: Vec<Problem>,
}

impl RawPart<'_> {
    /// The mesh and every piece that could be read.
    fn solids(&self) -> impl Iterator<Item = &RawObject> {
        self.mesh
            .iter()
            .chain(self.pieces.iter().filter_map(|p| p.1.as_ref()))
    }
}

/// One object (or all merged) of a file, with the transform applied; a mirroring
/// transform reverses the faces so that they stay outward. `last` use takes the object
/// out of the file's list rather than copying it.
fn resolve(
    s: &SourceRef,
    objects: Result<&mut Vec<RawObject>, &String>,
    last: bool,
) -> Result<RawObject, Problem> {
    let objects =
        objects.map_err(|e| Problem::error(e.clone()).with_kind(ProblemKind::Unreadable))?;
    let take = |o: &mut RawObject| if last { std::mem::take(o) } else { o.clone() };
    let mut o = match s.object {
        Some(k) => take(objects.get_mut(k).ok_or_else(|| {
            Problem::error(format!("the file has no object {k}")).with_kind(ProblemKind::Unreadable)
        })?),
        None if objects.is_empty() => {
            return Err(Problem::error("the file holds no mesh").with_kind(ProblemKind::Unreadable))
        }
        None if objects.len() == 1 => take(&mut objects[0]),
        None => RawObject::merged(objects, None),
    };
    if !s.transform.is_identity() {
        o.map_vertices(|v| s.transform.apply(v));
        if s.transform.det() < 0.0 {
            o.faces.reverse_each();
        }
    }
    Ok(o)
}

/// A stated tolerance finer than the grid: integer inputs get the unit grid, and a
/// piece shrunk by `eps` is cut by `eps` plus one step, so a tolerance of 0.001 on
/// parts 2 units thick would leave nothing. The grid is then refined to a step of at
/// most `eps / 64` (a power of two), or the finest that `bits` allow, whichever is
/// coarser: any tolerance is honoured as long as a part is a few steps thick, and
/// `bits` steps span the assembly (30 bits: 1e-9 of its size).
fn finer_for_tolerance(grid: Grid, max_abs: f64, opts: &LoadOptions) -> Result<Grid, LoadError> {
    let Tolerance::Fixed(eps) = opts.tolerance else {
        return Ok(grid);
    };
    if !(eps.is_finite() && eps > 0.0) || eps >= 64.0 * grid.step() {
        return Ok(grid);
    }
    // The finest grid the bits allow: as if some coordinate were not an integer.
    let finest = Grid::choose([max_abs, 0.5], opts.grid_bits)?;
    let want = eps.log2().floor() as i32 - 6;
    Ok(Grid {
        exp: want.clamp(finest.exp, grid.exp),
        bits: grid.bits,
    })
}
