//! The crates' floors (ARCHITECTURE.md, "Floors"): every library crate depends only on
//! crates of lower floors, read from the workspace's manifests, so that an upward
//! dependency (placement calling the planner, drawing calling the planner) fails here.

use std::path::Path;

/// Each crate and its floor, as ARCHITECTURE.md draws them.
const FLOORS: &[(&str, u32)] = &[
    ("apart-testkit", 0),
    ("apart-kernel", 0),
    ("apart-formats", 1),
    ("apart-pieces", 1),
    ("apart-sphere", 1),
    ("apart-mesh", 2),
    ("apart-decompose", 2),
    ("apart-minkowski", 2),
    ("apart-assembly", 3),
    ("apart-stack", 3),
    ("apart-plan", 4),
    ("apart-draw", 5),
    ("apart-jobs", 5),
    ("apart", 6),
];

/// The `apart-*` names in a manifest's `[dependencies]` section (not dev-dependencies).
fn dependencies(manifest: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            inside = line == "[dependencies]";
            continue;
        }
        if inside && line.starts_with("apart-") {
            let name = line
                .split(|c: char| c == '.' || c == '=' || c.is_whitespace())
                .next()
                .unwrap();
            out.push(name.to_string());
        }
    }
    out
}

/// The package name of a manifest.
fn name(manifest: &str) -> String {
    manifest
        .lines()
        .find_map(|l| l.trim().strip_prefix("name = "))
        .expect("a package name")
        .trim_matches('"')
        .to_string()
}

fn floor(name: &str) -> u32 {
    FLOORS
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("{name} has no floor in this test and ARCHITECTURE.md"))
        .1
}

#[test]
fn every_crate_depends_only_on_lower_floors() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut manifests = vec![root.join("Cargo.toml")];
    for entry in std::fs::read_dir(root.join("crates")).unwrap() {
        let path = entry.unwrap().path().join("Cargo.toml");
        if path.is_file() {
            manifests.push(path);
        }
    }
    let mut seen = 0;
    for path in manifests {
        let text = std::fs::read_to_string(&path).unwrap();
        let this = name(&text);
        for dep in dependencies(&text) {
            assert!(
                floor(&dep) < floor(&this),
                "{this} (floor {}) depends on {dep} (floor {})",
                floor(&this),
                floor(&dep)
            );
        }
        seen += 1;
    }
    assert_eq!(
        seen,
        FLOORS.len(),
        "a crate was added or removed: give it a floor"
    );
}

#[test]
fn the_manifest_reader_sees_dependencies() {
    let text = "[package]\nname = \"x\"\n[dependencies]\napart-kernel.workspace = true\n\
                apart-pieces = { path = \"p\" }\nrayon = \"1\"\n[dev-dependencies]\napart-plan.workspace = true\n";
    assert_eq!(name(text), "x");
    assert_eq!(dependencies(text), ["apart-kernel", "apart-pieces"]);
}
