//! Loading: read every file once (in parallel), apply transforms, choose one grid for
//! all coordinates, then snap and validate every part and piece (in parallel), then
//! check the parts against each other.

use crate::error::LoadError;
use crate::inputs::{self, PartSpec, SourceRef};
use crate::model::Repairs;
use crate::model::{Assembly, Loaded, Part};
use crate::options::{Decompose, LoadOptions, Stage, Tracker};
use crate::tolerance::{self, Tolerance};
use crate::{overlap, pieces};
use apart_kernel::{Grid, Int, Rational};
use apart_mesh::formats::{read_file, ReadError};
use apart_mesh::repair::{bodies, repair, RepairOptions};
use apart_mesh::validate::{validate, MeshInfo};
use apart_mesh::{Aabb, Mesh, Problem, RawObject};
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
    let built: Vec<Built> = raw
        .into_par_iter()
        .map(|r| {
            let out = build_parts(r, &grid, opts);
            tracker.tick();
            out
        })
        .collect();
    let mut parts = Vec::with_capacity(built.len());
    let mut repairs = Vec::new();
    for b in built {
        if let Some(mut record) = b.repairs {
            record.parts = b.parts.iter().map(|(p, _)| p.name.clone()).collect();
            repairs.push(record);
        }
        for (part, probs) in b.parts {
            parts.push(part);
            problems.extend(probs);
        }
    }
    problems.extend(unique_names(&mut parts));
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
    Ok(Loaded {
        assembly,
        problems,
        repairs,
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

/// The parts one specification gave (several when its mesh holds separate solids), and
/// what repair did to its mesh.
struct Built {
    parts: Vec<(Part, Vec<Problem>)>,
    repairs: Option<Repairs>,
}

/// Snaps the mesh of a specification, repairs it (unless strict), splits it into its
/// separate solids when allowed, and builds one part per solid.
fn build_parts(r: RawPart, grid: &Grid, opts: &LoadOptions) -> Built {
    let spec = r.spec;
    let (Some(raw), Some(src)) = (&r.mesh, &spec.mesh) else {
        return Built {
            parts: vec![build_part(
                &r,
                spec.name.clone(),
                None,
                r.problems.clone(),
                grid,
                opts.repair,
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
            parts: vec![build_part(
                &r,
                spec.name.clone(),
                None,
                problems,
                grid,
                opts.repair,
            )],
            repairs: None,
        };
    };
    let mut repairs = None;
    if opts.repair {
        let report = repair(&mut mesh, &RepairOptions::default());
        if !report.is_empty() {
            problems.push(
                Problem::warning(format!("repaired: {report}"))
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
            parts: vec![build_part(
                &r,
                spec.name.clone(),
                m,
                problems,
                grid,
                opts.repair,
            )],
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
            build_part(&r, name, Some(m), probs, grid, opts.repair)
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

/// Makes part names unique (files split into bodies may collide with other names),
/// in one pass over a set of the names in use.
fn unique_names(parts: &mut [Part]) -> Vec<Problem> {
    let mut used: std::collections::HashSet<String> = std::collections::HashSet::new();
    let mut problems = Vec::new();
    for p in parts.iter_mut() {
        if used.insert(p.name.clone()) {
            continue;
        }
        let mut k = 2;
        while used.contains(&format!("{}-{k}", p.name)) {
            k += 1;
        }
        let name = format!("{}-{k}", p.name);
        problems.push(
            Problem::note(format!("renamed to \"{name}\": the name was taken"))
                .in_part(p.name.clone()),
        );
        p.name = name.clone();
        used.insert(name);
    }
    problems
}

/// True for validation's reports of faces that cross.
fn is_crossing(p: &Problem) -> bool {
    p.message.starts_with("self-intersection")
        || p.message.ends_with("more intersecting face pairs")
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
    let note = format!(
        "repaired: {} pairs of faces cross; the part is the solid they enclose (their union, {} exact convex pieces)",
        info.self_intersections,
        d.pieces.len()
    );
    Some((d.pieces, note))
}

/// One part of a specification, from its (repaired) mesh and its declared pieces.
fn build_part(
    r: &RawPart,
    name: String,
    mesh: Option<Mesh>,
    mut problems: Vec<Problem>,
    grid: &Grid,
    repair: bool,
) -> (Part, Vec<Problem>) {
    let spec = r.spec;
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
                probs.push(Problem::warning(note));
                part.volume = pieces
                    .iter()
                    .fold(Rational::zero(), |s, p| &s + &p.volume());
                part.pieces = pieces;
                part.decomposed = true;
            }
        }
        mesh_ok = info.volume6.is_some() && !probs.iter().any(Problem::is_error);
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
