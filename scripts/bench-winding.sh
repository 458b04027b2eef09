#!/usr/bin/env bash
# Whole-process time and peak memory of `apart check` on large soups that only the
# winding-number rule makes solid (apart-testkit's write_winding_scale: gears whose
# flanks cross at every root, threads of stacked crossing rings with open seams and
# slivers), as a markdown table for BENCHMARKS.md.
#
#   scripts/bench-winding.sh [TIMEOUT_SECONDS]
#
# Each row runs once (the machine is shared: repeat for stable figures). Needs GNU time.
set -uo pipefail
cd "$(dirname "$0")/.."
limit="${1:-300}"
cargo build --release -q && cargo build --release -q -p apart-testkit --example write_winding_scale || exit 1
apart=target/release/apart
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
target/release/examples/write_winding_scale "$work" >"$work/sizes.txt"

echo "| soup | triangles | crossing pairs | pieces | volume right | wall s | peak MiB |"
echo "|---|---:|---:|---:|---|---:|---:|"
while read -r line; do
  dir=${line%%:*}
  name=$(basename "$dir")
  tris=$(echo "$line" | sed 's/.*: \([0-9]*\) triangles.*/\1/')
  known=$(echo "$line" | sed 's/.*triangles, volume //')
  /usr/bin/time -f "%e %M" -o "$work/time.txt" timeout "$limit" "$apart" check --json "$dir" >"$work/out.json" 2>"$work/err.txt"
  rc=$?
  read -r wall kb < <(tail -n 1 "$work/time.txt" 2>/dev/null) || true
  [ "$rc" = 124 ] && wall="> $limit (timed out)"
  python3 - "$work/out.json" "$known" "$tris" "$name" "$wall" "${kb:-0}" "$work/err.txt" <<'PY'
import json, sys
out, known, tris, name, wall, kb, err = sys.argv[1:]
try:
    a = json.load(open(out))
except Exception:
    print(f"| {name} | {tris} | ? | ? | not loaded | {wall} | {int(kb) // 1024} |")
    sys.exit()
w = [w for r in a.get("repairs", []) for w in r.get("winding", [])]
part = a["parts"][0]
pairs = w[0]["crossing_pairs"] if w else 0
from fractions import Fraction
v = Fraction(part.get("volume", "0"))
if "Monte Carlo" in known:
    est, bound = [float(x) for x in known.replace("≈", "").split("(")[0].split("±")]
    right = ("yes" if abs(float(v) - est) <= bound else "no") + f" (Monte Carlo {est:.4e} ± {bound:.1e})"
else:
    right = "yes (exact)" if v == Fraction(known) else f"no ({v} vs {known})"
print(f"| {name} | {tris} | {pairs} | {part.get('pieces')} | {right} | {wall} | {int(kb) // 1024} |")
PY
done <"$work/sizes.txt"
