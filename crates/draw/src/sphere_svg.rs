//! The motion-space sphere as an SVG picture: both hemispheres in Lambert equal-area
//! projection, faces shaded by how many ordered pairs of parts block them, arcs drawn,
//! and solutions marked.

use apart_kernel::predicates::dot_sign;
use apart_kernel::{Sign, Vec3};
use apart_plan::{BlockingRegions, CellKind, MotionSpace, Solution};
use apart_sphere::Arc;
use std::fmt::Write;

/// Choices for [`motion_space_svg`].
#[derive(Clone, Debug)]
pub struct SphereSvgOptions {
    /// Radius of each hemisphere disk in pixels.
    pub radius: f64,
    /// Title line at the top.
    pub title: String,
    /// A direction to mark specially (e.g. the one chosen for a step).
    pub highlight: Option<Vec3>,
}

impl Default for SphereSvgOptions {
    fn default() -> Self {
        SphereSvgOptions {
            radius: 220.0,
            title: "motion space".into(),
            highlight: None,
        }
    }
}

/// Colours for moving subsets, cycled.
const PALETTE: [&str; 10] = [
    "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2",
    "#bcbd22", "#7f7f7f",
];

type V3 = [f64; 3];

/// Lambert azimuthal equal-area projection of unit `p` for the upper (`up`) or lower
/// hemisphere, seen from outside the sphere; the hemisphere maps to a disk of radius √2.
fn project(p: &V3, up: bool) -> (f64, f64) {
    if up {
        let k = (2.0 / (1.0 + p[2]).max(1e-12)).sqrt();
        (p[0] * k, p[1] * k)
    } else {
        // Seen from below: mirror x so the picture is what one sees looking up at it.
        let k = (2.0 / (1.0 - p[2]).max(1e-12)).sqrt();
        (-p[0] * k, p[1] * k)
    }
}

fn slerp_points(a: &V3, b: &V3, steps: usize) -> Vec<V3> {
    let dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0);
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
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / n, v[1] / n, v[2] / n]
        })
        .collect()
}

fn arc_points(arc: &Arc) -> Vec<V3> {
    let (a, b) = (arc.start.unit_f64(), arc.end.unit_f64());
    let dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0);
    let steps = ((dot.acos().to_degrees() / 2.0).ceil() as usize).max(1);
    slerp_points(&a, &b, steps)
}

struct Frame {
    r: f64,
    centers: [(f64, f64); 2],
}

impl Frame {
    fn screen(&self, p: &V3, up: bool) -> (f64, f64) {
        let (x, y) = project(p, up);
        let (cx, cy) = self.centers[if up { 0 } else { 1 }];
        let s = self.r / std::f64::consts::SQRT_2;
        (cx + x * s, cy - y * s)
    }
}

/// Which hemisphere a face of the equator-split arrangement lies in (`true` = z >= 0).
fn face_is_upper(ms: &MotionSpace, f: u32) -> bool {
    let arr = ms.arrangement();
    let z = Vec3::new(0, 0, 1);
    for lp in arr.boundary_loops(f) {
        for &h in &lp {
            match dot_sign(&z, &arr.vertices()[arr.origin(h) as usize].point) {
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

/// Draws the motion space of the parts `subset` as SVG.
pub fn motion_space_svg(
    regions: &BlockingRegions,
    subset: &[usize],
    solutions: &[Solution],
    opts: &SphereSvgOptions,
) -> String {
    let eq = [[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]].map(Vec3::from);
    let guides: Vec<Arc> = (0..4)
        .map(|k| Arc::between(&eq[k], &eq[(k + 1) % 4]).unwrap())
        .collect();
    let ms = MotionSpace::build_with_guides(regions, subset, &guides);
    let arr = ms.arrangement();
    let st = ms.statuses();
    let names = regions.names();
    let r = opts.radius;
    let margin = 60.0;
    let legend_w = 460.0;
    let width = 4.0 * r + 3.0 * margin + legend_w;
    let frame = Frame {
        r,
        centers: [
            (margin + r, margin + 40.0 + r),
            (2.0 * margin + 3.0 * r, margin + 40.0 + r),
        ],
    };
    let height = (2.0 * r + 2.0 * margin + 80.0)
        .max(160.0 + 22.0 * (solutions.len().min(30) as f64 + names.len() as f64));
    let max_count = (0..arr.faces().len())
        .map(|f| ms.blocked_pairs(&st.faces[f]))
        .max()
        .unwrap_or(0)
        .max(1);

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        svg,
        r#"<text x="{margin}" y="28" font-size="18">{}</text>"#,
        escape(&opts.title)
    );
    for (k, label) in [
        "upper hemisphere (z ≥ 0), seen from above",
        "lower hemisphere (z ≤ 0), seen from below",
    ]
    .iter()
    .enumerate()
    {
        let (cx, cy) = frame.centers[k];
        let _ = writeln!(
            svg,
            r#"<text x="{cx:.1}" y="{:.1}" font-size="13" text-anchor="middle">{label}</text>"#,
            cy + r + 24.0
        );
        let _ = writeln!(
            svg,
            r#"<clipPath id="disk{k}"><circle cx="{cx:.2}" cy="{cy:.2}" r="{r:.2}"/></clipPath>"#
        );
    }

    // Faces.
    for f in 0..arr.faces().len() as u32 {
        let count = ms.blocked_pairs(&st.faces[f as usize]);
        let up = face_is_upper(&ms, f);
        let shade = 245.0 - 165.0 * count as f64 / max_count as f64;
        let fill = if count == 0 {
            "#ffffff".to_string()
        } else {
            format!(
                "rgb({0:.0},{0:.0},{1:.0})",
                shade,
                (shade + 20.0).min(255.0)
            )
        };
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
    // Arcs (region boundaries), drawn in both views where they lie.
    for (e, edge) in arr.edges().iter().enumerate() {
        if edge.structural
            || edge
                .labels
                .iter()
                .all(|l| l.map as usize >= ms.pair_count())
        {
            continue;
        }
        let pts = arc_points(&arr.edge_arc(e as u32));
        draw_polyline(&mut svg, &frame, &pts, "#333333", 0.8, None);
    }
    for k in 0..2 {
        let (cx, cy) = frame.centers[k];
        let _ = writeln!(
            svg,
            r##"<circle cx="{cx:.2}" cy="{cy:.2}" r="{r:.2}" fill="none" stroke="#000" stroke-width="1.2"/>"##
        );
        // Axis hints.
        let sx = if k == 0 { 1.0 } else { -1.0 };
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" font-size="11" fill="#555">+x</text>"##,
            cx + sx * (r + 6.0) - if k == 1 { 14.0 } else { 0.0 },
            cy + 4.0
        );
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" font-size="11" fill="#555">+y</text>"##,
            cx - 6.0,
            cy - r - 6.0
        );
    }

    // Solutions.
    let mut subsets: Vec<Vec<usize>> = Vec::new();
    for s in solutions {
        if !subsets.contains(&s.moving) {
            subsets.push(s.moving.clone());
        }
    }
    let colour =
        |m: &Vec<usize>| PALETTE[subsets.iter().position(|x| x == m).unwrap_or(0) % PALETTE.len()];
    for s in solutions {
        let c = colour(&s.moving);
        let u = s.unit;
        match s.cell {
            CellKind::Vertex => mark(&mut svg, &frame, &u, c, 5.0, "vertex"),
            CellKind::Face => mark(
                &mut svg,
                &frame,
                &u,
                c,
                7.0,
                &format!("face, clearance {:.1}°", s.clearance_deg),
            ),
            CellKind::Edge => {
                // Thicken the whole edge through the representative direction.
                for e in edge_run(&ms, &s.direction) {
                    let pts = arc_points(&arr.edge_arc(e));
                    draw_polyline(&mut svg, &frame, &pts, c, 4.0, Some("edge (sliding)"));
                }
            }
        }
    }
    if let Some(h) = &opts.highlight {
        let u = h.unit_f64();
        for up in [true, false] {
            if (u[2] >= 0.0) == up || u[2] == 0.0 {
                let (x, y) = frame.screen(&u, up);
                let _ = writeln!(
                    svg,
                    r##"<circle cx="{x:.2}" cy="{y:.2}" r="11" fill="none" stroke="#000" stroke-width="2.5"><title>chosen direction</title></circle>"##
                );
            }
        }
    }

    // Legend.
    let lx = 4.0 * r + 3.0 * margin;
    let mut ly = margin + 40.0;
    let _ = writeln!(
        svg,
        r#"<text x="{lx}" y="{ly}" font-size="14" font-weight="bold">shade: blocked ordered pairs (max {max_count})</text>"#
    );
    ly += 22.0;
    let _ = writeln!(
        svg,
        r#"<text x="{lx}" y="{ly}" font-size="12">white: no pair blocks; darker: more pairs block</text>"#
    );
    ly += 26.0;
    let _ = writeln!(
        svg,
        r#"<text x="{lx}" y="{ly}" font-size="14" font-weight="bold">{}</text>"#,
        if solutions.is_empty() {
            "interlocked: no solution".to_string()
        } else {
            format!("solutions ({})", solutions.len())
        }
    );
    ly += 20.0;
    for m in &subsets {
        let kinds: Vec<&str> = solutions
            .iter()
            .filter(|s| &s.moving == m)
            .map(|s| s.cell.name())
            .collect();
        let count = |k: &str, plural: &str| {
            let n = kinds.iter().filter(|x| **x == k).count();
            format!("{n} {}", if n == 1 { k } else { plural })
        };
        let label: Vec<&str> = m.iter().map(|&k| names[k].as_str()).collect();
        let _ = writeln!(
            svg,
            r#"<circle cx="{}" cy="{}" r="6" fill="{}"/>"#,
            lx + 6.0,
            ly - 4.0,
            colour(m)
        );
        let _ = writeln!(
            svg,
            r#"<text x="{}" y="{ly}" font-size="12">{} moves: {}, {}, {}</text>"#,
            lx + 18.0,
            escape(&label.join(", ")),
            count("face", "faces"),
            count("edge", "edges"),
            count("vertex", "vertices")
        );
        ly += 20.0;
        if ly > height - 20.0 {
            break;
        }
    }
    svg.push_str("</svg>\n");
    svg
}

/// The arrangement edges of the edge cell through point `d`: the edge containing it,
/// extended along its circle through vertices where the blocking status does not change.
fn edge_run(ms: &MotionSpace, d: &Vec3) -> Vec<u32> {
    let arr = ms.arrangement();
    let st = ms.statuses();
    let p = d.primitive();
    let Some(e0) = (0..arr.edges().len() as u32).find(|&e| {
        arr.edge_arc(e)
            .locate(&p)
            .is_some_and(|pos| pos != apart_kernel::spherical::ArcPosition::Outside)
    }) else {
        return Vec::new();
    };
    let circle = arr.edges()[e0 as usize].circle;
    let mut run = vec![e0];
    for forward in [true, false] {
        let mut e = e0;
        loop {
            let edge = &arr.edges()[e as usize];
            let v = if forward { edge.to } else { edge.from };
            if st.vertices[v as usize] != st.edges[e as usize] {
                break;
            }
            let next = arr.vertices()[v as usize]
                .around
                .iter()
                .map(|&h| h / 2)
                .find(|&g| {
                    g != e
                        && arr.edges()[g as usize].circle == circle
                        && st.edges[g as usize] == st.edges[e as usize]
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

fn mark(svg: &mut String, frame: &Frame, u: &V3, colour: &str, radius: f64, title: &str) {
    for up in [true, false] {
        if (u[2] > 0.0 && !up) || (u[2] < 0.0 && up) {
            continue;
        }
        let (x, y) = frame.screen(u, up);
        let _ = writeln!(
            svg,
            r##"<circle cx="{x:.2}" cy="{y:.2}" r="{radius}" fill="{colour}" stroke="#000" stroke-width="0.8"><title>{}</title></circle>"##,
            escape(title)
        );
    }
}

fn draw_polyline(
    svg: &mut String,
    frame: &Frame,
    pts: &[V3],
    colour: &str,
    width: f64,
    title: Option<&str>,
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
        let _ = writeln!(
            svg,
            r#"<path d="{d}" fill="none" stroke="{colour}" stroke-width="{width}" clip-path="url(#disk{})">{t}</path>"#,
            if up { 0 } else { 1 }
        );
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
