//! Progress reports and cooperative stopping for the long planners: the kernel's
//! [`apart_kernel::progress`] (one type shared with apart-stack), re-exported here so
//! that `apart_plan::progress::{Progress, phases}` keeps working.

pub use apart_kernel::progress::*;

/// A planner stopped by the flag before it had anything to return.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Stopped;
