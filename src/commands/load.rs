//! Loading an assembly for a command: progress bar, and the validity gate of the
//! planning commands.

use crate::output;
use crate::Global;
use apart::assembly::{
    load, load_description, Assembly, Decompose, DescribedPart, Description, LoadOptions, Loaded,
    MeshSource,
};
use apart::formats::escape::{escape, path as escaped};
use std::path::{Path, PathBuf};

/// What a command loads: an assembly by its path, or mesh files named on the command
/// line.
#[derive(Clone, Copy)]
enum Input<'a> {
    Path(&'a Path),
    Named(&'a NamedFiles),
}

/// Loads `path` with the global options, a progress bar on a terminal, and the given
/// decomposition policy.
pub fn load_with(path: &Path, global: &Global, decompose: Decompose) -> anyhow::Result<Loaded> {
    load_input(Input::Path(path), global, decompose)
}

/// Loads `input` as [`load_with`] does.
fn load_input(input: Input, global: &Global, decompose: Decompose) -> anyhow::Result<Loaded> {
    // A STEP file is read (tessellated) by the Python package first, before the bar.
    let step = match input {
        Input::Path(path) if crate::step::is_step(path) => {
            crate::limits::set_phase("reading the STEP file");
            Some(crate::step::description(path, global)?)
        }
        _ => {
            crate::step::no_tessellation(global)?;
            None
        }
    };
    let (bar, progress) = output::progress(global);
    // The loader's other options keep their defaults (also any added later).
    #[allow(clippy::needless_update)]
    let opts = LoadOptions {
        grid_bits: global.grid_bits,
        progress,
        decompose,
        verify: global.verify,
        tolerance: crate::input_facts::tolerance(global)?,
        repair: !global.strict,
        split_bodies: !global.one_part_per_file,
        allow_outside: global.allow_outside,
        ..LoadOptions::default()
    };
    let loaded = match (input, step) {
        (_, Some(description)) => load_description(description, &opts),
        (Input::Path(path), None) => load(path, &opts),
        (Input::Named(named), None) => load_description(named.description.clone(), &opts),
    };
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let loaded = loaded?;
    // Files the user may have expected to be parts (printed also with --quiet, which
    // keeps warnings).
    for s in &loaded.skipped {
        output::eline(format_args!(
            "warning: {}: not read: {}",
            escaped(&s.path),
            s.reason
        ));
    }
    warn_many_pieces(&loaded);
    Ok(loaded)
}

/// From this many convex pieces, an automatic decomposition is worth a warning.
pub const MANY_PIECES: usize = 200;

/// Warns about every part whose automatic convex decomposition gave
/// [`MANY_PIECES`] pieces or more: planning pairs every piece of a part with every
/// piece of a part it may touch, so its time and memory grow with the product of the
/// two piece counts, and such a run can take minutes to hours without being stuck.
/// Printed also with `--quiet`, which keeps warnings.
fn warn_many_pieces(loaded: &Loaded) {
    let many: Vec<_> = loaded
        .assembly
        .parts
        .iter()
        .filter(|p| p.decomposed && p.pieces.len() >= MANY_PIECES)
        .collect();
    let Some(largest) = many.iter().map(|p| p.pieces.len()).max() else {
        return;
    };
    for p in &many {
        output::eline(format_args!(
            "warning: part \"{}\": its automatic convex decomposition has {} pieces",
            p.name,
            p.pieces.len()
        ));
    }
    let pairs = largest.saturating_mul(largest);
    output::eline(format_args!(
        "  planning time and memory grow with the product of two parts' piece counts \
         (up to {largest} x {largest} = {pairs} piece pairs here), so a run may take \
         minutes or more; a coarser mesh of the part, or convex pieces given with it \
         (README, Input formats), makes it faster"
    ));
}

/// Loads an assembly for planning (every non-convex part decomposed); when it has
/// errors, prints every problem on standard error and fails naming how many.
pub fn load_valid(path: &Path, global: &Global) -> anyhow::Result<Loaded> {
    load_valid_but(path, global, None)
}

/// [`load_valid`], except that overlaps of the part named `free` with other parts are
/// allowed (a part about to be placed may start where others are).
pub fn load_valid_but(path: &Path, global: &Global, free: Option<&str>) -> anyhow::Result<Loaded> {
    valid_but(Input::Path(path), global, free)
}

/// [`load_valid_but`] for mesh files named on the command line.
pub fn load_valid_named(
    named: &NamedFiles,
    global: &Global,
    free: Option<&str>,
) -> anyhow::Result<Loaded> {
    valid_but(Input::Named(named), global, free)
}

/// [`load_valid_but`] of either input.
fn valid_but(input: Input, global: &Global, free: Option<&str>) -> anyhow::Result<Loaded> {
    let loaded = load_input(input, global, Decompose::Always)?;
    let errors = apart::jobs::gate::errors(&loaded, free);
    if !errors.is_empty() {
        for p in &errors {
            output::eline(p);
        }
        let count = format!(
            "{} error{}",
            errors.len(),
            if errors.len() == 1 { "" } else { "s" }
        );
        let message = match input {
            // No single path to `apart check`: the errors above are all there is.
            Input::Named(named) => format!(
                "{} do not make a valid assembly ({count} above)",
                named.given.join(" and ")
            ),
            Input::Path(path) => format!(
                "{} is not a valid assembly ({count}); run `apart check {}` for the details",
                escaped(path),
                escaped(path)
            ),
        };
        let problems = errors.into_iter().cloned().collect();
        return Err(anyhow::Error::new(crate::output::Invalid {
            message,
            problems,
        }));
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

/// Mesh files named on the command line as the parts of one assembly (so that they
/// are snapped to one grid): each file one part, named by its stem (made unique), read
/// wherever it lies and named in messages as given.
pub struct NamedFiles {
    /// The files as given, escaped for messages, in order.
    given: Vec<String>,
    /// The part names, in order.
    names: Vec<String>,
    /// The assembly to load.
    description: Description,
}

impl NamedFiles {
    /// The part names, one per file, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }
}

/// The mesh files `files`, each to be loaded as one part with [`load_valid_named`]; an
/// error when one is a folder or cannot be found.
pub fn named_files(files: &[&String]) -> anyhow::Result<NamedFiles> {
    for f in files {
        match std::fs::metadata(f.as_str()) {
            Ok(m) if m.is_dir() => anyhow::bail!(
                "{}: is a folder; give two mesh files, or an assembly and two part names",
                escape(f)
            ),
            Ok(_) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                anyhow::bail!("{}: no such file", escape(f))
            }
            Err(e) => anyhow::bail!("cannot read {}: {e}", escape(f)),
        }
    }
    let mut names: Vec<String> = Vec::new();
    let mut parts = Vec::new();
    for (k, f) in files.iter().enumerate() {
        let mut name = Path::new(f.as_str())
            .file_stem()
            .map_or(format!("part{}", k + 1), |s| {
                s.to_string_lossy().into_owned()
            });
        while names.contains(&name) {
            name.push_str("_2");
        }
        parts.push(DescribedPart::new(
            name.clone(),
            MeshSource::File(PathBuf::from(f.as_str())),
        ));
        names.push(name);
    }
    Ok(NamedFiles {
        given: files.iter().map(|f| escape(f)).collect(),
        description: Description {
            name: names.join(" and "),
            parts,
        },
        names,
    })
}

/// The index of the part named `name`, or an error that names the closest part names
/// (all of them when there are at most [`LIST_ALL`]). `what` says where the name was
/// given ("--base"; empty for a positional argument).
pub fn part_index(asm: &Assembly, name: &str, what: &str) -> anyhow::Result<usize> {
    if let Some(k) = asm.parts.iter().position(|p| p.name == name) {
        return Ok(k);
    }
    let names: Vec<&str> = asm.parts.iter().map(|p| p.name.as_str()).collect();
    anyhow::bail!(
        "{what}{}the assembly \"{}\" has no part named \"{}\"{}",
        if what.is_empty() { "" } else { ": " },
        escape(&asm.name),
        escape(name),
        closest_names(name, &names)
    )
}

/// With at most this many parts, a wrong name lists them all.
pub const LIST_ALL: usize = 12;

/// "; did you mean \"tray\"? The parts are: ..." for a name not found among `names`:
/// the names within a small edit distance as suggestions, then every name when there
/// are few, or the closest few.
pub fn closest_names(name: &str, names: &[&str]) -> String {
    let mut by_distance: Vec<(usize, &str)> = names
        .iter()
        .map(|n| (edit_distance(&name.to_lowercase(), &n.to_lowercase()), *n))
        .collect();
    by_distance.sort();
    // Close enough to be a typo: a third of the name's letters, at least one.
    let near = (name.chars().count() / 3).max(1);
    let quote = |n: &str| format!("\"{}\"", escape(n));
    let suggestions: Vec<String> = by_distance
        .iter()
        .filter(|(d, _)| *d <= near)
        .take(3)
        .map(|(_, n)| quote(n))
        .collect();
    let mut out = String::new();
    if !suggestions.is_empty() {
        out.push_str(&format!("; did you mean {}?", suggestions.join(" or ")));
    }
    let lead = if suggestions.is_empty() {
        "; its"
    } else {
        " Its"
    };
    if names.len() <= LIST_ALL {
        let all: Vec<String> = names.iter().map(|n| quote(n)).collect();
        out.push_str(&format!("{lead} parts: {}", all.join(", ")));
    } else if suggestions.is_empty() {
        let few: Vec<String> = by_distance.iter().take(5).map(|(_, n)| quote(n)).collect();
        out.push_str(&format!(
            "{lead} {} parts include {}",
            names.len(),
            few.join(", ")
        ));
    }
    out
}

/// The edit distance between two strings, in characters: insertions, deletions,
/// substitutions and transpositions of two neighbours ("trya" is one from "tray").
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    // d[i][j]: distance between the first i characters of a and the first j of b.
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    d[0] = (0..=b.len()).collect();
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let mut best = (d[i - 1][j - 1] + usize::from(a[i - 1] != b[j - 1]))
                .min(d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = best;
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distances() {
        assert_eq!(edit_distance("tray", "trya"), 1);
        assert_eq!(edit_distance("slot", "slto"), 1);
        assert_eq!(edit_distance("ab", "ba"), 1);
        assert_eq!(edit_distance("abc", "ca"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("lid", "lid"), 0);
    }

    #[test]
    fn wrong_names_list_the_closest() {
        let few = ["slot", "tenon", "cap"];
        assert_eq!(
            closest_names("slto", &few),
            "; did you mean \"slot\"? Its parts: \"slot\", \"tenon\", \"cap\""
        );
        assert_eq!(
            closest_names("zzz", &few),
            "; its parts: \"slot\", \"tenon\", \"cap\""
        );
        let many: Vec<String> = (0..20).map(|k| format!("cube_{k:02}")).collect();
        let mut many: Vec<&str> = many.iter().map(String::as_str).collect();
        many.push("tray");
        assert_eq!(closest_names("trya", &many), "; did you mean \"tray\"?");
        let far = closest_names("lid", &many);
        assert!(far.starts_with("; its 21 parts include "), "{far}");
        assert_eq!(far.matches('"').count(), 10, "{far}");
    }
}
