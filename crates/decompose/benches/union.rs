//! Union-solid benchmark: self-crossing surfaces (shells that cross each other) and, for
//! comparison, valid solids; prints a markdown table (best of several runs).

use apart_decompose::{decompose, decompose_union, Decomposition, Options};
use apart_kernel::predicates::det3_sign;
use apart_kernel::{Rational, Sign, Vec3};
use apart_testkit::shapes;
use std::time::Instant;

struct Soup {
    name: String,
    points: Vec<Vec3>,
    raw: Vec<[i64; 3]>,
    tris: Vec<[u32; 3]>,
}

impl Soup {
    fn new(name: &str) -> Soup {
        Soup {
            name: name.into(),
            points: vec![],
            raw: vec![],
            tris: vec![],
        }
    }

    /// Adds a shape's triangles (fresh point indices), its points mapped by `f`.
    fn add(&mut self, s: &shapes::Shape, f: impl Fn([i64; 3]) -> [i64; 3]) {
        let base = self.points.len() as u32;
        for p in &s.points {
            let q = f(*p);
            self.points.push(Vec3::from_i64(q));
            self.raw.push(q);
        }
        self.tris.extend(s.tris.iter().map(|t| t.map(|v| v + base)));
    }

    fn cuboid(&mut self, lo: [i64; 3], hi: [i64; 3]) {
        let s = shapes::rectilinear(
            "box",
            [&[lo[0], hi[0]], &[lo[1], hi[1]], &[lo[2], hi[2]]],
            |_| true,
            None,
        );
        self.add(&s, |p| p);
    }

    fn bbox(&self) -> [[i64; 3]; 2] {
        bounds(self.raw.iter())
    }

    /// Pairs of triangles sharing no point index where an edge of one passes through
    /// the other's relative interior, crossing its plane (exact; for reporting only).
    fn crossing_pairs(&self) -> usize {
        let n = self.tris.len();
        let bb: Vec<[[i64; 3]; 2]> = self
            .tris
            .iter()
            .map(|t| bounds(t.iter().map(|&v| &self.raw[v as usize])))
            .collect();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&i| bb[i][0][0]);
        let pierces = |t: &[u32; 3], p: &Vec3, q: &Vec3| -> bool {
            let [a, b, c] = t.map(|v| &self.points[v as usize]);
            let s1 = det3_sign(&b.sub(a), &c.sub(a), &p.sub(a));
            let s2 = det3_sign(&b.sub(a), &c.sub(a), &q.sub(a));
            if s1 * s2 != Sign::Negative {
                return false;
            }
            let d = q.sub(p);
            let e = [
                det3_sign(&a.sub(p), &b.sub(p), &d),
                det3_sign(&b.sub(p), &c.sub(p), &d),
                det3_sign(&c.sub(p), &a.sub(p), &d),
            ];
            e[0] != Sign::Zero && e[0] == e[1] && e[1] == e[2]
        };
        let mut count = 0;
        for (x, &i) in order.iter().enumerate() {
            for &j in &order[x + 1..] {
                if bb[j][0][0] > bb[i][1][0] {
                    break;
                }
                if !(0..3).all(|a| bb[i][0][a] <= bb[j][1][a] && bb[j][0][a] <= bb[i][1][a]) {
                    continue;
                }
                let (ti, tj) = (self.tris[i], self.tris[j]);
                if ti.iter().any(|v| tj.contains(v)) {
                    continue;
                }
                let edge = |t: &[u32; 3], k: usize| {
                    (
                        &self.points[t[k] as usize],
                        &self.points[t[(k + 1) % 3] as usize],
                    )
                };
                if (0..3).any(|k| {
                    let (p, q) = edge(&tj, k);
                    pierces(&ti, p, q)
                }) || (0..3).any(|k| {
                    let (p, q) = edge(&ti, k);
                    pierces(&tj, p, q)
                }) {
                    count += 1;
                }
            }
        }
        count
    }
}

/// The bounding box of some points.
fn bounds<'a>(pts: impl Iterator<Item = &'a [i64; 3]>) -> [[i64; 3]; 2] {
    let mut b = [[i64::MAX; 3], [i64::MIN; 3]];
    for p in pts {
        for (a, &c) in p.iter().enumerate() {
            b[0][a] = b[0][a].min(c);
            b[1][a] = b[1][a].max(c);
        }
    }
    b
}

fn best_of(s: &Soup, opts: &Options, runs: usize, union: bool) -> (Decomposition, f64) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        let d = if union {
            decompose_union(&s.points, &s.tris, opts).expect("decompose_union")
        } else {
            decompose(&s.points, &s.tris, opts).expect("decompose")
        };
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(d);
    }
    (last.unwrap(), best)
}

fn volume(d: &Decomposition) -> f64 {
    let mut v = Rational::zero();
    for p in &d.pieces {
        v = &v + &p.volume();
    }
    v.to_f64()
}

fn row(s: &Soup, valid: bool) {
    let seq = Options {
        parallel: false,
        ..Options::default()
    };
    let par = Options::default();
    let runs = if s.tris.len() > 5000 { 2 } else { 5 };
    let (d, ts) = best_of(s, &seq, runs, true);
    let (_, tp) = best_of(s, &par, runs, true);
    let reference = if valid {
        let (r, t) = best_of(s, &par, runs, false);
        assert_eq!(volume(&r), volume(&d));
        format!("{} pieces, {:.1} ms", r.pieces.len(), t * 1e3)
    } else {
        "–".into()
    };
    let (lo, hi) = d.stats.winding.unwrap();
    println!(
        "| {} | {} | {} | {lo}..{hi} | {} | {} | {} | {:.1} | {:.1} | {} |",
        s.name,
        s.tris.len(),
        s.crossing_pairs(),
        d.stats.cells,
        d.stats.partition_pieces,
        d.pieces.len(),
        ts * 1e3,
        tp * 1e3,
        reference
    );
}

fn main() {
    let mut seed = 12345u64;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        seed >> 33
    };
    println!("| surface | triangles | crossing pairs | winding | cells | kept cells | pieces | sequential ms | parallel ms | decompose (valid solids) |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let ring = shapes::Ring::new(64).shape();
    let mut r = Soup::new("ring (64 x 16-gon), valid");
    r.add(&ring, |p| p);
    let [lo, hi] = r.bbox();
    row(&r, true);
    let w = hi[0] - lo[0];
    let mut two = Soup::new("two crossing rings, shifted by 0.3 width");
    two.add(&ring, |p| p);
    two.add(&ring, |p| [p[0] + 3 * w / 10, p[1] + w / 7, p[2]]);
    row(&two, false);
    let mut linked = Soup::new("two linked rings (not touching)");
    linked.add(&ring, |p| p);
    linked.add(&ring, |p| [p[0] + w / 3, -p[2], p[1]]);
    row(&linked, true);
    let mut bars = Soup::new("ring crossed by 8 random bars");
    bars.add(&ring, |p| p);
    let th = hi[2] - lo[2];
    for _ in 0..8 {
        let c = [0, 1].map(|a| lo[a] + (next() as i64 % (hi[a] - lo[a])));
        let (along, across) = if next() % 2 == 0 { (0, 1) } else { (1, 0) };
        let mut blo = [0; 3];
        let mut bhi = [0; 3];
        blo[along] = lo[along] - 10;
        bhi[along] = hi[along] + 10;
        blo[across] = c[across] - w / 20;
        bhi[across] = c[across] + w / 20;
        blo[2] = lo[2] + th / 4;
        bhi[2] = hi[2] - th / 4;
        bars.cuboid(blo, bhi);
    }
    row(&bars, false);
    let on: Vec<bool> = (0..10 * 10 * 6).map(|_| next() % 2 == 0).collect();
    let vox = shapes::voxels([10, 10, 6], &on);
    let mut v = Soup::new("voxels 10 x 10 x 6, valid");
    v.add(&vox, |p| [p[0] * 6, p[1] * 6, p[2] * 6]);
    row(&v, true);
    let mut vb = Soup::new("voxels 10 x 10 x 6 + 12 random boxes");
    vb.add(&vox, |p| [p[0] * 6, p[1] * 6, p[2] * 6]);
    for _ in 0..12 {
        let a = [0, 1, 2].map(|k| 1 + next() as i64 % [50, 50, 25][k]);
        let b = [0, 1, 2].map(|_| 5 + next() as i64 % 20);
        vb.cuboid(a, [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
    }
    row(&vb, false);
    let h: Vec<i64> = (0..21 * 21).map(|_| 2000 + next() as i64 % 3000).collect();
    let terrain = shapes::terrain(20, 1000, &h);
    let mut t = Soup::new("terrain 20 x 20, valid");
    t.add(&terrain, |p| p);
    row(&t, true);
    let mut tp = Soup::new("terrain 20 x 20 + 16 posts through its top");
    tp.add(&terrain, |p| p);
    for _ in 0..16 {
        let x = 500 + next() as i64 % 18000;
        let y = 500 + next() as i64 % 18000;
        tp.cuboid([x, y, 1000], [x + 700, y + 900, 6000]);
    }
    row(&tp, false);
    let mut tt = Soup::new("two crossing terrains 20 x 20");
    tt.add(&terrain, |p| p);
    tt.add(&terrain, |p| {
        [
            p[0] + 3100,
            p[1] + 4700,
            p[2] + if p[2] > 0 { 400 } else { 0 },
        ]
    });
    row(&tt, false);
    println!();
    println!("Scaling:");
    println!();
    println!("| surface | triangles | crossing pairs | winding | cells | kept cells | pieces | sequential ms | parallel ms | decompose (valid solids) |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let big = shapes::Ring::with_section(256, 1105, 40, 5 * 13 * 17 * 29 * 37).shape();
    let mut r = Soup::new("ring (256 x 32-gon), valid");
    r.add(&big, |p| p);
    row(&r, true);
    let [lo, hi] = r.bbox();
    let w = hi[0] - lo[0];
    let mut two = Soup::new("two crossing rings (256 x 32-gon)");
    two.add(&big, |p| p);
    two.add(&big, |p| [p[0] + 3 * w / 10, p[1] + w / 7, p[2]]);
    row(&two, false);
}
