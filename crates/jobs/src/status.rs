//! The status of an answer: complete, or cut short by a stop flag, and why.

use serde::Serialize;

/// Where and why a run was stopped, as the answer states it.
#[derive(Clone, Debug, Serialize)]
pub struct StopFacts {
    /// What stopped it, in the front end's words ("--timeout", "--max-memory",
    /// "Ctrl-C").
    pub by: String,
    /// The timeout given, or the seconds from the start of the run.
    pub after_seconds: f64,
    /// The phase it was in.
    pub phase: String,
    /// For the memory budget: the estimate refused, or the heap in use.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

/// The status fields every planning answer starts with.
#[derive(Clone, Debug, Serialize)]
pub struct Status {
    /// "done", or why the answer is partial ("stopped" from a job; the front ends name
    /// the cause: "timeout", "out of memory", "interrupted").
    pub status: String,
    /// Every answer was searched for (false after a stop).
    pub complete: bool,
    /// What stopped the run, and where; absent when it ran to its end or the front end
    /// does not say.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<StopFacts>,
}

impl Status {
    /// The status of a job that ran to its end (`stopped` false) or was stopped by its
    /// flag: "done" or "stopped", without the cause.
    pub fn of(stopped: bool) -> Status {
        Status {
            status: if stopped { "stopped" } else { "done" }.to_string(),
            complete: !stopped,
            stopped: None,
        }
    }

    /// The same status with the cause the front end knows: `status` names it
    /// ("timeout") and `facts` says where.
    pub fn stopped_by(&mut self, status: &str, facts: StopFacts) {
        self.status = status.to_string();
        self.complete = false;
        self.stopped = Some(facts);
    }
}
