//! Where the parts are after each step of a disassembly: every step moves its moving
//! side out along its direction by one fixed distance, and parts stay where earlier
//! steps left them, so a part's offset is the sum of the displacements of the steps
//! that moved it.

use apart_kernel::fvec::{add, scale};
use apart_plan::Sequence;

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

/// The displacement vector of every step (unit direction × `distance`).
pub fn step_displacements(sequence: &Sequence, distance: f64) -> Vec<[f64; 3]> {
    sequence
        .steps
        .iter()
        .map(|s| scale(s.unit, distance))
        .collect()
}

/// The offset of every part after the first `done` steps.
pub fn offsets_after(
    sequence: &Sequence,
    displacements: &[[f64; 3]],
    parts: usize,
    done: usize,
) -> Vec<[f64; 3]> {
    let mut offsets = vec![[0.0; 3]; parts];
    for (step, d) in sequence.steps.iter().zip(displacements).take(done) {
        for &k in &step.moving {
            if k < parts {
                offsets[k] = add(offsets[k], *d);
            }
        }
    }
    offsets
}
