//! Affine transforms applied to input coordinates before snapping, in `f64`.
//!
//! Rotations computed from angles or quaternions are never exact in floating point
//! (cos 90° = 6.1e-17). [`Affine::snapped`] moves every matrix entry that lies within a
//! few ulps of 0, ±1/2 or ±1 onto that value, so that quarter turns, half turns and
//! mirrorings stay exact and contacts between parts survive.

/// `p ↦ m·p + t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine {
    /// The linear part, row-major: `m[row][column]`.
    pub m: [[f64; 3]; 3],
    /// The translation.
    pub t: [f64; 3],
}

/// Tolerance for `f64` data: 4 ulps of 1.0 (4 · 2^-52).
pub const TOL_F64: f64 = 4.0 * f64::EPSILON;
/// Tolerance for `f32` data (glTF): 4 ulps of 1.0f32 (4 · 2^-23).
pub const TOL_F32: f64 = 4.0 * f32::EPSILON as f64;

impl Default for Affine {
    fn default() -> Affine {
        Affine::IDENTITY
    }
}

impl Affine {
    /// The identity.
    pub const IDENTITY: Affine = Affine {
        m: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        t: [0.0; 3],
    };

    /// A translation.
    pub fn translation(t: [f64; 3]) -> Affine {
        Affine {
            t,
            ..Affine::IDENTITY
        }
    }

    /// The rotation by `angle` radians about `axis` (right-hand rule); `None` for a
    /// zero or non-finite axis.
    pub fn rotation(axis: [f64; 3], angle: f64) -> Option<Affine> {
        let n = apart_kernel::fvec::norm(axis);
        if !(n > 0.0 && n.is_finite() && angle.is_finite()) {
            return None;
        }
        let [x, y, z] = axis.map(|a| a / n);
        let (s, c) = angle.sin_cos();
        let k = 1.0 - c;
        Some(Affine {
            m: [
                [c + x * x * k, x * y * k - z * s, x * z * k + y * s],
                [y * x * k + z * s, c + y * y * k, y * z * k - x * s],
                [z * x * k - y * s, z * y * k + x * s, c + z * z * k],
            ],
            t: [0.0; 3],
        })
    }

    /// The rotation of the quaternion `[x, y, z, w]` (normalised first); `None` for a
    /// zero or non-finite quaternion.
    pub fn quaternion(q: [f64; 4]) -> Option<Affine> {
        let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        let [x, y, z, w] = q.map(|v| v / n);
        Some(Affine {
            m: [
                [
                    1.0 - 2.0 * (y * y + z * z),
                    2.0 * (x * y - z * w),
                    2.0 * (x * z + y * w),
                ],
                [
                    2.0 * (x * y + z * w),
                    1.0 - 2.0 * (x * x + z * z),
                    2.0 * (y * z - x * w),
                ],
                [
                    2.0 * (x * z - y * w),
                    2.0 * (y * z + x * w),
                    1.0 - 2.0 * (x * x + y * y),
                ],
            ],
            t: [0.0; 3],
        })
    }

    /// A diagonal scaling.
    pub fn scale(s: [f64; 3]) -> Affine {
        Affine {
            m: [[s[0], 0.0, 0.0], [0.0, s[1], 0.0], [0.0, 0.0, s[2]]],
            t: [0.0; 3],
        }
    }

    /// From a 4x4 row-major matrix; `None` unless the last row is `0 0 0 1`.
    pub fn from_rows(r: [[f64; 4]; 4]) -> Option<Affine> {
        if r[3] != [0.0, 0.0, 0.0, 1.0] {
            return None;
        }
        Some(Affine {
            m: [
                [r[0][0], r[0][1], r[0][2]],
                [r[1][0], r[1][1], r[1][2]],
                [r[2][0], r[2][1], r[2][2]],
            ],
            t: [r[0][3], r[1][3], r[2][3]],
        })
    }

    /// `self ∘ other`: first `other`, then `self`.
    pub fn then_after(&self, other: &Affine) -> Affine {
        let mut m = [[0.0; 3]; 3];
        let mut t = self.t;
        for (i, row) in m.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e = (0..3).map(|k| self.m[i][k] * other.m[k][j]).sum();
            }
            t[i] += (0..3).map(|k| self.m[i][k] * other.t[k]).sum::<f64>();
        }
        Affine { m, t }
    }

    /// The matrix with entries within `tol` of 0, ±1/2 or ±1 set to that value.
    pub fn snapped(&self, tol: f64) -> Affine {
        let mut a = *self;
        for row in &mut a.m {
            for e in row.iter_mut() {
                for target in [0.0, 0.5, -0.5, 1.0, -1.0] {
                    if (*e - target).abs() <= tol {
                        *e = target;
                    }
                }
            }
        }
        a
    }

    /// Applies the transform to a point.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let m = &self.m;
        [0, 1, 2].map(|i| m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + self.t[i])
    }

    /// Determinant of the linear part (negative for a mirroring).
    pub fn det(&self) -> f64 {
        let m = &self.m;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// True when every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.m
            .iter()
            .flatten()
            .chain(&self.t)
            .all(|v| v.is_finite())
    }

    /// True for the identity.
    pub fn is_identity(&self) -> bool {
        *self == Affine::IDENTITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turns_are_exact_after_snapping() {
        let r = Affine::rotation([0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2)
            .unwrap()
            .snapped(TOL_F64);
        assert_eq!(r.apply([1.0, 2.0, 3.0]), [-2.0, 1.0, 3.0]);
        let h = Affine::rotation([1.0, 0.0, 0.0], std::f64::consts::PI)
            .unwrap()
            .snapped(TOL_F64);
        assert_eq!(h.apply([1.0, 2.0, 3.0]), [1.0, -2.0, -3.0]);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let q = Affine::quaternion([0.0, s, 0.0, s])
            .unwrap()
            .snapped(TOL_F64);
        assert_eq!(q.apply([1.0, 0.0, 0.0]), [0.0, 0.0, -1.0]);
        let sixty = Affine::rotation([0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_3)
            .unwrap()
            .snapped(TOL_F64);
        assert_eq!(sixty.m[0][0], 0.5);
        assert!(Affine::rotation([0.0; 3], 1.0).is_none());
    }

    #[test]
    fn composition_and_rows() {
        let t = Affine::translation([1.0, 0.0, 0.0]);
        let r = Affine::rotation([0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2)
            .unwrap()
            .snapped(TOL_F64);
        // Rotate first, then translate.
        assert_eq!(t.then_after(&r).apply([1.0, 0.0, 0.0]), [1.0, 1.0, 0.0]);
        let m = Affine::from_rows([
            [0.0, -1.0, 0.0, 1.0],
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ])
        .unwrap();
        assert_eq!(m, t.then_after(&r));
        assert!(Affine::scale([-1.0, 1.0, 1.0]).det() < 0.0);
        assert!(Affine::from_rows([[0.0; 4]; 4]).is_none());
    }
}
