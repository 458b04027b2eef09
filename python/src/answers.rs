//! The answers as JSON values, field for field as the command line's `--json` prints
//! them (`apart check`, `partition`, `sequence`, `disassemble`, `separate`, `place`, `stack`), so that the Python
//! objects and the command line say the same thing. A partition lists what the command
//! line lists ([`Listing`]): by default at most 20 moving sets with at most 5 solutions
//! of each kind, every solution still counted.

use apart_assembly::Loaded;
use apart_jobs::partition::PartitionOptions;
use apart_jobs::place::PlaceJobOptions;
use apart_jobs::sequence::SequenceJobOptions;
use apart_jobs::stack::StackJobOptions;
use apart_jobs::JobError;
use apart_kernel::Vec3;
use apart_mesh::Problem;
use apart_plan::progress::Progress;
use apart_plan::SequenceOptions;
use serde_json::Value;
use std::sync::Arc;

/// Every problem, as the command line's JSON lists them.
pub fn problems(problems: &[Problem]) -> Value {
    serde_json::to_value(problems).unwrap_or(Value::Null)
}

/// The check report.
pub fn check(loaded: &Loaded, units: Option<&str>) -> Value {
    serde_json::to_value(apart_jobs::check::check(loaded, units)).unwrap_or(Value::Null)
}

/// Snaps a direction like the command line's `--direction X,Y,Z` (see
/// [`apart_jobs::partition::snap_direction`]), phrased for Python.
pub fn snap_direction(v: [f64; 3]) -> Result<Vec3, String> {
    use apart_jobs::partition::DirectionError;
    apart_jobs::partition::snap_direction(v).map_err(|e| match e {
        DirectionError::NonFinite => format!("direction {v:?} has a non-finite number"),
        DirectionError::Zero => format!("direction {v:?} is zero"),
    })
}

/// Partitioning: one direction's blocking graph (`direction`, with two parts or more),
/// or the job's partition (see [`apart_jobs::partition`]), with the seconds it took.
pub fn partition(
    loaded: &Loaded,
    units: Option<&str>,
    direction: Option<Vec3>,
    opts: &PartitionOptions,
    progress: &Progress,
) -> Result<Value, JobError> {
    if let Some(d) = direction.filter(|_| loaded.assembly.parts.len() >= 2) {
        let a = apart_jobs::partition::direction(loaded, units, &d)?;
        return Ok(serde_json::to_value(a).unwrap_or(Value::Null));
    }
    let t = std::time::Instant::now();
    let mut a = apart_jobs::partition::partition(loaded, units, opts, progress)?.answer;
    a.stats.seconds.total = Some(t.elapsed().as_secs_f64());
    Ok(serde_json::to_value(a).unwrap_or(Value::Null))
}

/// A disassembly plan (the job's, every step with why it was chosen) with the seconds
/// it took, and the plan itself (for its pictures).
pub fn sequence(
    loaded: &Loaded,
    units: Option<&str>,
    opts: &SequenceOptions,
    first: bool,
    progress: &Progress,
) -> Result<(Value, Arc<apart_plan::Sequence>), JobError> {
    let t = std::time::Instant::now();
    let job = SequenceJobOptions {
        plan: opts.clone(),
        first,
        explain: true,
    };
    let mut a = apart_jobs::sequence::sequence(loaded, units, &job, progress, &mut |_, _| {})?;
    a.seconds.total = Some(t.elapsed().as_secs_f64());
    let plan = a.plan.clone();
    Ok((serde_json::to_value(a).unwrap_or(Value::Null), plan))
}

/// Every direction along which part `a` leaves part `b`; `None` when the stop flag
/// ended the run before it had the pair regions.
pub fn separate(
    loaded: &Loaded,
    units: Option<&str>,
    a: usize,
    b: usize,
    progress: &Progress,
) -> Result<Option<Value>, JobError> {
    Ok(
        apart_jobs::separate::separate(loaded, units, a, b, progress)?
            .map(|s| serde_json::to_value(s).unwrap_or(Value::Null)),
    )
}

/// Interference-free positions of one part among the others, cheapest first (the
/// job's answer, as `apart place ASSEMBLY NAME --json` prints it).
pub fn place(loaded: &Loaded, opts: &PlaceJobOptions) -> Result<Value, JobError> {
    let a = apart_jobs::place::place(loaded, opts)?.answer;
    Ok(serde_json::to_value(a).unwrap_or(Value::Null))
}

/// A stack of identical parts on a floor (the job's answer, as `apart stack --json`
/// prints it but for the engine's counters: the seconds alone). A run stopped by the
/// flag has `"status": "stopped"`.
pub fn stack(
    loaded: &Loaded,
    opts: &StackJobOptions,
    progress: &Progress,
) -> Result<Value, JobError> {
    let mut a = apart_jobs::stack::stack(loaded, opts, progress)?;
    a.seconds = a.stats.take().map(|s| s.seconds.total);
    Ok(serde_json::to_value(a).unwrap_or(Value::Null))
}

/// A plan of several moves, with the seconds it took.
pub fn disassemble(
    loaded: &Loaded,
    units: Option<&str>,
    opts: &apart_plan::MoveOptions,
    progress: &Progress,
) -> Result<Value, JobError> {
    let t = std::time::Instant::now();
    let mut a = apart_jobs::disassemble::disassemble(loaded, units, opts, progress)?;
    a.stats.seconds.total = Some(t.elapsed().as_secs_f64());
    Ok(serde_json::to_value(a).unwrap_or(Value::Null))
}
