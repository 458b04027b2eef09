//! Pictures of an assembly's answers, drawn by apart-draw exactly as the command line
//! draws them (`apart partition --svg/--png`; the sequence's GLB and HTML are
//! [`crate::Plan`]'s), so that the files are byte for byte the command line's.

use apart_assembly::Loaded;
use apart_draw::{motion_space_png, motion_space_svg, SphereProjection, SphereSvgOptions};
use apart_plan::progress::Progress;
use apart_plan::{
    partition_subset_with, parts_of, BlockingRegions, MotionSpace, Options, PlanError,
};

/// The motion-space sphere of `apart partition --svg` (or `--png`) with every solution
/// marked; `None` when the stop flag ended the planning first.
pub fn motion_space(
    loaded: &Loaded,
    svg: bool,
    orthographic: bool,
    progress: &Progress,
) -> Result<Option<Vec<u8>>, PlanError> {
    let asm = &loaded.assembly;
    let parts = parts_of(asm)?;
    let regions = match BlockingRegions::compute_with(parts, progress) {
        Ok(r) => r,
        Err(PlanError::Stopped { .. }) => return Ok(None),
        Err(e) => return Err(e),
    };
    let all: Vec<usize> = (0..parts.len()).collect();
    // A motion space over what the memory budget leaves is not built (the refusal is
    // noted by the budget's keeper: the call raises apart.OutOfMemoryBudget).
    let estimate = MotionSpace::estimate(&regions, &all);
    if !progress.affordable(apart_plan::progress::phases::MOTION_SPACE, estimate.bytes) {
        return Ok(None);
    }
    let (p, _) = partition_subset_with(&regions, &all, &Options::default(), progress);
    if p.stopped {
        return Ok(None);
    }
    let opts = SphereSvgOptions {
        title: format!("{}: motion space", asm.name),
        projection: if orthographic {
            SphereProjection::Orthographic
        } else {
            SphereProjection::EqualArea
        },
        ..Default::default()
    };
    // One motion space cut at the equator, with the solutions planned above (as the
    // command line draws it).
    let ms = MotionSpace::build_split_at_equator(&regions, &all);
    let names = regions.names();
    Ok(Some(if svg {
        motion_space_svg(&ms, names, &p.solutions, &opts).into_bytes()
    } else {
        motion_space_png(&ms, names, &p.solutions, &opts)
    }))
}
