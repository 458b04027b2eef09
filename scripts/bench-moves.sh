#!/usr/bin/env bash
# Whole-process time and peak memory of `apart disassemble`: the voxel puzzles of
# apart-testkit's benchmark fixture (4 to 8 pieces in boxes up to 6x6x6, levels 2 to
# 10, each level computed by the brute-force oracle) with --axes, then the off-grid
# examples, as markdown tables for BENCHMARKS.md. A row says whether the level found
# is the oracle's.
#
#   scripts/bench-moves.sh [TIMEOUT_SECONDS]
#
# Each row runs once (the machine is shared: repeat for stable figures). Needs GNU time.
set -uo pipefail
cd "$(dirname "$0")/.."
limit="${1:-120}"
cargo build --release -q && cargo build --release -q -p apart-testkit --example write_bench_puzzles || exit 1
apart=target/release/apart
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
target/release/examples/write_bench_puzzles "$work" >"$work/list.txt"

row() { # name pieces box expected-level dir flags...
  local name=$1 pieces=$2 box=$3 want=$4 dir=$5
  shift 5
  /usr/bin/time -f "%e %M" -o "$work/time.txt" timeout "$limit" "$apart" disassemble --json "$@" "$dir" >"$work/out.json" 2>"$work/err.txt"
  local rc=$?
  read -r wall kb < <(tail -n 1 "$work/time.txt" 2>/dev/null) || true
  [ "$rc" = 124 ] && wall="> $limit (timed out)"
  python3 - "$work/out.json" "$name" "$pieces" "$box" "$want" "$wall" "${kb:-0}" <<'PY'
import json, sys
out, name, pieces, box, want, wall, kb = sys.argv[1:]
try:
    a = json.load(open(out))
except Exception:
    print(f"| {name} | {pieces} | {box} | {want} | not solved | | | | {wall} | {int(kb) // 1024} |")
    sys.exit()
lvl = a["level"]
ok = "yes" if str(lvl) == want else "no"
s = a["stats"]["seconds"]
print(f"| {name} | {pieces} | {box} | {want} | {lvl} ({ok}) | {'yes' if a['complete'] else 'no'} | {a['states_explored']} "
      f"| {s['obstacles'] + s['search']:.3f} | {wall} | {int(kb) // 1024} |")
PY
}

echo "| puzzle | pieces | box | oracle level | level found | complete | states | plan s | wall s | peak MiB |"
echo "|---|---:|---|---:|---|---|---:|---:|---:|---:|"
while read -r dir pieces box level; do
  row "$(basename "$dir")" "$pieces" "$box" "$level" "$dir" --axes
done <"$work/list.txt"
echo
# Exhaustive searches: unit cubes shut in a closed box (every arrangement of them in the
# 4x4x4 cavity is reachable and none separates: C(64, k) states, congruent cubes
# interchangeable).
python3 - "$work" <<'PY'
import json, os, sys
def box(lo, hi):
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    f = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return "OFF\n8 6 0\n" + "".join(f"{a} {b} {c}\n" for a, b, c in v) + "".join(f"4 {a} {b} {c} {d}\n" for a, b, c, d in f)
for k in (2, 3, 4):
    d = os.path.join(sys.argv[1], f"cubes-in-box-{k}")
    os.makedirs(os.path.join(d, "frame"), exist_ok=True)
    n = 6
    slabs = [((0, 0, 0), (n, n, 1)), ((0, 0, n - 1), (n, n, n)), ((0, 0, 1), (n, 1, n - 1)),
             ((0, n - 1, 1), (n, n, n - 1)), ((0, 1, 1), (1, n - 1, n - 1)), ((n - 1, 1, 1), (n, n - 1, n - 1))]
    for i, (lo, hi) in enumerate(slabs):
        open(os.path.join(d, "frame", f"s{i}.off"), "w").write(box([10 * c for c in lo], [10 * c for c in hi]))
    parts = [{"name": "frame", "pieces": [f"frame/s{i}.off" for i in range(6)]}]
    for i in range(k):
        open(os.path.join(d, f"c{i}.off"), "w").write(box([10 * (1 + i), 10, 10], [10 * (2 + i), 20, 20]))
        parts.append({"name": f"c{i}", "mesh": f"c{i}.off"})
    json.dump({"name": f"cubes-in-box-{k}", "parts": parts}, open(os.path.join(d, "assembly.json"), "w"))
PY
echo "| exhaustive search | parts | states (C(64, k)) | verdict | search s | wall s | peak MiB |"
echo "|---|---:|---:|---|---:|---:|---:|"
for k in 2 3 4; do
  d="$work/cubes-in-box-$k"
  /usr/bin/time -f "%e %M" -o "$work/time.txt" timeout "$limit" "$apart" disassemble --json --axes "$d" >"$work/out.json" 2>/dev/null
  read -r wall kb < <(tail -n 1 "$work/time.txt" 2>/dev/null) || true
  python3 - "$work/out.json" "$k" "$wall" "${kb:-0}" <<'PY'
import json, sys
out, k, wall, kb = sys.argv[1:]
try:
    a = json.load(open(out))
except Exception:
    print(f"| cubes-in-box-{k} | {int(k) + 1} | | timed out | | {wall} | {int(kb) // 1024} |")
    sys.exit()
v = "exhaustive" if a["searches"][0]["end"] == "interlocked" else a["searches"][0]["end"]
print(f"| cubes-in-box-{k} | {int(k) + 1} | {a['states_explored']} | {v} | {a['stats']['seconds']['search']:.2f} | {wall} | {int(kb) // 1024} |")
PY
done
echo
echo "| example | parts | known level | level found | complete | states | plan s | wall s | peak MiB |"
echo "|---|---:|---:|---|---|---:|---:|---:|---:|"
for e in l-slot keyhole drawer diagonal-two-move; do
  want=$(python3 -c "import json; print(json.load(open('examples/$e/expected.json'))['level'])")
  row "$e" 2 "" "$want" "examples/$e" | sed 's/^| \([^|]*\)| 2 |  |/| \1| 2 |/'
done
