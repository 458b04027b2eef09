//! Loading: read every file once (in parallel), apply transforms, choose one grid for
//! all coordinates, then snap and validate every part and piece (in parallel), then
//! check the parts against each other.

use crate::error::LoadError;
use crate::inputs::{self, Names, PartSpec, Root, SourceRef};
use crate::model::Repairs;
use crate::model::{Assembly, LoadSeconds, Loaded, Part};
use crate::options::{Decompose, LoadOptions, Stage, Tracker};
use crate::tolerance::{self, Tolerance};
use crate::{overlap, pieces};
use apart_formats::escape::escape;
use apart_formats::{read_file_with, RawObject, ReadOptions};
use apart_kernel::grid::{GridError, MAX_BITS, MIN_BITS};
use apart_kernel::Aabb;
use apart_kernel::{Grid, Int, Rational};
use apart_mesh::locate::Locator;
use apart_mesh::repair::{bodies, repair, RepairOptions};
use apart_mesh::validate::{validate, MeshInfo};
use apart_mesh::{Mesh, Problem, ProblemKind};
use apart_pieces::Polytope;
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Loads an assembly from a folder, a mesh file or a manifest (see the crate docs).
/// Fails only when nothing can be loaded; every problem with parts, pieces or their
/// relations is collected in [`Loaded::problems`].
pub fn load(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    // Before reading anything: the bits the snapper can honour (see `apart_kernel::grid`).
    if !(MIN_BITS..=MAX_BITS).contains(&opts.grid_bits) {
        return Err(GridError::BitsOutOfRange(opts.grid_bits).into());
    }
    // glTF buffers outside the file's folder follow the same rule as mesh files.
    let read_opts = ReadOptions::default().allow_outside(opts.allow_outside);
    let plan = inputs::plan(path, &read_opts)?;
    let mut problems = plan.problems.clone();
    let mut seconds = LoadSeconds::default();
    let mut clock = Instant::now();
    let mut lap = || {
        let now = Instant::now();
        let s = now.duration_since(clock).as_secs_f64();
        clock = now;
        s
    };

    // Read every file once; a file outside the assembly's folder or that is not a
    // regular file is never opened.
    let mut files: Vec<&Path> = plan
        .parts
        .iter()
        .flat_map(|p| p.mesh.iter().chain(&p.pieces))
        .map(|s| s.path.as_path())
        .filter(|p| !plan.preloaded.contains_key(*p))
        .collect();
    files.sort();
    files.dedup();
    let root = match opts.allow_outside {
        false => plan.root.as_deref().map(Root::new),
        true => None,
    };
    let tracker = Tracker::start(opts, Stage::Reading, files.len());
    let mut read: HashMap<PathBuf, Result<Vec<RawObject>, String>> = files
        .par_iter()
        .map(|p| {
            let r = root
                .as_ref()
                .map_or(Ok(()), |root| root.inside(p))
                .and_then(|()| inputs::regular_file(p))
                .and_then(|()| read_file_with(p, &read_opts).map_err(|e| e.to_string()));
            tracker.tick();
            (p.to_path_buf(), r)
        })
        .collect();
    read.extend(plan.preloaded.into_iter().map(|(p, o)| (p, Ok(o))));
    seconds.read = lap();
    // How often each object is used: the last use takes it instead of copying it.
    let mut uses: HashMap<(PathBuf, Option<usize>), usize> = HashMap::new();
    for s in plan
        .parts
        .iter()
        .flat_map(|p| p.mesh.iter().chain(&p.pieces))
    {
        *uses.entry((s.path.clone(), s.object)).or_default() += 1;
    }

    // The raw solids of every part, transformed.
    let raw: Vec<RawPart> = plan
        .parts
        .iter()
        .map(|spec| {
            let mut probs = Vec::new();
            let mut get = |s: &SourceRef| {
                let left = uses.get_mut(&(s.path.clone(), s.object)).map(|n| {
                    *n -= 1;
                    *n
                });
                let objects = match read.get_mut(&s.path) {
                    Some(Ok(o)) => Ok(o),
                    Some(Err(e)) => Err(&*e),
                    None => unreachable!("every file of the plan was read"),
                };
                match resolve(s, objects, left == Some(0)) {
                    Ok(o) => Some(o),
                    Err(p) => {
                        probs.push(p.in_file(&s.path).in_part(&spec.name));
                        None
                    }
                }
            };
            let mesh = spec.mesh.as_ref().and_then(&mut get);
            let pieces = spec
                .pieces
                .iter()
                .map(|s| (s.path.clone(), get(s)))
                .collect();
            RawPart {
                spec,
                mesh,
                pieces,
                problems: probs,
            }
        })
        .collect();
    drop(read);

    // One grid for everything. `Grid::choose` depends only on the largest magnitude and
    // on whether some value is not an integer, so both are found in parallel (per part,
    // to name the part that sets the step) and the grid is chosen from that value and
    // one non-integer witness.
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
            r.mesh
                .iter()
                .chain(r.pieces.iter().filter_map(|p| p.1.as_ref()))
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
    let solids: Vec<&RawObject> = raw
        .iter()
        .flat_map(|r| {
            r.mesh
                .iter()
                .chain(r.pieces.iter().filter_map(|p| p.1.as_ref()))
        })
        .collect();
    let max_snap_displacement = solids
        .iter()
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
    drop(solids);
    let ctx = Ctx {
        grid: &grid,
        opts,
        largest: largest.as_ref(),
    };

    // Parts, in parallel.
    let tracker = Tracker::start(opts, Stage::Validating, raw.len());
    let built: Vec<Built> = raw
        .into_par_iter()
        .map(|r| {
            let out = build_parts(r, &ctx);
            tracker.tick();
            out
        })
        .collect();
    let mut parts = Vec::with_capacity(built.len());
    let mut raw_points = Vec::with_capacity(built.len());
    let mut repairs = Vec::new();
    // Part names are made unique (files split into bodies may collide with other names)
    // before the problems are gathered, so that a renamed part's problems name it.
    let mut names = Names::default();
    for mut b in built {
        for (part, probs, _) in &mut b.parts {
            unique_name(&mut names, part, probs);
        }
        if let Some(mut record) = b.repairs {
            record.parts = b.parts.iter().map(|(p, _, _)| p.name.clone()).collect();
            repairs.push(record);
        }
        for (part, probs, points) in b.parts {
            parts.push(part);
            raw_points.push(points);
            problems.extend(probs);
        }
    }
    seconds.validate = lap();
    // A tolerance shrinks convex pieces, so every part needs its pieces.
    let decompose = match opts.decompose {
        _ if opts.tolerance != Tolerance::None => true,
        Decompose::Never => false,
        Decompose::WhenNeeded => parts.len() >= 2,
        Decompose::Always => true,
    };
    if decompose {
        problems.extend(decompose_parts(&mut parts, opts));
    }
    seconds.decompose = lap();
    // Relations between parts that snapping changed (needs the pieces, for the exact
    // overlap test of the few pairs it asks about). When snapping moved no coordinate
    // (integer inputs, or values already on the grid), no relation can have changed:
    // the search, most of loading a small integer assembly, is skipped.
    // Pairs of parts whose interiors that check found disjoint: the overlap check
    // below skips them.
    let mut disjoint = Vec::new();
    if max_snap_displacement > 0.0 {
        let (warnings, apart) = snapping::changed_relations(&parts, &raw_points, &grid);
        problems.extend(warnings);
        disjoint = apart;
    }
    drop(raw_points);
    seconds.snapping = lap();
    let mut assembly = Assembly {
        name: plan.name,
        grid,
        max_snap_displacement,
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
    seconds.overlaps = lap();
    Ok(Loaded {
        assembly,
        problems,
        repairs,
        skipped: plan.skipped,
        seconds,
    })
}

/// Decomposes every valid non-convex part without pieces, in parallel.
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
    let tracker = Tracker::start(opts, Stage::Decomposing, todo.len());
    let results: Vec<(usize, Result<Vec<Polytope>, Problem>)> = todo
        .par_iter()
        .map(|&k| {
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
            tracker.tick();
            (k, r.map_err(|e| e.in_part(p.name.clone())))
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

struct RawPart<'a> {
    spec: &'a PartSpec,
    mesh: Option<RawObject>,
    pieces: Vec<(PathBuf, Option<RawObject>)>,
    problems: Vec<Problem>,
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

/// The bounding box of a polytope's vertices (true coordinates, rounded outwards).
pub(crate) fn polytope_bbox(p: &Polytope) -> Aabb {
    let den = p.den();
    p.vertices().iter().fold(Aabb::EMPTY, |b, v| {
        if *den == Int::ONE {
            if let Some(c) = v.as_small() {
                return b.with(c);
            }
        }
        let c = v.to_ints();
        let lo = [0, 1, 2].map(|k| {
            let q = &c[k] / den;
            let q = if c[k] < Int::ZERO && &q * den != c[k] {
                q - Int::ONE
            } else {
                q
            };
            i64::try_from(&q).unwrap_or(i64::MIN / 2)
        });
        let hi = lo.map(|x| x.saturating_add(1));
        b.with(&lo).with(&hi)
    })
}

/// The parts one specification gave (several when its mesh holds separate solids), and
/// what repair did to its mesh.
struct Built {
    /// Each part, its problems, and for a part with a usable mesh the input coordinates
    /// (before snapping) of each of its vertices.
    parts: Vec<BuiltPart>,
    repairs: Option<Repairs>,
}

/// A part, its problems, and the input coordinates of its mesh's vertices.
type BuiltPart = (Part, Vec<Problem>, Option<Vec<[f64; 3]>>);

/// The part whose coordinates reach the largest magnitude, which sets the grid step.
struct Largest {
    part: String,
    magnitude: f64,
}

/// What building every part shares.
struct Ctx<'a> {
    grid: &'a Grid,
    opts: &'a LoadOptions,
    largest: Option<&'a Largest>,
}

/// Snaps the mesh of a specification, repairs it (unless strict), splits it into its
/// separate solids when allowed, and builds one part per solid.
fn build_parts(r: RawPart, ctx: &Ctx) -> Built {
    let (grid, opts) = (ctx.grid, ctx.opts);
    let spec = r.spec;
    let (Some(raw), Some(src)) = (&r.mesh, &spec.mesh) else {
        return Built {
            parts: vec![build_part(
                &r,
                spec.name.clone(),
                None,
                r.problems.clone(),
                ctx,
            )],
            repairs: None,
        };
    };
    let (mesh, probs) = Mesh::from_raw(raw, grid);
    let mut problems = r.problems.clone();
    problems.extend(
        probs
            .into_iter()
            .map(|p| p.in_file(&src.path).in_part(&spec.name)),
    );
    let Some(mut mesh) = mesh else {
        return Built {
            parts: vec![build_part(&r, spec.name.clone(), None, problems, ctx)],
            repairs: None,
        };
    };
    let mut repairs = None;
    if opts.repair {
        let report = repair(&mut mesh, &RepairOptions::default());
        if !report.is_empty() {
            problems.push(
                Problem::warning(format!("repaired: {report}"))
                    .with_kind(ProblemKind::Repaired)
                    .in_file(&src.path)
                    .in_part(&spec.name),
            );
            repairs = Some(Repairs {
                file: src.path.clone(),
                parts: Vec::new(),
                report,
            });
        }
    }
    // A mesh without triangles has no body; it stays whole for validation to report.
    let solids = match opts.repair && opts.split_bodies && spec.splittable {
        true => Some(joined_bodies(&mesh)).filter(|b| !b.is_empty()),
        false => None,
    }
    .unwrap_or_else(|| vec![mesh]);
    if solids.len() <= 1 {
        let m = solids.into_iter().next();
        return Built {
            parts: vec![build_part(&r, spec.name.clone(), m, problems, ctx)],
            repairs,
        };
    }
    let names: Vec<String> = (1..=solids.len())
        .map(|k| format!("{}_{k}", spec.name))
        .collect();
    problems.push(
        Problem::note(format!(
            "the mesh holds {} separate solids, loaded as parts {} (--one-part-per-file reads it as one part)",
            solids.len(),
            names.join(", ")
        ))
        .in_file(&src.path),
    );
    let parts = solids
        .into_iter()
        .zip(names)
        .enumerate()
        .map(|(k, (m, name))| {
            let probs = if k == 0 {
                std::mem::take(&mut problems)
            } else {
                Vec::new()
            };
            build_part(&r, name, Some(m), probs, ctx)
        })
        .collect();
    Built { parts, repairs }
}

/// The separate solids of a repaired mesh, where solids sharing a vertex stay together:
/// a part that touches itself along an edge or at a corner (voxel puzzles, sheet metal)
/// is one rigid part, and joining is the conservative choice (parts that move together
/// can only make fewer motions possible, never a wrong one).
fn joined_bodies(mesh: &Mesh) -> Vec<Mesh> {
    let bodies = bodies(mesh);
    if bodies.len() <= 1 {
        return bodies;
    }
    let mut owner: HashMap<[i64; 3], usize> = HashMap::new();
    let mut parent: Vec<usize> = (0..bodies.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for (b, m) in bodies.iter().enumerate() {
        for v in &m.vertices {
            if let Some(&o) = owner.get(v) {
                let (x, y) = (find(&mut parent, o), find(&mut parent, b));
                parent[x.max(y)] = x.min(y);
            } else {
                owner.insert(*v, b);
            }
        }
    }
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); bodies.len()];
    for b in 0..bodies.len() {
        let r = find(&mut parent, b);
        groups[r].push(b);
    }
    if groups.iter().filter(|g| !g.is_empty()).count() == bodies.len() {
        return bodies;
    }
    let mut bodies: Vec<Option<Mesh>> = bodies.into_iter().map(Some).collect();
    groups
        .into_iter()
        .filter(|g| !g.is_empty())
        .map(|g| {
            let mut it = g
                .into_iter()
                .map(|b| bodies[b].take().expect("one group each"));
            let first = it.next().expect("non-empty group");
            it.fold(first, |m, other| merged(m, &other))
        })
        .collect()
}

/// Two meshes as one, identifying equal grid points.
fn merged(mut m: Mesh, other: &Mesh) -> Mesh {
    let mut index: HashMap<[i64; 3], u32> = m
        .vertices
        .iter()
        .enumerate()
        .map(|(i, v)| (*v, i as u32))
        .collect();
    let remap: Vec<u32> = other
        .vertices
        .iter()
        .zip(&other.source_vertices)
        .map(|(v, &s)| {
            *index.entry(*v).or_insert_with(|| {
                m.vertices.push(*v);
                m.source_vertices.push(s);
                (m.vertices.len() - 1) as u32
            })
        })
        .collect();
    m.triangles
        .extend(other.triangles.iter().map(|t| t.map(|v| remap[v as usize])));
    m.source_faces.extend_from_slice(&other.source_faces);
    m
}

/// Gives `part` a name no earlier part has (`name-2`, `name-3`...), renaming its own
/// problems with it so that none names the other part, and notes the renaming.
fn unique_name(names: &mut Names, part: &mut Part, problems: &mut Vec<Problem>) {
    let Err((old, new)) = names.unique(part.name.clone()) else {
        return;
    };
    for p in problems.iter_mut() {
        if p.part.as_deref() == Some(old.as_str()) {
            p.part = Some(new.clone());
        }
    }
    problems.push(
        Problem::note(format!(
            "renamed from \"{}\" to \"{}\": another part has that name",
            escape(&old),
            escape(&new)
        ))
        .in_file(&part.source)
        .in_part(new.clone()),
    );
    part.name = new;
}

/// True for validation's reports of faces that cross.
fn is_crossing(p: &Problem) -> bool {
    p.kind == ProblemKind::SelfIntersection
}

/// The convex pieces of the solid a closed surface with crossing faces encloses (its
/// union, where the winding number is at least 1), with a note saying so; `None` when
/// that solid is ambiguous (a region of negative winding number: a fold turned inside
/// out) or cannot be computed, so that validation's witnesses stand.
fn union_of_crossing(mesh: &Mesh, info: &MeshInfo) -> Option<(Vec<Polytope>, String)> {
    let d = apart_decompose::decompose_union(&mesh.points(), &mesh.triangles, &Default::default())
        .ok()?;
    let (lowest, _) = d.stats.winding?;
    if lowest < 0 || d.pieces.is_empty() {
        return None;
    }
    let (pairs, pieces) = (info.self_intersections, d.pieces.len());
    let note = format!(
        "repaired: {pairs} {}; the part is the solid they enclose (their union, {pieces} exact convex {})",
        if pairs == 1 { "pair of faces crosses" } else { "pairs of faces cross" },
        if pieces == 1 { "piece" } else { "pieces" }
    );
    Some((d.pieces, note))
}

/// One part of a specification, from its (repaired) mesh and its declared pieces.
fn build_part(
    r: &RawPart,
    name: String,
    mesh: Option<Mesh>,
    mut problems: Vec<Problem>,
    ctx: &Ctx,
) -> BuiltPart {
    let (grid, repair) = (ctx.grid, ctx.opts.repair);
    let spec = r.spec;
    let mut raw_points = None;
    let name = &name;
    let mut part = Part {
        name: name.clone(),
        source: spec.source.clone(),
        mesh: None,
        info: None,
        pieces: Vec::new(),
        piece_sources: Vec::new(),
        declared_pieces: !spec.pieces.is_empty(),
        decomposed: false,
        convex: false,
        volume: Rational::zero(),
        reflex_edges: 0,
        bbox: None,
        unshrunk_pieces: Vec::new(),
    };
    let mut mesh_ok = false;
    if let (Some(mut mesh), Some(src)) = (mesh, &spec.mesh) {
        let (info, mut probs) = validate(&mut mesh, grid);
        if repair && info.closed && info.self_intersections > 0 {
            if let Some((pieces, note)) = union_of_crossing(&mesh, &info) {
                // The crossings are resolved: the part is the solid they enclose.
                probs.retain(|p| !(p.is_error() && is_crossing(p)));
                probs.push(Problem::warning(note).with_kind(ProblemKind::Repaired));
                part.volume = pieces
                    .iter()
                    .fold(Rational::zero(), |s, p| &s + &p.volume());
                part.pieces = pieces;
                part.decomposed = true;
            }
        }
        mesh_ok = info.volume6.is_some() && !probs.iter().any(Problem::is_error);
        if let Some(raw) = &r.mesh {
            explain_collapse(&mut probs, raw, &spec.name, ctx);
            if info.closed && info.volume6.is_some() && info.self_intersections == 0 {
                raw_points = Some(
                    mesh.source_vertices
                        .iter()
                        .zip(&mesh.vertices)
                        .map(|(&s, v)| match raw.vertices.get(s as usize) {
                            Some(p) => *p,
                            None => v.map(|c| grid.to_units(c)),
                        })
                        .collect(),
                );
            }
        }
        problems.extend(
            probs
                .into_iter()
                .map(|p| p.in_file(&src.path).in_part(name)),
        );
        part.reflex_edges = info.reflex_edges;
        part.convex = mesh_ok && info.convex;
        part.bbox = info.bbox;
        if let (true, Some(v), false) = (mesh_ok, info.volume(), part.decomposed) {
            part.volume = v;
        }
        part.mesh = Some(mesh);
        part.info = Some(info);
    }
    // Declared pieces.
    let mut pieces_ok = !r.pieces.is_empty();
    for (path, raw) in &r.pieces {
        let Some(raw) = raw else {
            pieces_ok = false;
            continue;
        };
        match pieces::convex_piece(raw, grid) {
            Ok(p) => {
                part.pieces.push(p);
                part.piece_sources.push(path.clone());
            }
            Err(mut probs) => {
                explain_collapse(&mut probs, raw, &spec.name, ctx);
                pieces_ok = false;
                problems.extend(probs.into_iter().map(|p| p.in_file(path).in_part(name)));
            }
        }
    }
    if part.declared_pieces {
        if pieces_ok {
            problems.extend(
                pieces::overlapping_pieces(&part.pieces, &part.piece_sources, grid)
                    .into_iter()
                    .map(|p| p.in_part(name)),
            );
            let sum = part.pieces.iter().fold(Rational::zero(), |s, p| {
                &s + &Rational::new(p.volume6(), Int::from(6))
            });
            if let (true, false, Some(mesh)) = (mesh_ok, part.decomposed, &part.mesh) {
                problems.extend(
                    pieces::pieces_outside_mesh(
                        &part.pieces,
                        &part.piece_sources,
                        &Locator::new(mesh),
                        grid,
                    )
                    .into_iter()
                    .map(|p| p.in_part(name)),
                );
            }
            if mesh_ok && sum != part.volume {
                problems.push(
                    Problem::error(format!(
                        "the pieces do not make up the part: their volumes add up to {} but the part's volume is {}",
                        crate::fmt_volume(&sum, grid),
                        crate::fmt_volume(&part.volume, grid)
                    ))
                    .in_part(name)
                    .with_kind(ProblemKind::Piece),
                );
            }
            if r.mesh.is_none() {
                part.volume = sum;
                part.convex = part.pieces.len() == 1;
            }
        }
        if part.bbox.is_none() {
            let b = part
                .pieces
                .iter()
                .fold(Aabb::EMPTY, |b, p| b.union(&polytope_bbox(p)));
            part.bbox = (!b.is_empty()).then_some(b);
        }
    } else if part.convex {
        if let Some(mesh) = &part.mesh {
            match crate::convex::convex_polytope(mesh) {
                Ok(p) => part.pieces.push(p),
                Err(e) => problems.push(
                    Problem::error(format!("convex part rejected by the polytope builder: {e}"))
                        .in_part(name),
                ),
            }
        }
    }
    if spec.mesh.is_none() && spec.pieces.is_empty() {
        problems.push(Problem::error("the part has neither a mesh nor pieces").in_part(name));
    }
    (part, problems, raw_points)
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

/// True when some face of `raw` has a non-zero area before snapping (its Newell normal
/// is not zero).
fn has_area(raw: &RawObject) -> bool {
    raw.faces.iter().any(|f| {
        let mut n = [0f64; 3];
        for (k, &i) in f.iter().enumerate() {
            let j = f[(k + 1) % f.len()];
            let (Some(a), Some(b)) = (raw.vertices.get(i as usize), raw.vertices.get(j as usize))
            else {
                return false;
            };
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
        }
        n.iter().any(|c| *c != 0.0 && c.is_finite())
    })
}

/// Says why a mesh with faces of non-zero area is empty after snapping: the grid step,
/// the part's size, and the part whose coordinates set the step (validation alone only
/// knows that no face is left).
fn explain_collapse(problems: &mut [Problem], raw: &RawObject, part: &str, ctx: &Ctx) {
    let Some(p) = problems
        .iter_mut()
        .find(|p| p.is_error() && p.element.is_none() && p.kind == ProblemKind::EmptyMesh)
    else {
        return;
    };
    if !has_area(raw) {
        return;
    }
    let b = raw
        .vertices
        .iter()
        .fold(Aabb::<f64>::EMPTY, |b, v| b.with(v));
    let size = [0, 1, 2].map(|k| fmt_len(b.max[k] - b.min[k]));
    let grid = ctx.grid;
    let why = match ctx.largest {
        Some(l) if l.part == part => format!("its own coordinates reach {}", fmt_len(l.magnitude)),
        Some(l) => format!(
            "part \"{}\" has coordinates reaching {}",
            escape(&l.part),
            fmt_len(l.magnitude)
        ),
        None => "the assembly's coordinates".to_string(),
    };
    p.message = format!(
        "empty mesh after snapping: every face has zero area on the grid of step {} (2^{}), which is coarser than this part ({} x {} x {}); the step is that coarse because {why} and every coordinate must stay below 2^{} steps; a larger --grid-bits (at most {MAX_BITS}) makes the step finer",
        fmt_len(grid.step()),
        grid.exp,
        size[0],
        size[1],
        size[2],
        grid.bits,
    );
}

/// A length in input units for messages: 4 significant digits.
fn fmt_len(v: f64) -> String {
    // Rounded to 4 significant digits first, so that 0.000999999 prints as 0.001.
    let v: f64 = format!("{v:.3e}").parse().unwrap_or(v);
    if v == 0.0 || !v.is_finite() {
        return v.abs().to_string();
    }
    let a = v.abs();
    if (1e-3..1e6).contains(&a) {
        let digits = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.digits$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        return s;
    }
    format!("{v:.3e}")
}

/// Relations between parts that snapping changed: two parts apart before snapping that
/// touch (or overlap) after, two that overlapped by less than a grid step and only touch
/// (or are apart) after, two that touched and are apart after. Each is a warning naming
/// both parts, the distance or depth before snapping, a point near it, and the grid
/// bits that would keep the relation.
///
/// Cheap by construction: only pairs of triangles of different parts whose snapped boxes
/// come within [`REACH`] grid steps of each other are looked at. Snapping rounds each
/// coordinate on its own and is monotone, so two input triangles whose boxes meet keep
/// meeting boxes, and snapped triangles that meet have meeting boxes: every pair whose
/// relation can change is among those.
///
/// The relation after snapping is exact: snapped triangles meet by the mesh crate's exact
/// test, and interiors overlap by the loader's exact overlap test (asked only for the few
/// pairs where it decides the warning). The relation before snapping is measured in
/// `f64` on the input coordinates of the same triangles, which only decides whether to
/// warn:
///
/// - *apart*: every pair of triangles is farther apart than the rounding noise of its
///   coordinates (the distance reported is the smallest);
/// - *overlapping*: some point of a triangle of one part lies behind a face of the other,
///   strictly inside the prism over that face, less than two grid steps deep, with no
///   other face of that part in between (so the point lies inside it); the depth
///   reported is the deepest such;
/// - *touching* otherwise.
// Float measures here are written so that a NaN (from a degenerate triangle) fails
// every test: `!(x > 0.0)` is meant, not `x <= 0.0`.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
mod snapping {
    use super::fmt_len;
    use crate::model::Part;
    use crate::overlap;
    use apart_formats::escape::escape;
    use apart_kernel::grid::MAX_BITS;
    use apart_kernel::Aabb;
    use apart_kernel::Bvh;
    use apart_kernel::Grid;
    use apart_mesh::intersect::triangles_meet;
    use apart_mesh::{Mesh, Problem};
    use rayon::prelude::*;

    use apart_kernel::fvec::{add, cross, dot, lerp, norm, scale, sub, F3};
    type Tri = [F3; 3];

    /// Grid steps by which triangle boxes are grown when looking for pairs: snapping
    /// moves a point by at most `sqrt(3)/2` steps, two points by at most `sqrt(3)`
    /// steps relative to each other.
    pub(crate) const REACH: i64 = 2;

    /// Rounding noise of a float measure, relative to the magnitude of the (local)
    /// coordinates it is computed from.
    const NOISE: f64 = 64.0 * f64::EPSILON;

    fn max_abs<'a>(points: impl IntoIterator<Item = &'a F3>) -> f64 {
        points
            .into_iter()
            .flat_map(|p| p.iter())
            .fold(0.0, |m: f64, c| m.max(c.abs()))
    }

    /// The point of triangle `t` nearest to `p` (Ericson, Real-Time Collision Detection,
    /// 5.1.5).
    fn closest_on_triangle(p: F3, t: &Tri) -> F3 {
        let [a, b, c] = *t;
        let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
        let (d1, d2) = (dot(ab, ap), dot(ac, ap));
        if d1 <= 0.0 && d2 <= 0.0 {
            return a;
        }
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        if d3 >= 0.0 && d4 <= d3 {
            return b;
        }
        let vc = d1 * d4 - d3 * d2;
        if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            return add(a, scale(ab, d1 / (d1 - d3)));
        }
        let cp = sub(p, c);
        let (d5, d6) = (dot(ab, cp), dot(ac, cp));
        if d6 >= 0.0 && d5 <= d6 {
            return c;
        }
        let vb = d5 * d2 - d1 * d6;
        if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            return add(a, scale(ac, d2 / (d2 - d6)));
        }
        let va = d3 * d6 - d5 * d4;
        if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
            return add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
        }
        let denom = 1.0 / (va + vb + vc);
        add(a, add(scale(ab, vb * denom), scale(ac, vc * denom)))
    }

    /// The nearest points of segments `p1 q1` and `p2 q2` (Ericson 5.1.9).
    fn closest_on_segments(p1: F3, q1: F3, p2: F3, q2: F3) -> (F3, F3) {
        let (d1, d2, r) = (sub(q1, p1), sub(q2, p2), sub(p1, p2));
        let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
        let (s, t);
        if a == 0.0 && e == 0.0 {
            return (p1, p2);
        }
        if a == 0.0 {
            s = 0.0;
            t = (f / e).clamp(0.0, 1.0);
        } else {
            let c = dot(d1, r);
            if e == 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else {
                let b = dot(d1, d2);
                let denom = a * e - b * b;
                let s0 = match denom != 0.0 {
                    true => ((b * f - c * e) / denom).clamp(0.0, 1.0),
                    false => 0.0,
                };
                let t0 = (b * s0 + f) / e;
                (s, t) = if t0 < 0.0 {
                    ((-c / a).clamp(0.0, 1.0), 0.0)
                } else if t0 > 1.0 {
                    (((b - c) / a).clamp(0.0, 1.0), 1.0)
                } else {
                    (s0, t0)
                };
            }
        }
        (add(p1, scale(d1, s)), add(p2, scale(d2, t)))
    }

    /// Where segment `p q` crosses triangle `t` (not in its plane), if it does.
    fn segment_crosses(p: F3, q: F3, t: &Tri) -> Option<F3> {
        let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        let (dp, dq) = (dot(n, sub(p, t[0])), dot(n, sub(q, t[0])));
        if (dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq {
            return None;
        }
        let x = lerp(p, q, dp / (dp - dq));
        let inside = (0..3).all(|i| {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            dot(n, cross(sub(b, a), sub(x, a))) >= 0.0
        });
        inside.then_some(x)
    }

    /// The distance between segment `p q` and triangle `t`.
    fn segment_distance(p: F3, q: F3, t: &Tri) -> f64 {
        if segment_crosses(p, q, t).is_some() {
            return 0.0;
        }
        let mut best = norm(sub(p, closest_on_triangle(p, t)));
        best = best.min(norm(sub(q, closest_on_triangle(q, t))));
        for i in 0..3 {
            let (x, y) = closest_on_segments(p, q, t[i], t[(i + 1) % 3]);
            best = best.min(norm(sub(x, y)));
        }
        best
    }

    /// The distance between two triangles, and the point halfway between their nearest
    /// points. NaN measures of degenerate triangles are skipped.
    fn distance(a: &Tri, b: &Tri) -> (f64, F3) {
        for (s, t) in [(a, b), (b, a)] {
            for i in 0..3 {
                if let Some(x) = segment_crosses(s[i], s[(i + 1) % 3], t) {
                    return (0.0, x);
                }
            }
        }
        let mut best = (f64::INFINITY, a[0]);
        let mut consider = |x: F3, y: F3| {
            let d = norm(sub(x, y));
            if d < best.0 {
                best = (d, lerp(x, y, 0.5));
            }
        };
        for (s, t) in [(a, b), (b, a)] {
            for p in s {
                consider(*p, closest_on_triangle(*p, t));
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                let (x, y) = closest_on_segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
                consider(x, y);
            }
        }
        best
    }

    /// The part of convex polygon `poly` on the side `dot(w, x - a) >= 0`.
    fn clip(poly: &[F3], a: F3, w: F3) -> Vec<F3> {
        let mut out = Vec::with_capacity(poly.len() + 1);
        for (i, &p) in poly.iter().enumerate() {
            let q = poly[(i + 1) % poly.len()];
            let (dp, dq) = (dot(w, sub(p, a)), dot(w, sub(q, a)));
            if dp >= 0.0 {
                out.push(p);
            }
            if (dp >= 0.0) != (dq >= 0.0) {
                out.push(lerp(p, q, dp / (dp - dq)));
            }
        }
        out
    }

    /// A point of triangle `t` (of one part) inside the other part just behind its face
    /// `f = faces[k]` (outward, counter-clockwise), less than `cap` deep: the deepest
    /// depth of `t` behind `f` within the prism over `f`, and the point. The other
    /// `faces` are those of the other part near `t`: none may lie between the point and
    /// `f`.
    /// Coordinates are relative to a nearby origin; only depths above `floor` count.
    fn witness(t: &Tri, faces: &[(Tri, F3)], k: usize, cap: f64, floor: f64) -> Option<(f64, F3)> {
        let (f, n) = (&faces[k].0, faces[k].1);
        if n == [0.0; 3] {
            return None;
        }
        let z = |x: F3| dot(n, sub(x, f[0]));
        // The part of `t` over `f` lies between the heights of `t`'s corners. (Most
        // pairs end at the first test, before the noise bound is computed.)
        let zt = t.map(z);
        let (lo, hi) = (zt[0].min(zt[1]).min(zt[2]), zt[0].max(zt[1]).max(zt[2]));
        if lo >= 0.0 || hi < -cap || -lo <= floor {
            return None;
        }
        let noise = NOISE * max_abs(t.iter().chain(f));
        if !(lo < -noise) {
            return None;
        }
        let mut walls = [(f[0], n); 3];
        let mut poly: Vec<F3> = t.to_vec();
        for i in 0..3 {
            let (a, b) = (f[i], f[(i + 1) % 3]);
            let w = cross(n, sub(b, a));
            let lw = norm(w);
            if !(lw > 0.0) {
                return None;
            }
            walls[i] = (a, scale(w, 1.0 / lw));
            poly = clip(&poly, a, walls[i].1);
            if poly.is_empty() {
                return None;
            }
        }
        let (vmin, zmin) =
            poly.iter()
                .map(|&v| (v, z(v)))
                .fold(
                    (poly[0], f64::INFINITY),
                    |a, b| if b.1 < a.1 { b } else { a },
                );
        if !(zmin < -noise) || -zmin > cap || -zmin <= floor {
            return None;
        }
        let c = scale(
            poly.iter().fold([0.0; 3], |s, &v| add(s, v)),
            1.0 / poly.len() as f64,
        );
        let margin = |x: F3| {
            walls
                .iter()
                .map(|(a, w)| dot(*w, sub(x, *a)))
                .fold(f64::INFINITY, f64::min)
        };
        let mc = margin(c);
        if !(mc > noise) {
            return None;
        }
        // A point strictly inside the prism and strictly behind the face: the centroid,
        // or a point between the deepest vertex and the centroid.
        let zc = z(c);
        let x = if zc < -noise {
            c
        } else {
            let l = 0.5 * (-noise - zmin) / (zc - zmin);
            if !(l * mc > noise) {
                return None;
            }
            lerp(vmin, c, l)
        };
        let foot = sub(x, scale(n, z(x)));
        let between = faces
            .iter()
            .enumerate()
            .any(|(j, o)| j != k && segment_distance(x, foot, &o.0) <= noise);
        if between {
            return None;
        }
        Some((-zmin, x))
    }

    fn grow(b: Aabb, r: i64) -> Aabb {
        Aabb {
            min: b.min.map(|c| c.saturating_sub(r)),
            max: b.max.map(|c| c.saturating_add(r)),
        }
    }

    fn tri_box(m: &Mesh, t: u32) -> Aabb {
        let [a, b, c] = m.corners(t as usize);
        Aabb::of([a, b, c])
    }

    /// Input coordinates of triangle `t`, relative to `origin`.
    fn input_tri(m: &Mesh, raw: &[F3], t: u32, origin: F3) -> Tri {
        m.triangles[t as usize].map(|v| sub(raw[v as usize], origin))
    }

    /// One side of a part pair: a part's mesh, input coordinates, and the unit normals
    /// of its input triangles near the other part (zero elsewhere, and for degenerate
    /// ones).
    #[derive(Clone, Copy)]
    struct Side<'a> {
        mesh: &'a Mesh,
        raw: &'a [F3],
        normals: &'a [F3],
    }

    /// Unit normals of the input triangles `near` of `m` (indexed by triangle).
    fn unit_normals(m: &Mesh, raw: &[F3], near: &[u32]) -> Vec<F3> {
        let mut out = vec![[0.0; 3]; m.triangles.len()];
        for &t in near {
            let [a, b, c] = m.triangles[t as usize].map(|v| raw[v as usize]);
            let n = cross(sub(b, a), sub(c, a));
            let l = norm(n);
            if l > 0.0 && l.is_finite() {
                out[t as usize] = scale(n, 1.0 / l);
            }
        }
        out
    }

    /// Witnesses of triangle `t` of `s` inside the part of `o`, behind its triangles
    /// `near`.
    fn witnesses(deepest: &mut (f64, F3), s: Side, t: u32, o: Side, near: &[u32], cap: f64) {
        let origin = s.raw[s.mesh.triangles[t as usize][0] as usize];
        let tt = input_tri(s.mesh, s.raw, t, origin);
        let faces: Vec<(Tri, F3)> = near
            .iter()
            .map(|&u| (input_tri(o.mesh, o.raw, u, origin), o.normals[u as usize]))
            .collect();
        for k in 0..faces.len() {
            if let Some((d, x)) = witness(&tt, &faces, k, cap, deepest.0) {
                *deepest = (d, add(x, origin));
            }
        }
    }

    /// For each triangle `t` of `ts` (of mesh `m`), the triangles of `os` (of mesh `o`)
    /// whose boxes come within [`REACH`] steps of its box, when there are some.
    fn near_lists(m: &Mesh, ts: &[u32], o: &Mesh, os: &[u32]) -> Vec<(u32, Vec<u32>)> {
        let bvh = Bvh::new(os.iter().map(|&u| grow(tri_box(o, u), REACH)).collect());
        ts.par_iter()
            .map(|&t| {
                let mut c = Vec::new();
                bvh.query(&tri_box(m, t), |k| c.push(os[k as usize]));
                (t, c)
            })
            .filter(|(_, c)| !c.is_empty())
            .collect()
    }

    /// The triangles of two parts near each other, and what their pairs say, each
    /// measure taken only when [`judge`] needs it.
    struct Near<'a> {
        a: Side<'a>,
        b: Side<'a>,
        /// Each triangle of `a` near `b`, with the triangles of `b` near it.
        from_a: Vec<(u32, Vec<u32>)>,
        /// The triangles of `a` and of `b` near the other part.
        near: [Vec<u32>; 2],
        /// Overlap witnesses count up to this depth (two grid steps).
        cap: f64,
        /// The unit normals of the near triangles, indexed by triangle, for `a` and `b`.
        normals: [Vec<F3>; 2],
        /// Whether the boxes of the input coordinates overlap in volume (otherwise the
        /// input parts cannot overlap).
        inputs_overlap: bool,
    }

    /// Whether the boxes of two sets of points overlap in volume (exact comparisons).
    fn boxes_overlap_open(p: &[F3], q: &[F3]) -> bool {
        let bounds = |v: &[F3]| v.iter().fold(Aabb::<f64>::EMPTY, |b, x| b.with(x));
        bounds(p).overlaps_open(&bounds(q))
    }

    /// The deeper of two overlap witnesses (the first on a tie).
    fn deeper(p: (f64, F3), q: (f64, F3)) -> (f64, F3) {
        if q.0 > p.0 {
            q
        } else {
            p
        }
    }

    /// The nearer of two distances (the first on a tie).
    fn nearer(p: (f64, F3), q: (f64, F3)) -> (f64, F3) {
        if q.0 < p.0 {
            q
        } else {
            p
        }
    }

    impl Near<'_> {
        /// Whether some snapped triangles of the two parts meet (exact).
        fn meet(&self) -> bool {
            let (ma, mb) = (self.a.mesh, self.b.mesh);
            self.from_a.par_iter().any(|(t, near)| {
                let (ta, boxed) = (ma.corners(*t as usize), tri_box(ma, *t));
                near.iter().any(|&u| {
                    boxed.overlaps(&tri_box(mb, u))
                        && triangles_meet(ta, mb.corners(u as usize)).is_some()
                })
            })
        }

        /// The distance between input triangles `t` of `a` and `u` of `b`, the point
        /// halfway between their nearest points, and the rounding noise of the measure.
        fn distance(&self, t: u32, u: u32) -> (f64, F3, f64) {
            let (a, b) = (&self.a, &self.b);
            let origin = a.raw[a.mesh.triangles[t as usize][0] as usize];
            let fa = input_tri(a.mesh, a.raw, t, origin);
            let fb = input_tri(b.mesh, b.raw, u, origin);
            let (d, x) = distance(&fa, &fb);
            (d, add(x, origin), NOISE * max_abs(fa.iter().chain(&fb)))
        }

        /// Where some input triangles are within rounding noise of each other (the
        /// first such pair in order), if any are.
        fn touch(&self) -> Option<F3> {
            self.from_a.par_iter().find_map_first(|(t, near)| {
                near.iter().find_map(|&u| {
                    let (d, x, noise) = self.distance(*t, u);
                    (d <= noise).then_some(x)
                })
            })
        }

        /// The smallest distance between input triangles, and where.
        fn gap(&self) -> (f64, F3) {
            let none = (f64::INFINITY, [0.0; 3]);
            self.from_a
                .par_iter()
                .map(|(t, near)| {
                    near.iter().fold(none, |best, &u| {
                        let (d, x, _) = self.distance(*t, u);
                        nearer(best, (d, x))
                    })
                })
                .reduce(|| none, nearer)
        }

        /// The deepest overlap of the input parts found (0: none), and where: points of
        /// each part's triangles inside the other, less than `cap` deep.
        fn depth(&self) -> (f64, F3) {
            let none = (0.0, [0.0; 3]);
            if !self.inputs_overlap {
                return none;
            }
            let deepest = |lists: &[(u32, Vec<u32>)], s: Side, o: Side| {
                lists
                    .par_iter()
                    .fold(
                        || none,
                        |mut acc, (t, near)| {
                            witnesses(&mut acc, s, *t, o, near, self.cap);
                            acc
                        },
                    )
                    .reduce(|| none, deeper)
            };
            let (sa, sb) = (self.side(0), self.side(1));
            // The pairs seen from `b`'s triangles, built only here: most pairs never
            // need a depth.
            let from_b = near_lists(sb.mesh, &self.near[1], sa.mesh, &self.near[0]);
            deeper(deepest(&self.from_a, sa, sb), deepest(&from_b, sb, sa))
        }

        /// Part `k`'s side (0: `a`, 1: `b`) with its near triangles' unit normals.
        fn side(&self, k: usize) -> Side<'_> {
            let s = if k == 0 { &self.a } else { &self.b };
            Side {
                normals: &self.normals[k],
                ..*s
            }
        }
    }

    /// The near triangles of parts `a` and `b` (with input coordinates `ra`, `rb` of
    /// their vertices), if any.
    fn near<'a>(
        a: &'a Part,
        ra: &'a [F3],
        b: &'a Part,
        rb: &'a [F3],
        grid: &Grid,
    ) -> Option<Near<'a>> {
        let (ma, mb) = (a.mesh.as_ref()?, b.mesh.as_ref()?);
        let (ga, gb) = (grow(a.bbox?, REACH), grow(b.bbox?, REACH));
        let region = Aabb {
            min: [0, 1, 2].map(|k| ga.min[k].max(gb.min[k])),
            max: [0, 1, 2].map(|k| ga.max[k].min(gb.max[k])),
        };
        if region.is_empty() {
            return None;
        }
        let near = |m: &Mesh| -> Vec<u32> {
            (0..m.triangles.len() as u32)
                .filter(|&t| tri_box(m, t).overlaps(&region))
                .collect()
        };
        let (na, nb) = (near(ma), near(mb));
        if na.is_empty() || nb.is_empty() {
            return None;
        }
        let from_a = near_lists(ma, &na, mb, &nb);
        if from_a.is_empty() {
            return None;
        }
        let normals = [unit_normals(ma, ra, &na), unit_normals(mb, rb, &nb)];
        let side = |mesh, raw| Side {
            mesh,
            raw,
            normals: &[],
        };
        Some(Near {
            a: side(ma, ra),
            b: side(mb, rb),
            from_a,
            near: [na, nb],
            cap: 2.0 * grid.step(),
            normals,
            inputs_overlap: boxes_overlap_open(ra, rb),
        })
    }

    /// The smallest `--grid-bits` whose step is at most a quarter of `len`, if any.
    fn bits_for(grid: &Grid, len: f64) -> Option<u32> {
        if !(len > 0.0) {
            return None;
        }
        let more = (4.0 * grid.step() / len).log2().ceil().max(1.0);
        let bits = grid.bits as f64 + more;
        (bits <= MAX_BITS as f64).then_some(bits as u32)
    }

    /// `--grid-bits N (step S) keeps <what>`, or why no grid does.
    fn finer(grid: &Grid, len: f64, what: &str) -> String {
        match bits_for(grid, len) {
            Some(b) => format!(
                "--grid-bits {b} (step {}) keeps {what}",
                fmt_len(grid.step() / 2f64.powi((b - grid.bits) as i32))
            ),
            None => format!(
                "even --grid-bits {MAX_BITS} (step {}) is too coarse to keep {what} at these coordinates",
                fmt_len(grid.step() / 2f64.powi((MAX_BITS - grid.bits) as i32))
            ),
        }
    }

    fn fmt_point(p: F3) -> String {
        let c = p.map(|v| {
            if v == 0.0 {
                "0".to_string()
            } else if (1e-3..1e12).contains(&v.abs()) {
                let s = format!("{v:.6}");
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                format!("{v:.6e}")
            }
        });
        format!("near ({}, {}, {})", c[0], c[1], c[2])
    }

    /// The warning for parts `a` and `b`, if snapping changed how they meet, and
    /// whether their interiors overlap after snapping, when that was decided.
    fn judge(a: &Part, b: &Part, near: &Near, grid: &Grid) -> (Option<Problem>, Option<bool>) {
        let mut known_overlap = None;
        let warning = warning(a, b, near, grid, &mut known_overlap);
        (warning, known_overlap)
    }

    /// [`judge`]'s warning; `known_overlap` caches the exact overlap test.
    fn warning(
        a: &Part,
        b: &Part,
        near: &Near,
        grid: &Grid,
        known_overlap: &mut Option<bool>,
    ) -> Option<Problem> {
        let step = fmt_len(grid.step());
        let pair = format!(
            "part \"{}\" and part \"{}\"",
            escape(&a.name),
            escape(&b.name)
        );
        // The measures, each taken once and only when the answer needs it (the witness
        // scan behind `depth` is the costliest).
        let touch = near.touch();
        let meet = near.meet();
        let mut overlap_after =
            || *known_overlap.get_or_insert_with(|| overlap::parts_overlap(a, b));
        // Touching before snapping and meeting after: only an overlap that snapping
        // removed could be reported, and none was if the parts still overlap (as
        // interpenetrating tessellations do).
        if touch.is_some() && meet && overlap_after() {
            return None;
        }
        let depth = near.depth();
        let (message, at) = if depth.0 > 0.0 {
            if overlap_after() {
                return None;
            }
            let (depth, at) = depth;
            let after = match meet {
                true => "they only touch after snapping",
                false => "they are apart after snapping",
            };
            (
                format!(
                    "snapping to the grid (step {step}) removed an overlap of depth {} between {pair}: {after}; {}, and --tolerance {} then accepts it as contact",
                    fmt_len(depth),
                    finer(grid, depth, "the overlap (reported as an error)"),
                    fmt_len(depth)
                ),
                at,
            )
        } else if let Some(at) = touch {
            if meet {
                return None;
            }
            (
                format!(
                    "snapping to the grid (step {step}) separated {pair}, which touched before snapping: they are apart after it; a larger --grid-bits (at most {MAX_BITS}) makes the gap smaller"
                ),
                at,
            )
        } else {
            if !meet {
                return None;
            }
            let (gap, at) = near.gap();
            if !gap.is_finite() {
                return None;
            }
            let after = match overlap_after() {
                true => "they overlap after snapping",
                false => "they touch after snapping",
            };
            (
                format!(
                    "snapping to the grid (step {step}) closed a gap of {} between {pair}: {after}; {}",
                    fmt_len(gap),
                    finer(grid, gap, "the gap")
                ),
                at,
            )
        };
        Some(
            Problem::warning(message)
                .at(fmt_point(at))
                .in_part(a.name.clone()),
        )
    }

    /// Warnings for every pair of parts whose relation snapping changed. `raw[k]` holds
    /// the input coordinates of the vertices of part `k`'s mesh (`None`: the part has no
    /// usable mesh and is left out).
    /// Also returns the pairs `(i, j)` (sorted) of parts whose interiors the check found
    /// disjoint after snapping (exactly), so that the overlap check need not test them
    /// again.
    pub(crate) fn changed_relations(
        parts: &[Part],
        raw: &[Option<Vec<F3>>],
        grid: &Grid,
    ) -> (Vec<Problem>, Vec<(usize, usize)>) {
        let usable: Vec<usize> = (0..parts.len())
            .filter(|&k| raw[k].is_some() && parts[k].mesh.is_some() && parts[k].bbox.is_some())
            .collect();
        let mut pairs = Vec::new();
        for (x, &i) in usable.iter().enumerate() {
            let bi = grow(parts[i].bbox.expect("usable"), REACH);
            for &j in &usable[x + 1..] {
                if bi.overlaps(&parts[j].bbox.expect("usable")) {
                    pairs.push((i, j));
                }
            }
        }
        let judged: Vec<_> = pairs
            .par_iter()
            .filter_map(|&(i, j)| {
                let (ra, rb) = (raw[i].as_deref()?, raw[j].as_deref()?);
                let near = near(&parts[i], ra, &parts[j], rb, grid)?;
                Some(((i, j), judge(&parts[i], &parts[j], &near, grid)))
            })
            .collect();
        let disjoint = judged
            .iter()
            .filter(|(_, (_, overlap))| *overlap == Some(false))
            .map(|&(pair, _)| pair)
            .collect();
        let warnings = judged.into_iter().filter_map(|(_, (w, _))| w).collect();
        (warnings, disjoint)
    }
}
