//! A bolted joint of five coaxial parts, each tessellated with its own number of
//! segments, as CAD exports of real joints are: a bolt through two plates, a washer and
//! a nut.

use crate::curved::{lathe, NamedSoup};

/// The bolt's shaft radius; the holes of the plates, washer and nut have the same
/// radius, so every tessellation with another segment count interpenetrates the shaft
/// (by at most `SHAFT_RADIUS · (1 − cos(π/n))` for the coarser `n`).
pub const SHAFT_RADIUS: f64 = 2.0;

/// Five parts along the z axis, `segments[k]` segments for part `k` in the order
/// bolt, lower plate, upper plate, washer, nut:
///
/// - `"bolt"`: head of radius 6 (z from −2 to 0), shaft of radius 2 up to z = 12;
/// - `"plate_a"`: a disc of radius 10 with the shaft's hole, z from 0 to 4;
/// - `"plate_b"`: the same, z from 4 to 8;
/// - `"washer"`: radii 2 to 4, z from 8 to 9;
/// - `"nut"`: radii 2 to 5, z from 9 to 12.
///
/// Each rests on the one below (the lower plate on the bolt's head). Known answer: once
/// the overlaps at the shaft are accepted by a tolerance, the parts come apart one at a
/// time along the axis, top first: nut, washer, upper plate, lower plate up (+z), or the
/// bolt down (−z) out of whatever is left; nothing comes apart sideways.
pub fn bolted_joint(segments: [usize; 5]) -> Vec<NamedSoup> {
    let r = SHAFT_RADIUS;
    let sleeve = |r_out: f64, z0: f64, z1: f64, n: usize| {
        lathe(&[[r, z0], [r_out, z0], [r_out, z1], [r, z1]], n, 0.0)
    };
    vec![
        (
            "bolt".into(),
            lathe(
                &[
                    [0.0, -2.0],
                    [6.0, -2.0],
                    [6.0, 0.0],
                    [r, 0.0],
                    [r, 12.0],
                    [0.0, 12.0],
                ],
                segments[0],
                0.0,
            ),
        ),
        ("plate_a".into(), sleeve(10.0, 0.0, 4.0, segments[1])),
        ("plate_b".into(), sleeve(10.0, 4.0, 8.0, segments[2])),
        ("washer".into(), sleeve(4.0, 8.0, 9.0, segments[3])),
        ("nut".into(), sleeve(5.0, 9.0, 12.0, segments[4])),
    ]
}
