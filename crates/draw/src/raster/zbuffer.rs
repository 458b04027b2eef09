//! The z-buffer: triangles in picture coordinates rasterized at `SS` × `SS` samples per
//! pixel, keeping the nearest face at each sample.

/// Samples per pixel along each axis.
pub(crate) const SS: usize = 2;

/// One depth layer: nearest depth and face id (0 = nothing) per sample.
pub(crate) struct Layer {
    /// Nearest depth per sample.
    pub(crate) depth: Vec<f32>,
    /// Face id per sample (0 = nothing).
    pub(crate) face: Vec<u32>,
}

impl Layer {
    /// `n` samples with nothing drawn.
    pub(crate) fn new(n: usize) -> Layer {
        Layer {
            depth: vec![f32::INFINITY; n],
            face: vec![0; n],
        }
    }
}

/// A triangle in picture coordinates (x, y, depth) with its face id (at least 1).
pub(crate) type PictureTriangle = ([(f64, f64, f64); 3], u32);

/// A z-buffer at `SS` samples per pixel along each axis of triangles given in picture
/// coordinates with their face ids.
pub(crate) fn zbuffer(tris: &[PictureTriangle], width: usize, height: usize) -> Layer {
    let (w, h) = (width * SS, height * SS);
    let mut layer = Layer::new(w * h);
    for (v, face) in tris {
        let v = v.map(|(x, y, z)| (x * SS as f64, y * SS as f64, z));
        fill_triangle(&mut layer, w, h, v, *face);
    }
    layer
}

/// Which triangles (given in picture coordinates, face id `t + 1` for triangle `t`) are
/// nearest at some sample of a z-buffer at `SS` samples per pixel along each axis,
/// strictly: a sample where two triangles are at the same depth (up to rounding) shows
/// neither. A face hidden inside a part (the top of a piece under another piece, flush
/// with it) meets the visible faces only along an edge, where its depth ties with
/// theirs; it is not shown.
pub(crate) fn shown_triangles(tris: &[PictureTriangle], width: usize, height: usize) -> Vec<bool> {
    let (w, h) = (width * SS, height * SS);
    let mut depth = vec![f64::INFINITY; w * h];
    let mut owner = vec![u32::MAX; w * h];
    let mut tied = vec![false; w * h];
    let scale = tris
        .iter()
        .flat_map(|(v, _)| v.iter().map(|p| p.2.abs()))
        .fold(0.0f64, f64::max);
    let eps = 1e-9 * scale.max(1.0);
    for (t, (v, _)) in tris.iter().enumerate() {
        let v = v.map(|(x, y, z)| (x * SS as f64, y * SS as f64, z));
        raster_triangle(w, h, v, |p, z| {
            if z < depth[p] - eps {
                depth[p] = z;
                owner[p] = t as u32;
                tied[p] = false;
            } else if z <= depth[p] + eps {
                tied[p] = true;
                if z < depth[p] {
                    depth[p] = z;
                    owner[p] = t as u32;
                }
            }
        });
    }
    let mut shown = vec![false; tris.len()];
    for p in 0..w * h {
        if owner[p] != u32::MAX && !tied[p] {
            shown[owner[p] as usize] = true;
        }
    }
    shown
}

/// Z-buffered fill of one triangle (sample centres at half-integers).
pub(crate) fn fill_triangle(
    layer: &mut Layer,
    w: usize,
    h: usize,
    v: [(f64, f64, f64); 3],
    face: u32,
) {
    raster_triangle(w, h, v, |p, z| {
        let z = z as f32;
        if z < layer.depth[p] {
            layer.depth[p] = z;
            layer.face[p] = face;
        }
    });
}

/// Calls `sample(index, depth)` for every sample of a `w` × `h` grid (centres at
/// half-integers) inside the triangle `v` (picture coordinates and depth), edges
/// included, with the depth interpolated there.
pub(crate) fn raster_triangle(
    w: usize,
    h: usize,
    v: [(f64, f64, f64); 3],
    mut sample: impl FnMut(usize, f64),
) {
    let [(x0, y0, z0), (x1, y1, z1), (x2, y2, z2)] = v;
    let area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let min_x = x0.min(x1).min(x2).floor().max(0.0) as usize;
    let max_x = (x0.max(x1).max(x2).ceil() as isize).min(w as isize - 1);
    let min_y = y0.min(y1).min(y2).floor().max(0.0) as usize;
    let max_y = (y0.max(y1).max(y2).ceil() as isize).min(h as isize - 1);
    if max_x < 0 || max_y < 0 {
        return;
    }
    let inv = 1.0 / area;
    for y in min_y..=max_y as usize {
        let py = y as f64 + 0.5;
        for x in min_x..=max_x as usize {
            let px = x as f64 + 0.5;
            // Barycentric weights; all of one sign inside (either orientation).
            let w0 = ((x1 - px) * (y2 - py) - (x2 - px) * (y1 - py)) * inv;
            let w1 = ((x2 - px) * (y0 - py) - (x0 - px) * (y2 - py)) * inv;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            sample(y * w + x, w0 * z0 + w1 * z1 + w2 * z2);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_fills_its_samples_and_keeps_the_nearest() {
        let mut layer = Layer::new(16);
        fill_triangle(
            &mut layer,
            4,
            4,
            [(0.0, 0.0, 1.0), (4.0, 0.0, 1.0), (0.0, 4.0, 1.0)],
            1,
        );
        fill_triangle(
            &mut layer,
            4,
            4,
            [(0.0, 0.0, 0.5), (0.0, 4.0, 0.5), (4.0, 0.0, 0.5)],
            2,
        );
        fill_triangle(
            &mut layer,
            4,
            4,
            [(0.0, 0.0, 2.0), (4.0, 0.0, 2.0), (4.0, 4.0, 2.0)],
            3,
        );
        // The lower-left half (x + y < 4) is face 2 (nearer than 1); the upper-right
        // corner only face 3 covers.
        assert_eq!(layer.face[0], 2);
        assert_eq!(layer.face[15], 3);
        assert_eq!(layer.face.iter().filter(|&&f| f == 1).count(), 0);
    }
}
