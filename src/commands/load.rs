//! Loading an assembly for a command: progress bar, and the validity gate of the
//! planning commands.

use crate::output;
use crate::Global;
use apart::assembly::{load, Decompose, LoadOptions, Loaded};
use std::path::Path;

/// Loads `path` with the global options, a progress bar on a terminal, and the given
/// decomposition policy.
pub fn load_with(path: &Path, global: &Global, decompose: Decompose) -> anyhow::Result<Loaded> {
    let bar = output::progress(global);
    let opts = LoadOptions {
        grid_bits: global.grid_bits,
        progress: bar.as_ref().map(|(_, hook)| hook.clone()),
        decompose,
        verify: global.verify,
    };
    let loaded = load(path, &opts);
    if let Some((bar, _)) = &bar {
        bar.finish_and_clear();
    }
    Ok(loaded?)
}

/// Loads an assembly for planning (every non-convex part decomposed); when it has
/// errors, prints every problem on standard error and fails naming how many.
pub fn load_valid(path: &Path, global: &Global) -> anyhow::Result<Loaded> {
    let loaded = load_with(path, global, Decompose::Always)?;
    if !loaded.is_valid() {
        let errors: Vec<_> = loaded.problems.iter().filter(|p| p.is_error()).collect();
        for p in &errors {
            output::eline(p);
        }
        anyhow::bail!(
            "{} is not a valid assembly ({} error{}); run `apart check` for the details",
            path.display(),
            errors.len(),
            if errors.len() == 1 { "" } else { "s" }
        );
    }
    for p in loaded
        .problems
        .iter()
        .filter(|p| p.severity == apart::mesh::Severity::Warning)
    {
        if !global.quiet {
            output::eline(p);
        }
    }
    Ok(loaded)
}
