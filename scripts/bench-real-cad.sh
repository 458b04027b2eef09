#!/usr/bin/env bash
# Whole-process times and peak memory of the CLI on generated tessellated CAD-like
# assemblies (apart-testkit's write_curved), as a markdown table for BENCHMARKS.md.
#
#   scripts/bench-real-cad.sh [TIMEOUT_SECONDS] [MEMORY_LIMIT_GIB]
#
# Each row runs one command once (the machine is shared: repeat for stable figures);
# a run past the timeout (default 300 s) or the address-space limit (default 8 GiB) is
# reported as such. Needs /usr/bin/time (GNU time).
set -uo pipefail
cd "$(dirname "$0")/.."
limit="${1:-300}"
mem_gib="${2:-8}"
cargo build --release -q && cargo build --release -q -p apart-testkit --example write_curved || exit 1
apart=target/release/apart
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| assembly | triangles | command | wall s | peak MiB | phases (ms) |"
echo "|---|---:|---|---:|---:|---|"
row() { # name spec command...
  local name=$1 spec=$2; shift 2
  local dir="$work/$name"
  [ -d "$dir" ] || target/release/examples/write_curved "$spec" "$dir" >"$work/tri.txt"
  local tris
  tris=$(awk '{print $1}' "$work/tri.txt")
  (ulimit -v $((mem_gib * 1024 * 1024)) && exec /usr/bin/time -f "%e %M" -o "$work/time.txt" timeout "$limit" "$apart" "$@" "$dir") >"$work/out.txt" 2>&1
  local rc=$?
  local wall="?" kb=0
  read -r wall kb < <(tail -n 1 "$work/time.txt" 2>/dev/null) || true
  case "$kb" in ''|*[!0-9]*) kb=0 ;; esac
  local phases
  phases=$(grep -h '^time:' "$work/out.txt" | sed 's/^time: //; s/ ms//g' | head -1)
  if [ "$rc" = 124 ]; then wall="> $limit (timed out)"; fi
  if grep -q "memory allocation\|out of memory" "$work/out.txt"; then wall="$wall (out of memory at the ${mem_gib} GiB limit)"; fi
  printf '| %s | %s | `%s` | %s | %.0f | %s |\n' "$name" "$tris" "$*" "$wall" "$((kb / 1024))" "$phases"
}
row pin-64 pin:64 check
row pin-64 pin:64 partition
row plug-2k plug:2000 partition
row plug-20k plug:20000 check
row plug-20k plug:20000 partition --direction 0,0,1
row plug-20k plug:20000 partition --first
row plug-20k plug:20000 partition
row nut-64 nut:64 partition
row joint-same-5k joint-same:128 sequence
row joint-5k joint:128 sequence --tolerance auto
row joint-5k joint:128 sequence --first --tolerance auto
row joint-50k joint:1250 sequence --tolerance auto
row joint-50k joint:1250 sequence --first --tolerance auto
row rack-4 rack:4 partition
row rack-4 rack:4 sequence
row rack-4 rack:4 sequence --first
