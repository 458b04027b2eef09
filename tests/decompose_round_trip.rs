//! `apart decompose` output loads back as the same solids, for float, rational
//! (decimal) and integer inputs, with pieces on the grid (written and declared) and off
//! it (the part written as its mesh alone). Each case: decompose, `apart check` the
//! output (valid, no error), then load input and output with the library and compare
//! per part the exact volume, the sum of the pieces' exact volumes against the volume of
//! the input mesh (an independent divergence-theorem sum), and the pieces themselves as
//! sets of exact vertex coordinates in input units.

use apart::assembly::{load, Decompose, LoadOptions, Loaded};
use apart::kernel::{Grid, Int, Rational};
use apart::mesh::validate::volume_in_units;
use apart::pieces::Polytope;
use apart_testkit::curved;
use apart_testkit::Scratch;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh folder for one test's files.
fn folder(tag: &str) -> Scratch {
    Scratch::new(&format!("roundtrip-{}", tag))
}

/// The OFF text of the prism over the counter-clockwise polygon `poly` from `z0` to `z1`,
/// every coordinate times `scale`.
fn prism(poly: &[[i64; 2]], z0: i64, z1: i64, scale: f64) -> String {
    let n = poly.len();
    let mut out = format!("OFF\n{} {} 0\n", 2 * n, n + 2);
    for z in [z0, z1] {
        for p in poly {
            let c = [p[0] as f64 * scale, p[1] as f64 * scale, z as f64 * scale];
            out.push_str(&format!("{} {} {}\n", c[0], c[1], c[2]));
        }
    }
    let bottom: Vec<String> = (0..n).rev().map(|k| k.to_string()).collect();
    let top: Vec<String> = (n..2 * n).map(|k| k.to_string()).collect();
    out.push_str(&format!(
        "{n} {}\n{n} {}\n",
        bottom.join(" "),
        top.join(" ")
    ));
    for k in 0..n {
        let j = (k + 1) % n;
        out.push_str(&format!("4 {k} {j} {} {}\n", j + n, k + n));
    }
    out
}

/// A block with a V notch whose slanted walls meet at (3, 1): its decomposition cuts
/// along a wall's plane to (8/3, 0), off the integer grid.
const NOTCHED: [[i64; 2]; 7] = [[0, 0], [6, 0], [6, 4], [4, 4], [3, 1], [2, 4], [0, 4]];
/// An L: its decomposition has every vertex on the grid.
const ELL: [[i64; 2]; 6] = [[0, 0], [6, 0], [6, 2], [2, 2], [2, 5], [0, 5]];
/// A box beside both (x from 7 to 9).
const BOX: [[i64; 2]; 4] = [[7, 0], [9, 0], [9, 4], [7, 4]];

fn apart(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_apart"))
        .args(args)
        .output()
        .unwrap()
}

fn load_all(path: &Path) -> Loaded {
    let opts = LoadOptions {
        decompose: Decompose::Always,
        ..LoadOptions::default()
    };
    let l = load(path, &opts).unwrap();
    assert!(l.is_valid(), "{}: {:?}", path.display(), l.problems);
    l
}

/// `q / den · 2^exp` exactly.
fn units(q: &Int, den: &Int, grid: &Grid) -> Rational {
    let p = Int::from(1) << (grid.exp.unsigned_abs() as usize);
    if grid.exp >= 0 {
        Rational::new(q * &p, den.clone())
    } else {
        Rational::new(q.clone(), den * &p)
    }
}

/// A piece as its sorted vertices in input units (exact rationals, as text).
fn piece_key(p: &Polytope, grid: &Grid) -> Vec<[String; 3]> {
    let mut v: Vec<[String; 3]> = p
        .vertices()
        .iter()
        .map(|v| {
            let c = v.to_ints();
            [0, 1, 2].map(|k| units(&c[k], p.den(), grid).to_string())
        })
        .collect();
    v.sort();
    v
}

/// Decomposes `input`, checks the output with `apart check`, and compares every part's
/// solid and pieces; returns how many parts had their pieces written.
fn round_trip(input: &Path, tag: &str) -> usize {
    let out = folder(&format!("{tag}-out"));
    let _ = std::fs::remove_dir_all(&out);
    let d = apart(&[
        "decompose",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(d.status.success(), "{}", String::from_utf8_lossy(&d.stderr));
    let c = apart(&["check", out.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&c.stdout);
    assert!(
        c.status.success() && text.contains("valid: 0 error(s)"),
        "{tag}: {text}{}",
        String::from_utf8_lossy(&c.stderr)
    );
    let (a, b) = (load_all(input), load_all(&out));
    let (ga, gb) = (&a.assembly.grid, &b.assembly.grid);
    assert_eq!(a.assembly.parts.len(), b.assembly.parts.len());
    let manifest = std::fs::read_to_string(out.join("assembly.json")).unwrap();
    let mut written = 0;
    for pa in &a.assembly.parts {
        let pb = b.assembly.part(&pa.name).expect("same part names");
        // The same solid: the same exact volume, from the two meshes.
        assert_eq!(
            pa.volume_units(ga),
            pb.volume_units(gb),
            "{tag} {}",
            pa.name
        );
        // The pieces make up the input part exactly.
        let sum = pb.pieces.iter().fold(Rational::zero(), |s, p| {
            &s + &volume_in_units(&p.volume(), gb)
        });
        assert_eq!(sum, pa.volume_units(ga), "{tag} {}", pa.name);
        // The same pieces as the decomposer made from the input.
        let mut ka: Vec<_> = pa.pieces.iter().map(|p| piece_key(p, ga)).collect();
        let mut kb: Vec<_> = pb.pieces.iter().map(|p| piece_key(p, gb)).collect();
        ka.sort();
        kb.sort();
        assert_eq!(ka, kb, "{tag} {}", pa.name);
        if pb.declared_pieces {
            written += 1;
        }
        // Pieces off the grid are never declared (they could not be written exactly).
        let off_grid = pa.pieces.iter().any(|p| *p.den() != Int::ONE);
        assert_eq!(
            pb.declared_pieces, !off_grid,
            "{tag} {}: {manifest}",
            pa.name
        );
    }
    written
}

fn write_case(tag: &str, parts: &[(&str, String)]) -> Scratch {
    let dir = folder(tag);
    for (name, off) in parts {
        std::fs::write(dir.join(format!("{name}.off")), off).unwrap();
    }
    dir
}

#[test]
fn integer_input_with_pieces_off_the_grid() {
    let dir = write_case(
        "int",
        &[
            ("notched", prism(&NOTCHED, 0, 3, 1.0)),
            ("box", prism(&BOX, 0, 3, 1.0)),
        ],
    );
    // The notched block's pieces have the vertex (8/3, 0, z): it is written as its mesh.
    let l = load_all(&dir);
    let notched = l.assembly.part("notched").unwrap();
    assert!(notched.pieces.iter().any(|p| *p.den() != Int::ONE));
    assert_eq!(round_trip(&dir, "int"), 1);
}

#[test]
fn integer_input_with_pieces_on_the_grid() {
    let dir = write_case(
        "int-ell",
        &[
            ("ell", prism(&ELL, 0, 3, 1.0)),
            ("box", prism(&BOX, 0, 3, 1.0)),
        ],
    );
    assert_eq!(round_trip(&dir, "int-ell"), 2);
}

#[test]
fn rational_input_decimals() {
    // Tenths are not binary fractions: every coordinate snaps to the grid on load.
    let dir = write_case(
        "dec",
        &[
            ("notched", prism(&NOTCHED, 0, 3, 0.1)),
            ("ell", {
                let moved: Vec<[i64; 2]> = ELL.iter().map(|p| [p[0], p[1] + 6]).collect();
                prism(&moved, 0, 3, 0.1)
            }),
            ("box", prism(&BOX, 0, 3, 0.1)),
        ],
    );
    assert_eq!(round_trip(&dir, "dec"), 2);
}

#[test]
fn float_input_tessellated_pin_in_a_hole() {
    // cos and sin of multiples of 2π/16: doubles with every bit used.
    let dir = folder("float");
    curved::write_off_dir(&curved::pin_in_hole(16, 16, 0.0), &dir).unwrap();
    round_trip(&dir, "float");
}

#[test]
fn the_shipped_tray_round_trips() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/tray-of-cubes");
    assert_eq!(round_trip(&dir, "tray"), 20);
}
