//! The jobs of apart, one function per job, shared by both front ends (the command line
//! and the Python binding).
//!
//! A job takes a loaded assembly ([`apart_assembly::Loaded`]), its options and, when it
//! can be stopped, a [`Progress`] (callback, stop flag and memory budget question), and
//! returns a typed answer that serialises to the JSON both front ends print. The front
//! ends parse their arguments, call the job and present the answer (text, JSON, Python
//! objects, pictures); they never run a planner themselves.
//!
//! What every answer shares lives here too: the facts of its input ([`facts`]), its
//! status when a stop flag cut it short ([`status`]), and the validity gate of the
//! planning jobs ([`gate`]).

pub mod check;
pub mod decompose;
pub mod disassemble;
pub mod facts;
pub mod gate;
pub mod partition;
pub mod place;
pub mod separate;
pub mod sequence;
pub mod stack;
pub mod status;

pub use apart_kernel::progress::Progress;
pub use facts::InputFacts;
pub use status::{Status, StopFacts};

/// Why a job has no answer.
#[derive(Debug)]
pub enum JobError {
    /// The planner failed or was stopped before it had an answer.
    Plan(apart_plan::PlanError),
    /// The memory budget refused a structure the job was about to build (its estimate).
    OverBudget {
        /// The phase that was refused ([`apart_kernel::progress::phases`]).
        phase: &'static str,
        /// What it would have built, and its estimated size.
        what: String,
        /// The estimated size in bytes.
        bytes: u64,
    },
    /// The placement engine refused the request.
    Stack(apart_stack::part::StackError),
    /// A part cannot be placed or stacked.
    Part {
        /// Its name.
        part: String,
        /// Why.
        error: apart_stack::part::StackError,
    },
    /// An option in input units is no finite number of grid units (a huge value over a
    /// small grid step).
    NotFinite {
        /// The option, in snake case ("floor_point"); each front end words it its way.
        setting: &'static str,
        /// The value given.
        value: f64,
    },
}

impl std::fmt::Display for JobError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            JobError::Plan(e) => e.fmt(f),
            JobError::OverBudget { what, .. } => f.write_str(what),
            JobError::Stack(e) => e.fmt(f),
            JobError::Part { part, error } => write!(f, "part \"{part}\": {error}"),
            JobError::NotFinite { setting, value } => {
                write!(f, "{setting} {value} is not a finite number")
            }
        }
    }
}

impl std::error::Error for JobError {}

impl From<apart_plan::PlanError> for JobError {
    fn from(e: apart_plan::PlanError) -> JobError {
        JobError::Plan(e)
    }
}

impl From<apart_stack::part::StackError> for JobError {
    fn from(e: apart_stack::part::StackError) -> JobError {
        JobError::Stack(e)
    }
}
