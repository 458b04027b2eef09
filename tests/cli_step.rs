//! STEP files on the command line: the binary hands the file to a child Python
//! (`APART_PYTHON`, else `python3`) running `apart.step.emit`, and loads the parts it
//! prints. Tested here: the message when that Python cannot read STEP files (any
//! machine), the protocol with a stand-in `apart.step` module (any machine with
//! python3), and, when `APART_PYTHON` names a Python with the apart package and OCP, a
//! real STEP file against `apart.load` (otherwise that test prints that it is skipped;
//! CI runs the same comparison in python/tests/test_step.py with its venv's Python).

use apart_testkit::Scratch;
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

const INSTALL: &str = "pip install './python[step]'";

fn apart(args: &[&str], python: &str, pythonpath: Option<&Path>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_apart"));
    cmd.args(args).env("APART_PYTHON", python);
    match pythonpath {
        Some(p) => cmd.env("PYTHONPATH", p),
        None => cmd.env_remove("PYTHONPATH"),
    };
    cmd.output().unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn has_python3() -> bool {
    Command::new("python3")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn without_python_the_error_names_the_file_and_the_install_command() {
    let dir = Scratch::new("step-nopython");
    let file = dir.path().join("gearbox.step");
    std::fs::write(&file, "ISO-10303-21;").unwrap();
    let f = file.to_str().unwrap();
    for args in [vec!["check", f], vec!["partition", f], vec!["sequence", f]] {
        let out = apart(&args, "/nonexistent/python3", None);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(f) && err.contains(INSTALL), "{err}");
        assert!(err.contains("APART_PYTHON=/nonexistent/python3"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    // In JSON, the same message as the error.
    let out = apart(&["check", f, "--json"], "/nonexistent/python3", None);
    let j: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(j["error"].as_str().unwrap().contains(INSTALL), "{j}");
}

#[test]
fn a_python_without_the_apart_package_gets_the_install_command() {
    if !has_python3() {
        println!("skipped: no python3 on this machine");
        return;
    }
    let dir = Scratch::new("step-noapart");
    let file = dir.path().join("pin.STP");
    std::fs::write(&file, "ISO-10303-21;").unwrap();
    // -S: no site-packages, so that an installed apart is not found.
    let wrapper = dir.path().join("python-bare");
    std::fs::write(&wrapper, "#!/bin/sh\nexec python3 -S \"$@\"\n").unwrap();
    make_executable(&wrapper);
    let out = apart(
        &["check", file.to_str().unwrap()],
        wrapper.to_str().unwrap(),
        None,
    );
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("pin.STP") && err.contains(INSTALL), "{err}");
    assert!(err.contains("No module named 'apart'"), "{err}");
}

#[cfg(unix)]
fn make_executable(p: &Path) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(p, std::fs::Permissions::from_mode(0o755)).unwrap();
}

#[cfg(not(unix))]
fn make_executable(_: &Path) {}

/// A stand-in for the package's `apart.step` (its `emit` protocol): two unit cubes
/// side by side for any file but those holding `FAIL` (a message naming the file,
/// status 1) or `NOOCP` (status 3, as without OCP); the arguments it got are written
/// to `args.json` beside the module.
const FAKE_STEP: &str = r#"
import json, os, struct, sys

def cube(x):
    v = [[x + a, b, c] for a in (0, 1) for b in (0, 1) for c in (0, 1)]
    t = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
         [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    bits = [struct.unpack("<Q", struct.pack("<d", float(c)))[0] for p in v for c in p]
    return bits, [i for tri in t for i in tri]

def emit(argv):
    with open(os.path.join(os.path.dirname(__file__), "args.json"), "w") as f:
        json.dump(argv, f)
    text = open(argv[0]).read()
    if "FAIL" in text:
        print("cannot read " + argv[0] + ": not a STEP file OpenCASCADE can read", file=sys.stderr)
        return 1
    if "NOOCP" in text:
        print("reading STEP files needs OCP (OpenCASCADE)", file=sys.stderr)
        return 3
    parts = []
    for name, x in (("left", 0), ("right", 1)):
        v, t = cube(x)
        parts.append({"name": name, "vertices": v, "triangles": t})
    json.dump({"name": "cubes", "units": "mm", "chordal_tolerance": 0.001,
               "angular_tolerance": 0.5, "parts": parts}, sys.stdout)
    return 0
"#;

#[test]
fn the_parts_printed_by_the_reader_are_loaded_in_millimetres() {
    if !has_python3() {
        println!("skipped: no python3 on this machine");
        return;
    }
    let dir = Scratch::new("step-fake");
    let pkg = dir.path().join("pylib").join("apart");
    std::fs::create_dir_all(&pkg).unwrap();
    std::fs::write(pkg.join("__init__.py"), "").unwrap();
    std::fs::write(pkg.join("step.py"), FAKE_STEP).unwrap();
    let pylib = dir.path().join("pylib");
    let file = dir.path().join("cubes.step");
    std::fs::write(&file, "ISO-10303-21;").unwrap();
    let f = file.to_str().unwrap();
    let args_seen = || -> Vec<String> {
        serde_json::from_str(&std::fs::read_to_string(pkg.join("args.json")).unwrap()).unwrap()
    };

    let out = apart(&["check", f, "--json"], "python3", Some(&pylib));
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let j: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["valid"], true, "{j}");
    assert_eq!(j["units"], "mm", "{j}");
    let names: Vec<&str> = j["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["left", "right"]);
    assert_eq!(args_seen(), [f, "--units", "mm"]);

    // The tessellation flags and --units go to the reader.
    let out = apart(
        &[
            "partition",
            f,
            "--json",
            "--chordal-tolerance",
            "0.25",
            "--angular-tolerance",
            "0.1",
            "--units",
            "in",
        ],
        "python3",
        Some(&pylib),
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let j: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["units"], "in", "{j}");
    assert!(!j["solutions"].as_array().unwrap().is_empty(), "{j}");
    assert_eq!(
        args_seen(),
        [
            f,
            "--chordal-tolerance",
            "0.25",
            "--angular-tolerance",
            "0.1",
            "--units",
            "in"
        ]
    );

    // A file the reader refuses: its message, which names the file.
    std::fs::write(&file, "FAIL").unwrap();
    let out = apart(&["sequence", f], "python3", Some(&pylib));
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(&format!("cannot read {f}: not a STEP file")),
        "{err}"
    );
    // No OCP: the install command.
    std::fs::write(&file, "NOOCP").unwrap();
    let out = apart(&["check", f], "python3", Some(&pylib));
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(f) && err.contains(INSTALL) && err.contains("needs OCP"),
        "{err}"
    );
    // The tessellation flags refuse other inputs.
    let out = apart(
        &[
            "check",
            dir.path().to_str().unwrap(),
            "--chordal-tolerance",
            "1",
        ],
        "python3",
        Some(&pylib),
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("STEP files (.step, .stp) only"));
}

/// Writes a STEP file of two touching boxes with OCP, and prints `apart.load`'s check of
/// it as JSON (run by the Python under test).
const REAL: &str = r#"
import json, sys
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
from OCP.gp import gp_Pnt
from OCP.STEPControl import STEPControl_Writer, STEPControl_AsIs
from OCP.TopoDS import TopoDS_Compound
from OCP.BRep import BRep_Builder
import apart
b = BRep_Builder(); c = TopoDS_Compound(); b.MakeCompound(c)
b.Add(c, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(10, 10, 5)).Shape())
b.Add(c, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 5), gp_Pnt(10, 10, 7.5)).Shape())
w = STEPControl_Writer(); w.Transfer(c, STEPControl_AsIs); w.Write(sys.argv[1])
print(json.dumps(apart.load(sys.argv[1]).check().to_dict()))
"#;

#[test]
fn a_real_step_file_loads_as_apart_load_loads_it() {
    let Ok(python) = std::env::var("APART_PYTHON") else {
        println!(
            "skipped: APART_PYTHON is not set (set it to a Python with the apart package and OCP: {INSTALL}); \
             CI compares with apart.load in python/tests/test_step.py"
        );
        return;
    };
    let dir = Scratch::new("step-real");
    let file = dir.path().join("two-boxes.step");
    let f = file.to_str().unwrap();
    let py = Command::new(&python).args(["-c", REAL, f]).output();
    let Some(py) = py.ok().filter(|o| o.status.success()) else {
        println!("skipped: APART_PYTHON={python} cannot write a STEP file with OCP or load it with apart");
        return;
    };
    // The last line: OpenCASCADE's writer prints its statistics before it.
    let stdout = text(&py.stdout);
    let expected: Value = serde_json::from_str(stdout.lines().last().unwrap()).unwrap();
    let out = apart(&["check", f, "--json"], &python, None);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let got: Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in ["valid", "units", "grid", "parts", "problems"] {
        assert_eq!(got[key], expected[key], "{key}");
    }
    assert_eq!(got["units"], "mm");
    assert_eq!(got["parts"].as_array().unwrap().len(), 2);
    let out = apart(&["partition", f, "--json"], &python, None);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
}
