//! Where the parts are after each step of a disassembly, as keyframes that the animated
//! exports play: a step of a [`Sequence`] moves its moving side out along its direction
//! by one fixed distance; a finite move of a [`MovePlan`] translates its moving parts by
//! exactly its translation, and its moves to infinity move their side out by the fixed
//! distance. Parts stay where earlier steps left them.

use apart_kernel::fvec::{add, scale};
use apart_plan::{MovePlan, Sequence};

/// How the disassembly is played in the animated exports.
#[derive(Clone, Debug, PartialEq)]
pub struct AnimationOptions {
    /// Each step moves its side by this many times the assembly's bounding-box diagonal.
    pub distance_factor: f64,
    /// Seconds a step's motion lasts.
    pub step_seconds: f64,
    /// Seconds of rest after each step.
    pub pause_seconds: f64,
}

impl Default for AnimationOptions {
    fn default() -> Self {
        AnimationOptions {
            distance_factor: 1.5,
            step_seconds: 1.0,
            pause_seconds: 0.5,
        }
    }
}

/// The motion of a plan: the parts each step moves, and the offset of every part from
/// its assembled pose (input units) before the first step and after each step.
#[derive(Clone, Debug, PartialEq)]
pub struct Keyframes {
    /// The parts step `k` moves.
    pub moving: Vec<Vec<usize>>,
    /// `offsets[k][p]`: part `p`'s offset after the first `k` steps (`offsets[0]` is
    /// all zero; one more entry than steps).
    pub offsets: Vec<Vec<[f64; 3]>>,
}

impl Keyframes {
    /// The steps of `sequence` for `parts` parts, each moving its side by `distance`
    /// along its direction.
    pub fn of_sequence(sequence: &Sequence, parts: usize, distance: f64) -> Keyframes {
        let mut frames = Keyframes::start(parts);
        for step in &sequence.steps {
            let d = scale(step.unit, distance);
            let mut next = frames.last().to_vec();
            for &k in step.moving.iter().filter(|&&k| k < parts) {
                next[k] = add(next[k], d);
            }
            frames.push(step.moving.clone(), next);
        }
        frames
    }

    /// The moves of `plan` for `parts` parts: a finite move puts its subassembly's
    /// parts at the plan's exact offsets (grid units times `grid_step`), a move to
    /// infinity moves its side by `distance` along its direction; a part's offset is
    /// its exact offset plus the moves to infinity that took it along.
    pub fn of_moves(plan: &MovePlan, parts: usize, grid_step: f64, distance: f64) -> Keyframes {
        let mut frames = Keyframes::start(parts);
        let mut exact = vec![[0.0; 3]; parts];
        let mut out = vec![[0.0; 3]; parts];
        for mv in &plan.moves {
            match mv.distance {
                Some(_) => {
                    for (k, o) in mv.offsets.iter().filter(|(k, _)| *k < parts) {
                        exact[*k] = o.clone().map(|c| c.to_f64() * grid_step);
                    }
                }
                None => {
                    let d = scale(mv.unit, distance);
                    for &k in mv.moving.iter().filter(|&&k| k < parts) {
                        out[k] = add(out[k], d);
                    }
                }
            }
            let next = (0..parts).map(|k| add(exact[k], out[k])).collect();
            frames.push(mv.moving.clone(), next);
        }
        frames
    }

    /// Every part in place, no step yet.
    fn start(parts: usize) -> Keyframes {
        Keyframes {
            moving: Vec::new(),
            offsets: vec![vec![[0.0; 3]; parts]],
        }
    }

    /// The offsets after the last step.
    fn last(&self) -> &[[f64; 3]] {
        self.offsets.last().expect("the start frame")
    }

    /// Appends a step.
    fn push(&mut self, moving: Vec<usize>, offsets: Vec<[f64; 3]>) {
        self.moving.push(moving);
        self.offsets.push(offsets);
    }

    /// The number of steps.
    pub fn steps(&self) -> usize {
        self.moving.len()
    }
}
