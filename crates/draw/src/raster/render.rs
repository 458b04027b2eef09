//! The shaded raster picture: the parts drawn into two z-buffers (coloured and grey),
//! composed, outlined and averaged down to pixels.

use super::camera::Camera;
use super::zbuffer::{fill_triangle, Layer, SS};
use super::Item;
use crate::colors::{mix, Rgb, BACKGROUND};
use crate::shapes::PartShape;
use apart_kernel::fvec::{add, dot};
use resvg::tiny_skia::{Pixmap, PremultipliedColorU8};

/// Opacity of the grey parts.
const GHOST_ALPHA: f64 = 0.72;
/// Colour of outlines.
pub(crate) const EDGE: Rgb = Rgb(35, 35, 40);

/// The flat-shaded colour of a face with unit normal `n`.
pub(crate) fn shade(base: Rgb, n: [f64; 3], light: [f64; 3]) -> Rgb {
    let s = 0.42 + 0.58 * dot(n, light).max(0.0);
    let f = |c: u8| (c as f64 * s).round().min(255.0) as u8;
    Rgb(f(base.0), f(base.1), f(base.2))
}

/// A visible face: its shaded colour and the item it belongs to.
struct Face {
    color: Rgb,
    item: u32,
}

/// The shaded picture of `items` seen by `camera`: the coloured parts opaque, the
/// grey ones blended over them where nearer, outlines where the visible face changes,
/// each pixel the average of its samples.
pub(crate) fn render(
    shapes: &[PartShape],
    items: &[Item],
    camera: &Camera,
    width: u32,
    height: u32,
) -> Pixmap {
    let (w, h) = (width.max(1) as usize * SS, height.max(1) as usize * SS);
    let mut opaque = Layer::new(w * h);
    let mut ghost = Layer::new(w * h);
    let mut faces = vec![Face {
        color: BACKGROUND,
        item: u32::MAX,
    }];
    let light = camera.light();
    for (i, it) in items.iter().enumerate() {
        let shape = &shapes[it.part];
        let planes = shape.plane.iter().max().map_or(0, |&m| m as usize + 1);
        let base = faces.len() as u32;
        let mut shaded = vec![false; planes];
        faces.extend((0..planes).map(|_| Face {
            color: it.color,
            item: i as u32,
        }));
        let layer = if it.ghost { &mut ghost } else { &mut opaque };
        for (t, tri) in shape.triangles.iter().enumerate() {
            let n = shape.normal(t);
            if dot(n, camera.eye) <= 0.0 {
                continue;
            }
            let plane = shape.plane[t] as usize;
            if !shaded[plane] {
                faces[base as usize + plane].color = shade(it.color, n, light);
                shaded[plane] = true;
            }
            let v = tri.map(|p| {
                let (x, y, z) = camera.project(add(p, it.offset));
                (x * SS as f64, y * SS as f64, z)
            });
            fill_triangle(layer, w, h, v, base + plane as u32);
        }
    }

    // Compose: the grey layer over the coloured one where it is in front.
    let mut color = vec![BACKGROUND; w * h];
    let mut front = vec![0u32; w * h];
    for p in 0..w * h {
        let (o, g) = (opaque.face[p], ghost.face[p]);
        let c = faces[o as usize].color;
        if g != 0 && ghost.depth[p] < opaque.depth[p] {
            color[p] = mix(c, faces[g as usize].color, GHOST_ALPHA);
            front[p] = g;
        } else {
            color[p] = c;
            front[p] = o;
        }
    }
    // Outlines: both samples on either side of a change of visible face.
    let mut edge = vec![0f64; w * h];
    for y in 0..h {
        for x in 0..w {
            let p = y * w + x;
            for q in [(x + 1 < w).then(|| p + 1), (y + 1 < h).then(|| p + w)]
                .into_iter()
                .flatten()
            {
                let (a, b) = (front[p], front[q]);
                if a != b {
                    let strength = if faces[a as usize].item != faces[b as usize].item {
                        0.9
                    } else {
                        0.45
                    };
                    edge[p] = edge[p].max(strength);
                    edge[q] = edge[q].max(strength);
                }
            }
        }
    }
    // Average each SS × SS block.
    let mut pixmap = Pixmap::new(width.max(1), height.max(1)).expect("non-zero size");
    let out = pixmap.pixels_mut();
    for py in 0..height.max(1) as usize {
        for px in 0..width.max(1) as usize {
            let mut sum = [0f64; 3];
            for dy in 0..SS {
                for dx in 0..SS {
                    let p = (py * SS + dy) * w + px * SS + dx;
                    let c = mix(color[p], EDGE, edge[p]);
                    sum[0] += c.0 as f64;
                    sum[1] += c.1 as f64;
                    sum[2] += c.2 as f64;
                }
            }
            let n = (SS * SS) as f64;
            let [r, g, b] = sum.map(|s| (s / n).round() as u8);
            out[py * width.max(1) as usize + px] =
                PremultipliedColorU8::from_rgba(r, g, b, 255).expect("opaque");
        }
    }
    pixmap
}
