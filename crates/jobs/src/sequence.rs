//! Sequencing: a complete disassembly plan by recursive two-handed partitioning (its
//! reverse is an assembly plan), each step handed to the caller as it is found.

use crate::{InputFacts, JobError, Progress, Status, StopFacts};
use apart_assembly::Loaded;
use apart_plan::along::holds_without_tolerance;
use apart_plan::sequence::{Choice, Keys, LocalStats};
use apart_plan::{
    parts_of, sequence_first_with, sequence_parts, Growth, Ranking, Sequence, SequenceOptions, Step,
};
use serde::Serialize;
use std::sync::Arc;

/// How to sequence.
#[derive(Clone, Debug, Default)]
pub struct SequenceJobOptions {
    /// The planner's options.
    pub plan: SequenceOptions,
    /// Split along the first likely direction that frees a subset, not ranked.
    pub first: bool,
    /// Each step states why it was chosen (`choice`).
    pub explain: bool,
}

/// A candidate's ranking keys.
#[derive(Clone, Debug, Serialize)]
pub struct KeysAnswer {
    /// Both sides connected through contacts; null unless asked for.
    pub connected: Option<bool>,
    /// One part moves.
    pub single: bool,
    /// The direction is an axis.
    pub axis: bool,
    /// "face", "edge" or "vertex".
    pub cell: &'static str,
    /// Its clearance.
    pub clearance_deg: f64,
    /// Parts that move.
    pub parts: usize,
}

impl KeysAnswer {
    fn of(k: &Keys) -> KeysAnswer {
        KeysAnswer {
            connected: k.connected,
            single: k.single,
            axis: k.axis,
            cell: k.cell.name(),
            clearance_deg: k.clearance_deg,
            parts: k.parts,
        }
    }
}

/// The best candidate the chosen one beat.
#[derive(Clone, Debug, Serialize)]
pub struct RivalAnswer {
    /// Its moving set.
    pub moving: Vec<String>,
    /// Its direction.
    pub exact_direction: [String; 3],
    /// Its keys.
    #[serde(flatten)]
    pub keys: KeysAnswer,
    /// The first key it lost on: connected, single, axis, cell, clearance, fewer_parts,
    /// order.
    pub lost_on: &'static str,
}

/// Why a step was chosen.
#[derive(Clone, Debug, Serialize)]
pub struct ChoiceAnswer {
    /// Candidates ranked.
    pub candidates: usize,
    /// The chosen one's keys.
    #[serde(flatten)]
    pub keys: KeysAnswer,
    /// The best one it beat.
    pub runner_up: Option<RivalAnswer>,
}

impl ChoiceAnswer {
    fn of(names: &[String], c: &Choice) -> ChoiceAnswer {
        ChoiceAnswer {
            candidates: c.candidates,
            keys: KeysAnswer::of(&c.keys),
            runner_up: c.runner_up.as_ref().map(|r| RivalAnswer {
                moving: names_of(names, &r.moving),
                exact_direction: r.direction.to_strings(),
                keys: KeysAnswer::of(&r.keys),
                lost_on: r.lost_on.key(),
            }),
        }
    }
}

/// One step of a plan.
#[derive(Clone, Debug, Serialize)]
pub struct StepAnswer {
    /// The subassembly it splits.
    pub subassembly: Vec<String>,
    /// The side that moves.
    pub moving: Vec<String>,
    /// The direction as a unit vector.
    pub direction: [f64; 3],
    /// Exactly.
    pub exact_direction: [String; 3],
    /// "face", "edge" or "vertex".
    pub cell: &'static str,
    /// Its clearance.
    pub clearance_deg: f64,
    /// Depth of the split.
    pub depth: usize,
    /// The rule that chose the step: "ranked", "single", "pair", "likely", "full".
    pub rule: &'static str,
    /// Largest uniform growth in input units that keeps the step possible (when asked
    /// for); null when unbounded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub growth: Option<Option<f64>>,
    /// Under a tolerance: the step also holds for the parts as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub holds_without_tolerance: Option<bool>,
    /// Why the step was chosen (when asked for).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub choice: Option<ChoiceAnswer>,
}

/// The answer's form of a planner's step: `names` of the parts, `step_unit` the grid
/// step (growths are stated in input units).
pub fn step_answer(
    names: &[String],
    s: &Step,
    step_unit: f64,
    holds: Option<bool>,
    explain: bool,
) -> StepAnswer {
    StepAnswer {
        subassembly: names_of(names, &s.subassembly),
        moving: names_of(names, &s.moving),
        direction: s.unit,
        exact_direction: s.direction.to_strings(),
        cell: s.cell.name(),
        clearance_deg: s.clearance_deg,
        depth: s.depth,
        rule: s.rule.key(),
        growth: s.tolerance.map(|t| match t {
            Growth::Finite(x) => Some(x * step_unit),
            Growth::Unbounded => None,
        }),
        holds_without_tolerance: holds,
        choice: explain.then(|| ChoiceAnswer::of(names, &s.choice)),
    }
}

/// The planner's work (not with `first`).
#[derive(Clone, Debug, Serialize)]
pub struct WorkAnswer {
    /// Parts whose free directions alone were computed (recomputations included).
    pub singles: usize,
    /// Pairs of touching parts whose free directions together were computed.
    pub pairs: usize,
    /// Likely directions tested over a whole subassembly.
    pub likely_directions: usize,
    /// Steps by a single part.
    pub single_steps: usize,
    /// Steps by a pair.
    pub pair_steps: usize,
    /// Steps along a likely direction.
    pub likely_steps: usize,
    /// Steps ranked over a full motion space.
    pub ranked_steps: usize,
    /// Subassemblies searched over their full motion space because nothing simpler
    /// split them.
    pub full_searches: usize,
}

impl From<&LocalStats> for WorkAnswer {
    fn from(s: &LocalStats) -> WorkAnswer {
        WorkAnswer {
            singles: s.singles,
            pairs: s.pairs,
            likely_directions: s.likely_directions,
            single_steps: s.single_steps,
            pair_steps: s.pair_steps,
            likely_steps: s.likely_steps,
            ranked_steps: s.ranked,
            full_searches: s.full_searches,
        }
    }
}

/// Every step of a plan, each made as it is written (a plan of thousands of steps is
/// never held in its answer's form at once).
#[derive(Clone, Debug)]
pub struct Steps {
    plan: Arc<Sequence>,
    holds: Option<Vec<bool>>,
    step_unit: f64,
    explain: bool,
}

impl Serialize for Steps {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let names = &self.plan.names;
        serializer.collect_seq(self.plan.steps.iter().enumerate().map(|(k, s)| {
            let holds = self.holds.as_ref().map(|h| h[k]);
            step_answer(names, s, self.step_unit, holds, self.explain)
        }))
    }
}

/// Where a plan's time went (seconds).
#[derive(Clone, Debug, Serialize)]
pub struct SequenceSeconds {
    /// The whole job, when the front end states it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub total: Option<f64>,
    /// Loading, when the front end loaded the assembly for this answer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load: Option<f64>,
    /// Making the pair regions (their sums, projections and unions), a part of `steps`.
    pub regions: f64,
    /// Finding the steps.
    pub steps: f64,
}

/// The answer of a sequence.
#[derive(Clone, Debug, Serialize)]
pub struct SequenceAnswer {
    /// "done", or why the run was cut short: `steps` are the steps found until then
    /// and `not_yet_split` the subassemblies still to split.
    pub status: String,
    /// What stopped the run, and where; absent when it ran to its end or the front end
    /// does not say.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<StopFacts>,
    /// Some subassembly is interlocked.
    pub interlocked: bool,
    /// Every part came apart: no subassembly interlocked, left whole or not yet split.
    pub complete: bool,
    /// The assembly has one part: there is nothing to separate (complete, no step).
    pub nothing_to_separate: bool,
    /// Part names.
    pub parts: Vec<String>,
    /// Every step (absent when a front end printed them before).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<Steps>,
    /// The number of steps (only where `steps` is absent).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step_count: Option<usize>,
    /// Subassemblies no single translation can split.
    pub stuck: Vec<Vec<String>>,
    /// Subassemblies left whole by the depth limit.
    pub unsplit: Vec<Vec<String>>,
    /// Subassemblies not yet split when the run was stopped (empty otherwise), in the
    /// order they would have been split.
    pub not_yet_split: Vec<Vec<String>>,
    /// With `first`: subassemblies that no likely direction split, searched in full;
    /// null otherwise (see `work`).
    pub full_searches: Option<usize>,
    /// How steps were chosen; null with `first`.
    pub ranking: Option<&'static str>,
    /// Pair regions made (lazily, as steps needed them); null with `first`.
    pub pair_regions: Option<usize>,
    /// The planner's work; null with `first`.
    pub work: Option<WorkAnswer>,
    /// Time.
    pub seconds: SequenceSeconds,
    /// What the answer holds under.
    #[serde(flatten)]
    pub input: InputFacts,
    /// The plan itself (for text and pictures).
    #[serde(skip)]
    pub plan: Arc<Sequence>,
}

impl SequenceAnswer {
    /// States the status a front end knows (why the run stopped); `complete` keeps its
    /// own meaning.
    pub fn set_status(&mut self, status: Status) {
        self.status = status.status;
        self.stopped = status.stopped;
    }

    /// Leaves the steps out of the answer (a front end printed them as they came),
    /// stating their number instead.
    pub fn without_steps(&mut self) {
        self.step_count = self.steps.take().map(|s| s.plan.steps.len());
    }
}

fn names_of(names: &[String], set: &[usize]) -> Vec<String> {
    set.iter().map(|&k| names[k].clone()).collect()
}

/// The name of a ranking.
pub fn ranking_key(r: Ranking) -> &'static str {
    match r {
        Ranking::Auto => "auto",
        Ranking::Full => "full",
        Ranking::Local => "local",
    }
}

/// Plans the disassembly of a loaded (valid) assembly. Each step is handed to
/// `on_step` with whether it holds without the tolerance as soon as it is found; a run
/// stopped by the flag of `progress` returns the steps found until then, with the
/// status "stopped".
pub fn sequence(
    loaded: &Loaded,
    units: Option<&str>,
    opts: &SequenceJobOptions,
    progress: &Progress,
    on_step: &mut dyn FnMut(&Step, Option<bool>),
) -> Result<SequenceAnswer, JobError> {
    let asm = &loaded.assembly;
    let names: Vec<String> = asm.parts.iter().map(|p| p.name.clone()).collect();
    let mut holds: Vec<Option<bool>> = Vec::new();
    let mut error = None;
    let mut each = |s: &Step| {
        let motion = [(
            s.moving.as_slice(),
            Some(s.subassembly.as_slice()),
            &s.direction,
        )];
        let h = match holds_without_tolerance(asm, &motion) {
            Ok(h) => h.map(|h| h[0]),
            Err(e) => {
                error.get_or_insert(e);
                None
            }
        };
        holds.push(h);
        on_step(s, h);
    };
    let plan = if names.len() < 2 {
        Sequence::empty(names)
    } else if opts.first {
        sequence_first_with(parts_of(asm)?, &opts.plan, progress, &mut each)?
    } else {
        sequence_parts(parts_of(asm)?, &opts.plan, progress, &mut each)?
    };
    if let Some(e) = error {
        return Err(e.into());
    }
    let holds: Option<Vec<bool>> = holds.into_iter().collect();
    let plan = Arc::new(plan);
    let sets = |s: &[Vec<usize>]| -> Vec<Vec<String>> {
        s.iter().map(|s| names_of(&plan.names, s)).collect()
    };
    let first = opts.first;
    Ok(SequenceAnswer {
        status: Status::of(plan.stopped).status,
        stopped: None,
        interlocked: !plan.stuck.is_empty(),
        complete: plan.complete(),
        nothing_to_separate: plan.names.len() < 2,
        parts: plan.names.clone(),
        steps: Some(Steps {
            plan: plan.clone(),
            holds,
            step_unit: asm.grid.step(),
            explain: opts.explain,
        }),
        step_count: None,
        stuck: sets(&plan.stuck),
        unsplit: sets(&plan.unsplit),
        not_yet_split: sets(&plan.pending),
        full_searches: first.then_some(plan.full_searches),
        ranking: (!first).then(|| ranking_key(opts.plan.ranking)),
        pair_regions: (!first).then(|| plan.regions.as_ref().map_or(0, |(n, _)| *n)),
        work: (!first).then(|| WorkAnswer::from(&plan.local)),
        seconds: SequenceSeconds {
            total: None,
            load: None,
            regions: region_seconds(&plan),
            steps: plan.step_seconds,
        },
        input: InputFacts::of(loaded, units),
        plan,
    })
}

/// The seconds spent making pair regions (their sums, projections and unions).
pub fn region_seconds(plan: &Sequence) -> f64 {
    plan.regions.as_ref().map_or(0.0, |(_, s)| {
        s.sums_seconds + s.projection_seconds + s.unions_seconds
    })
}
