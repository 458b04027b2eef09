//! Side-by-side bench of apart and the exact CGAL peer of paper 001's pipeline,
//! which also cross-checks their answers.
//!
//! ```sh
//! cargo build --release                                    # the apart binary it times
//! APART_PEER=/path/to/ndbg_cgal cargo run --release -p apart-plan --example peer_bench [-- FILTER...]
//! ```
//!
//! It writes every input itself (under `PEER_BENCH_DIR`, default a folder in the system's
//! temporary directory), as a folder with `assembly.json` whose parts list their convex
//! pieces as OFF files of exact integer coordinates, which both programs read: the
//! shipped examples, passed through `apart decompose` (apart's exact convex pieces),
//! and generated families: rows of zig-zag sticks, log-cabin stacks of notched sticks,
//! random boxes in parts (paper 003) and voxel puzzles of 6 to 13 parts on a 6×6×6 grid.
//!
//! For each input it runs `apart partition DIR --json --threads 1` and the peer as whole
//! processes, alternating: a warm-up run under `/usr/bin/time -f %M` for the peak
//! resident set, then `PEER_BENCH_REPS` timed runs (default 3) and their median wall
//! time (a program taking over 1 s is timed under the wrapper every run, over 30 s only
//! once). Then it cross-checks the answers (`apart partition --all`):
//!
//! - the moving sets (minimal movable subsets) of both are the same;
//! - for each moving set, the best kind of cell where it moves (face, edge, vertex) is
//!   the same (apart merges cells with equal blocking graphs, the peer lists every cell);
//! - every vertex solution of apart is a vertex solution of the peer with the same exact
//!   direction and the set among its sink components, and the sets that move only along
//!   isolated directions have the same directions in both;
//! - the peer, asked at apart's exact face and edge directions (`--probe`), finds the
//!   set among the sinks there;
//! - the brute-force oracle of the planner tests (an exact linear program over two
//!   pieces' facet inequalities) finds every checked solution of either program free.
//!
//! Every disagreement is printed. The peer is optional: without `APART_PEER` (or when the
//! file is missing) only apart runs, with a note. Other settings: `APART_BIN` (default:
//! the `apart` binary of this target folder), `PEER_BENCH_TIMEOUT` (seconds per run,
//! default 600), `PEER_BENCH_CHECKS` (solutions probed and oracle-checked per input,
//! default 300), `PEER_BENCH_ORACLE_SECONDS` (time for the oracle's checks per input,
//! default 30). Arguments keep only the inputs whose name contains one of them.

#[path = "../tests/common/mod.rs"]
mod common;

use apart_kernel::Vec3;
use apart_pieces::Polytope;
use apart_plan::Part;
use apart_testkit::solids::{random_boxes, rectilinear, voxels, IntMesh, Lcg};
use common::oracle::Oracle;
use serde_json::{json, Value};
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// One input: its folder (with `assembly.json`) and what the table shows.
struct Case {
    name: String,
    dir: PathBuf,
}

/// One finished process: wall seconds, peak resident set in MiB (when measured), exit
/// code (None when killed at the timeout), standard output.
struct Run {
    seconds: f64,
    mib: Option<f64>,
    code: Option<i32>,
    stdout: String,
}

/// Repeated runs of one program on one input.
#[derive(Default)]
struct Series {
    /// Wall seconds of the timed runs.
    times: Vec<f64>,
    /// Largest peak resident set measured, MiB.
    mib: Option<f64>,
    /// Standard output of the first run.
    output: Option<String>,
    /// Runs take more than a second: each is timed under the memory wrapper.
    long: bool,
    /// Why the runs stopped: a timeout or an error.
    failed: Option<String>,
}

impl Series {
    /// Runs of more than 30 s are not repeated.
    fn done(&self, reps: usize) -> bool {
        let wanted = if self.times.first().is_some_and(|&t| t > 30.0) {
            1
        } else {
            reps
        };
        self.failed.is_some() || self.times.len() >= wanted
    }

    /// One more run. The first is a warm-up under `/usr/bin/time` for the peak memory;
    /// it is also timed when the program takes more than a second (then the wrapper's
    /// start-up does not matter and every run is wrapped).
    fn step(&mut self, program: &Path, args: &[&std::ffi::OsStr], timeout: Duration, reps: usize) {
        if self.done(reps) {
            return;
        }
        let warm = self.output.is_none();
        let r = run(program, args, timeout, warm || self.long);
        match r.code {
            None => {
                self.failed = Some(format!("timeout ({:.0} s)", timeout.as_secs_f64()));
                return;
            }
            Some(0 | 2) => {}
            Some(c) => {
                self.failed = Some(format!("exit code {c}"));
                self.output = Some(r.stdout);
                return;
            }
        }
        self.mib = larger(self.mib, r.mib);
        if warm {
            self.long = r.seconds > 1.0;
            self.output = Some(r.stdout);
            if !self.long {
                return;
            }
        }
        self.times.push(r.seconds);
    }
}

/// Runs `program args` to its end (or kills it at `timeout`), timing the whole process.
/// With `memory`, the process runs under `/usr/bin/time -f %M`, which reports its peak
/// resident set (the wrapper's own start-up then counts in the time: the caller
/// measures memory in a separate run when the process is short).
fn run(program: &Path, args: &[&std::ffi::OsStr], timeout: Duration, memory: bool) -> Run {
    let tmp = std::env::temp_dir();
    let out_path = tmp.join(format!("peer-bench-out-{}", std::process::id()));
    let mem_path = tmp.join(format!("peer-bench-mem-{}", std::process::id()));
    let out = fs::File::create(&out_path).expect("temporary output file");
    let mut cmd = if memory {
        let mut c = Command::new("/usr/bin/time");
        c.arg("-f").arg("%M").arg("-o").arg(&mem_path).arg(program);
        c
    } else {
        Command::new(program)
    };
    cmd.args(args).stdout(out).stderr(Stdio::null());
    let start = Instant::now();
    let mut child = cmd
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {}: {e}", program.display()));
    let pid = child.id().to_string();
    let (done, wait) = mpsc::channel::<()>();
    let watchdog = std::thread::spawn(move || {
        if wait.recv_timeout(timeout).is_err() {
            // Under /usr/bin/time the program is the wrapper's child: end it first.
            let _ = Command::new("pkill").args(["-KILL", "-P", &pid]).status();
            let _ = Command::new("kill").args(["-KILL", &pid]).status();
        }
    });
    let status = child.wait().expect("wait for the child");
    let seconds = start.elapsed().as_secs_f64();
    let _ = done.send(());
    let _ = watchdog.join();
    let stdout = fs::read_to_string(&out_path).unwrap_or_default();
    let _ = fs::remove_file(&out_path);
    let mib = memory
        .then(|| fs::read_to_string(&mem_path).ok())
        .flatten()
        .and_then(|t| t.lines().last()?.trim().parse::<f64>().ok())
        .map(|kib| kib / 1024.0);
    let _ = fs::remove_file(&mem_path);
    let killed = std::os::unix::process::ExitStatusExt::signal(&status).is_some()
        || (memory && seconds >= timeout.as_secs_f64());
    Run {
        seconds,
        mib,
        code: if killed { None } else { status.code() },
        stdout,
    }
}

fn larger(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.max(b)),
        _ => a.or(b),
    }
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

// ----------------------------------------------------------------------------
// Inputs

fn off_text(points: &[[i64; 3]], faces: &[Vec<usize>]) -> String {
    let mut s = format!("OFF\n{} {} 0\n", points.len(), faces.len());
    for p in points {
        s += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for f in faces {
        s += &f.len().to_string();
        for i in f {
            s += &format!(" {i}");
        }
        s += "\n";
    }
    s
}

fn box_faces() -> Vec<Vec<usize>> {
    apart_testkit::solids::CUBOID_QUADS
        .iter()
        .map(|f| f.iter().map(|&v| v as usize).collect())
        .collect()
}

fn box_points(lo: [i64; 3], hi: [i64; 3]) -> Vec<[i64; 3]> {
    apart_testkit::solids::cuboid_corners(lo, hi)
}

/// Writes part meshes into `raw/` and lets `apart decompose` write the folder with exact
/// convex pieces; then lists every convex part as its own single piece.
fn decomposed(apart: &Path, root: &Path, name: &str, parts: &[(String, IntMesh)]) -> Case {
    let raw = root.join("raw").join(name);
    let _ = fs::remove_dir_all(&raw);
    fs::create_dir_all(&raw).unwrap();
    for (part, mesh) in parts {
        fs::write(raw.join(format!("{part}.off")), mesh.off_text()).unwrap();
    }
    decompose_folder(apart, &raw, root, name)
}

/// `apart decompose SRC -o ROOT/NAME`, then pieces for the convex parts.
fn decompose_folder(apart: &Path, src: &Path, root: &Path, name: &str) -> Case {
    let dir = root.join(name);
    let _ = fs::remove_dir_all(&dir);
    let st = Command::new(apart)
        .arg("decompose")
        .arg(src)
        .arg("-o")
        .arg(&dir)
        .arg("-q")
        .stdout(Stdio::null())
        .status()
        .expect("apart decompose");
    assert!(st.success(), "apart decompose {} failed", src.display());
    let path = dir.join("assembly.json");
    let mut m: Value = serde_json::from_str(&fs::read_to_string(&path).unwrap()).unwrap();
    for p in m["parts"].as_array_mut().unwrap() {
        let empty = p
            .get("pieces")
            .and_then(Value::as_array)
            .is_none_or(|a| a.is_empty());
        if empty {
            p["pieces"] = json!([p["mesh"].clone()]);
        }
    }
    fs::write(&path, serde_json::to_string_pretty(&m).unwrap()).unwrap();
    Case {
        name: name.to_string(),
        dir,
    }
}

/// Parts given as lists of boxes: the part's mesh is its boxes' shells (the boxes of
/// one part never touch), each box one piece.
fn boxes_case(root: &Path, name: &str, parts: &[Vec<([i64; 3], [i64; 3])>]) -> Case {
    let dir = root.join(name);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    let mut list = Vec::new();
    for (i, boxes) in parts.iter().enumerate() {
        let part = format!("p{i}");
        fs::create_dir_all(dir.join(&part)).unwrap();
        let (mut pts, mut faces) = (Vec::new(), Vec::new());
        let mut pieces = Vec::new();
        for (k, &(lo, hi)) in boxes.iter().enumerate() {
            let base = pts.len();
            pts.extend(box_points(lo, hi));
            faces.extend(
                box_faces()
                    .into_iter()
                    .map(|f| f.into_iter().map(|i| i + base).collect::<Vec<_>>()),
            );
            let file = format!("{part}/piece_{k}.off");
            fs::write(dir.join(&file), off_text(&box_points(lo, hi), &box_faces())).unwrap();
            pieces.push(file);
        }
        fs::write(dir.join(format!("{part}.off")), off_text(&pts, &faces)).unwrap();
        list.push(json!({"name": part, "mesh": format!("{part}.off"), "pieces": pieces}));
    }
    let m = json!({"name": name, "parts": list});
    fs::write(
        dir.join("assembly.json"),
        serde_json::to_string_pretty(&m).unwrap(),
    )
    .unwrap();
    Case {
        name: name.to_string(),
        dir,
    }
}

/// `n` sticks side by side along x, each a zig-zag wall of `m` courses (course k of
/// stick i is [2i + k mod 2, 2i + 2 + k mod 2] × [0, 3] × [k, k + 1]), so that every
/// stick interlocks with its neighbours.
fn stick_row(n: usize, m: usize) -> Vec<(String, IntMesh)> {
    let xs: Vec<i64> = (0..=2 * n as i64 + 1).collect();
    let ys = [0, 3];
    let zs: Vec<i64> = (0..=m as i64).collect();
    (0..n)
        .map(|i| {
            let mesh = rectilinear([&xs, &ys, &zs], |[x, _, z]| {
                let lo = 2 * i + z % 2;
                x >= lo && x < lo + 2
            });
            (format!("s{i:02}"), mesh)
        })
        .collect()
}

/// A log cabin of `layers` layers on a `w × w` plan: two sticks a layer, along x in even
/// layers and along y in odd ones, one cell past each corner; each stick is two half
/// levels high and gives the upper half of its two corner cells to the stick of the
/// layer above (half-lap notches), so neighbouring layers interlock.
fn log_cabin(layers: usize, w: usize) -> Vec<(String, IntMesh)> {
    let dims = [w, w, layers + 1];
    let corner = |c: usize| c == 1 || c == w - 2;
    let mut parts = Vec::new();
    for k in 0..layers {
        for row in [1, w - 2] {
            let mut on = vec![false; w * w * (layers + 1)];
            for a in 0..w {
                let (x, y) = if k % 2 == 0 { (a, row) } else { (row, a) };
                let zs: &[usize] = if corner(a) { &[k] } else { &[k, k + 1] };
                for &z in zs {
                    on[(x * w + y) * (layers + 1) + z] = true;
                }
            }
            parts.push((
                format!("l{k:02}{}", if row == 1 { "a" } else { "b" }),
                voxels(dims, &on),
            ));
        }
    }
    parts
}

/// A voxel puzzle: the 6×6×6 cube cut into `k` face-connected parts grown from random
/// seed cells.
fn voxel_puzzle(k: usize, seed: u64) -> Vec<(String, IntMesh)> {
    const N: usize = 6;
    let idx = |c: [usize; 3]| (c[0] * N + c[1]) * N + c[2];
    let mut rng = Lcg(seed);
    let mut owner = vec![usize::MAX; N * N * N];
    let mut cells: Vec<Vec<[usize; 3]>> = Vec::new();
    while cells.len() < k {
        let c = [0, 0, 0].map(|_| rng.below(N as u64) as usize);
        if owner[idx(c)] == usize::MAX {
            owner[idx(c)] = cells.len();
            cells.push(vec![c]);
        }
    }
    let mut left = N * N * N - k;
    while left > 0 {
        let p = rng.below(k as u64) as usize;
        let c = cells[p][rng.below(cells[p].len() as u64) as usize];
        let axis = rng.below(3) as usize;
        let mut nb = c;
        if rng.below(2) == 0 {
            if nb[axis] == 0 {
                continue;
            }
            nb[axis] -= 1;
        } else {
            if nb[axis] == N - 1 {
                continue;
            }
            nb[axis] += 1;
        }
        if owner[idx(nb)] == usize::MAX {
            owner[idx(nb)] = p;
            cells[p].push(nb);
            left -= 1;
        }
    }
    (0..k)
        .map(|p| {
            let on: Vec<bool> = owner.iter().map(|&o| o == p).collect();
            (format!("v{p:02}"), voxels([N, N, N], &on))
        })
        .collect()
}

fn cases(apart: &Path, root: &Path, keep: &dyn Fn(&str) -> bool) -> Vec<Case> {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut out = Vec::new();
    let shipped = [
        "split-star",
        "split-star-3",
        "split-star-5",
        "split-star-8",
        "peg-in-the-hole",
        "dovetail-and-cap",
        "hinge",
        "linked-rings",
        "tray-of-cubes",
        "ring-and-cone",
    ];
    for ex in shipped {
        if keep(ex) {
            out.push(decompose_folder(apart, &examples.join(ex), root, ex));
        }
    }
    for (n, m) in [(4, 4), (8, 6), (12, 6)] {
        let name = format!("stick-row-{n}x{m}");
        if keep(&name) {
            out.push(decomposed(apart, root, &name, &stick_row(n, m)));
        }
    }
    for layers in [4, 6, 9] {
        let name = format!("log-cabin-{layers}");
        if keep(&name) {
            out.push(decomposed(apart, root, &name, &log_cabin(layers, 6)));
        }
    }
    for (n, k) in [(8, 4), (16, 4), (32, 8)] {
        let name = format!("random-boxes-{n}/{k}").replace('/', "-in-");
        if keep(&name) {
            out.push(boxes_case(root, &name, &random_boxes(n, k, 1)));
        }
    }
    for (k, seed) in [(6, 1), (9, 2), (13, 3)] {
        let name = format!("voxel-puzzle-{k}");
        if keep(&name) {
            out.push(decomposed(apart, root, &name, &voxel_puzzle(k, seed)));
        }
    }
    out
}

// ----------------------------------------------------------------------------
// Answers

/// A set of part names, sorted.
type Set = Vec<String>;

fn names(v: &Value) -> Set {
    let mut s: Set = v
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|x| x.as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default();
    s.sort();
    s
}

/// The best kind of cell a set moves in: 0 face, 1 edge, 2 vertex.
fn best_kind(faces: u64, edges: u64) -> usize {
    if faces > 0 {
        0
    } else if edges > 0 {
        1
    } else {
        2
    }
}

const KIND: [&str; 3] = ["face", "edge", "vertex"];

fn gcd(a: i128, b: i128) -> i128 {
    if b == 0 {
        a.abs()
    } else {
        gcd(b, a % b)
    }
}

/// A direction given as three exact rationals ("p/q" or "p") as the primitive integer
/// vector in the same direction, when it fits in 128 bits.
fn primitive(parts: &[String]) -> Option<[i128; 3]> {
    let mut num = [0i128; 3];
    let mut den = [1i128; 3];
    for (k, t) in parts.iter().enumerate() {
        let (p, q) = match t.split_once('/') {
            Some((p, q)) => (p.trim().parse().ok()?, q.trim().parse().ok()?),
            None => (t.trim().parse().ok()?, 1),
        };
        num[k] = p;
        den[k] = q;
    }
    let mut l = 1i128;
    for q in den {
        l = l.checked_mul(q / gcd(l, q))?;
    }
    let mut v = [0i128; 3];
    for k in 0..3 {
        v[k] = num[k].checked_mul(l / den[k])?;
    }
    let g = gcd(gcd(v[0], v[1]), v[2]);
    (g != 0).then(|| v.map(|x| x / g))
}

fn strings(v: &Value) -> Vec<String> {
    v.as_array()
        .map(|a| {
            a.iter()
                .map(|x| match x {
                    Value::String(s) => s.clone(),
                    other => other.to_string(),
                })
                .collect()
        })
        .unwrap_or_default()
}

/// apart's answer: moving sets with their counts, and every solution.
struct ApartAnswer {
    sets: BTreeMap<Set, [u64; 3]>,
    solutions: Vec<(usize, [i128; 3], Set)>,
}

fn apart_answer(json: &Value) -> ApartAnswer {
    let mut sets = BTreeMap::new();
    for g in json["groups"].as_array().into_iter().flatten() {
        let c = ["faces", "edges", "vertices"].map(|k| g[k].as_u64().unwrap_or(0));
        sets.insert(names(&g["moving"]), c);
    }
    let mut solutions = Vec::new();
    for s in json["solutions"].as_array().into_iter().flatten() {
        let kind = KIND
            .iter()
            .position(|k| Some(*k) == s["cell"].as_str())
            .unwrap_or(0);
        if let Some(d) = primitive(&strings(&s["exact_direction"])) {
            solutions.push((kind, d, names(&s["moving"])));
        }
    }
    ApartAnswer { sets, solutions }
}

/// The peer's answer: moving sets with their cell counts, vertex solutions (exact
/// direction, every sink).
struct PeerAnswer {
    sets: BTreeMap<Set, [u64; 3]>,
    vertices: Vec<([i128; 3], Vec<Set>)>,
    vertex_cells: u64,
    witnesses: Vec<(usize, [f64; 3], Vec<Set>)>,
}

fn sinks(s: &Value) -> Vec<Set> {
    match s.get("all_sinks").and_then(Value::as_array) {
        Some(all) => all.iter().map(names).collect(),
        None => vec![names(&s["moving"])],
    }
}

fn peer_answer(json: &Value) -> PeerAnswer {
    let mut sets = BTreeMap::new();
    for d in json["distinct_moving_sets"]
        .as_array()
        .into_iter()
        .flatten()
    {
        let c = ["face_cells", "edge_cells", "vertex_cells"].map(|k| d[k].as_u64().unwrap_or(0));
        sets.insert(names(&d["set"]), c);
    }
    let mut vertices = Vec::new();
    for s in json["vertex_solutions"].as_array().into_iter().flatten() {
        if let Some(d) = primitive(&strings(&s["dir_exact"])) {
            vertices.push((d, sinks(s)));
        }
    }
    let mut witnesses = Vec::new();
    for (kind, key) in [(0, "face_solutions"), (1, "edge_solutions")] {
        for s in json[key].as_array().into_iter().flatten() {
            let d: Vec<f64> = s["dir"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(Value::as_f64)
                .collect();
            if d.len() == 3 {
                witnesses.push((kind, [d[0], d[1], d[2]], sinks(s)));
            }
        }
    }
    PeerAnswer {
        sets,
        vertices,
        vertex_cells: json["solution_cells"]["vertices"].as_u64().unwrap_or(0),
        witnesses,
    }
}

/// The pieces of every part, read back from the input's OFF files (integer coordinates),
/// for the oracle; None when a coordinate is not an integer.
fn load_parts(dir: &Path) -> Option<Vec<Part>> {
    let m: Value =
        serde_json::from_str(&fs::read_to_string(dir.join("assembly.json")).ok()?).ok()?;
    let mut parts = Vec::new();
    for p in m["parts"].as_array()? {
        let mut pieces = Vec::new();
        for f in p["pieces"].as_array()? {
            let pts = off_points(&fs::read_to_string(dir.join(f.as_str()?)).ok()?)?;
            let v: Vec<Vec3> = pts.into_iter().map(Vec3::from).collect();
            pieces.push(Polytope::hull_of_points(&v).ok()?);
        }
        parts.push(Part::from_pieces(p["name"].as_str()?, pieces));
    }
    Some(parts)
}

/// The vertices of an OFF file whose coordinates are all integers.
fn off_points(text: &str) -> Option<Vec<[i64; 3]>> {
    let mut tokens = text
        .lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .flat_map(str::split_whitespace);
    if tokens.next()? != "OFF" {
        return None;
    }
    let nv: usize = tokens.next()?.parse().ok()?;
    let (_, _) = (tokens.next()?, tokens.next()?);
    (0..nv)
        .map(|_| {
            let mut c = [0i64; 3];
            for x in &mut c {
                *x = tokens.next()?.parse().ok()?;
            }
            Some(c)
        })
        .collect()
}

/// Every coordinate of every OFF file the manifest names is an exact integer or decimal.
fn coordinates_exact(dir: &Path) -> bool {
    let Ok(text) = fs::read_to_string(dir.join("assembly.json")) else {
        return false;
    };
    let m: Value = serde_json::from_str(&text).unwrap_or(Value::Null);
    let exact = |t: &str| {
        let t = t.strip_prefix('-').unwrap_or(t);
        !t.is_empty()
            && t.chars().all(|c| c.is_ascii_digit() || c == '.')
            && t.matches('.').count() <= 1
    };
    let files = m["parts"].as_array().into_iter().flatten().flat_map(|p| {
        let mut f = vec![p["mesh"].clone()];
        f.extend(p["pieces"].as_array().cloned().unwrap_or_default());
        f
    });
    // A part given by its pieces alone has no mesh (null).
    for f in files.filter(|f| !f.is_null()) {
        let Some(text) = f
            .as_str()
            .and_then(|f| fs::read_to_string(dir.join(f)).ok())
        else {
            return false;
        };
        let mut lines = text
            .lines()
            .map(|l| l.split('#').next().unwrap_or("").trim())
            .filter(|l| !l.is_empty());
        let _ = lines.next();
        let nv: usize = lines
            .next()
            .and_then(|l| l.split_whitespace().next()?.parse().ok())
            .unwrap_or(0);
        for l in lines.take(nv) {
            if !l.split_whitespace().all(exact) {
                return false;
            }
        }
    }
    true
}

fn vec3(d: [i128; 3]) -> Option<Vec3> {
    Some(Vec3::from([
        i64::try_from(d[0]).ok()?,
        i64::try_from(d[1]).ok()?,
        i64::try_from(d[2]).ok()?,
    ]))
}

/// Evenly spaced indices: at most `max` of `0..n`.
fn sample(n: usize, max: usize) -> Vec<usize> {
    if n <= max {
        (0..n).collect()
    } else {
        (0..max).map(|i| i * n / max).collect()
    }
}

/// What the cross-check found.
struct Check {
    problems: Vec<String>,
    notes: Vec<String>,
}

fn cross_check(
    case: &Case,
    apart: &ApartAnswer,
    peer: &PeerAnswer,
    peer_cmd: &Path,
    timeout: Duration,
    checks: usize,
    oracle_budget: Duration,
) -> Check {
    let mut problems = Vec::new();
    let mut notes = Vec::new();
    let set_text = |s: &Set| format!("{{{}}}", s.join(", "));
    // 1. moving sets and the best kind of cell of each.
    for (s, c) in &apart.sets {
        match peer.sets.get(s) {
            None => problems.push(format!(
                "apart moves {} ({} faces, {} edges, {} vertices); the peer never does",
                set_text(s),
                c[0],
                c[1],
                c[2]
            )),
            Some(p) => {
                let (a, b) = (best_kind(c[0], c[1]), best_kind(p[0], p[1]));
                if a != b {
                    problems.push(format!(
                        "{}: apart's best cell is a {}, the peer's a {} (peer cells f/e/v {}/{}/{}, apart {}/{}/{})",
                        set_text(s), KIND[a], KIND[b], p[0], p[1], p[2], c[0], c[1], c[2]
                    ));
                }
            }
        }
    }
    for (s, p) in &peer.sets {
        if !apart.sets.contains_key(s) {
            problems.push(format!(
                "the peer moves {} (cells f/e/v {}/{}/{}); apart never does",
                set_text(s),
                p[0],
                p[1],
                p[2]
            ));
        }
    }
    // 2. vertex solutions, exactly.
    let peer_vertices: BTreeSet<([i128; 3], Set)> = peer
        .vertices
        .iter()
        .flat_map(|(d, ss)| ss.iter().map(move |s| (*d, s.clone())))
        .collect();
    let complete = peer.vertices.len() as u64 == peer.vertex_cells;
    if !complete {
        notes.push(format!(
            "the peer listed {} of {} vertex cells",
            peer.vertices.len(),
            peer.vertex_cells
        ));
    }
    let apart_vertices: BTreeSet<([i128; 3], Set)> = apart
        .solutions
        .iter()
        .filter(|s| s.0 == 2)
        .map(|s| (s.1, s.2.clone()))
        .collect();
    if complete {
        for (d, s) in &apart_vertices {
            if !peer_vertices.contains(&(*d, s.clone())) {
                problems.push(format!(
                    "apart's vertex solution {} along {:?} is not a vertex solution of the peer",
                    set_text(s),
                    d
                ));
            }
        }
        for (d, s) in &peer_vertices {
            let vertex_only = peer.sets.get(s).is_some_and(|c| c[0] == 0 && c[1] == 0);
            if vertex_only && !apart_vertices.contains(&(*d, s.clone())) {
                problems.push(format!(
                    "the peer's vertex solution {} along {:?} (the set moves only along isolated directions) is missing in apart",
                    set_text(s),
                    d
                ));
            }
        }
    }
    // 3. the peer at apart's face and edge directions.
    let probed: Vec<&(usize, [i128; 3], Set)> = {
        let fe: Vec<_> = apart.solutions.iter().filter(|s| s.0 < 2).collect();
        sample(fe.len(), checks)
            .into_iter()
            .map(|i| fe[i])
            .collect()
    };
    let fits = |d: &[i128; 3]| d.iter().all(|x| i64::try_from(*x).is_ok());
    let mut args: Vec<std::ffi::OsString> =
        vec![case.dir.clone().into(), "--max-list".into(), "0".into()];
    let mut asked = 0;
    for (_, d, _) in &probed {
        if fits(d) {
            args.push("--probe".into());
            args.push(format!("{},{},{}", d[0], d[1], d[2]).into());
            asked += 1;
        }
    }
    if asked > 0 {
        let args: Vec<&std::ffi::OsStr> = args.iter().map(|a| a.as_os_str()).collect();
        let r = run(peer_cmd, &args, timeout, false);
        let json: Value = serde_json::from_str(&r.stdout).unwrap_or(Value::Null);
        let mut at: BTreeMap<[i128; 3], (String, Vec<Set>)> = BTreeMap::new();
        for p in json["probes"].as_array().into_iter().flatten() {
            let d: Vec<i128> = p["dir"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|x| x.as_i64().map(i128::from))
                .collect();
            if d.len() == 3 {
                let cell = p["cell"].as_str().unwrap_or("?").to_string();
                let ss = p["sinks"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .map(names)
                    .collect();
                at.insert([d[0], d[1], d[2]], (cell, ss));
            }
        }
        let mut skipped = 0;
        for (kind, d, s) in &probed {
            match at.get(d) {
                None => skipped += 1,
                Some((cell, ss)) if !ss.contains(s) => problems.push(format!(
                    "apart's {} solution {} along {:?}: the peer's {} there has sinks {:?}",
                    KIND[*kind],
                    set_text(s),
                    d,
                    cell,
                    ss
                )),
                _ => {}
            }
        }
        notes.push(format!(
            "peer probed at the {} distinct directions of {} of apart's face/edge solutions{}",
            at.len(),
            probed.len(),
            if skipped > 0 {
                format!(" ({skipped} not answered: on the peer's parameterization boundary)")
            } else {
                String::new()
            }
        ));
    }
    // 4. the brute-force oracle on both programs' exact directions.
    match load_parts(&case.dir) {
        None => notes.push("oracle skipped: non-integer coordinates".into()),
        Some(parts) => {
            let oracle = Oracle::new(&parts);
            let index: BTreeMap<&str, usize> = parts
                .iter()
                .enumerate()
                .map(|(i, p)| (p.name.as_str(), i))
                .collect();
            let free = |s: &Set, d: &Vec3| {
                let moving: Vec<usize> = s
                    .iter()
                    .filter_map(|n| index.get(n.as_str()).copied())
                    .collect();
                let rest: Vec<usize> = (0..parts.len()).filter(|i| !moving.contains(i)).collect();
                moving.len() == s.len() && oracle.free(&moving, &rest, d)
            };
            // Spread over the solutions and bounded in time (a moving ring of 64 pieces
            // against 65 others is 4,160 linear programs per solution).
            let started = Instant::now();
            let in_time = || started.elapsed() < oracle_budget;
            let mut n = 0;
            for i in sample(apart.solutions.len(), checks) {
                if !in_time() {
                    break;
                }
                let (kind, d, s) = &apart.solutions[i];
                if let Some(v) = vec3(*d) {
                    n += 1;
                    if !free(s, &v) {
                        problems.push(format!(
                            "oracle: apart's {} solution {} along {:?} is blocked",
                            KIND[*kind],
                            set_text(s),
                            d
                        ));
                    }
                }
            }
            let pv: Vec<_> = peer_vertices.iter().collect();
            for i in sample(pv.len(), checks) {
                if !in_time() {
                    break;
                }
                let (d, s) = pv[i];
                if let Some(v) = vec3(*d) {
                    n += 1;
                    if !free(s, &v) {
                        problems.push(format!(
                            "oracle: the peer's vertex solution {} along {:?} is blocked",
                            set_text(s),
                            d
                        ));
                    }
                }
            }
            // Sets only the peer reports: its approximate witnesses, rounded.
            for (kind, w, ss) in &peer.witnesses {
                for s in ss.iter().filter(|s| !apart.sets.contains_key(*s)) {
                    let d = w.map(|x| (x * 1e6).round() as i64);
                    let verdict = if free(s, &Vec3::from(d)) {
                        "free"
                    } else {
                        "blocked"
                    };
                    notes.push(format!(
                        "oracle at the peer's approximate {} witness {:?} for {}: {verdict}",
                        KIND[*kind],
                        d,
                        set_text(s)
                    ));
                }
            }
            let of = sample(apart.solutions.len(), checks).len() + sample(pv.len(), checks).len();
            notes.push(format!(
                "oracle checked {n} of {of} sampled solutions{}",
                if in_time() {
                    String::new()
                } else {
                    format!(" (stopped after {} s)", oracle_budget.as_secs())
                }
            ));
        }
    }
    Check { problems, notes }
}

// ----------------------------------------------------------------------------

fn main() {
    let filters: Vec<String> = std::env::args().skip(1).collect();
    let keep = |name: &str| filters.is_empty() || filters.iter().any(|f| name.contains(f.as_str()));
    let env = |k: &str| std::env::var(k).ok().filter(|v| !v.is_empty());
    let apart = env("APART_BIN").map(PathBuf::from).unwrap_or_else(|| {
        let exe = std::env::current_exe().expect("own path");
        exe.parent()
            .and_then(Path::parent)
            .expect("target folder")
            .join("apart")
    });
    assert!(
        apart.is_file(),
        "{} not found: build it first (cargo build --release) or set APART_BIN",
        apart.display()
    );
    let peer = env("APART_PEER").map(PathBuf::from).filter(|p| p.is_file());
    if peer.is_none() {
        println!("note: APART_PEER is not set to the peer's binary (ndbg_cgal): the peer is skipped, apart runs alone\n");
    }
    let reps: usize = env("PEER_BENCH_REPS")
        .and_then(|v| v.parse().ok())
        .unwrap_or(3)
        .max(1);
    let timeout = Duration::from_secs_f64(
        env("PEER_BENCH_TIMEOUT")
            .and_then(|v| v.parse().ok())
            .unwrap_or(600.0),
    );
    let checks: usize = env("PEER_BENCH_CHECKS")
        .and_then(|v| v.parse().ok())
        .unwrap_or(300);
    let oracle_budget = Duration::from_secs_f64(
        env("PEER_BENCH_ORACLE_SECONDS")
            .and_then(|v| v.parse().ok())
            .unwrap_or(30.0),
    );
    let root = env("PEER_BENCH_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("apart-peer-bench"));
    fs::create_dir_all(&root).unwrap();
    let cases = cases(&apart, &root, &keep);

    let mut rows = Vec::new();
    let mut phases = Vec::new();
    let mut findings = Vec::new();
    for case in &cases {
        eprintln!("{} ...", case.name);
        let exact = coordinates_exact(&case.dir);
        let dir = case.dir.as_os_str();
        let os = |v: &[&'static str]| -> Vec<&std::ffi::OsStr> {
            v.iter()
                .map(|a| std::ffi::OsStr::new(*a))
                .chain([dir])
                .collect()
        };
        let check: Value = {
            let args = os(&["partition", "--json", "--all", "--threads", "1", "-q"]);
            let r = run(&apart, &args, timeout, false);
            serde_json::from_str(&r.stdout).unwrap_or(Value::Null)
        };
        let stats = &check["stats"];
        let parts = check["parts"].as_array().map_or(0, Vec::len);
        let pieces = stats["pieces"].as_u64().unwrap_or(0);
        let apart_args = os(&["partition", "--json", "--threads", "1"]);
        let peer_args = os(&[]);
        let mut a = Series::default();
        let mut p = Series::default();
        if peer.is_none() {
            p.failed = Some("not run".into());
        }
        while !(a.done(reps) && p.done(reps)) {
            a.step(&apart, &apart_args, timeout, reps);
            if let Some(peer) = &peer {
                p.step(peer, &peer_args, timeout, reps);
            }
        }
        let a_s = median(&mut a.times);
        let p_s = (!p.times.is_empty()).then(|| median(&mut p.times));
        let (am, pm) = (a.mib, p.mib);
        let peer_json: Value = p
            .output
            .as_deref()
            .and_then(|o| serde_json::from_str(o).ok())
            .unwrap_or(Value::Null);
        let peer_state = p.failed.clone().unwrap_or_default();
        let agree = match (&peer, peer_state.as_str(), p_s) {
            (Some(p), "", Some(_)) => {
                let mut pj = peer_json.clone();
                let listed = pj["vertex_solutions"].as_array().map_or(0, Vec::len) as u64;
                if pj["solution_cells"]["vertices"].as_u64().unwrap_or(0) > listed {
                    let args = os(&["--max-list", "100000000"]);
                    let args = [&args[2..], &args[..2]].concat();
                    let r = run(p, &args, timeout, false);
                    pj = serde_json::from_str(&r.stdout).unwrap_or(Value::Null);
                }
                let c = cross_check(
                    case,
                    &apart_answer(&check),
                    &peer_answer(&pj),
                    p,
                    timeout,
                    checks,
                    oracle_budget,
                );
                let ok = c.problems.is_empty() && !check.is_null();
                findings.push((case.name.clone(), c));
                if ok { "yes" } else { "**no**" }.to_string()
            }
            (Some(_), state, _) => {
                let why = match peer_json["error"].as_str() {
                    Some(e) => format!("peer: {e}"),
                    None => format!("peer: {state}"),
                };
                format!("— ({why})")
            }
            (None, _, _) => "—".to_string(),
        };
        let fmt_s = |s: f64| {
            if s < 0.1 {
                format!("{:.4}", s)
            } else {
                format!("{:.3}", s)
            }
        };
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {}{} |",
            case.name,
            parts,
            pieces,
            fmt_s(a_s),
            p_s.map_or(
                if peer_state.starts_with("timeout") {
                    format!("> {:.0}", timeout.as_secs_f64())
                } else {
                    "—".into()
                },
                fmt_s
            ),
            p_s.map_or("—".into(), |p| format!("{:.1}x", p / a_s)),
            am.map_or("—".into(), |m| format!("{m:.1}")),
            pm.map_or("—".into(), |m| format!("{m:.1}")),
            agree,
            if exact { "" } else { " (inexact coordinates)" }
        ));
        eprintln!("{}", rows.last().expect("a row"));
        if let Some((_, c)) = findings.last().filter(|(n, _)| *n == case.name) {
            for line in c.problems.iter().chain(&c.notes) {
                eprintln!("  {line}");
            }
        }
        let sec = &stats["seconds"];
        let ms = |k: &str| sec[k].as_f64().unwrap_or(f64::NAN) * 1e3;
        let pms = |k: &str| {
            peer_json["times_s"][k]
                .as_f64()
                .map_or("—".into(), |x| format!("{:.1}", x * 1e3))
        };
        phases.push(format!(
            "| {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {} | {} | {} | {} | {} |",
            case.name,
            check["solution_count"].as_u64().unwrap_or(0),
            ms("load"),
            ms("sums"),
            ms("projection"),
            ms("unions"),
            ms("overlay"),
            ms("graphs"),
            pms("read"),
            pms("minkowski"),
            pms("projection"),
            pms("union"),
            pms("overlay"),
            pms("dbg"),
            peer_json["solution_cells"]
                .as_object()
                .map_or("—".into(), |c| format!(
                    "{}/{}/{}",
                    c["faces"], c["edges"], c["vertices"]
                )),
        ));
    }
    println!(
        "Whole process, apart `partition DIR --json --threads 1` and the peer alternating: a warm-up run under `/usr/bin/time -f %M` for the peak resident set, then the median of {reps} runs (a program taking over 1 s is timed under the wrapper every run; over 30 s, once).\n"
    );
    println!("| input | parts | pieces | apart s | peer s | ratio | apart MiB | peer MiB | answers agree |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---|");
    for r in &rows {
        println!("{r}");
    }
    println!("\nPhase times (ms) of one run each: apart's (from its JSON, `--all`) and the peer's (`times_s`); the peer's solution cells faces/edges/vertices.\n");
    println!("| input | apart solutions | load | sums | projection | unions | overlay | graphs | peer read | minkowski | projection | union | overlay | dbg | peer cells f/e/v |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    for r in &phases {
        println!("{r}");
    }
    if !findings.is_empty() {
        println!("\nCross-checks:\n");
        for (name, c) in &findings {
            println!(
                "- {name}: {}; {}",
                if c.problems.is_empty() {
                    "agree".to_string()
                } else {
                    format!("{} disagreement(s)", c.problems.len())
                },
                c.notes.join("; ")
            );
            for p in &c.problems {
                println!("  - DISAGREEMENT: {p}");
            }
        }
    }
    println!("\ninputs written under {}", root.display());
}
