//! `apart._apart`: the compiled half of the Python package `apart`.
//!
//! It holds no geometry: it loads assemblies with apart-assembly, plans with apart-plan,
//! and hands every answer to Python as JSON text with the fields of the command line's
//! `--json` output (the pure-Python package wraps them in typed objects). Long work
//! runs on a worker thread with the GIL released ([`work::run`]): progress goes to a
//! Python callback, and Ctrl-C, a stop asked by the callback or a timeout raise the
//! planners' stop flag, as does the memory budget ([`budget`]: the command line's
//! counting allocator, by default 80 % of the machine's memory). Every argument is
//! checked here with the command line's ranges ([`args`]), as `apart._core` checks
//! them. Errors become the exceptions of `apart._errors`; a panic is caught at the
//! boundary and becomes `apart.InternalError`.

mod answers;
mod args;
mod budget;
mod errors;
mod memory;
mod pictures;
mod work;

use apart_assembly::{Decompose, LoadOptions, Loaded, Tolerance};
use apart_jobs::partition::{Listing, PartitionOptions, DEFAULT_LIMIT, EXAMPLES_PER_KIND};
use apart_kernel::progress::{phases, Progress};
use errors::{input_error, load_error};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::PathBuf;
use std::sync::Arc;
use work::{run, Limits};

/// A loaded assembly: parts snapped to one grid, every problem found while loading, and
/// whether the parts came from arrays (no files) rather than from files.
#[pyclass(module = "apart._apart", name = "Assembly")]
pub struct Assembly {
    loaded: Arc<Loaded>,
    units: Option<String>,
}

/// The loader's options, as Python gives them.
#[derive(Clone, Copy)]
struct LoadArgs {
    grid_bits: u32,
    tolerance: Option<f64>,
    tolerance_auto: bool,
    strict: bool,
    one_part_per_file: bool,
    allow_outside: bool,
    verify: bool,
    decompose_all: bool,
}

impl LoadArgs {
    /// The library's options, with loading phases reported to `progress` under the
    /// names Python shows, and its stop flag watched.
    fn options(self, progress: &Progress) -> LoadOptions {
        let p = progress.clone();
        let tolerance = match (self.tolerance_auto, self.tolerance) {
            (true, _) => Tolerance::Auto,
            (false, Some(v)) => Tolerance::Fixed(v),
            (false, None) => Tolerance::None,
        };
        // The loader's other options keep their defaults (also any added later).
        #[allow(clippy::needless_update)]
        LoadOptions {
            grid_bits: self.grid_bits,
            progress: Progress::with_callback(move |phase, done, total| {
                p.report(phase_label(phase), done, total);
            })
            .with_stop_flag(progress.stop_flag()),
            decompose: if self.decompose_all {
                Decompose::Always
            } else {
                Decompose::WhenNeeded
            },
            verify: self.verify,
            tolerance,
            repair: !self.strict,
            split_bodies: !self.one_part_per_file,
            allow_outside: self.allow_outside,
            ..LoadOptions::default()
        }
    }
}

/// The name Python shows for a loading phase.
fn phase_label(phase: &'static str) -> &'static str {
    match phase {
        phases::READING => "loading: reading files",
        phases::VALIDATING => "loading: validating parts",
        phases::DECOMPOSING => "loading: convex decomposition",
        phases::OVERLAPS => "loading: overlaps between parts",
        other => other,
    }
}

/// Loads a folder, a mesh file or an `assembly.json` manifest.
#[pyfunction]
#[pyo3(signature = (path, *, grid_bits, tolerance, tolerance_auto, strict, one_part_per_file, allow_outside, verify, units, progress, timeout, decompose_all=false))]
#[allow(clippy::too_many_arguments)]
fn load(
    py: Python<'_>,
    path: PathBuf,
    grid_bits: i64,
    tolerance: Option<f64>,
    tolerance_auto: bool,
    strict: bool,
    one_part_per_file: bool,
    allow_outside: bool,
    verify: bool,
    units: Option<String>,
    progress: Option<Py<PyAny>>,
    timeout: Option<f64>,
    decompose_all: bool,
) -> PyResult<Assembly> {
    args::units(py, units.as_deref())?;
    args::tolerance(py, tolerance, tolerance_auto)?;
    let grid_bits = args::grid_bits(py, grid_bits)?;
    let timeout = args::timeout(py, timeout)?;
    let args = LoadArgs {
        grid_bits,
        tolerance,
        tolerance_auto,
        strict,
        one_part_per_file,
        allow_outside,
        verify,
        decompose_all,
    };
    let limits = Limits {
        callback: progress,
        timeout,
        stoppable: false,
    };
    let (loaded, _) = run(py, limits, move |p| {
        apart_assembly::load(&path, &args.options(p)).map_err(|e| (e.to_string(), path))
    })?;
    let loaded = loaded.map_err(|(message, path)| load_error(py, message, Some(path)))?;
    Ok(Assembly {
        loaded: Arc::new(loaded),
        units,
    })
}

/// Builds an assembly from triangle meshes given as little-endian bytes: per part its
/// name, `n x 3` float64 vertices and `m x 3` int64 faces.
#[pyfunction]
#[pyo3(signature = (name, parts, *, grid_bits, tolerance, tolerance_auto, strict, one_part_per_file, verify, units, progress, timeout))]
#[allow(clippy::too_many_arguments)]
fn from_meshes(
    py: Python<'_>,
    name: String,
    parts: Vec<(String, Bound<'_, PyBytes>, Bound<'_, PyBytes>)>,
    grid_bits: i64,
    tolerance: Option<f64>,
    tolerance_auto: bool,
    strict: bool,
    one_part_per_file: bool,
    verify: bool,
    units: Option<String>,
    progress: Option<Py<PyAny>>,
    timeout: Option<f64>,
) -> PyResult<Assembly> {
    args::units(py, units.as_deref())?;
    args::tolerance(py, tolerance, tolerance_auto)?;
    let grid_bits = args::grid_bits(py, grid_bits)?;
    let timeout = args::timeout(py, timeout)?;
    if parts.is_empty() {
        return Err(errors::value_error(py, "no meshes given".into()));
    }
    let mut meshes = Vec::with_capacity(parts.len());
    for (part, v, f) in &parts {
        meshes.push(memory::mesh(part, v.as_bytes(), f.as_bytes()).map_err(
            |(element, message)| input_error(py, message, None, Some(part.clone()), element),
        )?);
    }
    let args = LoadArgs {
        grid_bits,
        tolerance,
        tolerance_auto,
        strict,
        one_part_per_file,
        allow_outside: false,
        verify,
        decompose_all: false,
    };
    let limits = Limits {
        callback: progress,
        timeout,
        stoppable: false,
    };
    let (loaded, _) = run(py, limits, move |p| {
        memory::load(name, meshes, &args.options(p))
    })?;
    let loaded = loaded.map_err(|message| load_error(py, message, None))?;
    Ok(Assembly {
        loaded: Arc::new(loaded),
        units,
    })
}

#[pymethods]
impl Assembly {
    /// The assembly's name.
    #[getter]
    fn name(&self) -> String {
        self.loaded.assembly.name.clone()
    }

    /// The part names, in order.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.loaded
            .assembly
            .parts
            .iter()
            .map(|p| p.name.clone())
            .collect()
    }

    /// True when no problem found while loading is an error.
    #[getter]
    fn valid(&self) -> bool {
        self.loaded.is_valid()
    }

    /// The check report (`apart check --json`), as JSON text.
    fn check_json(&self) -> String {
        answers::check(&self.loaded, self.units.as_deref()).to_string()
    }

    /// Raises `InvalidAssemblyError` when loading found errors.
    fn require_valid(&self, py: Python<'_>) -> PyResult<()> {
        errors::require_valid(py, &self.loaded)
    }

    /// The solutions (`apart partition --json`), the first one only, or one direction's
    /// blocking graph, as JSON text. Listed as the command line lists them: at most
    /// `limit` moving sets (default 20) with at most `max_per_set` solutions of each
    /// kind (default 5), or everything with `all`; every solution is counted.
    #[pyo3(signature = (*, first=false, direction=None, max_solutions=None, max_per_set=None, limit=None, all=false, progress=None, timeout=None))]
    #[allow(clippy::too_many_arguments)]
    fn partition_json(
        &self,
        py: Python<'_>,
        first: bool,
        direction: Option<[f64; 3]>,
        max_solutions: Option<i64>,
        max_per_set: Option<i64>,
        limit: Option<i64>,
        all: bool,
        progress: Option<Py<PyAny>>,
        timeout: Option<f64>,
    ) -> PyResult<String> {
        let max_solutions = args::positive(py, "max_solutions", max_solutions)?;
        let max_per_set = args::positive(py, "max_per_set", max_per_set)?;
        let limit = args::positive(py, "limit", limit)?;
        let timeout = args::timeout(py, timeout)?;
        if all && (limit.is_some() || max_per_set.is_some()) {
            return Err(errors::value_error(
                py,
                "all=True lists every solution: it takes no limit or max_per_set".into(),
            ));
        }
        let listing = if all {
            Listing::all()
        } else {
            Listing {
                sets: Some(limit.unwrap_or(DEFAULT_LIMIT)),
                per_set: Some(max_per_set.unwrap_or(EXAMPLES_PER_KIND)),
            }
        };
        errors::require_valid(py, &self.loaded)?;
        let loaded = self.loaded.clone();
        let units = self.units.clone();
        let d = match direction {
            Some(d) => Some(answers::snap_direction(d).map_err(|m| errors::value_error(py, m))?),
            None => None,
        };
        let opts = PartitionOptions {
            first,
            max_solutions,
            listing,
            keep_for_pictures: false,
        };
        let limits = Limits {
            callback: progress,
            timeout,
            // The first solution and one direction's graph watch no stop flag.
            stoppable: !first && d.is_none(),
        };
        let (answer, stop) = run(py, limits, move |p| {
            answers::partition(&loaded, units.as_deref(), d, &opts, p)
        })?;
        let mut answer = answer.map_err(|e| errors::job_error(py, e, &stop))?;
        work::mark(&mut answer, &stop);
        Ok(answer.to_string())
    }

    /// A disassembly plan (`apart sequence --json`), as JSON text, with the plan for
    /// its pictures (`None` when the run stopped: the command line draws no partial
    /// plan either).
    #[pyo3(signature = (*, base, first, prefer_single, prefer_connected, prefer_axes, max_depth, growth, progress, timeout, ranking = None))]
    #[allow(clippy::too_many_arguments)]
    fn sequence_json(
        &self,
        py: Python<'_>,
        base: Option<String>,
        first: bool,
        prefer_single: bool,
        prefer_connected: bool,
        prefer_axes: bool,
        max_depth: Option<i64>,
        growth: bool,
        progress: Option<Py<PyAny>>,
        timeout: Option<f64>,
        ranking: Option<String>,
    ) -> PyResult<(String, Option<Plan>)> {
        errors::require_valid(py, &self.loaded)?;
        let base = match base {
            Some(name) => Some(errors::part_index(py, &self.loaded.assembly, &name)?),
            None => None,
        };
        let max_depth = args::positive(py, "max_depth", max_depth)?;
        let timeout = args::timeout(py, timeout)?;
        let opts = apart_plan::SequenceOptions {
            prefer_single,
            prefer_connected,
            prefer_axes,
            base,
            max_depth,
            tolerance: growth,
            keep_solutions: apart_plan::KeepSolutions::Nothing,
            ranking: match ranking.as_deref() {
                None | Some("auto") => apart_plan::Ranking::Auto,
                Some("full") => apart_plan::Ranking::Full,
                Some("local") => apart_plan::Ranking::Local,
                Some(other) => {
                    return Err(errors::value_error(
                        py,
                        format!("ranking must be 'auto', 'full' or 'local', not {other:?}"),
                    ))
                }
            },
        };
        let loaded = self.loaded.clone();
        let units = self.units.clone();
        let limits = Limits {
            callback: progress,
            timeout,
            stoppable: true,
        };
        let (answer, stop) = run(py, limits, move |p| {
            answers::sequence(&loaded, units.as_deref(), &opts, first, p)
        })?;
        let (mut answer, plan) = answer.map_err(|e| errors::job_error(py, e, &stop))?;
        let plan = (!plan.stopped).then(|| Plan {
            loaded: self.loaded.clone(),
            plan,
        });
        work::mark(&mut answer, &stop);
        Ok((answer.to_string(), plan))
    }

    /// A plan of several moves with the puzzle's level (`apart disassemble --json`), as
    /// JSON text.
    #[pyo3(signature = (*, axes, max_moves, max_states, symmetry, progress, timeout))]
    #[allow(clippy::too_many_arguments)]
    fn disassemble_json(
        &self,
        py: Python<'_>,
        axes: bool,
        max_moves: Option<i64>,
        max_states: Option<i64>,
        symmetry: bool,
        progress: Option<Py<PyAny>>,
        timeout: Option<f64>,
    ) -> PyResult<String> {
        errors::require_valid(py, &self.loaded)?;
        let timeout = args::timeout(py, timeout)?;
        let defaults = apart_plan::MoveOptions::default();
        let opts = apart_plan::MoveOptions {
            axes,
            max_moves: args::positive(py, "max_moves", max_moves)?.unwrap_or(defaults.max_moves),
            max_states: args::positive(py, "max_states", max_states)?
                .unwrap_or(defaults.max_states),
            symmetry,
        };
        let loaded = self.loaded.clone();
        let units = self.units.clone();
        let limits = Limits {
            callback: progress,
            timeout,
            stoppable: true,
        };
        let (answer, stop) = run(py, limits, move |p| {
            answers::disassemble(&loaded, units.as_deref(), &opts, p)
        })?;
        let mut answer = answer.map_err(|e| errors::job_error(py, e, &stop))?;
        work::mark(&mut answer, &stop);
        Ok(answer.to_string())
    }

    /// Every direction along which part `a` leaves part `b` (`apart separate --json`),
    /// as JSON text.
    #[pyo3(signature = (a, b, *, progress, timeout))]
    fn separate_json(
        &self,
        py: Python<'_>,
        a: String,
        b: String,
        progress: Option<Py<PyAny>>,
        timeout: Option<f64>,
    ) -> PyResult<String> {
        let timeout = args::timeout(py, timeout)?;
        errors::require_valid(py, &self.loaded)?;
        let asm = &self.loaded.assembly;
        if asm.parts.len() < 2 {
            return Err(errors::value_error(
                py,
                format!(
                    "separate needs two parts, and \"{}\" has only {}",
                    asm.name,
                    asm.parts.len()
                ),
            ));
        }
        let (ia, ib) = (
            errors::part_index(py, asm, &a)?,
            errors::part_index(py, asm, &b)?,
        );
        if ia == ib {
            return Err(errors::value_error(py, "the two parts must differ".into()));
        }
        let loaded = self.loaded.clone();
        let units = self.units.clone();
        let limits = Limits {
            callback: progress,
            timeout,
            stoppable: true,
        };
        let (answer, stop) = run(py, limits, move |p| {
            answers::separate(&loaded, units.as_deref(), ia, ib, p)
        })?;
        let answer = answer.map_err(|e| errors::job_error(py, e, &stop))?;
        match (answer, stop) {
            (Some(answer), None) => Ok(answer.to_string()),
            // Separation has no partial answer: a stop ends it with no result.
            (_, stop) => Err(errors::stopped(py, stop)),
        }
    }

    /// Interference-free positions of part `part` among the others, cheapest first
    /// (`apart place ASSEMBLY NAME --json`), as JSON text; the options are in input
    /// units, their ranges checked by the caller.
    #[pyo3(signature = (part, *, target, weight, floor_point, region, translations, dtheta, bases, clearance, candidates, timeout))]
    #[allow(clippy::too_many_arguments)]
    fn place_json(
        &self,
        py: Python<'_>,
        part: String,
        target: [f64; 3],
        weight: Option<f64>,
        floor_point: [f64; 3],
        region: Option<[f64; 6]>,
        translations: Option<[f64; 6]>,
        dtheta: f64,
        bases: Option<Vec<(u8, u8)>>,
        clearance: Option<f64>,
        candidates: i64,
        timeout: Option<f64>,
    ) -> PyResult<String> {
        let target = args::all_finite(py, "target", target)?;
        let weight = weight.map(|w| args::weight(py, w)).transpose()?;
        let floor_point = args::all_finite(py, "floor_point", floor_point)?;
        if region.is_some() && translations.is_some() {
            return Err(errors::value_error(
                py,
                "give region= or translations=, not both".into(),
            ));
        }
        let region = args::region(py, "region", region)?;
        let translations = args::region(py, "translations", translations)?;
        let dtheta = args::dtheta(py, dtheta)?;
        let bases = args::bases(py, bases)?;
        let clearance = args::clearance(py, clearance)?;
        let candidates = args::count(py, "candidates", candidates, 1, Some(1000))?;
        let timeout = args::timeout(py, timeout)?;
        errors::require_valid_but(py, &self.loaded, Some(&part))?;
        let k = errors::part_index(py, &self.loaded.assembly, &part)?;
        let asm = &self.loaded.assembly;
        if asm.parts.len() < 2 {
            return Err(errors::value_error(
                py,
                format!("place needs a fixed part besides \"{part}\""),
            ));
        }
        if let Some(p) = asm.parts.iter().find(|p| p.pieces.is_empty()) {
            return Err(errors::value_error(
                py,
                format!("part \"{}\" has no convex pieces", p.name),
            ));
        }
        let opts = apart_jobs::place::PlaceJobOptions {
            part: k,
            target,
            weight,
            floor_point,
            region,
            translations,
            dtheta,
            bases,
            clearance,
            candidates,
        };
        let loaded = self.loaded.clone();
        let limits = Limits {
            callback: None,
            timeout,
            // The placement engine watches no stop flag.
            stoppable: false,
        };
        let (answer, stop) = run(py, limits, move |_| answers::place(&loaded, &opts))?;
        Ok(answer
            .map_err(|e| errors::job_error(py, e, &stop))?
            .to_string())
    }

    /// The motion-space sphere with every solution marked (`apart partition --svg` or
    /// `--png`), as bytes.
    #[pyo3(signature = (*, svg, orthographic, progress, timeout))]
    fn motion_space_picture<'py>(
        &self,
        py: Python<'py>,
        svg: bool,
        orthographic: bool,
        progress: Option<Py<PyAny>>,
        timeout: Option<f64>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let timeout = args::timeout(py, timeout)?;
        errors::require_valid(py, &self.loaded)?;
        let asm = &self.loaded.assembly;
        if asm.parts.len() < 2 {
            return Err(errors::value_error(
                py,
                format!(
                    "\"{}\" has {} part: a motion space needs two parts or more",
                    asm.name,
                    asm.parts.len()
                ),
            ));
        }
        let loaded = self.loaded.clone();
        let limits = Limits {
            callback: progress,
            timeout,
            stoppable: true,
        };
        let (answer, stop) = run(py, limits, move |p| {
            pictures::motion_space(&loaded, svg, orthographic, p)
        })?;
        match (answer.map_err(|e| errors::plan_error(py, e))?, stop) {
            (Some(bytes), None) => Ok(PyBytes::new(py, &bytes)),
            // A picture of a partial answer is not drawn (nor by the command line).
            (_, stop) => Err(errors::stopped(py, stop)),
        }
    }

    /// A stack of copies of part `part` on a floor (`apart stack --json`), as JSON
    /// text; the options are in input units, their ranges checked by the caller.
    #[pyo3(signature = (part, *, count, weight, floor, floor_z, max_height, dtheta, bases, clearance, max_candidates, extrapolate, progress, timeout))]
    #[allow(clippy::too_many_arguments)]
    fn stack_json(
        &self,
        py: Python<'_>,
        part: String,
        count: i64,
        weight: f64,
        floor: Option<[f64; 4]>,
        floor_z: f64,
        max_height: Option<f64>,
        dtheta: f64,
        bases: Option<Vec<(u8, u8)>>,
        clearance: Option<f64>,
        max_candidates: i64,
        extrapolate: bool,
        progress: Option<Py<PyAny>>,
        timeout: Option<f64>,
    ) -> PyResult<String> {
        let count = args::count(py, "count", count, 1, Some(1000))?;
        let weight = args::weight(py, weight)?;
        if let Some(f) = floor {
            if !(args::all_finite(py, "floor", f)?[0] < f[2] && f[1] < f[3]) {
                return Err(errors::value_error(
                    py,
                    format!("floor must be (x0, y0, x1, y1) with x0 < x1 and y0 < y1, not {f:?}"),
                ));
            }
        }
        let floor_z = args::finite(py, "floor_z", floor_z)?;
        if let Some(h) = max_height {
            if !(h.is_finite() && h > 0.0) {
                return Err(errors::value_error(
                    py,
                    format!("max_height must be a positive length, not {h}"),
                ));
            }
        }
        let dtheta = args::dtheta(py, dtheta)?;
        let bases = args::bases(py, bases)?;
        let clearance = args::clearance(py, clearance)?;
        let max_candidates = args::count(py, "max_candidates", max_candidates, 1, Some(100_000))?;
        let timeout = args::timeout(py, timeout)?;
        errors::require_valid(py, &self.loaded)?;
        let k = errors::part_index(py, &self.loaded.assembly, &part)?;
        if self.loaded.assembly.parts[k].pieces.is_empty() {
            return Err(errors::value_error(
                py,
                format!("part \"{part}\" has no convex pieces: load it with apart.stack(path) or apart.load(path) with two parts or more"),
            ));
        }
        let opts = apart_jobs::stack::StackJobOptions {
            part: k,
            count,
            weight,
            floor,
            floor_z,
            max_height,
            dtheta,
            bases,
            clearance,
            max_candidates,
            extrapolate,
        };
        let loaded = self.loaded.clone();
        let limits = Limits {
            callback: progress,
            timeout,
            stoppable: true,
        };
        let (answer, stop) = run(py, limits, move |p| answers::stack(&loaded, &opts, p))?;
        let mut answer = answer.map_err(|e| errors::job_error(py, e, &stop))?;
        work::mark(&mut answer, &stop);
        Ok(answer.to_string())
    }
}

/// A disassembly plan with its assembly: what the sequence pictures are drawn from.
#[pyclass(module = "apart._apart", name = "Plan", frozen)]
pub struct Plan {
    loaded: Arc<Loaded>,
    plan: Arc<apart_plan::Sequence>,
}

#[pymethods]
impl Plan {
    /// The animated GLB of the disassembly (`apart sequence --glb`), as bytes.
    fn glb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let (loaded, plan) = (self.loaded.clone(), self.plan.clone());
        let bytes = py.detach(move || apart_draw::disassembly_glb(&loaded.assembly, &plan));
        Ok(PyBytes::new(py, &bytes))
    }

    /// The self-contained HTML viewer of the disassembly (`apart sequence --html`).
    fn html(&self, py: Python<'_>) -> String {
        let (loaded, plan) = (self.loaded.clone(), self.plan.clone());
        py.detach(move || apart_draw::disassembly_html(&loaded.assembly, &plan))
    }
}

/// Sets the memory budget of the extension's heap: a number of bytes (at least 1 MiB;
/// 0: none), a size such as `"4G"`, `"500M"` or `"1.5G"` (K, M, G, T are powers of
/// 1024), `"default"` (80 % of the machine's memory, the budget when the module is
/// loaded), or `None` / `"none"` (no budget), as the command line's `--max-memory`.
#[pyfunction]
fn set_memory_budget(py: Python<'_>, size: Option<Bound<'_, PyAny>>) -> PyResult<()> {
    let bad = |why: String| errors::value_error(py, format!("memory budget {why}"));
    let Some(size) = size else {
        budget::set(None, false);
        return Ok(());
    };
    if size.is_instance_of::<pyo3::types::PyBool>() {
        return Err(bad(format!(
            "must be a size in bytes, a text such as \"4G\", \"default\" or None, not {size}"
        )));
    }
    if let Ok(text) = size.extract::<String>() {
        let t = text.trim();
        if t.eq_ignore_ascii_case("none") || t == "0" {
            budget::set(None, false);
        } else if t.eq_ignore_ascii_case("default") {
            budget::set(budget::machine(), budget::machine().is_some());
        } else {
            let bytes = apart_kernel::budget::parse_size(t).map_err(bad)?;
            budget::set(Some(bytes), false);
        }
        return Ok(());
    }
    match size.extract::<i128>() {
        Ok(0) => budget::set(None, false),
        Ok(b) if b >= i128::from(apart_kernel::budget::MIN_MEMORY) && b < i128::from(u64::MAX) => {
            budget::set(Some(b as u64), false)
        }
        Ok(b) => {
            return Err(bad(format!(
                "must be at least 1M (1048576 bytes), or 0 for none, not {b}"
            )))
        }
        Err(_) => {
            return Err(bad(format!(
                "must be a size in bytes, a text such as \"4G\", \"default\" or None, not {}",
                size.repr().map_or_else(|_| "?".into(), |r| r.to_string())
            )))
        }
    }
    Ok(())
}

/// The memory budget in bytes (`None`: none).
#[pyfunction]
fn memory_budget() -> Option<u64> {
    apart_kernel::budget::limit()
}

/// The extension's live heap, in bytes, as the budget counts it.
#[pyfunction]
fn memory_in_use() -> u64 {
    apart_kernel::budget::live()
}

/// The compiled module.
#[pymodule]
fn _apart(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Third-party mesh parsers' panics are caught and become errors; their default
    // message on standard error would only repeat it.
    apart_formats::quiet_parser_panics();
    budget::init();
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(set_memory_budget, m)?)?;
    m.add_function(wrap_pyfunction!(memory_budget, m)?)?;
    m.add_function(wrap_pyfunction!(memory_in_use, m)?)?;
    m.add("DEFAULT_MEMORY_BUDGET", budget::machine())?;
    m.add("MIN_MEMORY_BUDGET", apart_kernel::budget::MIN_MEMORY)?;
    m.add_function(wrap_pyfunction!(from_meshes, m)?)?;
    m.add_class::<Assembly>()?;
    m.add_class::<Plan>()?;
    m.add("DEFAULT_GRID_BITS", apart_kernel::grid::DEFAULT_BITS)?;
    m.add(
        "GRID_BITS_RANGE",
        (apart_kernel::grid::MIN_BITS, apart_kernel::grid::MAX_BITS),
    )?;
    Ok(())
}
