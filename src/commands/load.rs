//! Loading an assembly for a command: progress bar, and the validity gate of the
//! planning commands.

use crate::output;
use crate::Global;
use apart::assembly::{load, Decompose, LoadOptions, Loaded};
use std::path::Path;

/// Loads `path` with the global options, a progress bar on a terminal, and the given
/// decomposition policy.
pub fn load_with(path: &Path, global: &Global, decompose: Decompose) -> anyhow::Result<Loaded> {
    let (bar, hook) = output::progress(global);
    // The loader's other options keep their defaults (also any added later).
    #[allow(clippy::needless_update)]
    let opts = LoadOptions {
        grid_bits: global.grid_bits,
        progress: Some(hook),
        decompose,
        verify: global.verify,
        tolerance: crate::input_facts::tolerance(global)?,
        repair: !global.strict,
        split_bodies: !global.one_part_per_file,
        allow_outside: global.allow_outside,
        ..LoadOptions::default()
    };
    let loaded = load(path, &opts);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    Ok(loaded?)
}

/// Loads an assembly for planning (every non-convex part decomposed); when it has
/// errors, prints every problem on standard error and fails naming how many.
pub fn load_valid(path: &Path, global: &Global) -> anyhow::Result<Loaded> {
    load_valid_but(path, global, None)
}

/// [`load_valid`], except that overlaps of the part named `free` with other parts are
/// allowed (a part about to be placed may start where others are).
pub fn load_valid_but(path: &Path, global: &Global, free: Option<&str>) -> anyhow::Result<Loaded> {
    let loaded = load_with(path, global, Decompose::Always)?;
    let excused = |p: &apart::mesh::Problem| {
        free.is_some_and(|n| {
            let with = format!("overlaps part \"{n}\"");
            p.message.starts_with(&with)
                || (p.part.as_deref() == Some(n) && p.message.starts_with("overlaps part \""))
        })
    };
    let errors: Vec<_> = loaded
        .problems
        .iter()
        .filter(|p| p.is_error() && !excused(p))
        .collect();
    if !errors.is_empty() {
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

/// The global options for loading a [`files_manifest`]: the files were named on the
/// command line, so they may lie outside the manifest's temporary folder.
pub fn for_named_files(global: &Global) -> Global {
    Global {
        allow_outside: true,
        ..global.clone()
    }
}

/// A temporary manifest naming mesh files as parts of one assembly (so that they are
/// snapped to one grid), with the part names (file stems, made unique) and a guard that
/// removes the manifest's folder when dropped. Load it with [`for_named_files`].
pub fn files_manifest(
    files: &[&String],
    tag: &str,
) -> anyhow::Result<(std::path::PathBuf, Vec<String>, TempDir)> {
    let dir = std::env::temp_dir().join(format!("apart-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let guard = TempDir(dir.clone());
    let mut names: Vec<String> = Vec::new();
    let mut parts = Vec::new();
    for (k, f) in files.iter().enumerate() {
        let abs = std::fs::canonicalize(f).map_err(|e| anyhow::anyhow!("cannot read {f}: {e}"))?;
        let mut name = Path::new(f.as_str())
            .file_stem()
            .map_or(format!("part{}", k + 1), |s| {
                s.to_string_lossy().into_owned()
            });
        while names.contains(&name) {
            name.push_str("_2");
        }
        parts.push(serde_json::json!({"name": name, "mesh": abs}));
        names.push(name);
    }
    let manifest = serde_json::json!({"name": names.join(" and "), "parts": parts});
    let file = dir.join("assembly.json");
    std::fs::write(&file, serde_json::to_string(&manifest)?)?;
    Ok((file, names, guard))
}

/// A temporary folder, removed when dropped.
pub struct TempDir(std::path::PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
