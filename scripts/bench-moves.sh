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
echo "| example | parts | known level | level found | complete | states | plan s | wall s | peak MiB |"
echo "|---|---:|---:|---|---|---:|---:|---:|---:|"
for e in l-slot keyhole drawer diagonal-two-move; do
  want=$(python3 -c "import json; print(json.load(open('examples/$e/expected.json'))['level'])")
  row "$e" 2 "" "$want" "examples/$e" | sed 's/^| \([^|]*\)| 2 |  |/| \1| 2 |/'
done
