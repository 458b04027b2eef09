//! What is written over the pictures: the legend naming the coloured parts, the axis
//! triad, the scale bar, and the texts naming parts and directions.

use super::camera::Camera;
use crate::colors::Rgb;
use crate::svg_png::{escape, FONT_FAMILY};
use apart_kernel::fvec::dot;
use apart_kernel::Vec3;
use apart_plan::Step;
use std::fmt::Write;

/// Room kept below the scene, when labels are on, for the axis triad and the scale bar.
pub(crate) const ANNOTATION_H: f64 = 78.0;

/// Colours of the x, y and z axes: red, green, blue, pure enough that no part colour
/// shaded by the light looks like them.
pub const AXIS_COLORS: [Rgb; 3] = [Rgb(225, 0, 0), Rgb(0, 150, 0), Rgb(0, 70, 235)];

/// The opening `<svg>` tag of a picture `width` × `height`, in the pictures' font.
pub(crate) fn svg_open(width: u32, height: u32) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="{FONT_FAMILY}">"#
    ) + "\n"
}

/// Width of the legend column for a picture `width` wide.
pub(crate) fn legend_width(width: u32) -> f64 {
    (width as f64 * 0.24).clamp(90.0, 200.0)
}

/// The legend's rows (a colour swatch and a name per lit part) at `x`, the first
/// baseline at `top`, as many as fit above the scale bar.
pub(crate) fn legend_rows(
    svg: &mut String,
    names: &[String],
    colors: &[Rgb],
    lit: &[usize],
    top: f64,
    height: u32,
    x: f64,
) {
    let line = 18.0;
    let fit = ((height as f64 - top - ANNOTATION_H + 14.0) / line)
        .floor()
        .max(1.0) as usize;
    for (row, &k) in lit.iter().enumerate() {
        let y = top + row as f64 * line;
        if row + 1 == fit && lit.len() > fit {
            let _ = writeln!(
                svg,
                r##"<text x="{x:.1}" y="{y:.1}" font-size="12" fill="#333">… and {} more</text>"##,
                lit.len() - row
            );
            break;
        }
        let _ = writeln!(
            svg,
            r##"<rect x="{x:.1}" y="{:.1}" width="12" height="12" fill="{}" stroke="#333" stroke-width="0.6"/><text x="{:.1}" y="{y:.1}" font-size="13" fill="#222">{}</text>"##,
            y - 10.5,
            colors[k].hex(),
            x + 18.0,
            escape(&names[k])
        );
    }
}

/// The axis triad (lower left: the x, y and z axes as the camera sees them, far ones
/// first, each an arrow with its letter; an axis seen end-on is a ⊙ or ⊗) and the scale
/// bar beside it (a round length in model units: 1, 2 or 5 times a power of ten, and
/// its label), as SVG elements in picture coordinates.
pub(crate) fn annotations(camera: &Camera, width: u32, height: u32) -> String {
    let mut svg = String::from(r#"<g id="axes" font-weight="bold" font-size="13">"#);
    let (ox, oy) = (40.0, height as f64 - 38.0);
    let len = 26.0;
    let mut axes: Vec<(usize, f64, f64, f64)> = (0..3)
        .map(|k| {
            let mut a = [0.0; 3];
            a[k] = 1.0;
            // Picture direction (x right, y down) and depth (larger is farther).
            (
                k,
                dot(a, camera.right),
                -dot(a, camera.up),
                -dot(a, camera.eye),
            )
        })
        .collect();
    axes.sort_by(|a, b| b.3.total_cmp(&a.3));
    let _ = write!(
        svg,
        r##"<circle cx="{ox:.1}" cy="{oy:.1}" r="2.2" fill="#333"/>"##
    );
    for (k, dx, dy, depth) in axes {
        let c = AXIS_COLORS[k].hex();
        let name = ["x", "y", "z"][k];
        let l = (dx * dx + dy * dy).sqrt();
        if l < 0.2 {
            // Along the line of sight: ⊙ towards the eye, ⊗ away from it.
            let (cx, cy) = (ox + 14.0 + 12.0 * k as f64, oy + 18.0);
            let _ = write!(
                svg,
                r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="5" fill="white" stroke="{c}" stroke-width="1.6"/>"##
            );
            if depth < 0.0 {
                let _ = write!(
                    svg,
                    r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="1.6" fill="{c}"/>"##
                );
            } else {
                let _ = write!(
                    svg,
                    r##"<path d="M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1}" stroke="{c}" stroke-width="1.4"/>"##,
                    cx - 3.0,
                    cy - 3.0,
                    cx + 3.0,
                    cy + 3.0,
                    cx - 3.0,
                    cy + 3.0,
                    cx + 3.0,
                    cy - 3.0
                );
            }
            let _ = write!(
                svg,
                r##"<text x="{cx:.1}" y="{:.1}" fill="{c}" text-anchor="middle">{name}</text>"##,
                cy + 18.0
            );
            continue;
        }
        let (ux, uy) = (dx / l, dy / l);
        let (bx, by) = (ox + dx * len, oy + dy * len);
        let head = 7.0;
        let (lx, ly) = (
            bx - ux * head - uy * head * 0.5,
            by - uy * head + ux * head * 0.5,
        );
        let (rx, ry) = (
            bx - ux * head + uy * head * 0.5,
            by - uy * head - ux * head * 0.5,
        );
        let _ = write!(
            svg,
            r##"<line x1="{ox:.1}" y1="{oy:.1}" x2="{:.1}" y2="{:.1}" stroke="{c}" stroke-width="2.2" stroke-linecap="round"/><path d="M{lx:.1},{ly:.1} L{bx:.1},{by:.1} L{rx:.1},{ry:.1} Z" fill="{c}"/><text x="{:.1}" y="{:.1}" fill="{c}" text-anchor="middle">{name}</text>"##,
            bx - ux * head * 0.8,
            by - uy * head * 0.8,
            ox + dx * len + ux * 12.0,
            oy + dy * len + uy * 12.0 + 4.5
        );
    }
    svg.push_str("</g>\n");
    // The scale bar: the largest round length at most 140 pixels long (less in a
    // narrow picture).
    let x0 = 92.0;
    let room = (width as f64 - x0 - 16.0).min(140.0);
    if room > 20.0 && camera.scale.is_finite() && camera.scale > 0.0 {
        if let Some((length, label)) = round_length(room / camera.scale) {
            let px = length * camera.scale;
            let y = height as f64 - 20.0;
            let _ = writeln!(
                svg,
                r##"<g id="scale" stroke="#222" stroke-width="1.6" fill="#222"><path d="M{x0:.1},{:.1} L{x0:.1},{y:.1} L{:.1},{y:.1} L{:.1},{:.1}" fill="none"/><text x="{:.1}" y="{:.1}" font-size="12" stroke="none" text-anchor="middle">{label} {}</text></g>"##,
                y - 5.0,
                x0 + px,
                x0 + px,
                y - 5.0,
                x0 + px / 2.0,
                y - 8.0,
                if label == "1" { "unit" } else { "units" }
            );
        }
    }
    svg
}

/// The largest of 1, 2 or 5 times a power of ten not above `max`, and its decimal text
/// (`None` for a length that is not a positive finite number).
pub(crate) fn round_length(max: f64) -> Option<(f64, String)> {
    if !max.is_finite() || max <= 0.0 {
        return None;
    }
    let mut e = max.log10().floor() as i32;
    // log10 may round across a power of ten.
    if 10f64.powi(e) > max {
        e -= 1;
    }
    let m = [5u32, 2, 1]
        .into_iter()
        .find(|&m| m as f64 * 10f64.powi(e) <= max)
        .unwrap_or(1);
    let value = m as f64 * 10f64.powi(e);
    let text = if (0..=15).contains(&e) {
        format!("{}", m as u64 * 10u64.pow(e as u32))
    } else if (-15..0).contains(&e) {
        format!("{:.*}", (-e) as usize, value)
    } else {
        format!("{m}e{e}")
    };
    Some((value, text))
}

/// "(0.577, 0.577, 0.577)" with the exact integer direction when it is short.
pub(crate) fn direction_label(step: &Step) -> String {
    vector_label(&step.direction, step.unit)
}

/// The integer `direction` as "(1, 1, 0)" when its coordinates are short, else its
/// `unit` vector as "(0.577, 0.577, 0.577)".
pub(crate) fn vector_label(direction: &Vec3, unit: [f64; 3]) -> String {
    let exact = direction.to_strings();
    if exact.iter().all(|s| s.len() <= 6) {
        format!("({})", exact.join(", "))
    } else {
        format!("({:.3}, {:.3}, {:.3})", unit[0], unit[1], unit[2])
    }
}

/// Names of parts `ks` joined by commas, shortened past `max` names.
pub(crate) fn names_list(names: &[String], ks: &[usize], max: usize) -> String {
    let mut out: Vec<&str> = ks
        .iter()
        .take(max)
        .map(|&k| names.get(k).map_or("?", |s| s.as_str()))
        .collect();
    let more;
    if ks.len() > max {
        more = format!("… ({} more)", ks.len() - max);
        out.push(&more);
    }
    out.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_bars_have_round_lengths() {
        let l = round_length;
        assert_eq!(l(140.0), Some((100.0, "100".to_string())));
        assert_eq!(l(3.7), Some((2.0, "2".to_string())));
        assert_eq!(l(0.07), Some((0.05, "0.05".to_string())));
        assert_eq!(l(1.0), Some((1.0, "1".to_string())));
        assert_eq!(l(0.001), Some((0.001, "0.001".to_string())));
        assert_eq!(l(6.0e20).map(|p| p.1), Some("5e20".to_string()));
        assert_eq!(l(0.0), None);
        assert_eq!(l(f64::NAN), None);
    }
}
