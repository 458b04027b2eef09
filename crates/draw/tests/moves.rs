//! Pictures of a plan of moves: a key in an L-shaped slot of a frame must slide along
//! the slot (a finite move) before it lifts out (a move to infinity).

mod common;

use apart_assembly::Assembly;
use apart_draw::{moves_glb, moves_html, moves_svg, Keyframes};
use apart_plan::{disassemble, parts_of, MoveOptions, MovePlan, Progress};
use gltf::animation::util::ReadOutputs;

/// The frame (a 3 × 4 × 3 block of cells of size 2 less the slot) and the key (one
/// cell at the slot's bottom end), and its plan.
fn key_in_slot() -> (Assembly, MovePlan) {
    let slot = [[1, 1, 1], [1, 2, 1], [1, 2, 2]];
    let cell = |c: [i64; 3]| common::cuboid(c.map(|v| 2 * v), c.map(|v| 2 * v + 2));
    let frame: Vec<_> = (0..36)
        .map(|i| [i % 3, i / 3 % 4, i / 12])
        .filter(|c| !slot.contains(c))
        .map(cell)
        .collect();
    let a = common::assembly_of(
        "key-in-slot",
        vec![
            common::part("frame", frame),
            common::part("key", vec![cell([1, 1, 1])]),
        ],
    );
    let plan = disassemble(
        parts_of(&a).unwrap(),
        &MoveOptions::default(),
        &Progress::new(),
    )
    .unwrap();
    assert_eq!(plan.level, Some(2), "{plan:#?}");
    assert!(plan.complete);
    (a, plan)
}

/// The JSON embedded in the page.
fn embedded(html: &str) -> serde_json::Value {
    let start = html
        .find(r#"<script id="data" type="application/json">"#)
        .unwrap();
    let rest = &html[start..];
    let body = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    serde_json::from_str(body).unwrap()
}

/// The keyframes the exports play (moves to infinity: 1.5 diagonals).
fn frames(a: &Assembly, plan: &MovePlan) -> Keyframes {
    Keyframes::of_moves(plan, 2, a.grid.step(), 1.5 * common::diagonal(a))
}

#[test]
fn a_finite_move_is_played_by_its_exact_translation() {
    let (a, plan) = key_in_slot();
    let f = frames(&a, &plan);
    assert_eq!(f.steps(), plan.moves.len());
    assert_eq!(f.offsets.len(), plan.moves.len() + 1);
    let mut finite = 0;
    for (k, mv) in plan.moves.iter().enumerate() {
        assert_eq!(f.moving[k], mv.moving);
        let Some(t) = &mv.distance else { continue };
        finite += 1;
        // Nothing went to infinity before: the offset is the plan's, in input units,
        // and the step moved the moving parts by exactly distance × direction.
        for (p, o) in &mv.offsets {
            let want = o.clone().map(|c| c.to_f64() * a.grid.step());
            assert_eq!(f.offsets[k + 1][*p], want);
        }
        for &p in &mv.moving {
            for c in 0..3 {
                let d = apart_kernel::int::to_f64(&mv.direction.get(c));
                let moved = f.offsets[k + 1][p][c] - f.offsets[k][p][c];
                assert!((moved - t.to_f64() * d * a.grid.step()).abs() < 1e-12);
            }
        }
    }
    assert!(finite >= 1, "the key slides first: {plan:#?}");
    // The last move takes the key out by 1.5 diagonals; the frame never moved.
    let last = plan.moves.last().unwrap();
    assert!(last.distance.is_none());
    let (before, after) = (
        &f.offsets[plan.moves.len() - 1],
        &f.offsets[plan.moves.len()],
    );
    let out: f64 = (0..3)
        .map(|c| (after[1][c] - before[1][c]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!((out - 1.5 * common::diagonal(&a)).abs() < 1e-9);
    assert!(f.offsets.iter().all(|o| o[0] == [0.0; 3]));
}

#[test]
fn the_page_lists_every_move_and_plays_the_keyframes() {
    let (a, plan) = key_in_slot();
    let html = moves_html(&a, &plan);
    let data = embedded(&html);
    let names: Vec<&str> = data["parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["frame", "key"]);
    let steps = data["steps"].as_array().unwrap();
    assert_eq!(steps.len(), plan.moves.len());
    for (s, mv) in steps.iter().zip(&plan.moves) {
        assert_eq!(s["moving"], serde_json::json!(mv.moving));
        let label = s["label"].as_str().unwrap();
        match &mv.distance {
            Some(t) => assert!(label.ends_with(&format!("by {t}")), "{label}"),
            None => assert!(label.ends_with("to infinity"), "{label}"),
        }
        assert!(
            s["note"]
                .as_str()
                .unwrap()
                .contains("first separation (level 2)"),
            "{s}"
        );
    }
    let want = frames(&a, &plan);
    let got: Vec<Vec<[f64; 3]>> = serde_json::from_value(data["frames"].clone()).unwrap();
    assert_eq!(got, want.offsets);
}

#[test]
fn the_glb_animates_the_keyframes() {
    let (a, plan) = key_in_slot();
    let bytes = moves_glb(&a, &plan);
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = blob.unwrap();
    assert_eq!(document.animations().count(), 1);
    let anim = document.animations().next().unwrap();
    assert_eq!(anim.channels().count(), 2);
    let want = frames(&a, &plan);
    for channel in anim.channels() {
        let p = channel.target().node().index() - 1;
        let reader = channel.reader(|_| Some(&blob[..]));
        let times: Vec<f32> = reader.read_inputs().unwrap().collect();
        let Some(ReadOutputs::Translations(out)) = reader.read_outputs() else {
            panic!("translation outputs");
        };
        let out: Vec<[f32; 3]> = out.collect();
        // Keys at each move's start and end (1 s of motion, 0.5 s of rest).
        assert_eq!(out.len(), 2 * plan.moves.len());
        for (k, v) in out.iter().enumerate() {
            let (frame, t) = (k.div_ceil(2), (k / 2) as f32 * 1.5 + (k % 2) as f32);
            assert_eq!(times[k], t);
            assert_eq!(
                *v,
                want.offsets[frame][p].map(|c| c as f32),
                "part {p} key {k}"
            );
        }
    }
}

#[test]
fn the_svg_has_a_panel_per_state_with_the_moving_part_lit() {
    let (a, plan) = key_in_slot();
    let svg = moves_svg(&a, &plan);
    let panels: Vec<&str> = svg.split(r#"<g class="panel""#).skip(1).collect();
    assert_eq!(panels.len(), plan.moves.len() + 1);
    assert!(panels[0].contains("Assembled"));
    let key = apart_draw::colors::part_colors(&["frame", "key"])[1].hex();
    for (k, mv) in plan.moves.iter().enumerate() {
        let panel = panels[k + 1];
        assert!(panel.contains(r#"data-moving="key""#), "{panel}");
        assert!(panel.contains(&format!(
            "move {} of 2 of the first separation (level 2)",
            k + 1
        )));
        // The key is in the legend in its colour; the frame is grey and see-through.
        assert!(panel.contains(&format!(r#"fill="{key}""#)));
        assert!(panel.contains("fill-opacity"));
        match &mv.distance {
            Some(t) => assert!(panel.contains(&format!("key {t} × (")), "{panel}"),
            None => assert!(panel.contains("key → ∞ along ("), "{panel}"),
        }
    }
    assert!(svg.contains("key-in-slot: disassembly by 2 moves, level 2"));
}
