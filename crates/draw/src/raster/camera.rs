//! The orthographic camera of the pictures: where the eye looks from, how the scene is
//! scaled and centred to fill the picture, and where the light comes from.

use super::View;
use apart_kernel::fvec::{add, cross, dot, normalize, scale, sub};

/// Orthographic projection onto the picture.
#[derive(Clone, Debug)]
pub(crate) struct Camera {
    /// Unit vector pointing right in the picture.
    pub(crate) right: [f64; 3],
    /// Unit vector pointing up in the picture.
    pub(crate) up: [f64; 3],
    /// Unit vector from the scene towards the eye.
    pub(crate) eye: [f64; 3],
    /// The scene point drawn at `origin`.
    pub(crate) center: [f64; 3],
    /// Pixels per model unit.
    pub(crate) scale: f64,
    /// Picture coordinates of `center`.
    pub(crate) origin: (f64, f64),
}

impl Camera {
    /// The camera of `view` scaled and centred so that `points` fill the picture less
    /// the margins (top, bottom, left, right).
    pub(crate) fn fit(
        view: &View,
        points: &[[f64; 3]],
        width: u32,
        height: u32,
        margins: [f64; 4],
    ) -> Camera {
        let u = normalize(view.up);
        let u = if u == [0.0; 3] { [0.0, 0.0, 1.0] } else { u };
        let reference = if u[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let x = normalize(sub(reference, scale(u, dot(reference, u))));
        let y = cross(u, x);
        let (az, el) = (
            view.azimuth_deg.to_radians(),
            view.elevation_deg.to_radians(),
        );
        let eye = normalize(add(
            add(scale(x, el.cos() * az.cos()), scale(y, el.cos() * az.sin())),
            scale(u, el.sin()),
        ));
        let mut right = normalize(cross(scale(eye, -1.0), u));
        if right == [0.0; 3] {
            // Looking along the up axis: keep x to the right.
            right = x;
        }
        let up = cross(right, scale(eye, -1.0));
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points {
            let (a, b) = (dot(*p, right), dot(*p, up));
            lo = [lo[0].min(a), lo[1].min(b)];
            hi = [hi[0].max(a), hi[1].max(b)];
        }
        if points.is_empty() {
            (lo, hi) = ([-1.0; 2], [1.0; 2]);
        }
        let [top, bottom, left, right_margin] = margins;
        let avail_w = (width as f64 - left - right_margin).max(1.0);
        let avail_h = (height as f64 - top - bottom).max(1.0);
        let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
        let s = (avail_w / span[0]).min(avail_h / span[1]);
        let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        Camera {
            right,
            up,
            eye,
            center: add(scale(right, mid[0]), scale(up, mid[1])),
            scale: s,
            origin: (left + avail_w / 2.0, top + avail_h / 2.0),
        }
    }

    /// Picture coordinates (x right, y down) and depth (smaller is nearer).
    pub(crate) fn project(&self, p: [f64; 3]) -> (f64, f64, f64) {
        let q = sub(p, self.center);
        (
            self.origin.0 + self.scale * dot(q, self.right),
            self.origin.1 - self.scale * dot(q, self.up),
            -dot(q, self.eye),
        )
    }

    /// The light: from the upper left, in front.
    pub(crate) fn light(&self) -> [f64; 3] {
        normalize(add(
            add(scale(self.eye, 0.75), scale(self.up, 0.55)),
            scale(self.right, -0.35),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_camera_keeps_z_up_and_looks_from_the_front_left() {
        let c = Camera::fit(
            &View::default(),
            &[[1.0, 1.0, 1.0], [-1.0, -1.0, -1.0]],
            100,
            100,
            [0.0; 4],
        );
        assert!(c.up[2] > 0.8);
        assert!(dot(c.right, c.up).abs() < 1e-12 && dot(c.eye, c.up).abs() < 1e-12);
        let (_, y_top, _) = c.project([0.0, 0.0, 1.0]);
        let (_, y_bottom, _) = c.project([0.0, 0.0, -1.0]);
        assert!(y_top < y_bottom);
    }
}
