//! Disassembly by several moves: finite translations before the first move to
//! infinity, exact and off the grid, with the puzzle's level.

use crate::{InputFacts, JobError, Progress, Status, StopFacts};
use apart_assembly::Loaded;
use apart_kernel::Rational;
use apart_plan::{disassemble as plan_moves, parts_of, MoveOptions, MovePlan, SearchEnd};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::Arc;

/// One move of the plan.
#[derive(Clone, Debug, Serialize)]
pub struct MoveAnswer {
    /// The subassembly it works on.
    pub subassembly: Vec<String>,
    /// The parts that move.
    pub moving: Vec<String>,
    /// The direction as a unit vector.
    pub direction: [f64; 3],
    /// The direction as primitive integers.
    pub exact_direction: [String; 3],
    /// The translation is `distance × exact_direction` in input units: an exact
    /// rational, or "infinity".
    pub distance: String,
    /// The length of the translation in input units (null for infinity).
    pub length: Option<f64>,
    /// Offsets of the subassembly's parts from their assembled pose after the move,
    /// input units (moves to infinity not counted).
    pub positions: BTreeMap<String, [f64; 3]>,
    /// The same, exactly.
    pub exact_positions: BTreeMap<String, [String; 3]>,
}

/// One subassembly's search.
#[derive(Clone, Debug, Serialize)]
pub struct SearchAnswer {
    /// Its parts.
    pub subassembly: Vec<String>,
    /// Moves to its first move to infinity, when found.
    pub level: Option<usize>,
    /// States explored.
    pub states: usize,
    /// "separated", "interlocked" (every reachable state explored), "move limit"
    /// (every state within it explored), "state limit" or "stopped".
    pub end: &'static str,
}

/// Where the time went (seconds).
#[derive(Clone, Debug, Serialize)]
pub struct DisassembleSeconds {
    /// The whole job, when the front end states it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub total: Option<f64>,
    /// Loading, when the front end loaded the assembly for this answer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load: Option<f64>,
    /// Making the c-space obstacles of every pair of parts.
    pub obstacles: f64,
    /// Searching.
    pub search: f64,
}

/// The planner's work.
#[derive(Clone, Debug, Serialize)]
pub struct DisassembleStats {
    /// Subassemblies searched.
    pub searches: usize,
    /// Moves in the plan.
    pub moves: usize,
    /// Moves of a finite distance.
    pub finite_moves: usize,
    /// Time.
    pub seconds: DisassembleSeconds,
}

/// The answer of a disassembly by moves.
#[derive(Clone, Debug, Serialize)]
pub struct DisassembleAnswer {
    /// "done", or why the run was cut short.
    pub status: String,
    /// What stopped the run; absent when it ran to its end or the front end does not say.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<StopFacts>,
    /// Moves up to and including the first move to infinity (null: not separated).
    pub level: Option<usize>,
    /// Every part came apart.
    pub complete: bool,
    /// When not complete: why, and whether the search was exhaustive.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdict: Option<String>,
    /// The move model: "axes" or "free cone" (see the documentation).
    pub model: &'static str,
    /// Part names.
    pub parts: Vec<String>,
    /// Every move, subassembly after subassembly.
    pub moves: Vec<MoveAnswer>,
    /// Every subassembly's search.
    pub searches: Vec<SearchAnswer>,
    /// States explored over all searches.
    pub states_explored: usize,
    /// The planner's work and time.
    pub stats: DisassembleStats,
    /// What the answer holds under.
    #[serde(flatten)]
    pub input: InputFacts,
    /// The plan itself (for text and pictures).
    #[serde(skip)]
    pub plan: Arc<MovePlan>,
}

impl DisassembleAnswer {
    /// States the status a front end knows (why the run stopped).
    pub fn set_status(&mut self, status: Status) {
        self.status = status.status;
        self.stopped = status.stopped;
    }
}

/// A grid quantity in input units (`q × 2^exp`), exactly.
fn units(q: &Rational, exp: i32) -> Rational {
    q * &Rational::pow2(exp)
}

/// Why a plan is not complete, in words.
pub fn verdict(plan: &MovePlan, opts: &MoveOptions) -> Option<String> {
    let names = |s: &[usize]| -> String {
        let v: Vec<&str> = s.iter().map(|&k| plan.names[k].as_str()).collect();
        format!("{{{}}}", v.join(", "))
    };
    let s = plan
        .searches
        .iter()
        .find(|s| s.end != SearchEnd::Separated)?;
    let what = names(&s.subassembly);
    Some(match s.end {
        SearchEnd::Separated => unreachable!(),
        SearchEnd::Interlocked => format!(
            "no plan exists for {what}: every reachable state was explored ({} states), exhaustively",
            s.states
        ),
        SearchEnd::MoveLimit => format!(
            "no plan with at most {} moves exists for {what} (every state within the limit explored, {} states)",
            opts.max_moves, s.states
        ),
        SearchEnd::StateLimit => format!(
            "cut off for {what} by the state limit ({} states): a plan may exist",
            opts.max_states
        ),
        SearchEnd::Stopped => {
            format!("cut off for {what} after {} states: a plan may exist", s.states)
        }
    })
}

/// Plans the disassembly of a loaded (valid) assembly by moves.
pub fn disassemble(
    loaded: &Loaded,
    units_name: Option<&str>,
    opts: &MoveOptions,
    progress: &Progress,
) -> Result<DisassembleAnswer, JobError> {
    let asm = &loaded.assembly;
    let plan = plan_moves(parts_of(asm)?, opts, progress)?;
    let exp = asm.grid.exp;
    let names = &plan.names;
    let name_list = |s: &[usize]| -> Vec<String> { s.iter().map(|&k| names[k].clone()).collect() };
    let moves: Vec<MoveAnswer> = plan
        .moves
        .iter()
        .map(|m| {
            let distance = m.distance.as_ref().map(|t| units(t, exp));
            let length = distance.as_ref().map(|t| {
                let d = m.direction.approx();
                t.to_f64() * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
            });
            let exact: Vec<(String, [Rational; 3])> = m
                .offsets
                .iter()
                .map(|(g, p)| (names[*g].clone(), p.clone().map(|c| units(&c, exp))))
                .collect();
            MoveAnswer {
                subassembly: name_list(&m.subassembly),
                moving: name_list(&m.moving),
                direction: m.unit,
                exact_direction: m.direction.to_strings(),
                distance: distance.map_or("infinity".into(), |t| t.to_string()),
                length,
                positions: exact
                    .iter()
                    .map(|(n, p)| (n.clone(), p.clone().map(|c| c.to_f64())))
                    .collect(),
                exact_positions: exact
                    .iter()
                    .map(|(n, p)| (n.clone(), p.clone().map(|c| c.to_string())))
                    .collect(),
            }
        })
        .collect();
    let searches = plan
        .searches
        .iter()
        .map(|s| SearchAnswer {
            subassembly: name_list(&s.subassembly),
            level: s.moves,
            states: s.states,
            end: s.end.name(),
        })
        .collect();
    let finite = plan.moves.iter().filter(|m| m.distance.is_some()).count();
    Ok(DisassembleAnswer {
        status: Status::of(plan.stopped).status,
        stopped: None,
        level: plan.level,
        complete: plan.complete,
        verdict: verdict(&plan, opts),
        model: if opts.axes { "axes" } else { "free cone" },
        parts: names.clone(),
        searches,
        states_explored: plan.states_explored,
        stats: DisassembleStats {
            searches: plan.searches.len(),
            moves: moves.len(),
            finite_moves: finite,
            seconds: DisassembleSeconds {
                total: None,
                load: None,
                obstacles: plan.obstacle_seconds,
                search: plan.search_seconds,
            },
        },
        moves,
        input: InputFacts::of(loaded, units_name),
        plan: Arc::new(plan),
    })
}
