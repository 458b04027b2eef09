//! Long work off the interpreter: a worker thread runs it with the GIL released, while
//! the calling thread forwards its progress to the Python callback, checks for Ctrl-C,
//! the timeout and the memory budget ([`crate::budget`]), and raises the planners' stop
//! flag when asked to stop.

use crate::budget;
use apart_kernel::progress::Progress;
use pyo3::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::Ordering;
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How a run may be stopped, and who hears its progress.
pub struct Limits {
    /// Called with `(phase, done, total)`; raising `apart.Stop` asks for the partial
    /// answer, any other exception stops the run and is raised again.
    pub callback: Option<Py<PyAny>>,
    /// Seconds after which the stop flag is raised.
    pub timeout: Option<f64>,
    /// The work watches the stop flag and has a partial answer (planners do; the
    /// loader watches it but has none, so on Ctrl-C `KeyboardInterrupt` is raised at
    /// once and the raised flag ends the loader in the background). Only such work is
    /// stopped by the memory budget's soft limit.
    pub stoppable: bool,
}

/// What raised the stop flag: the memory budget (its soft limit, or a structure a
/// planner estimated over what the budget leaves).
pub const BY_MEMORY: &str = "memory budget";

/// Why the stop flag was raised, and when.
#[derive(Clone, Debug)]
pub struct Stopped {
    /// "timeout", "callback" or [`BY_MEMORY`].
    pub by: &'static str,
    /// Seconds from the start of the run.
    pub after_seconds: f64,
    /// The last phase reported before the stop.
    pub phase: String,
    /// For the memory budget: what was refused or how much was in use.
    pub detail: Option<String>,
}

impl Stopped {
    /// Stopped by the memory budget.
    pub fn by_memory(&self) -> bool {
        self.by == BY_MEMORY
    }
}

/// A planner's refusal of a structure over the budget: its phase and the detail.
type Refusal = Arc<Mutex<Option<(&'static str, String)>>>;

/// Why the memory budget stops the call now, if it does: a refusal, the budget passed,
/// or its soft limit passed.
fn memory_stop(watch: &budget::Watch, refused: &Refusal, phase: &str) -> Option<(String, String)> {
    if let Some((p, detail)) = refused.lock().unwrap_or_else(|e| e.into_inner()).clone() {
        return Some((p.to_string(), detail));
    }
    if let Some(live) = watch.over_passed() {
        return Some((
            phase.to_string(),
            format!("{} MiB of heap in use, past the budget", live >> 20),
        ));
    }
    watch.soft_passed().then(|| {
        (
            phase.to_string(),
            format!(
                "{} MiB of heap in use, past 90 % of the budget",
                apart_kernel::budget::live() >> 20
            ),
        )
    })
}

/// What the worker sends.
enum Msg<R> {
    Progress(&'static str, usize, usize),
    Done(std::thread::Result<R>),
}

/// Runs `work` on a worker thread with the GIL released and returns its result, with
/// why the stop flag was raised (`None`: it was not). A panic in the work becomes
/// `apart.InternalError`; Ctrl-C raises the stop flag, waits for the planner's partial
/// answer (unless the work cannot stop, or Ctrl-C comes twice) and raises
/// `KeyboardInterrupt`; an exception from the callback other than `apart.Stop` does the
/// same with that exception. The memory budget's soft limit (or a planner's refusal of
/// a structure estimated over it) raises the stop flag of work that watches it, for
/// its partial answer; a call during which the heap passed the budget itself raises
/// `apart.OutOfMemoryBudget` once its work has returned (see [`crate::budget`]).
pub fn run<R, F>(py: Python<'_>, limits: Limits, work: F) -> PyResult<(R, Option<Stopped>)>
where
    R: Send + 'static,
    F: FnOnce(&Progress) -> R + Send + 'static,
{
    let (tx, rx) = channel::<Msg<R>>();
    let reports = tx.clone();
    let watch = budget::Watch::start();
    let refused: Refusal = Arc::default();
    let refusals = refused.clone();
    let progress = Progress::with_callback(move |phase, done, total| {
        let _ = reports.send(Msg::Progress(phase, done, total));
    })
    .with_budget(move |phase, bytes| match budget::affordable(phase, bytes) {
        Ok(()) => true,
        Err(detail) => {
            *refusals.lock().unwrap_or_else(|e| e.into_inner()) = Some((phase, detail));
            false
        }
    });
    let flag = progress.stop_flag();
    let worker = progress.clone();
    std::thread::Builder::new()
        .name("apart-worker".into())
        .spawn(move || {
            let result = catch_unwind(AssertUnwindSafe(|| work(&worker)));
            // Dropping the progress closes its sender too once the work is done.
            drop(worker);
            let _ = tx.send(Msg::Done(result));
        })
        .map_err(|e| crate::errors::internal(py, format!("cannot start a thread: {e}")))?;
    drop(progress);
    let start = Instant::now();
    let mut rx: Receiver<Msg<R>> = rx;
    let mut stop: Option<Stopped> = None;
    let mut raised: Option<PyErr> = None;
    let mut phase = String::from("starting");
    // The last report per phase, so that the callback sees counts that never go back
    // (the loader's threads may report out of order).
    let mut last: Option<(&'static str, usize)> = None;
    budget::set_phase("starting");
    let stop_stamp = |by: &'static str, phase: &str| Stopped {
        by,
        after_seconds: start.elapsed().as_secs_f64(),
        phase: phase.to_string(),
        detail: None,
    };
    let memory_stamp = |(phase, detail): (String, String)| Stopped {
        by: BY_MEMORY,
        after_seconds: start.elapsed().as_secs_f64(),
        phase,
        detail: Some(detail),
    };
    let result = loop {
        let (msg, back) = py.detach(move || {
            let m = rx.recv_timeout(Duration::from_millis(50));
            (m, rx)
        });
        rx = back;
        match msg {
            Ok(Msg::Done(r)) => break r,
            Ok(Msg::Progress(p, done, total)) => {
                phase = p.to_string();
                budget::set_phase(p);
                if last.is_some_and(|(q, d)| q == p && done < d) {
                    continue;
                }
                last = Some((p, done));
                if let (Some(cb), None, None) = (&limits.callback, &stop, &raised) {
                    if let Err(e) = cb.call1(py, (p, done, total)) {
                        flag.store(true, Ordering::Relaxed);
                        if e.is_instance(py, &stop_class(py)?) {
                            stop = Some(stop_stamp("callback", &phase));
                        } else {
                            raised = Some(e);
                        }
                    }
                }
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => {
                return Err(crate::errors::internal(
                    py,
                    "the worker thread ended without an answer".into(),
                ))
            }
        }
        if let Err(e) = py.check_signals() {
            flag.store(true, Ordering::Relaxed);
            // A second Ctrl-C, or work that cannot stop: raise now and let the worker
            // finish on its own (its answer is dropped).
            if raised.is_some() || !limits.stoppable {
                return Err(e);
            }
            raised = Some(e);
        }
        if let Some(t) = limits.timeout {
            if stop.is_none() && raised.is_none() && start.elapsed().as_secs_f64() >= t {
                flag.store(true, Ordering::Relaxed);
                stop = Some(stop_stamp("timeout", &phase));
            }
        }
        if limits.stoppable && stop.is_none() && raised.is_none() {
            if let Some(m) = memory_stop(&watch, &refused, &phase) {
                flag.store(true, Ordering::Relaxed);
                stop = Some(memory_stamp(m));
            }
        }
        // Work that cannot stop has no partial answer: a stop ends the call now (the
        // worker finishes on its own and its answer is dropped).
        if stop.is_some() && !limits.stoppable {
            return Err(crate::errors::stopped(py, stop));
        }
    };
    if let Some(e) = raised {
        return Err(e);
    }
    // A Ctrl-C that came with the last reports, after the loop's last look, is still a
    // Ctrl-C during the call.
    py.check_signals()?;
    // Past the budget itself the command line would have ended: no answer.
    if let Some(live) = watch.over_passed() {
        drop(result);
        return Err(crate::errors::out_of_memory(
            py,
            &phase,
            &format!("{} MiB of heap asked for", live >> 20),
        ));
    }
    // A planner's refusal just before its work returned (it stopped on its own).
    if stop.is_none() {
        if let Some((p, detail)) = refused.lock().unwrap_or_else(|e| e.into_inner()).take() {
            stop = Some(memory_stamp((p.to_string(), detail)));
        }
    }
    match result {
        Ok(r) => Ok((r, stop)),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic".into());
            Err(crate::errors::internal(
                py,
                format!("internal error (please report it): {what}"),
            ))
        }
    }
}

/// `apart.Stop`, the exception a progress callback raises to ask for the partial
/// answer.
fn stop_class(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    py.import("apart._errors")?.getattr("Stop")
}

/// Marks a planner's answer that stopped early (`"status": "stopped"`, set by the
/// answer itself) with why and when: `"status"` becomes `"timeout"`, `"out of memory"`
/// (the memory budget) or `"stopped"` (asked by the callback), and `"stopped"` holds
/// `by`, `after_seconds` and `phase` as in the command line's JSON (and for the memory
/// budget its `detail`).
pub fn mark(answer: &mut serde_json::Value, stop: &Option<Stopped>) {
    let partial = answer.get("status").and_then(|s| s.as_str()) == Some("stopped");
    if !partial {
        return;
    }
    let (by, status, after, phase) = match stop {
        Some(s) if s.by == "timeout" => ("timeout", "timeout", s.after_seconds, s.phase.clone()),
        Some(s) if s.by_memory() => (BY_MEMORY, "out of memory", s.after_seconds, s.phase.clone()),
        Some(s) => ("callback", "stopped", s.after_seconds, s.phase.clone()),
        None => ("stop flag", "stopped", 0.0, String::new()),
    };
    answer["status"] = status.into();
    answer["stopped"] = serde_json::json!({
        "by": by,
        "after_seconds": after,
        "phase": phase,
    });
    if let Some(d) = stop.as_ref().and_then(|s| s.detail.as_ref()) {
        answer["stopped"]["detail"] = d.clone().into();
        answer["stopped"]["budget"] = budget::limit_text().into();
    }
}
