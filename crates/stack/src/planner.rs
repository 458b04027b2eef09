//! The stacking planner (paper 004 §II): `n` identical parts, one at a time, each placed
//! by the placement engine with the cost of eq. (1) and accepted only if it is
//! interference-free, stable, grippable from above and can be lowered into place.
//!
//! Each part is placed in two stages (§II-B): first inside the stack's bounding box
//! grown by a small slack (room for a nested part), then anywhere in the floor region up
//! to the maximum height. Within a stage the engine yields interference-free candidates
//! in increasing cost over all orientations; the first one passing the checks is taken.

use crate::orientation::{orientations, Base, Orientation};
use crate::part::{PartModel, StackError};
use crate::partial::{
    Candidate, Cost, Moving, ObstacleCache, ObstacleStats, PlaceOptions, PlaceStats, Placer,
    Region, SupportFilter,
};
use crate::scene::Scene;
use crate::stability::{contacts, lowerable, placed_pieces, stable, top, up_face_area, Contact};
use apart_kernel::progress::{phases, Progress};
use apart_kernel::{rational, Aabb, Rational};
use apart_pieces::Polytope;
use rustc_hash::FxHashMap as HashMap;
use std::time::Instant;

/// Settings of a stacking plan.
#[derive(Clone, Debug)]
pub struct StackOptions {
    /// Number of parts.
    pub count: usize,
    /// Weight `w` of eq. (1): 0 minds only height, 1 only floor space.
    pub weight: Rational,
    /// Floor region `[x0, y0, x1, y1]`; its centre is eq. (1)'s `(x0, y0)`.
    pub floor: [Rational; 4],
    /// Height of the floor (eq. (1)'s `z0`).
    pub floor_z: Rational,
    /// Maximum height of the stack above the floor.
    pub max_height: Rational,
    /// Step of the orientations about z, in degrees (360 or more: no turn).
    pub dtheta_deg: f64,
    /// Base orientations (quarter turns about x and y) to try.
    pub bases: Vec<Base>,
    /// Largest accepted error of an exact rotation against its wanted angle, degrees.
    pub max_angle_error_deg: f64,
    /// Horizontal clearance between parts (robot positioning error).
    pub clearance: Option<Rational>,
    /// Smallest exposed upward face area for the suction gripper (must be positive).
    pub min_grip_area: Rational,
    /// Growth of the stack's bounding box in the first stage (default: a quarter of
    /// the part's smallest extent).
    pub slack: Option<Rational>,
    /// Candidates examined per stage before giving up.
    pub max_candidates: usize,
    /// Extrapolate obstacles inside constant-topology intervals.
    pub extrapolate: bool,
}

impl StackOptions {
    /// Defaults for `count` parts with weight `w` on a floor region.
    pub fn new(
        count: usize,
        weight: Rational,
        floor: [Rational; 4],
        max_height: Rational,
    ) -> StackOptions {
        StackOptions {
            count,
            weight,
            floor,
            floor_z: Rational::zero(),
            max_height,
            dtheta_deg: 90.0,
            bases: vec![Base::IDENTITY],
            max_angle_error_deg: 0.05,
            clearance: None,
            min_grip_area: Rational::zero(),
            slack: None,
            max_candidates: 500,
            extrapolate: true,
        }
    }
}

/// One placed part.
#[derive(Clone, Debug)]
pub struct Placed {
    /// Its index in the stack (placing order).
    pub index: usize,
    /// Index into the plan's orientations.
    pub orientation_index: usize,
    /// Its orientation.
    pub orientation: Orientation,
    /// Translation applied after turning the part's mesh about its origin.
    pub translation: [Rational; 3],
    /// Its term of eq. (1).
    pub cost: Rational,
    /// 1: inside the stack's (grown) bounding box; 2: anywhere.
    pub stage: u8,
    /// Contacts with the floor and earlier parts.
    pub contacts: Vec<Contact>,
    /// Candidates examined before this one was accepted (itself included).
    pub examined: usize,
}

/// Counters of a plan.
#[derive(Clone, Copy, Debug, Default)]
pub struct PlanStats {
    /// Placement engine counters, summed.
    pub place: PlaceStats,
    /// Obstacle construction counters.
    pub obstacles: ObstacleStats,
    /// Candidates rejected as unstable.
    pub unstable: usize,
    /// Candidates rejected because they cannot be lowered into place.
    pub not_lowerable: usize,
    /// Orientations kept (distinct, with a gripping face).
    pub orientations: usize,
    /// Seconds in stability checks.
    pub stability_seconds: f64,
    /// Seconds in lowering checks.
    pub lowering_seconds: f64,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// A stacking plan.
#[derive(Clone, Debug)]
pub struct StackPlan {
    /// The parts placed, in order.
    pub placements: Vec<Placed>,
    /// Height of the stack above the floor.
    pub stack_height: Rational,
    /// Every part was placed.
    pub complete: bool,
    /// The stop flag of a [`Progress`] ended the run before every part was placed or
    /// given up: `placements` are the parts placed until then (each checked as usual),
    /// and `complete` is false. Never set by [`stack`].
    pub stopped: bool,
    /// The part in its orientations.
    pub moving: Moving,
    /// The stack as fixed parts.
    pub scene: Scene,
    /// Counters.
    pub stats: PlanStats,
}

impl StackPlan {
    /// The pieces of placed part `k`, in place.
    pub fn pieces_of(&self, k: usize) -> Vec<Polytope> {
        let p = &self.placements[k];
        placed_pieces(
            &self.moving.oriented[p.orientation_index].pieces,
            &p.translation,
        )
    }

    /// The sum of the parts' costs (eq. (1)).
    pub fn total_cost(&self) -> Rational {
        self.placements
            .iter()
            .fold(Rational::zero(), |s, p| &s + &p.cost)
    }
}

fn add_stats(a: &mut PlaceStats, b: &PlaceStats) {
    a.orientations_considered += b.orientations_considered;
    a.pairs_total += b.pairs_total;
    a.pairs_evaluated += b.pairs_evaluated;
    a.interference_tests += b.interference_tests;
    a.detect_seconds += b.detect_seconds;
    a.cells_seconds += b.cells_seconds;
    a.cells += b.cells;
    a.qps += b.qps;
    a.split.0 += b.split.0;
    a.split.1 += b.split.1;
    a.subtractions.0 += b.subtractions.0;
    a.subtractions.1 += b.subtractions.1;
    a.candidates += b.candidates;
    a.unsupported += b.unsupported;
}

/// Plans a stack of `opts.count` copies of `part`.
pub fn stack(part: &PartModel, opts: &StackOptions) -> Result<StackPlan, StackError> {
    stack_with(part, opts, &Progress::new())
}

/// [`stack`], reporting the parts placed of `opts.count` ([`phases::STACKING`]) and
/// watching the stop flag before each part and each candidate examined. Stopped, it
/// returns the parts placed so far, with [`StackPlan::stopped`] set.
pub fn stack_with(
    part: &PartModel,
    opts: &StackOptions,
    progress: &Progress,
) -> Result<StackPlan, StackError> {
    plan(part, opts, progress, true)
}

/// [`stack_with`]; `prune` drops cells in which no position can be stable
/// ([`SupportFilter`]), which changes no answer (tests compare against `false`).
fn plan(
    part: &PartModel,
    opts: &StackOptions,
    progress: &Progress,
    prune: bool,
) -> Result<StackPlan, StackError> {
    let start = Instant::now();
    let (centre, sigma) = floor_box(opts)?;
    let moving = Moving::new(part.clone(), &grippable(part, opts)?, true);
    let slack = opts.slack.clone().unwrap_or_else(|| default_slack(&moving));
    let cost = Cost::Stacking {
        w: opts.weight.clone(),
        floor: centre,
    };
    cost.validate()?;
    let run = Run {
        opts,
        progress,
        prune,
        sigma,
        slack,
        cost,
        moving,
    };
    let mut stack = Stack {
        scene: Scene::new(),
        shapes: HashMap::default(),
        cache: ObstacleCache::new(),
        stats: PlanStats {
            orientations: run.moving.orientations.len(),
            ..Default::default()
        },
        placements: Vec::new(),
        stopped: false,
    };
    let mut complete = true;
    progress.report(phases::STACKING, 0, opts.count);
    for n in 0..opts.count {
        if progress.stopped() {
            stack.stopped = true;
            break;
        }
        let Some(accepted) = run.place_next(n, &mut stack)? else {
            complete = false;
            break;
        };
        stack.add(n, accepted, &run.moving);
        progress.report(phases::STACKING, n + 1, opts.count);
    }
    let Stack {
        scene,
        cache,
        mut stats,
        placements,
        stopped,
        ..
    } = stack;
    let height = (0..scene.pieces().len())
        .filter_map(|k| top(&[scene.placed(k)]))
        .max()
        .map(|t| &t - &opts.floor_z)
        .unwrap_or_else(Rational::zero);
    stats.obstacles = cache.stats;
    stats.seconds = start.elapsed().as_secs_f64();
    Ok(StackPlan {
        placements,
        stack_height: height,
        complete: complete && !stopped,
        stopped,
        moving: run.moving,
        scene,
        stats,
    })
}

/// The centre of the floor region (eq. (1)'s `(x0, y0, z0)`) and the box parts may
/// take: the floor region up to the maximum height. An error when either is empty.
fn floor_box(opts: &StackOptions) -> Result<([Rational; 3], Aabb<Rational>), StackError> {
    let [x0, y0, x1, y1] = opts.floor.clone();
    if x0 >= x1 || y0 >= y1 || opts.max_height <= Rational::zero() {
        return Err(StackError::Invalid(
            "the floor region or the maximum height is empty".into(),
        ));
    }
    let half = Rational::from_i128(1, 2);
    let centre = [
        &(&x0 + &x1) * &half,
        &(&y0 + &y1) * &half,
        opts.floor_z.clone(),
    ];
    let sigma = Aabb {
        min: [x0.clone(), y0.clone(), opts.floor_z.clone()],
        max: [x1.clone(), y1.clone(), &opts.floor_z + &opts.max_height],
    };
    Ok((centre, sigma))
}

/// The orientations of `opts` showing an upward face large enough for the suction
/// gripper (the area computed once per base orientation); an error when none does.
fn grippable(part: &PartModel, opts: &StackOptions) -> Result<Vec<Orientation>, StackError> {
    let all = orientations(opts.dtheta_deg, &opts.bases, opts.max_angle_error_deg);
    let mut grip: HashMap<Base, bool> = HashMap::default();
    let usable: Vec<Orientation> = all
        .into_iter()
        .filter(|o| {
            *grip.entry(o.base).or_insert_with(|| {
                let a = up_face_area(&part.base_pieces(o.base));
                a > Rational::zero() && a >= opts.min_grip_area
            })
        })
        .collect();
    if usable.is_empty() {
        return Err(StackError::Invalid(
            "no orientation shows an upward face large enough for the gripper".into(),
        ));
    }
    Ok(usable)
}

/// The first stage's default growth of the stack's box: a quarter of the part's
/// smallest extent (in its first orientation).
fn default_slack(moving: &Moving) -> Rational {
    let e = &moving.oriented[0].extent;
    let m = (0..3)
        .map(|i| &e.max[i] - &e.min[i])
        .min()
        .expect("three axes");
    &m * &Rational::from_i128(1, 4)
}

/// What stays the same while the parts are placed one after another.
struct Run<'a> {
    opts: &'a StackOptions,
    progress: &'a Progress,
    prune: bool,
    /// The box parts may take (floor region up to the maximum height).
    sigma: Aabb<Rational>,
    /// Growth of the stack's box in the first stage.
    slack: Rational,
    cost: Cost,
    moving: Moving,
}

/// The stack so far, and the counters of the plan.
struct Stack {
    scene: Scene,
    /// The scene's shape of each piece of each orientation, added once.
    shapes: HashMap<(usize, usize), usize>,
    cache: ObstacleCache,
    stats: PlanStats,
    placements: Vec<Placed>,
    /// The stop flag was seen.
    stopped: bool,
}

/// A candidate that passed the checks: its contacts, stage and the candidates examined
/// in that stage up to it.
struct Accepted {
    candidate: Candidate,
    contacts: Vec<Contact>,
    stage: u8,
    examined: usize,
}

impl Run<'_> {
    /// The first acceptable placement of part `n`: in the stack's grown box, then
    /// anywhere (the first part anywhere at once). `None` when neither stage finds one
    /// or the stop flag is raised.
    fn place_next(&self, n: usize, stack: &mut Stack) -> Result<Option<Accepted>, StackError> {
        let stages: &[u8] = if n == 0 { &[2] } else { &[1, 2] };
        for &stage in stages {
            let accepted = self.search_stage(stage, stack)?;
            if accepted.is_some() || stack.stopped {
                return Ok(accepted);
            }
        }
        Ok(None)
    }

    /// The region of a stage: the stack's box grown by the slack, within the floor box
    /// (stage 1), or the whole floor box (stage 2).
    fn stage_region(&self, stage: u8, scene: &Scene) -> Aabb<Rational> {
        if stage == 1 {
            let bb = scene.bbox().expect("a stack with parts");
            let (sigma, slack) = (&self.sigma, &self.slack);
            Aabb {
                min: [0, 1, 2].map(|i| (&bb.min[i] - slack).max(sigma.min[i].clone())),
                max: [0, 1, 2].map(|i| (&bb.max[i] + slack).min(sigma.max[i].clone())),
            }
        } else {
            self.sigma.clone()
        }
    }

    /// The engine's candidates of one stage, cheapest first, up to
    /// `max_candidates`: the first that passes the checks. Sets `stack.stopped` when the
    /// stop flag ends the search.
    fn search_stage(&self, stage: u8, stack: &mut Stack) -> Result<Option<Accepted>, StackError> {
        let popts = PlaceOptions {
            region: Region::Container(self.stage_region(stage, &stack.scene)),
            cost: self.cost.clone(),
            clearance: self.opts.clearance.clone(),
            extrapolate: self.opts.extrapolate,
        };
        let mut placer = Placer::new(&stack.scene, &self.moving, &mut stack.cache, &popts)?;
        if self.prune {
            placer = placer.with_support_filter(SupportFilter {
                floor_z: self.opts.floor_z.clone(),
            });
        }
        let mut accepted = None;
        let mut examined = 0;
        while examined < self.opts.max_candidates {
            if self.progress.stopped() {
                stack.stopped = true;
                break;
            }
            let Some(c) = placer.next_candidate()? else {
                break;
            };
            examined += 1;
            if let Some(contacts) = self.check(&c, &stack.scene, &mut stack.stats)? {
                accepted = Some(Accepted {
                    candidate: c,
                    contacts,
                    stage,
                    examined,
                });
                break;
            }
        }
        add_stats(&mut stack.stats.place, &placer.stats);
        Ok(accepted)
    }

    /// The contacts of candidate `c` when it is stable and can be lowered into place
    /// among the parts of `scene`; else `None`, counted in `stats` with the checks'
    /// times.
    fn check(
        &self,
        c: &Candidate,
        scene: &Scene,
        stats: &mut PlanStats,
    ) -> Result<Option<Vec<Contact>>, StackError> {
        let oriented = &self.moving.oriented[c.orientation];
        let placed = placed_pieces(&oriented.pieces, &c.translation);
        let t0 = Instant::now();
        let cts = contacts(&placed, &self.opts.floor_z, scene);
        let cg = rational::add(&oriented.centroid, &c.translation);
        let ok = stable(&cg, &cts);
        stats.stability_seconds += t0.elapsed().as_secs_f64();
        if !ok {
            stats.unstable += 1;
            return Ok(None);
        }
        let t0 = Instant::now();
        let ok = lowerable(&placed, scene)?;
        stats.lowering_seconds += t0.elapsed().as_secs_f64();
        if !ok {
            stats.not_lowerable += 1;
            return Ok(None);
        }
        Ok(Some(cts))
    }
}

impl Stack {
    /// Adds the accepted placement of part `n` to the scene (each piece shape once per
    /// orientation) and to the placements.
    fn add(&mut self, n: usize, a: Accepted, moving: &Moving) {
        let c = a.candidate;
        let o = c.orientation;
        let ids: Vec<usize> = (0..moving.oriented[o].pieces.len())
            .map(|b| {
                *self
                    .shapes
                    .entry((o, b))
                    .or_insert_with(|| self.scene.add_shape(moving.oriented[o].pieces[b].clone()))
            })
            .collect();
        self.scene.add_part(&ids, &c.translation);
        self.placements.push(Placed {
            index: n,
            orientation_index: o,
            orientation: moving.orientations[o],
            translation: c.translation,
            cost: c.cost,
            stage: a.stage,
            contacts: a.contacts,
            examined: a.examined,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{q, qfrac};

    fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        Polytope::cuboid(lo, hi).unwrap()
    }

    /// The support filter against the planner without it (every cell solved and split,
    /// every candidate checked for stability): on random channels, plates with a post and
    /// L shapes, stacked with random weights, both plans place the same parts at the same
    /// positions, and the filter never examines more candidates.
    #[test]
    fn support_filter_changes_no_plan() {
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = |m: u64| -> i64 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % m) as i64
        };
        let mut pruned_total = 0;
        for case in 0..24 {
            let (a, b, h) = (3 + next(5), 2 + next(4), 2 + next(3));
            let pieces = match case % 3 {
                0 => vec![
                    cuboid([0, 0, 0], [a, b, 1]),
                    cuboid([0, 0, 1], [1, b, h]),
                    cuboid([a - 1, 0, 1], [a, b, h]),
                ],
                1 => vec![
                    cuboid([0, 0, 0], [a, b, 1]),
                    cuboid([a / 2, b / 2, 1], [a / 2 + 1, b / 2 + 1, h]),
                ],
                _ => vec![cuboid([0, 0, 0], [a, 1, 1]), cuboid([0, 1, 0], [1, b, h])],
            };
            let part = PartModel::from_pieces("random", pieces).unwrap();
            let w = [qfrac(1, 2), q(0), qfrac(1, 4), q(1)][next(4) as usize].clone();
            let side = 2 * a.max(b) + next(4);
            let mut opts = StackOptions::new(
                4 + next(4) as usize,
                w,
                [q(-side), q(-side), q(side), q(side)],
                q(8 * h),
            );
            opts.max_candidates = 200;
            let with = plan(&part, &opts, &Progress::new(), true).unwrap();
            let without = plan(&part, &opts, &Progress::new(), false).unwrap();
            let key = |p: &StackPlan| {
                p.placements
                    .iter()
                    .map(|x| (x.orientation_index, x.translation.clone(), x.cost.clone()))
                    .collect::<Vec<_>>()
            };
            assert_eq!(key(&with), key(&without), "case {case}");
            assert_eq!(with.complete, without.complete);
            assert!(with.stats.unstable <= without.stats.unstable);
            pruned_total += with.stats.place.unsupported;
        }
        assert!(pruned_total > 0, "the filter never applied");
    }

    /// Extrapolated obstacles are the fresh ones: plans with and without extrapolation
    /// agree exactly (same cells, same pairs), at 30° and 15° steps, where templates
    /// apply.
    #[test]
    fn extrapolation_changes_no_plan() {
        let part = PartModel::from_pieces(
            "channel",
            vec![
                cuboid([0, 0, 0], [6, 3, 1]),
                cuboid([0, 0, 1], [1, 3, 3]),
                cuboid([5, 0, 1], [6, 3, 3]),
            ],
        )
        .unwrap();
        let mut extrapolated = 0;
        for step in [30.0, 15.0] {
            let mut opts = StackOptions::new(5, qfrac(1, 2), [q(-9), q(-9), q(9), q(9)], q(20));
            opts.dtheta_deg = step;
            let with = plan(&part, &opts, &Progress::new(), true).unwrap();
            opts.extrapolate = false;
            let without = plan(&part, &opts, &Progress::new(), true).unwrap();
            let key = |p: &StackPlan| {
                p.placements
                    .iter()
                    .map(|x| (x.orientation_index, x.translation.clone(), x.cost.clone()))
                    .collect::<Vec<_>>()
            };
            assert_eq!(key(&with), key(&without), "step {step}");
            assert_eq!(with.stats.place.cells, without.stats.place.cells);
            assert_eq!(
                with.stats.obstacles.extrapolated + with.stats.obstacles.fresh,
                without.stats.obstacles.fresh
            );
            extrapolated += with.stats.obstacles.extrapolated;
        }
        assert!(extrapolated > 0, "no obstacle was extrapolated");
    }
}
