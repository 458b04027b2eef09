//! The motion-space sphere as an SVG (or PNG) picture: both hemispheres in Lambert
//! equal-area or orthographic projection, faces shaded by how many ordered pairs of
//! parts block them, arcs drawn, solutions marked in the colour of their moving subset,
//! a legend naming the parts of each subset, and the chosen direction ringed.

use crate::colors::part_colors;
use crate::raster::{direction_label, names_list};
use crate::svg_png::{escape, png_bytes, svg_to_pixmap, FONT_FAMILY};
use apart_kernel::fvec;
use apart_kernel::predicates::dot_sign;
use apart_kernel::{Sign, Vec3};
use apart_plan::{CellKind, MotionSpace, Solution, Step};
use apart_sphere::{Arc, EdgeId, FaceId};
use std::fmt::Write;

/// How each hemisphere is flattened onto its disk.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SphereProjection {
    /// Lambert azimuthal equal-area: areas on the disk are proportional to solid
    /// angles, so the share of free directions reads off directly.
    #[default]
    EqualArea,
    /// Orthographic: the hemisphere as seen from far away along the axis; shapes near
    /// the pole are true, the rim is compressed.
    Orthographic,
}

/// Choices for [`motion_space_svg`].
#[derive(Clone, Debug)]
pub struct SphereSvgOptions {
    /// Radius of each hemisphere disk in pixels.
    pub radius: f64,
    /// Title line at the top.
    pub title: String,
    /// A direction to mark specially (e.g. the one chosen for a step).
    pub highlight: Option<Vec3>,
    /// How the hemispheres are flattened.
    pub projection: SphereProjection,
}

impl Default for SphereSvgOptions {
    fn default() -> Self {
        SphereSvgOptions {
            radius: 220.0,
            title: "motion space".into(),
            highlight: None,
            projection: SphereProjection::EqualArea,
        }
    }
}

type V3 = [f64; 3];

/// Projection of unit `p` for the upper (`up`) or lower hemisphere, seen from outside
/// the sphere; the hemisphere maps to a disk of radius √2.
fn project(p: &V3, up: bool, projection: SphereProjection) -> (f64, f64) {
    let z = if up { p[2] } else { -p[2] };
    let k = match projection {
        SphereProjection::EqualArea => (2.0 / (1.0 + z).max(1e-12)).sqrt(),
        SphereProjection::Orthographic => std::f64::consts::SQRT_2,
    };
    // Seen from below: mirror x so the picture is what one sees looking up at it.
    (if up { p[0] * k } else { -p[0] * k }, p[1] * k)
}

fn slerp_points(a: &V3, b: &V3, steps: usize) -> Vec<V3> {
    let dot = fvec::dot(*a, *b).clamp(-1.0, 1.0);
    let theta = dot.acos();
    (0..=steps)
        .map(|k| {
            let t = k as f64 / steps as f64;
            if theta < 1e-12 {
                return *a;
            }
            let (sa, sb) = (
                ((1.0 - t) * theta).sin() / theta.sin(),
                (t * theta).sin() / theta.sin(),
            );
            let v = [
                sa * a[0] + sb * b[0],
                sa * a[1] + sb * b[1],
                sa * a[2] + sb * b[2],
            ];
            let n = fvec::norm(v);
            [v[0] / n, v[1] / n, v[2] / n]
        })
        .collect()
}

fn arc_points(arc: &Arc) -> Vec<V3> {
    let (a, b) = (arc.start.unit_f64(), arc.end.unit_f64());
    let dot = fvec::dot(a, b).clamp(-1.0, 1.0);
    let steps = ((dot.acos().to_degrees() / 2.0).ceil() as usize).max(1);
    slerp_points(&a, &b, steps)
}

struct Frame {
    r: f64,
    centers: [(f64, f64); 2],
    projection: SphereProjection,
}

impl Frame {
    fn screen(&self, p: &V3, up: bool) -> (f64, f64) {
        let (x, y) = project(p, up, self.projection);
        let (cx, cy) = self.centers[if up { 0 } else { 1 }];
        let s = self.r / std::f64::consts::SQRT_2;
        (cx + x * s, cy - y * s)
    }
}

/// Which hemisphere a face of the equator-split arrangement lies in (`true` = z >= 0).
fn face_is_upper(ms: &MotionSpace, f: FaceId) -> bool {
    let arr = ms.arrangement();
    let z = Vec3::new(0, 0, 1);
    for lp in arr.boundary_loops(f) {
        for &h in &lp {
            match dot_sign(&z, &arr.vertex(arr.origin(h)).point) {
                Sign::Positive => return true,
                Sign::Negative => return false,
                Sign::Zero => {}
            }
        }
    }
    // Bounded by the equator alone: the side the boundary's left normal points to.
    let h = arr.boundary_loops(f).into_iter().flatten().next();
    h.is_none_or(|h| dot_sign(&z, &arr.half_edge_arc(h).normal) != Sign::Negative)
}

/// Draws the motion space `ms` of a (sub)assembly as SVG, with the `solutions` of
/// partitioning it (e.g. from [`apart_plan::partition_subset`]); `names` are the part
/// names (global order, as [`apart_plan::BlockingRegions::names`]). The picture draws
/// each face in its hemisphere: build `ms` with
/// [`MotionSpace::build_split_at_equator`]. Nothing is planned here.
pub fn motion_space_svg(
    ms: &MotionSpace,
    names: &[String],
    solutions: &[Solution],
    opts: &SphereSvgOptions,
) -> String {
    let subset = ms.parts();
    let arr = ms.arrangement();
    let st = ms.statuses();
    let r = opts.radius;
    let margin = 60.0;
    let legend_w = 470.0;
    let width = 4.0 * r + 3.0 * margin + legend_w;
    let frame = Frame {
        r,
        centers: [
            (margin + r, margin + 40.0 + r),
            (2.0 * margin + 3.0 * r, margin + 40.0 + r),
        ],
        projection: opts.projection,
    };
    let max_count = (0..arr.faces().len())
        .map(|f| ms.blocked_pairs(&st.faces[f]))
        .max()
        .unwrap_or(0)
        .max(1);

    // Moving subsets in order of first appearance; a subset is drawn in the colours of
    // its parts (a pie for a mark, alternating dashes for an edge).
    let mut subsets: Vec<Vec<usize>> = Vec::new();
    for s in solutions {
        if !subsets.contains(&s.moving) {
            subsets.push(s.moving.clone());
        }
    }
    let part_hex: Vec<String> = part_colors(names).iter().map(|c| c.hex()).collect();

    // The legend first, to know the picture's height.
    let legend = legend(
        names,
        subset,
        solutions,
        &subsets,
        &subsets
            .iter()
            .map(|m| subset_colours(&part_hex, m))
            .collect::<Vec<_>>(),
        opts.highlight.as_ref(),
        max_count,
        4.0 * r + 3.0 * margin,
        margin + 40.0,
    );
    let height = (2.0 * r + 2.0 * margin + 80.0).max(legend.1 + 30.0);

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="{FONT_FAMILY}">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        svg,
        r#"<text x="{margin}" y="30" font-size="18" font-weight="bold">{}</text>"#,
        escape(&opts.title)
    );
    hemisphere_labels(&mut svg, &frame);
    draw_faces(&mut svg, ms, &frame, max_count);
    draw_arcs(&mut svg, ms, &frame);
    draw_rims(&mut svg, &frame);
    draw_solutions(&mut svg, ms, &frame, names, solutions, &part_hex);
    if let Some(h) = &opts.highlight {
        ring_direction(&mut svg, &frame, h);
    }
    svg.push_str(&legend.0);
    svg.push_str("</svg>\n");
    svg
}

/// The hex colours of the parts `m` of a moving subset.
fn subset_colours(part_hex: &[String], m: &[usize]) -> Vec<String> {
    m.iter().map(|&k| part_hex[k].clone()).collect()
}

/// The caption under each hemisphere disk (which side it is seen from, and the
/// projection), and the clip path of each disk.
fn hemisphere_labels(svg: &mut String, frame: &Frame) {
    let r = frame.r;
    let projection = match frame.projection {
        SphereProjection::EqualArea => "equal-area",
        SphereProjection::Orthographic => "orthographic",
    };
    for (k, label) in [
        format!("upper hemisphere (z ≥ 0) from above, {projection}"),
        format!("lower hemisphere (z ≤ 0) from below, {projection}"),
    ]
    .iter()
    .enumerate()
    {
        let (cx, cy) = frame.centers[k];
        let _ = writeln!(
            svg,
            r#"<text x="{cx:.1}" y="{:.1}" font-size="13" text-anchor="middle">{label}</text>"#,
            cy + r + 34.0
        );
        let _ = writeln!(
            svg,
            r#"<clipPath id="disk{k}"><circle cx="{cx:.2}" cy="{cy:.2}" r="{r:.2}"/></clipPath>"#
        );
    }
}

/// Every face of the arrangement in its hemisphere, shaded by how many of at most
/// `max_count` ordered pairs block it.
fn draw_faces(svg: &mut String, ms: &MotionSpace, frame: &Frame, max_count: usize) {
    let arr = ms.arrangement();
    let st = ms.statuses();
    for f in arr.face_ids() {
        let count = ms.blocked_pairs(&st.faces[f.index()]);
        let up = face_is_upper(ms, f);
        let fill = shade(count, max_count);
        let mut d = String::new();
        for lp in arr.boundary_loops(f) {
            let mut first = true;
            for h in lp {
                for p in arc_points(&arr.half_edge_arc(h)) {
                    let (x, y) = frame.screen(&p, up);
                    let _ = write!(d, "{}{x:.2},{y:.2} ", if first { "M" } else { "L" });
                    first = false;
                }
            }
            d.push_str("Z ");
        }
        if d.is_empty() {
            continue;
        }
        let _ = writeln!(
            svg,
            r#"<path d="{d}" fill="{fill}" fill-rule="evenodd" stroke="none" clip-path="url(#disk{})"><title>{count} blocked ordered pairs</title></path>"#,
            if up { 0 } else { 1 }
        );
    }
}

/// The arcs bounding blocked regions (not the structural ones), drawn in both views
/// where they lie.
fn draw_arcs(svg: &mut String, ms: &MotionSpace, frame: &Frame) {
    let arr = ms.arrangement();
    for e in arr.edge_ids() {
        let edge = arr.edge(e);
        if edge.structural
            || edge
                .labels
                .iter()
                .all(|l| l.map as usize >= ms.pair_count())
        {
            continue;
        }
        let pts = arc_points(&arr.edge_arc(e));
        draw_polyline(svg, frame, &pts, "#333333", 0.8, None);
    }
}

/// The rim of each disk, with its axis labels.
fn draw_rims(svg: &mut String, frame: &Frame) {
    let r = frame.r;
    for k in 0..2 {
        let (cx, cy) = frame.centers[k];
        let _ = writeln!(
            svg,
            r##"<circle cx="{cx:.2}" cy="{cy:.2}" r="{r:.2}" fill="none" stroke="#000" stroke-width="1.2"/>"##
        );
        // Axis labels in the colours of the renders' axis triad: +x to the right from
        // above, to the left from below; +y up in both; +z (above) or −z (below) at
        // the centre, marked by a small cross.
        let sx = if k == 0 { 1.0 } else { -1.0 };
        let [xc, yc, zc] = crate::raster::AXIS_COLORS.map(|c| c.hex());
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" font-size="12" font-weight="bold" fill="{xc}" text-anchor="{}">+x</text>"##,
            cx + sx * (r + 5.0),
            cy + 4.0,
            if k == 0 { "start" } else { "end" }
        );
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" font-size="12" font-weight="bold" fill="{yc}" text-anchor="middle">+y</text>"##,
            cx,
            cy - r - 10.0
        );
        let _ = writeln!(
            svg,
            r##"<path d="M{:.1},{cy:.1} L{:.1},{cy:.1} M{cx:.1},{:.1} L{cx:.1},{:.1}" stroke="{zc}" stroke-width="1.2"/><text x="{:.1}" y="{:.1}" font-size="12" font-weight="bold" fill="{zc}">{}</text>"##,
            cx - 4.0,
            cx + 4.0,
            cy - 4.0,
            cy + 4.0,
            cx + 5.0,
            cy + 15.0,
            if k == 0 { "+z" } else { "−z" }
        );
    }
}

/// The solutions in the colours of their moving parts: a vertex or face direction as a
/// mark, an edge as the whole run of arcs through its direction, thickened.
fn draw_solutions(
    svg: &mut String,
    ms: &MotionSpace,
    frame: &Frame,
    names: &[String],
    solutions: &[Solution],
    part_hex: &[String],
) {
    let arr = ms.arrangement();
    for s in solutions {
        let c = subset_colours(part_hex, &s.moving);
        let who = names_list(names, &s.moving, 8);
        let u = s.unit;
        match s.cell {
            CellKind::Vertex => mark(svg, frame, &u, &c, 5.0, &format!("{who}: vertex")),
            CellKind::Face => mark(
                svg,
                frame,
                &u,
                &c,
                7.0,
                &format!("{who}: face, clearance {:.1}°", s.clearance_deg),
            ),
            CellKind::Edge => {
                // Thicken the whole edge through the representative direction.
                for e in edge_run(ms, &s.direction) {
                    let pts = arc_points(&arr.edge_arc(e));
                    let title = format!("{who}: edge (sliding)");
                    let n = c.len() as f64;
                    for (i, c) in c.iter().enumerate() {
                        let dash = (n > 1.0).then(|| (8.0, 8.0 * (n - 1.0), -8.0 * i as f64));
                        draw_polyline_dashed(svg, frame, &pts, c, 4.5, Some(&title), dash);
                    }
                }
            }
        }
    }
}

/// A ring around direction `h` in each hemisphere it shows in: the chosen direction.
fn ring_direction(svg: &mut String, frame: &Frame, h: &Vec3) {
    let u = h.unit_f64();
    for up in [true, false] {
        if (u[2] >= 0.0) == up || u[2] == 0.0 {
            let (x, y) = frame.screen(&u, up);
            let _ = writeln!(
                svg,
                r##"<circle cx="{x:.2}" cy="{y:.2}" r="12" fill="none" stroke="#fff" stroke-width="5"/><circle cx="{x:.2}" cy="{y:.2}" r="12" fill="none" stroke="#000" stroke-width="2.5"><title>chosen direction</title></circle>"##
            );
        }
    }
}

/// The fill of a face blocked by `count` of at most `max` ordered pairs.
fn shade(count: usize, max: usize) -> String {
    if count == 0 {
        return "#ffffff".to_string();
    }
    let shade = 235.0 - 155.0 * count as f64 / max as f64;
    format!(
        "rgb({0:.0},{0:.0},{1:.0})",
        shade,
        (shade + 20.0).min(255.0)
    )
}

/// The legend (SVG elements) at `(x, y)` and the y where it ends.
#[allow(clippy::too_many_arguments)]
fn legend(
    names: &[String],
    subset: &[usize],
    solutions: &[Solution],
    subsets: &[Vec<usize>],
    colors: &[Vec<String>],
    highlight: Option<&Vec3>,
    max_count: usize,
    x: f64,
    mut y: f64,
) -> (String, f64) {
    let mut svg = String::new();
    let wrap = |text: &str| wrap_words(text, 62);
    for line in wrap(&format!("parts: {}", names_list(names, subset, 40))) {
        let _ = writeln!(
            svg,
            r#"<text x="{x}" y="{y}" font-size="13">{}</text>"#,
            escape(&line)
        );
        y += 18.0;
    }
    y += 12.0;
    let _ = writeln!(
        svg,
        r#"<text x="{x}" y="{y}" font-size="14" font-weight="bold">shade: blocked ordered pairs</text>"#
    );
    y += 12.0;
    let steps = max_count.min(8);
    for k in 0..=steps {
        let count = (k * max_count).checked_div(steps).unwrap_or(0);
        let _ = writeln!(
            svg,
            r##"<rect x="{:.1}" y="{y}" width="28" height="14" fill="{}" stroke="#999" stroke-width="0.5"/>"##,
            x + 28.0 * k as f64,
            shade(count, max_count)
        );
    }
    y += 28.0;
    let _ = writeln!(
        svg,
        r#"<text x="{x}" y="{y}" font-size="12">white: free of every pair; darkest: {max_count} {}</text>"#,
        if max_count == 1 {
            "pair blocks"
        } else {
            "pairs block"
        }
    );
    y += 30.0;
    let _ = writeln!(
        svg,
        r#"<text x="{x}" y="{y}" font-size="14" font-weight="bold">{}</text>"#,
        if solutions.is_empty() {
            "interlocked: no subset can move".to_string()
        } else {
            format!("solutions ({}), by moving parts", solutions.len())
        }
    );
    y += 8.0;
    let _ = writeln!(
        svg,
        r##"<text x="{x}" y="{:.0}" font-size="11" fill="#555">dot: vertex or deepest point of a face; thick arc: sliding edge</text>"##,
        y + 12.0
    );
    y += 32.0;
    const MAX_ROWS: usize = 24;
    for (i, m) in subsets.iter().enumerate() {
        if i == MAX_ROWS {
            let _ = writeln!(
                svg,
                r#"<text x="{x}" y="{y}" font-size="12">… and {} more subsets</text>"#,
                subsets.len() - MAX_ROWS
            );
            y += 20.0;
            break;
        }
        let count = |k: CellKind, one: &str, many: &str| {
            let n = solutions
                .iter()
                .filter(|s| &s.moving == m && s.cell == k)
                .count();
            (n > 0).then(|| format!("{n} {}", if n == 1 { one } else { many }))
        };
        let kinds: Vec<String> = [
            count(CellKind::Face, "face", "faces"),
            count(CellKind::Edge, "edge", "edges"),
            count(CellKind::Vertex, "vertex", "vertices"),
        ]
        .into_iter()
        .flatten()
        .collect();
        pie(&mut svg, x + 6.0, y - 4.0, 6.5, &colors[i], "");
        let text = format!(
            "{} {}: {}",
            names_list(names, m, 12),
            if m.len() == 1 { "moves" } else { "move" },
            kinds.join(", ")
        );
        for line in wrap_words(&text, 58) {
            let _ = writeln!(
                svg,
                r#"<text x="{}" y="{y}" font-size="12">{}</text>"#,
                x + 18.0,
                escape(&line)
            );
            y += 16.0;
        }
        y += 4.0;
    }
    if let Some(h) = highlight {
        y += 10.0;
        let _ = writeln!(
            svg,
            r##"<circle cx="{}" cy="{}" r="8" fill="none" stroke="#000" stroke-width="2.5"/>"##,
            x + 6.0,
            y - 4.0
        );
        let u = h.unit_f64();
        let exact = h.to_strings();
        let label = if exact.iter().all(|s| s.len() <= 6) {
            format!("({})", exact.join(", "))
        } else {
            format!("({:.3}, {:.3}, {:.3})", u[0], u[1], u[2])
        };
        let _ = writeln!(
            svg,
            r#"<text x="{}" y="{y}" font-size="12">chosen direction {}</text>"#,
            x + 18.0,
            escape(&label)
        );
        y += 20.0;
    }
    (svg, y)
}

/// Splits `text` into lines of at most about `width` characters at spaces.
fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split(' ') {
        let line = lines.last_mut().expect("non-empty");
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_string());
        } else {
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
    }
    lines
}

/// [`motion_space_svg`] rendered to PNG bytes (1 SVG pixel = 1 PNG pixel).
pub fn motion_space_png(
    ms: &MotionSpace,
    names: &[String],
    solutions: &[Solution],
    opts: &SphereSvgOptions,
) -> Vec<u8> {
    svg_png(&motion_space_svg(ms, names, solutions, opts))
}

/// The motion space `ms` of the subassembly a plan step splits (built with
/// [`MotionSpace::build_split_at_equator`] for `step.subassembly`), the step's
/// solutions ([`Step::solutions`], kept by the plan) and its direction ringed. When
/// `opts.title` is left at its default, the title says which parts move along which
/// direction.
///
/// # Panics
///
/// When the step kept no solutions (see [`apart_plan::SequenceOptions::keep_solutions`]).
pub fn step_motion_space_svg(
    ms: &MotionSpace,
    names: &[String],
    step: &Step,
    opts: &SphereSvgOptions,
) -> String {
    debug_assert_eq!(ms.parts(), &step.subassembly[..], "the step's motion space");
    let solutions = step
        .solutions
        .as_deref()
        .expect("the step kept its solutions (SequenceOptions::keep_solutions): draw never plans");
    let mut opts = opts.clone();
    if opts.title == SphereSvgOptions::default().title {
        opts.title = format!(
            "{} {} along {} ({} cell)",
            names_list(names, &step.moving, 6),
            if step.moving.len() == 1 {
                "moves"
            } else {
                "move"
            },
            direction_label(step),
            step.cell.name()
        );
    }
    opts.highlight = Some(step.direction.clone());
    motion_space_svg(ms, names, solutions, &opts)
}

/// [`step_motion_space_svg`] rendered to PNG bytes.
pub fn step_motion_space_png(
    ms: &MotionSpace,
    names: &[String],
    step: &Step,
    opts: &SphereSvgOptions,
) -> Vec<u8> {
    svg_png(&step_motion_space_svg(ms, names, step, opts))
}

fn svg_png(svg: &str) -> Vec<u8> {
    let pixmap = svg_to_pixmap(svg, 1.0).expect("the sphere SVG is well formed");
    png_bytes(&pixmap)
}

/// The arrangement edges of the edge cell through point `d`: the edge containing it,
/// extended along its circle through vertices where the blocking status does not change.
fn edge_run(ms: &MotionSpace, d: &Vec3) -> Vec<EdgeId> {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let p = d.primitive();
    let Some(e0) = arr.edge_ids().find(|&e| {
        arr.edge_arc(e)
            .locate(&p)
            .is_some_and(|pos| pos != apart_kernel::spherical::ArcPosition::Outside)
    }) else {
        return Vec::new();
    };
    let circle = arr.edge(e0).circle;
    let mut run = vec![e0];
    for forward in [true, false] {
        let mut e = e0;
        loop {
            let edge = arr.edge(e);
            let v = if forward { edge.to } else { edge.from };
            if st.vertices[v.index()] != st.edges[e.index()] {
                break;
            }
            let next = arr.vertex(v).around.iter().map(|&h| h.edge()).find(|&g| {
                g != e && arr.edge(g).circle == circle && st.edges[g.index()] == st.edges[e.index()]
            });
            match next {
                Some(g) if !run.contains(&g) => {
                    run.push(g);
                    e = g;
                }
                _ => break,
            }
        }
    }
    run
}

fn mark(svg: &mut String, frame: &Frame, u: &V3, colours: &[String], radius: f64, title: &str) {
    for up in [true, false] {
        if (u[2] > 0.0 && !up) || (u[2] < 0.0 && up) {
            continue;
        }
        let (x, y) = frame.screen(u, up);
        pie(svg, x, y, radius, colours, title);
    }
}

/// A disk at `(x, y)` split into equal slices of `colours` (one colour: a plain disk).
fn pie(svg: &mut String, x: f64, y: f64, r: f64, colours: &[String], title: &str) {
    let title = if title.is_empty() {
        String::new()
    } else {
        format!("<title>{}</title>", escape(title))
    };
    let _ = write!(svg, "<g>{title}");
    if colours.len() <= 1 {
        let c = colours.first().map_or("#000", |c| c.as_str());
        let _ = write!(
            svg,
            r#"<circle cx="{x:.2}" cy="{y:.2}" r="{r}" fill="{c}"/>"#
        );
    } else {
        let n = colours.len() as f64;
        for (i, c) in colours.iter().enumerate() {
            // Slices clockwise from the top.
            let a0 = std::f64::consts::TAU * i as f64 / n - std::f64::consts::FRAC_PI_2;
            let a1 = std::f64::consts::TAU * (i + 1) as f64 / n - std::f64::consts::FRAC_PI_2;
            let (x0, y0) = (x + r * a0.cos(), y + r * a0.sin());
            let (x1, y1) = (x + r * a1.cos(), y + r * a1.sin());
            let large = if a1 - a0 > std::f64::consts::PI { 1 } else { 0 };
            let _ = write!(
                svg,
                r#"<path d="M{x:.2},{y:.2} L{x0:.2},{y0:.2} A{r},{r} 0 {large} 1 {x1:.2},{y1:.2} Z" fill="{c}"/>"#
            );
        }
    }
    let _ = writeln!(
        svg,
        r##"<circle cx="{x:.2}" cy="{y:.2}" r="{r}" fill="none" stroke="#000" stroke-width="0.9"/></g>"##
    );
}

fn draw_polyline(
    svg: &mut String,
    frame: &Frame,
    pts: &[V3],
    colour: &str,
    width: f64,
    title: Option<&str>,
) {
    draw_polyline_dashed(svg, frame, pts, colour, width, title, None);
}

/// A polyline on the sphere, optionally dashed: `(dash, gap, offset)` in pixels.
fn draw_polyline_dashed(
    svg: &mut String,
    frame: &Frame,
    pts: &[V3],
    colour: &str,
    width: f64,
    title: Option<&str>,
    dash: Option<(f64, f64, f64)>,
) {
    // Split where the polyline changes hemisphere; draw each run in its view.
    let mut runs: Vec<(bool, Vec<V3>)> = Vec::new();
    for p in pts {
        let up = p[2] >= 0.0;
        match runs.last_mut() {
            Some((u, run)) if *u == up || p[2].abs() < 1e-12 => run.push(*p),
            _ => {
                if let Some((_, run)) = runs.last() {
                    let last = *run.last().unwrap();
                    runs.push((up, vec![last, *p]));
                } else {
                    runs.push((up, vec![*p]));
                }
            }
        }
    }
    for (up, run) in runs {
        let mut d = String::new();
        for (k, p) in run.iter().enumerate() {
            let (x, y) = frame.screen(p, up);
            let _ = write!(d, "{}{x:.2},{y:.2} ", if k == 0 { "M" } else { "L" });
        }
        let t = title
            .map(|t| format!("<title>{}</title>", escape(t)))
            .unwrap_or_default();
        let dashes = dash.map_or(String::new(), |(on, off, offset)| {
            format!(r#" stroke-dasharray="{on} {off}" stroke-dashoffset="{offset}""#)
        });
        let _ = writeln!(
            svg,
            r#"<path d="{d}" fill="none" stroke="{colour}" stroke-width="{width}"{dashes} clip-path="url(#disk{})">{t}</path>"#,
            if up { 0 } else { 1 }
        );
    }
}
