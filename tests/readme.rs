//! Checks of the README against the repository: its commands write only into `out/`
//! (ignored by git) or `/tmp`, its dependency table names every dependency the
//! workspace declares, and the papers it refers to are cited in full.

use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).unwrap()
}

/// The lines of the README's shell code blocks.
fn shell_lines(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if line.starts_with("```") {
            inside = line.trim() == "```sh" && !inside;
            continue;
        }
        if inside {
            out.push(line.split('#').next().unwrap().trim().to_string());
        }
    }
    out
}

#[test]
fn readme_commands_write_into_out_or_tmp() {
    // Every flag that names a file or folder to write.
    let writers = [
        "--svg",
        "--png",
        "--glb",
        "--html",
        "--renders",
        "-o",
        "--output",
    ];
    let mut seen = 0;
    for line in shell_lines(&readme()) {
        let words: Vec<&str> = line.split_whitespace().collect();
        for pair in words.windows(2) {
            if writers.contains(&pair[0]) {
                seen += 1;
                assert!(
                    pair[1].starts_with("out/") || pair[1].starts_with("/tmp/"),
                    "`{line}` writes {} outside out/ and /tmp",
                    pair[1]
                );
            }
        }
        // The generators that write examples write into examples/ (tracked) or /tmp.
        if line.contains("write_curved") {
            assert!(line.contains(" /tmp/"), "{line}");
        }
    }
    assert!(
        seen >= 6,
        "{seen} output flags found in the README's commands"
    );
    let ignore = std::fs::read_to_string(root().join(".gitignore")).unwrap();
    assert!(ignore
        .lines()
        .any(|l| l.trim() == "/out/" || l.trim() == "out/"));
}

#[test]
fn every_declared_dependency_is_in_the_readme_table() {
    let manifest = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
    let section = manifest
        .split("[workspace.dependencies]")
        .nth(1)
        .unwrap()
        .split("\n[")
        .next()
        .unwrap();
    let names: Vec<&str> = section
        .lines()
        .filter_map(|l| l.split_once('=').map(|(k, _)| k.trim()))
        .filter(|k| !k.is_empty() && !k.starts_with("apart-") && !k.starts_with('#'))
        .collect();
    assert!(names.len() >= 10, "{names:?}");
    let text = readme();
    let table = text
        .split("## Why these dependencies")
        .nth(1)
        .expect("a dependency table")
        .split("\n## ")
        .next()
        .unwrap();
    for name in names {
        assert!(
            table
                .lines()
                .any(|l| l.starts_with('|') && l.contains(&format!("`{name}`"))),
            "{name} is declared in Cargo.toml but not explained in the README"
        );
    }
}

#[test]
fn the_papers_are_cited_in_full() {
    let text = readme();
    let refs = text
        .split("## References")
        .nth(1)
        .expect("a references section")
        .split("\n## ")
        .next()
        .unwrap();
    // Authors, title, venue and year of each paper, as printed on its first page
    // (the copies at hand): [000]'s copy names no venue and no date (a preprint),
    // [001]'s no venue (given as [000] cites it), [004]'s no journal (its manuscript
    // dates are printed).
    for (label, facts) in [
        (
            "[000]",
            &[
                "Sacks",
                "Milenkovic",
                "Wu",
                "Robust approximate assembly",
                "Preprint",
                "no venue and no date",
            ][..],
        ),
        (
            "[001]",
            &[
                "Fogel",
                "Halperin",
                "importance of being exact",
                "[000] cites it as",
                "Eighth International Workshop on the Algorithmic Foundations of Robotics",
                "417–432",
                "2009",
            ][..],
        ),
        (
            "[003]",
            &[
                "Wilson",
                "Schweikard",
                "Assembling polyhedra with single",
                "Stanford",
                "STAN-CS-91-1387",
                "1991",
            ][..],
        ),
        (
            "[004]",
            &[
                "Ayyadevara",
                "Bourne",
                "Shimada",
                "Sturges",
                "Interference-free polyhedral configurations",
                "manuscript received August 7, 2000",
                "prints no journal",
                "IEEE Transactions on Robotics and Automation",
                "2002",
            ][..],
        ),
    ] {
        let entry = refs
            .split("- **")
            .find(|e| e.starts_with(label))
            .unwrap_or_else(|| panic!("{label} is not cited"));
        let flat = entry.split_whitespace().collect::<Vec<_>>().join(" ");
        for fact in facts {
            assert!(flat.contains(fact), "{label} lacks {fact}: {flat}");
        }
    }
    // Papers named elsewhere in the README are among the references.
    for k in ["000", "001", "003", "004"] {
        if text
            .replace(&format!("**[{k}]**"), "")
            .contains(&format!("paper {k}"))
        {
            panic!("the README says \"paper {k}\"; cite it as [{k}]");
        }
    }
}

#[test]
fn stack_and_place_help_cite_the_stacking_paper() {
    for command in ["place", "stack"] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_apart"))
            .args([command, "--help"])
            .output()
            .unwrap();
        let help = String::from_utf8_lossy(&out.stdout);
        let flat = help.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(
            !flat.contains("paper 004"),
            "{command}: a bare paper number"
        );
        for fact in [
            "eq. (1)",
            "Ayyadevara",
            "Sturges",
            "Interference-free polyhedral configurations for stacking",
            "manuscript received August 7, 2000",
            "IEEE Transactions on Robotics and Automation",
            "2002",
            "[004]",
        ] {
            assert!(flat.contains(fact), "{command} --help lacks {fact}");
        }
    }
}
