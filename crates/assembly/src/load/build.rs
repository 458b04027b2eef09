//! Building parts: each specification's mesh snapped, repaired and split into its
//! separate solids, validated, and given its convex pieces (declared, the part itself
//! when convex, or those of the solid a surface with crossing faces encloses).

use super::winding::{self, WindingSolid};
use super::RawPart;
use crate::inputs::{Names, PartSpec, SourceRef};
use crate::model::{Part, Repairs};
use crate::options::LoadOptions;
use crate::pieces::{self, piece_box};
use apart_formats::escape::escape;
use apart_formats::RawObject;
use apart_kernel::grid::MAX_BITS;
use apart_kernel::plane::HPoint;
use apart_kernel::{Aabb, Grid, Int, Rational};
use apart_mesh::locate::Locator;
use apart_mesh::repair::{bodies, repair_keeping_orientation, RepairOptions};
use apart_mesh::validate::validate;
use apart_mesh::{Mesh, Problem, ProblemKind};
use std::collections::HashMap;
use std::path::Path;

/// The parts one specification gave (several when its mesh holds separate solids), and
/// what repair did to its mesh.
pub(super) struct Built {
    /// Each part, its problems, and for a part with a usable mesh the input coordinates
    /// (before snapping) of each of its vertices.
    pub(super) parts: Vec<BuiltPart>,
    pub(super) repairs: Option<Repairs>,
}

/// A part, its problems, and the input coordinates of its mesh's vertices.
pub(super) type BuiltPart = (Part, Vec<Problem>, InputPoints);

/// The input coordinates (before snapping) of the vertices of a part's mesh, when the
/// mesh is a usable solid.
pub(super) type InputPoints = Option<Vec<[f64; 3]>>;

/// The part whose coordinates reach the largest magnitude, which sets the grid step.
pub(super) struct Largest {
    pub(super) part: String,
    pub(super) magnitude: f64,
}

/// What building every part shares.
pub(super) struct Ctx<'a> {
    pub(super) grid: &'a Grid,
    pub(super) opts: &'a LoadOptions,
    pub(super) largest: Option<&'a Largest>,
}

/// Snaps the mesh of a specification, repairs it (unless strict), splits it into its
/// separate solids when allowed, and builds one part per solid.
pub(super) fn build_parts(r: RawPart, ctx: &Ctx) -> Built {
    let (grid, opts) = (ctx.grid, ctx.opts);
    let spec = r.spec;
    let (Some(raw), Some(src)) = (&r.mesh, &spec.mesh) else {
        return Built {
            parts: vec![build_part(
                &r,
                spec.name.clone(),
                None,
                None,
                r.problems.clone(),
                ctx,
            )],
            repairs: None,
        };
    };
    let (mesh, probs) = Mesh::from_raw(raw, grid);
    let mut problems = r.problems.clone();
    problems.extend(probs.into_iter().map(|p| src.locate(p).in_part(&spec.name)));
    let Some(mut mesh) = mesh else {
        return Built {
            parts: vec![build_part(&r, spec.name.clone(), None, None, problems, ctx)],
            repairs: None,
        };
    };
    let (mut report, unoriented) = match opts.repair {
        true => repair_keeping_orientation(&mut mesh, &RepairOptions::default()),
        false => Default::default(),
    };
    // A mesh without triangles has no body; it stays whole for validation to report.
    let solids = match opts.repair && opts.split_bodies && spec.splittable {
        true => Some(joined_bodies(&mesh)).filter(|b| !b.is_empty()),
        false => None,
    }
    .unwrap_or_else(|| vec![mesh]);
    // One body whose faces disagree in orientation: a fold, or faces flipped by the
    // exporter (see `winding::as_given`).
    let mut given = None;
    if let (Some(u), 1) = (&unoriented, solids.len()) {
        given = winding::as_given(u, &solids[0], grid, opts);
        if given.is_some() {
            report.flipped_faces = 0;
            report.flipped_shells = 0;
        }
    }
    let mut repairs = None;
    if !report.is_empty() {
        problems.push(
            src.locate(
                Problem::warning(format!("repaired: {report}")).with_kind(ProblemKind::Repaired),
            )
            .in_part(&spec.name),
        );
        repairs = Some(Repairs {
            file: src.origin.file().map(Path::to_path_buf).unwrap_or_default(),
            parts: Vec::new(),
            report,
            winding: Vec::new(),
        });
    }
    if solids.len() <= 1 {
        let m = solids.into_iter().next();
        return Built {
            parts: vec![build_part(&r, spec.name.clone(), m, given, problems, ctx)],
            repairs,
        };
    }
    let names: Vec<String> = (1..=solids.len())
        .map(|k| format!("{}_{k}", spec.name))
        .collect();
    problems.push(src.locate(Problem::note(format!(
        "the mesh holds {} separate solids, loaded as parts {} (--one-part-per-file reads it as one part)",
        solids.len(),
        names.join(", ")
    ))));
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
            build_part(&r, name, Some(m), None, probs, ctx)
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
    deeply_overlapping(&bodies, &mut parent);
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
            merged(first, it)
        })
        .collect()
}

/// Pairs of bodies of one mesh that overlap deeply: a vertex of one, or the centroid of
/// one of its faces, lies inside the other (winding number positive) with none of the
/// other's faces within
/// [`crate::tolerance::AUTO_LIMIT`] of the pair's size (in every coordinate). Such
/// shells are one part modelled as overlapping solids, not two parts in contact: no
/// tolerance `--tolerance auto` may choose could make them apart. Shallower overlaps
/// stay separate parts, for the overlap check and a tolerance to judge.
fn deeply_overlapping(bodies: &[Mesh], parent: &mut [usize]) {
    let boxes: Vec<Option<Aabb>> = bodies.iter().map(Mesh::bbox).collect();
    let mut locators: Vec<Option<Locator>> = (0..bodies.len()).map(|_| None).collect();
    for a in 0..bodies.len() {
        for b in 0..bodies.len() {
            let (Some(ba), Some(bb)) = (&boxes[a], &boxes[b]) else {
                continue;
            };
            // Bodies already joined are not tested again.
            if a == b || !ba.overlaps_open(bb) || find(parent, a) == find(parent, b) {
                continue;
            }
            let size = (0..3)
                .map(|k| (ba.max[k] - ba.min[k]).max(bb.max[k] - bb.min[k]))
                .max()
                .unwrap_or(0);
            let margin = (size as f64) * crate::tolerance::AUTO_LIMIT;
            let lb = locators[b].get_or_insert_with(|| Locator::new(&bodies[b]));
            // Its vertices and the centroids of its faces (crossing shells may have
            // no vertex inside each other), three times over.
            let m = &bodies[a];
            let vertices = m.vertices.iter().map(|v| v.map(|c| 3 * c as i128));
            let centroids = m.triangles.iter().map(|t| {
                let [p, q, r] = t.map(|i| m.vertices[i as usize]);
                [0, 1, 2].map(|k| p[k] as i128 + q[k] as i128 + r[k] as i128)
            });
            let deep = vertices.chain(centroids).any(|x3| {
                let x = x3.map(|c| c as f64 / 3.0);
                let near = Aabb {
                    min: x.map(|c| (c - margin).floor() as i64 - 1),
                    max: x.map(|c| (c + margin).ceil() as i64 + 1),
                };
                if !near.overlaps(bb) {
                    return false;
                }
                let mut close = false;
                lb.bvh().query(&near, |t| {
                    close = close || within(&bodies[b], t as usize, &x, margin);
                });
                !close && matches!(lb.winding(&HPoint::from_wide(x3, 3)), Some(w) if w > 0)
            });
            if deep {
                let (x, y) = (find(parent, a), find(parent, b));
                parent[x.max(y)] = x.min(y);
            }
        }
    }
}

/// The representative of `x` in the union-find forest `p`.
fn find(p: &mut [usize], mut x: usize) -> usize {
    while p[x] != x {
        p[x] = p[p[x]];
        x = p[x];
    }
    x
}

/// True when face `t` of `mesh` may pass within `d` of `x` (its plane does, and its
/// box grown by `d` holds `x`; floating point, generous).
fn within(mesh: &Mesh, t: usize, x: &[f64; 3], d: f64) -> bool {
    let [a, b, c] = mesh.corners(t).map(|p| p.map(|v| v as f64));
    for k in 0..3 {
        let lo = a[k].min(b[k]).min(c[k]) - d;
        let hi = a[k].max(b[k]).max(c[k]) + d;
        if x[k] < lo || x[k] > hi {
            return false;
        }
    }
    let (u, v) = (
        [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
        [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
    );
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let off = n[0] * (x[0] - a[0]) + n[1] * (x[1] - a[1]) + n[2] * (x[2] - a[2]);
    len == 0.0 || off.abs() <= d * len * (1.0 + 1e-9) + 1e-9 * len
}

/// Meshes as one, identifying equal grid points (one index for the whole group, so a
/// part of many shells is joined in linear time).
fn merged(mut m: Mesh, others: impl Iterator<Item = Mesh>) -> Mesh {
    let mut index: HashMap<[i64; 3], u32> = m
        .vertices
        .iter()
        .enumerate()
        .map(|(i, v)| (*v, i as u32))
        .collect();
    for other in others {
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
    }
    m
}

/// Gives `part` a name no earlier part has (`name-2`, `name-3`...), renaming its own
/// problems with it so that none names the other part, and notes the renaming.
pub(super) fn unique_name(names: &mut Names, part: &mut Part, problems: &mut Vec<Problem>) {
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
        .in_part(new.clone()),
    );
    if !part.source.as_os_str().is_empty() {
        let note = problems.pop().expect("pushed");
        problems.push(note.in_file(&part.source));
    }
    part.name = new;
}

/// One part of a specification, from its (repaired) mesh and its declared pieces.
fn build_part(
    r: &RawPart,
    name: String,
    mesh: Option<Mesh>,
    given: Option<WindingSolid>,
    mut problems: Vec<Problem>,
    ctx: &Ctx,
) -> BuiltPart {
    let spec = r.spec;
    let mut part = empty_part(spec, name);
    let mut raw_points = None;
    let mut mesh_ok = false;
    if let (Some(mesh), Some(src)) = (mesh, &spec.mesh) {
        let (ok, points, probs) =
            add_mesh(&mut part, mesh, given, r.mesh.as_ref(), &spec.name, ctx);
        (mesh_ok, raw_points) = (ok, points);
        problems.extend(probs.into_iter().map(|p| src.locate(p).in_part(&part.name)));
    }
    if part.declared_pieces {
        add_declared_pieces(&mut part, r, mesh_ok, &mut problems, ctx);
    } else if part.convex {
        add_convex_piece(&mut part, &mut problems);
    }
    if spec.mesh.is_none() && spec.pieces.is_empty() {
        problems.push(Problem::error("the part has neither a mesh nor pieces").in_part(&part.name));
    }
    (part, problems, raw_points)
}

/// A part named `name` of `spec`, with nothing known yet.
fn empty_part(spec: &PartSpec, name: String) -> Part {
    Part {
        name,
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
        winding: None,
    }
}

/// Validates `mesh` and makes it the part's boundary: its volume, box and convexity,
/// and (when repair is on and its faces cross) the convex pieces of the solid it
/// encloses. Returns whether the mesh is a valid solid, the input coordinates of its
/// vertices when it is closed and without crossings (`raw` holds them), and the
/// mesh's problems, not yet placed in a file and part (`spec_name`, the name the
/// specification gave, explains an empty mesh).
fn add_mesh(
    part: &mut Part,
    mut mesh: Mesh,
    given: Option<WindingSolid>,
    raw: Option<&RawObject>,
    spec_name: &str,
    ctx: &Ctx,
) -> (bool, InputPoints, Vec<Problem>) {
    let grid = ctx.grid;
    let (info, mut probs) = validate(&mut mesh, grid);
    let mut winding_ok = false;
    let as_given = given.is_some();
    let solid = match given {
        Some(s) => Some(Ok(s)),
        None if ctx.opts.repair && probs.iter().any(winding::resolves) => Some(
            winding::winding_solid(&mesh, info.self_intersections, grid, ctx.opts),
        ),
        None => None,
    };
    match solid {
        Some(Ok(solid)) => {
            // The surface's defects are resolved: the part is the solid it winds around,
            // and the note says how it was found.
            probs.retain(|p| !winding::resolves(p));
            probs.push(
                Problem::warning(winding::note(&solid.report, as_given, grid))
                    .with_kind(ProblemKind::Repaired),
            );
            part.volume = solid.report.volume_after.clone();
            part.pieces = solid.pieces;
            part.decomposed = true;
            part.winding = Some(solid.report);
            mesh = solid.mesh;
            winding_ok = true;
        }
        Some(Err(refusal)) => probs.extend(refusal),
        None => {}
    }
    let mesh_ok = (info.volume6.is_some() || winding_ok) && !probs.iter().any(Problem::is_error);
    let mut raw_points = None;
    if let Some(raw) = raw {
        explain_collapse(&mut probs, raw, spec_name, ctx);
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
    part.reflex_edges = info.reflex_edges;
    part.convex = mesh_ok && info.convex;
    part.bbox = info.bbox;
    if let (true, Some(v), false) = (mesh_ok, info.volume(), part.decomposed) {
        part.volume = v;
    }
    part.mesh = Some(mesh);
    part.info = Some(info);
    (mesh_ok, raw_points, probs)
}

/// Adds the declared pieces to the part and checks them: each convex and closed, their
/// interiors disjoint, within the mesh, their volumes adding up to the part's.
fn add_declared_pieces(
    part: &mut Part,
    r: &RawPart,
    mesh_ok: bool,
    problems: &mut Vec<Problem>,
    ctx: &Ctx,
) {
    let grid = ctx.grid;
    let name = part.name.clone();
    let mut pieces_ok = !r.pieces.is_empty();
    // How problems name each piece: its file, or its number among the declared pieces.
    let mut labels = Vec::with_capacity(r.pieces.len());
    for (k, (src, raw)) in r.pieces.iter().enumerate() {
        let Some(raw) = raw else {
            pieces_ok = false;
            continue;
        };
        match pieces::convex_piece(raw, grid) {
            Ok(p) => {
                part.pieces.push(p);
                let file = src.origin.file();
                part.piece_sources
                    .push(file.map(Path::to_path_buf).unwrap_or_default());
                labels.push(file.map_or(k.to_string(), |f| f.display().to_string()));
            }
            Err(mut probs) => {
                explain_collapse(&mut probs, raw, &r.spec.name, ctx);
                pieces_ok = false;
                problems.extend(
                    probs
                        .into_iter()
                        .map(|p| piece_problem(p, src, k).in_part(&name)),
                );
            }
        }
    }
    if pieces_ok {
        problems.extend(
            pieces::overlapping_pieces(&part.pieces, &labels, grid)
                .into_iter()
                .map(|p| p.in_part(&name)),
        );
        let sum = part.pieces.iter().fold(Rational::zero(), |s, p| {
            &s + &Rational::new(p.volume6(), Int::from(6))
        });
        if let (true, false, Some(mesh)) = (mesh_ok, part.decomposed, &part.mesh) {
            problems.extend(
                pieces::pieces_outside_mesh(&part.pieces, &labels, &Locator::new(mesh), grid)
                    .into_iter()
                    .map(|p| p.in_part(&name)),
            );
        }
        if mesh_ok && sum != part.volume {
            problems.push(
                Problem::error(format!(
                    "the pieces do not make up the part: their volumes add up to {} but the part's volume is {}",
                    crate::fmt_volume(&sum, grid),
                    crate::fmt_volume(&part.volume, grid)
                ))
                .in_part(&name)
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
            .fold(Aabb::EMPTY, |b, p| b.union(&piece_box(p)));
        part.bbox = (!b.is_empty()).then_some(b);
    }
}

/// A problem of declared piece `k` (from `src`): in its file, or, for a piece given as
/// arrays, at `piece k` (before the element, if any).
fn piece_problem(mut p: Problem, src: &SourceRef, k: usize) -> Problem {
    if src.origin.file().is_some() {
        return src.locate(p);
    }
    p.element = Some(match p.element.take() {
        Some(e) => format!("piece {k}, {e}"),
        None => format!("piece {k}"),
    });
    p
}

/// A convex part's one piece: the polytope of its mesh.
fn add_convex_piece(part: &mut Part, problems: &mut Vec<Problem>) {
    let Some(mesh) = &part.mesh else {
        return;
    };
    match crate::convex::convex_polytope(mesh) {
        Ok(p) => part.pieces.push(p),
        Err(e) => problems.push(
            Problem::error(format!("convex part rejected by the polytope builder: {e}"))
                .in_part(&part.name),
        ),
    }
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
pub(crate) fn fmt_len(v: f64) -> String {
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
