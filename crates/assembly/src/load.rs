//! Loading: read every file once (in parallel), apply transforms, choose one grid for
//! all coordinates, then snap and validate every part and piece (in parallel), then
//! check the parts against each other.

use crate::error::LoadError;
use crate::inputs::{self, PartSpec, SourceRef};
use crate::model::{Assembly, Loaded, Part};
use crate::options::{Decompose, LoadOptions, Stage, Tracker};
use crate::tolerance::{self, Tolerance};
use crate::{overlap, pieces};
use apart_kernel::{Grid, Int, Rational};
use apart_mesh::formats::{read_file, ReadError};
use apart_mesh::validate::check_solid;
use apart_mesh::{Aabb, Problem, RawObject};
use apart_pieces::Polytope;
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Loads an assembly from a folder, a mesh file or a manifest (see the crate docs).
/// Fails only when nothing can be loaded; every problem with parts, pieces or their
/// relations is collected in [`Loaded::problems`].
pub fn load(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let plan = inputs::plan(path)?;
    let mut problems = plan.problems.clone();

    // Read every file once.
    let mut files: Vec<&Path> = plan
        .parts
        .iter()
        .flat_map(|p| p.mesh.iter().chain(&p.pieces))
        .map(|s| s.path.as_path())
        .filter(|p| !plan.preloaded.contains_key(*p))
        .collect();
    files.sort();
    files.dedup();
    let tracker = Tracker::start(opts, Stage::Reading, files.len());
    let mut read: HashMap<PathBuf, Result<Vec<RawObject>, ReadError>> = files
        .par_iter()
        .map(|p| {
            let r = read_file(p);
            tracker.tick();
            (p.to_path_buf(), r)
        })
        .collect();
    read.extend(plan.preloaded.into_iter().map(|(p, o)| (p, Ok(o))));
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
    // on whether some value is not an integer, so both are found in parallel and the
    // grid is chosen from that value and one non-integer witness.
    let solids: Vec<&RawObject> = raw
        .iter()
        .flat_map(|r| {
            r.mesh
                .iter()
                .chain(r.pieces.iter().filter_map(|p| p.1.as_ref()))
        })
        .collect();
    let scan = |o: &&RawObject| {
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
    let (max_abs, non_integer) = solids
        .iter()
        .map(scan)
        .fold((0f64, None), |(m, f), (n, g)| (m.max(n), f.or(g)));
    let grid = Grid::choose(std::iter::once(max_abs).chain(non_integer), opts.grid_bits)?;
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

    // Parts, in parallel.
    let tracker = Tracker::start(opts, Stage::Validating, raw.len());
    let built: Vec<(Part, Vec<Problem>)> = raw
        .into_par_iter()
        .map(|r| {
            let out = build_part(r, &grid);
            tracker.tick();
            out
        })
        .collect();
    let mut parts = Vec::with_capacity(built.len());
    for (part, probs) in built {
        parts.push(part);
        problems.extend(probs);
    }
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
    let mut assembly = Assembly {
        name: plan.name,
        grid,
        max_snap_displacement,
        parts,
        tolerance: None,
    };
    if opts.tolerance == Tolerance::None {
        problems.extend(overlap::check_parts(&assembly, opts));
    } else {
        problems.extend(tolerance::apply(&mut assembly, opts.tolerance, opts));
    }
    Ok(Loaded { assembly, problems })
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
                .map_err(|e| Problem::error(format!("exact convex decomposition failed: {e}")))
                .and_then(|d| {
                    if opts.verify {
                        apart_decompose::verify(&points, &mesh.triangles, &d.pieces).map_err(
                            |e| {
                                Problem::error(format!(
                                    "the convex decomposition did not verify: {e}"
                                ))
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
    objects: Result<&mut Vec<RawObject>, &ReadError>,
    last: bool,
) -> Result<RawObject, Problem> {
    let objects = objects.map_err(|e| Problem::error(e.to_string()))?;
    let take = |o: &mut RawObject| if last { std::mem::take(o) } else { o.clone() };
    let mut o = match s.object {
        Some(k) => take(
            objects
                .get_mut(k)
                .ok_or_else(|| Problem::error(format!("the file has no object {k}")))?,
        ),
        None if objects.is_empty() => return Err(Problem::error("the file holds no mesh")),
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

fn build_part(r: RawPart, grid: &Grid) -> (Part, Vec<Problem>) {
    let spec = r.spec;
    let name = &spec.name;
    let mut problems = r.problems;
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
    if let (Some(raw), Some(src)) = (&r.mesh, &spec.mesh) {
        let (mesh, info, probs) = check_solid(raw, grid);
        mesh_ok = mesh.is_some()
            && info.as_ref().is_some_and(|i| i.volume6.is_some())
            && !probs.iter().any(Problem::is_error);
        problems.extend(
            probs
                .into_iter()
                .map(|p| p.in_file(&src.path).in_part(name)),
        );
        if let Some(info) = &info {
            part.reflex_edges = info.reflex_edges;
            part.convex = mesh_ok && info.convex;
            part.bbox = info.bbox;
            if let (true, Some(v)) = (mesh_ok, info.volume()) {
                part.volume = v;
            }
        }
        part.mesh = mesh;
        part.info = info;
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
            Err(probs) => {
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
            if mesh_ok && sum != part.volume {
                problems.push(
                    Problem::error(format!(
                        "the pieces do not make up the part: their volumes add up to {} but the part's volume is {}",
                        crate::fmt_volume(&sum, grid),
                        crate::fmt_volume(&part.volume, grid)
                    ))
                    .in_part(name),
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
    (part, problems)
}
