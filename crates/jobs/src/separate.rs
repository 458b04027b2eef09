//! Separation of two parts: every direction along which one leaves the other, as exact
//! spherical regions, sliding arcs and isolated directions.

use crate::{InputFacts, JobError, Progress};
use apart_assembly::Loaded;
use apart_plan::along::holds_without_tolerance;
use apart_plan::{parts_of, separate as separate_parts, BlockingRegions, PlanError, Separation};
use apart_sphere::Arc;
use serde::Serialize;

/// An arc of a great circle, exactly.
#[derive(Clone, Debug, Serialize)]
pub struct ArcAnswer {
    /// The normal of its circle.
    pub normal: [String; 3],
    /// Its start.
    pub start: [String; 3],
    /// Its end.
    pub end: [String; 3],
}

impl ArcAnswer {
    /// The arc's exact coordinates.
    pub fn of(a: &Arc) -> ArcAnswer {
        ArcAnswer {
            normal: a.normal.to_strings(),
            start: a.start.to_strings(),
            end: a.end.to_strings(),
        }
    }
}

/// A region of separating directions.
#[derive(Clone, Debug, Serialize)]
pub struct RegionAnswer {
    /// Its area, as a fraction of the sphere.
    pub area_fraction: f64,
    /// Its deepest direction as a unit vector.
    pub direction: [f64; 3],
    /// The same, exactly.
    pub exact_direction: [String; 3],
    /// The clearance of that direction.
    pub clearance_deg: f64,
    /// Its boundary loops.
    pub loops: Vec<Vec<ArcAnswer>>,
}

/// The direction of largest clearance.
#[derive(Clone, Debug, Serialize)]
pub struct BestAnswer {
    /// As a unit vector.
    pub direction: [f64; 3],
    /// Exactly.
    pub exact_direction: [String; 3],
    /// Its clearance.
    pub clearance_deg: f64,
    /// Under a tolerance: this direction also separates the parts as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub holds_without_tolerance: Option<bool>,
}

/// The answer of a separation.
#[derive(Clone, Debug, Serialize)]
pub struct SeparateAnswer {
    /// The part that moves.
    pub moving: String,
    /// The part that stays.
    pub fixed: String,
    /// Some direction separates them.
    pub separable: bool,
    /// The separating directions' area, as a fraction of the sphere.
    pub area_fraction: f64,
    /// The direction of largest clearance.
    pub best: Option<BestAnswer>,
    /// The regions of separating directions.
    pub regions: Vec<RegionAnswer>,
    /// Sliding arcs.
    pub sliding: Vec<ArcAnswer>,
    /// Isolated directions.
    pub isolated: Vec<[String; 3]>,
    /// What the answer holds under.
    #[serde(flatten)]
    pub input: InputFacts,
    /// The separation itself (for text and pictures).
    #[serde(skip)]
    pub separation: Separation,
}

/// Every direction along which part `a` leaves part `b` of a loaded (valid) assembly;
/// `None` when the stop flag of `progress` ended the run first.
pub fn separate(
    loaded: &Loaded,
    units: Option<&str>,
    a: usize,
    b: usize,
    progress: &Progress,
) -> Result<Option<SeparateAnswer>, JobError> {
    let asm = &loaded.assembly;
    let regions = match BlockingRegions::compute_with(parts_of(asm)?, progress) {
        Ok(r) => r,
        Err(PlanError::Stopped { .. }) => return Ok(None),
        Err(e) => return Err(e.into()),
    };
    let s = separate_parts(&regions, a, b);
    let separable = !(s.faces.is_empty() && s.sliding.is_empty() && s.isolated.is_empty());
    let best = s.best();
    let pair = [a, b];
    let holds = match &best {
        Some((d, _)) => holds_without_tolerance(asm, &[(&[a], Some(&pair), d)])?.map(|h| h[0]),
        None => None,
    };
    Ok(Some(SeparateAnswer {
        moving: asm.parts[a].name.clone(),
        fixed: asm.parts[b].name.clone(),
        separable,
        area_fraction: s.area_fraction(),
        best: best.map(|(d, c)| BestAnswer {
            direction: d.unit_f64(),
            exact_direction: d.to_strings(),
            clearance_deg: c,
            holds_without_tolerance: holds,
        }),
        regions: s
            .faces
            .iter()
            .map(|f| RegionAnswer {
                area_fraction: f.area / (4.0 * std::f64::consts::PI),
                direction: f.direction.unit_f64(),
                exact_direction: f.direction.to_strings(),
                clearance_deg: f.clearance_deg,
                loops: f
                    .loops
                    .iter()
                    .map(|lp| lp.iter().map(ArcAnswer::of).collect())
                    .collect(),
            })
            .collect(),
        sliding: s.sliding.iter().map(ArcAnswer::of).collect(),
        isolated: s.isolated.iter().map(|d| d.to_strings()).collect(),
        input: InputFacts::of(loaded, units),
        separation: s,
    }))
}
