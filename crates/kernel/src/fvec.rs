//! Floating-point vectors `[f64; 3]`, for pictures, reported measurements (depths,
//! clearances, unit directions) and the float shadows that filters read. Nothing here
//! decides a combinatorial question: every decision is an exact predicate.
//!
//! Each function evaluates its formula in the order written (no fused operations), so
//! that a filter's error bound stated for that formula holds.

/// A vector of doubles.
pub type F3 = [f64; 3];

/// `a + b`.
#[inline]
pub fn add(a: F3, b: F3) -> F3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
#[inline]
pub fn sub(a: F3, b: F3) -> F3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a * s`.
#[inline]
pub fn scale(a: F3, s: f64) -> F3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `-a`.
#[inline]
pub fn neg(a: F3) -> F3 {
    a.map(|c| -c)
}

/// The dot product `a[0] b[0] + a[1] b[1] + a[2] b[2]`, summed left to right.
#[inline]
pub fn dot(a: F3, b: F3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The cross product.
#[inline]
pub fn cross(a: F3, b: F3) -> F3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a` against `b` coordinate by coordinate, each by `f64::total_cmp`: a total order of
/// vectors that depends on their values alone (for deterministic orders and tie-breaks).
#[inline]
pub fn lex_cmp(a: F3, b: F3) -> std::cmp::Ordering {
    a[0].total_cmp(&b[0])
        .then_with(|| a[1].total_cmp(&b[1]))
        .then_with(|| a[2].total_cmp(&b[2]))
}

/// The Euclidean length, `sqrt(dot(a, a))`.
#[inline]
pub fn norm(a: F3) -> f64 {
    dot(a, a).sqrt()
}

/// `a / |a|` (as `a * (1 / |a|)`), or zero for the zero vector.
#[inline]
pub fn normalize(a: F3) -> F3 {
    let n = norm(a);
    if n > 0.0 {
        scale(a, 1.0 / n)
    } else {
        [0.0; 3]
    }
}

/// `a + (b - a) t`.
#[inline]
pub fn lerp(a: F3, b: F3, t: f64) -> F3 {
    add(a, scale(sub(b, a), t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors() {
        let (x, y) = ([1.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        assert_eq!(cross(x, y), [0.0, 0.0, 2.0]);
        assert_eq!(dot(add(x, y), sub(x, y)), -3.0);
        assert_eq!(norm([3.0, 4.0, 0.0]), 5.0);
        assert_eq!(normalize(y), [0.0, 1.0, 0.0]);
        assert_eq!(normalize([0.0; 3]), [0.0; 3]);
        assert_eq!(lerp(x, y, 0.5), [0.5, 1.0, 0.0]);
        assert_eq!(neg(x), [-1.0, -0.0, -0.0]);
    }
}
