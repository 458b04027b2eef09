//! The extension's own checks of its arguments, with the command line's ranges: the
//! functions of `apart._apart` may be called directly (bypassing `apart._core`, which
//! checks the same), and a NaN, a negative count or an unknown unit must raise
//! `apart.InputError` naming the argument, never reach the library.

use crate::errors::value_error;
use apart_stack::orientation::Base;
use pyo3::prelude::*;

/// Largest timeout, in seconds (one week, as the command line's `--timeout`).
pub const MAX_TIMEOUT: f64 = 604_800.0;

/// Length units of input files (the command line's `--units`).
pub const UNITS: [&str; 6] = ["m", "cm", "mm", "um", "in", "ft"];

fn fail<T>(py: Python<'_>, message: String) -> PyResult<T> {
    Err(value_error(py, message))
}

/// `timeout`: seconds, more than 0 and at most a week.
pub fn timeout(py: Python<'_>, t: Option<f64>) -> PyResult<Option<f64>> {
    match t {
        Some(v) if !(v.is_finite() && v > 0.0 && v <= MAX_TIMEOUT) => fail(
            py,
            format!(
                "timeout must be more than 0 and at most {MAX_TIMEOUT} seconds (one week), not {v}"
            ),
        ),
        _ => Ok(t),
    }
}

/// `units`: one of [`UNITS`].
pub fn units(py: Python<'_>, u: Option<&str>) -> PyResult<()> {
    match u {
        Some(u) if !UNITS.contains(&u) => {
            fail(py, format!("units {u:?} is none of {}", UNITS.join(", ")))
        }
        _ => Ok(()),
    }
}

/// `grid_bits`: the range the kernel's grid supports.
pub fn grid_bits(py: Python<'_>, bits: i64) -> PyResult<u32> {
    use apart_kernel::grid::{MAX_BITS, MIN_BITS};
    match u32::try_from(bits) {
        Ok(b) if (MIN_BITS..=MAX_BITS).contains(&b) => Ok(b),
        _ => fail(
            py,
            format!("grid_bits must be an integer from {MIN_BITS} to {MAX_BITS}, not {bits}"),
        ),
    }
}

/// `tolerance`: a finite length more than 0 (and none with `tolerance_auto`).
pub fn tolerance(py: Python<'_>, eps: Option<f64>, auto: bool) -> PyResult<()> {
    match eps {
        Some(v) if !(v.is_finite() && v > 0.0) => fail(
            py,
            format!("tolerance must be a finite, positive length, not {v}"),
        ),
        Some(_) if auto => fail(
            py,
            "tolerance: give a length or tolerance_auto, not both".into(),
        ),
        _ => Ok(()),
    }
}

/// A whole number in `lo..=hi` named `what` (`hi`: `None` for no upper bound).
pub fn count(py: Python<'_>, what: &str, v: i64, lo: i64, hi: Option<i64>) -> PyResult<usize> {
    let ok = v >= lo && hi.is_none_or(|h| v <= h);
    match (ok, usize::try_from(v)) {
        (true, Ok(n)) => Ok(n),
        _ => match hi {
            Some(h) => fail(
                py,
                format!("{what} must be an integer from {lo} to {h}, not {v}"),
            ),
            None => fail(
                py,
                format!("{what} must be an integer of {lo} or more, not {v}"),
            ),
        },
    }
}

/// An optional whole number of at least 1 named `what`.
pub fn positive(py: Python<'_>, what: &str, v: Option<i64>) -> PyResult<Option<usize>> {
    v.map(|v| count(py, what, v, 1, None)).transpose()
}

/// A finite number named `what`.
pub fn finite(py: Python<'_>, what: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        fail(py, format!("{what} must be a finite number, not {v}"))
    }
}

/// Finite numbers named `what`.
pub fn all_finite<const N: usize>(py: Python<'_>, what: &str, v: [f64; N]) -> PyResult<[f64; N]> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(v)
    } else {
        fail(py, format!("{what} must be {N} finite numbers, not {v:?}"))
    }
}

/// A box `(x0, y0, z0, x1, y1, z1)` named `what`: finite, its low corner not above its
/// high one.
pub fn region(py: Python<'_>, what: &str, b: Option<[f64; 6]>) -> PyResult<Option<[f64; 6]>> {
    let Some(b) = b else { return Ok(None) };
    all_finite(py, what, b)?;
    if (0..3).any(|i| b[i] > b[i + 3]) {
        return fail(
            py,
            format!("{what} {b:?} is empty (a low corner above the high one)"),
        );
    }
    Ok(Some(b))
}

/// `weight`: in [0, 1].
pub fn weight(py: Python<'_>, w: f64) -> PyResult<f64> {
    if (0.0..=1.0).contains(&w) {
        Ok(w)
    } else {
        fail(py, format!("weight must be in [0, 1], not {w}"))
    }
}

/// `dtheta`: degrees from 0.1 to 360.
pub fn dtheta(py: Python<'_>, d: f64) -> PyResult<f64> {
    if (0.1..=360.0).contains(&d) {
        Ok(d)
    } else {
        fail(
            py,
            format!("dtheta must be from 0.1 to 360 degrees, not {d}"),
        )
    }
}

/// `clearance`: a finite length of 0 or more.
pub fn clearance(py: Python<'_>, c: Option<f64>) -> PyResult<Option<f64>> {
    match c {
        Some(v) if !(v.is_finite() && v >= 0.0) => {
            fail(py, format!("clearance must be 0 or more, not {v}"))
        }
        _ => Ok(c),
    }
}

/// `bases`: quarter turns (phi, psi), each 0 to 3.
pub fn bases(py: Python<'_>, b: Option<Vec<(u8, u8)>>) -> PyResult<Option<Vec<Base>>> {
    if let Some(q) = b
        .as_ref()
        .and_then(|v| v.iter().find(|(a, c)| *a > 3 || *c > 3))
    {
        return fail(
            py,
            format!("bases must be quarter turns from 0 to 3, not {q:?}"),
        );
    }
    Ok(b.map(|v| v.into_iter().map(|(phi, psi)| Base { phi, psi }).collect()))
}
