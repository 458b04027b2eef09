//! The library's errors as the exceptions of `apart._errors` (defined in Python, so
//! that `InputError` can be a `ValueError` too), each with the file, the part and the
//! element where the library's problem values name them.

use crate::work::Stopped;
use apart_assembly::{Assembly, Loaded};
use pyo3::prelude::*;
use std::path::PathBuf;

/// An exception of `apart._errors`, made by its `_make(kind, message, details_json)`.
fn make(py: Python<'_>, kind: &str, message: String, details: serde_json::Value) -> PyErr {
    let made = py
        .import("apart._errors")
        .and_then(|m| m.getattr("_make"))
        .and_then(|f| f.call1((kind, message.clone(), details.to_string())));
    match made {
        Ok(e) => PyErr::from_value(e),
        // The package is broken (its Python half missing): still a clear error.
        Err(e) => pyo3::exceptions::PyRuntimeError::new_err(format!("{message} ({e})")),
    }
}

/// `apart.InputError`: bad input, with what is known of where.
pub fn input_error(
    py: Python<'_>,
    message: String,
    file: Option<PathBuf>,
    part: Option<String>,
    element: Option<String>,
) -> PyErr {
    make(
        py,
        "InputError",
        message,
        serde_json::json!({"file": file, "part": part, "element": element}),
    )
}

/// A failure to load anything: `FileNotFoundError`-like `apart.InputError` naming the
/// path.
pub fn load_error(py: Python<'_>, message: String, file: Option<PathBuf>) -> PyErr {
    input_error(py, message, file, None, None)
}

/// `apart.InputError` for a wrong argument (a part name, a direction).
pub fn value_error(py: Python<'_>, message: String) -> PyErr {
    input_error(py, message, None, None, None)
}

/// `apart.InternalError`: a bug, never bad input.
pub fn internal(py: Python<'_>, message: String) -> PyErr {
    make(py, "InternalError", message, serde_json::json!({}))
}

/// `apart.OutOfMemoryBudget` (a `MemoryError`): "out of memory budget (SIZE) during
/// PHASE: DETAIL", as the command line's error line words it.
pub fn out_of_memory(py: Python<'_>, phase: &str, detail: &str) -> PyErr {
    make(
        py,
        "OutOfMemoryBudget",
        format!(
            "out of memory budget ({}) during {phase}: {detail}",
            crate::budget::limit_text()
        ),
        serde_json::json!({
            "phase": phase,
            "detail": detail,
            "budget": apart_kernel::budget::limit(),
        }),
    )
}

/// `apart.StoppedError`: the run was stopped before it had any answer
/// (`apart.OutOfMemoryBudget` when the memory budget stopped it).
pub fn stopped(py: Python<'_>, stop: Option<Stopped>) -> PyErr {
    if let Some(s) = stop.as_ref().filter(|s| s.by_memory()) {
        return out_of_memory(py, &s.phase, s.detail.as_deref().unwrap_or("stopped"));
    }
    let (by, phase, after) = match &stop {
        Some(s) => (s.by, s.phase.clone(), s.after_seconds),
        None => ("stop flag", String::new(), 0.0),
    };
    make(
        py,
        "StoppedError",
        format!("stopped by the {by} after {after:.2} s during {phase}: no answer yet"),
        serde_json::json!({"by": by, "phase": phase, "after_seconds": after}),
    )
}

/// `apart.InvalidAssemblyError` when loading found errors: the first error's file, part
/// and element, and every problem.
pub fn require_valid(py: Python<'_>, loaded: &Loaded) -> PyResult<()> {
    require_valid_but(py, loaded, None)
}

/// [`require_valid`], excusing the overlaps of part `free` (the part to place, which
/// may be given where it overlaps the others, as `apart place` allows).
pub fn require_valid_but(py: Python<'_>, loaded: &Loaded, free: Option<&str>) -> PyResult<()> {
    let errors = apart_jobs::gate::errors(loaded, free);
    let Some(first) = errors.first() else {
        return Ok(());
    };
    let message = format!(
        "\"{}\" is not a valid assembly ({} error{}); the first: {}",
        loaded.assembly.name,
        errors.len(),
        if errors.len() == 1 { "" } else { "s" },
        first
    );
    Err(make(
        py,
        "InvalidAssemblyError",
        message,
        serde_json::json!({
            "file": first.file,
            "part": first.part,
            "element": first.element,
            "problems": crate::answers::problems(&loaded.problems),
        }),
    ))
}

/// A planner's error: an overlap names both parts; anything else is internal.
pub fn plan_error(py: Python<'_>, e: apart_plan::PlanError) -> PyErr {
    match &e {
        apart_plan::PlanError::Overlap { names, .. } => make(
            py,
            "InputError",
            e.to_string(),
            serde_json::json!({"part": names.0, "other_part": names.1}),
        ),
        apart_plan::PlanError::NoPieces { name, .. } => make(
            py,
            "InputError",
            e.to_string(),
            serde_json::json!({"part": name}),
        ),
        apart_plan::PlanError::Stopped { phase } => make(
            py,
            "StoppedError",
            format!("stopped during {phase}: no answer yet"),
            serde_json::json!({"phase": phase}),
        ),
        apart_plan::PlanError::TooManyParts { parts, limit } => make(
            py,
            "InputError",
            e.to_string(),
            serde_json::json!({"parts": parts, "limit": limit}),
        ),
        apart_plan::PlanError::Internal(_) => internal(py, e.to_string()),
    }
}

/// A job's error: the memory budget's refusal as `apart.OutOfMemoryBudget`, a
/// planner's error as [`plan_error`] says.
pub fn job_error(py: Python<'_>, e: apart_jobs::JobError, stop: &Option<Stopped>) -> PyErr {
    match e {
        apart_jobs::JobError::OverBudget { .. } => stopped(py, stop.clone()),
        apart_jobs::JobError::Plan(e) => match stop {
            // The motion space refused by the memory budget.
            Some(s) if s.by_memory() => stopped(py, stop.clone()),
            _ => plan_error(py, e),
        },
        e @ (apart_jobs::JobError::Stack(_)
        | apart_jobs::JobError::Part { .. }
        | apart_jobs::JobError::NotFinite { .. }) => value_error(py, e.to_string()),
    }
}

/// The index of the part named `name`, or `apart.InputError` listing the parts.
pub fn part_index(py: Python<'_>, asm: &Assembly, name: &str) -> PyResult<usize> {
    if let Some(k) = asm.parts.iter().position(|p| p.name == name) {
        return Ok(k);
    }
    let names: Vec<String> = asm
        .parts
        .iter()
        .map(|p| format!("\"{}\"", p.name))
        .collect();
    let shown = if names.len() <= 12 {
        format!("; its parts: {}", names.join(", "))
    } else {
        format!("; it has {} parts", names.len())
    };
    Err(input_error(
        py,
        format!(
            "the assembly \"{}\" has no part named \"{name}\"{shown}",
            asm.name
        ),
        None,
        Some(name.to_string()),
        None,
    ))
}
