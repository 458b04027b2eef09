#!/usr/bin/env bash
# Time and peak memory of `apart sequence` (and `partition --first`) against the part
# count, on generated assemblies: racks of pins in blocks under a plate
# (`write_curved rack:N`, 2 N² + 1 parts) and lattices of touching unit cubes
# (`write_curved cubes:N`, N³ parts). Prints a table (markdown) and writes the rows as
# CSV for scripts/plot-scale.py.
#
#   scripts/bench-scale.sh OUT.csv [BASELINE_BINARY] [TIMEOUT_SECONDS]
#
# With a baseline binary (an earlier build of apart) every row is run with both, one
# after the other. Each run is bounded by the timeout (default 300 s) and by 8 GiB of
# memory (`--max-memory 8G` for builds that know a default budget, and an address-space
# limit of 12 GiB for the rest); a run past either is reported as such. Needs GNU time.
set -uo pipefail
cd "$(dirname "$0")/.."
csv=${1:?usage: scripts/bench-scale.sh OUT.csv [BASELINE_BINARY] [TIMEOUT_SECONDS]}
baseline=${2:-}
limit=${3:-300}
cargo build --release -q && cargo build --release -q -p apart-testkit --example write_curved || exit 1
apart=target/release/apart
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "binary,kind,n,parts,command,seconds,peak_mib,status" >"$csv"
echo "| binary | assembly | parts | command | wall s | peak MiB | status |"
echo "|---|---|---:|---|---:|---:|---|"
run() { # label binary kind n command...
  local label=$1 bin=$2 kind=$3 n=$4
  shift 4
  local dir="$work/$kind-$n"
  [ -d "$dir" ] || target/release/examples/write_curved "$kind:$n" "$dir" >/dev/null
  local parts
  parts=$(find "$dir" -name '*.off' | wc -l)
  (ulimit -v $((12 * 1024 * 1024)) && exec /usr/bin/time -f "%e %M" -o "$work/time.txt" \
    timeout "$limit" "$bin" "$@" "$dir" --quiet) >/dev/null 2>"$work/err.txt"
  local rc=$?
  local wall kb status=ok
  read -r wall kb < <(tail -n 1 "$work/time.txt" 2>/dev/null) || true
  case "$kb" in '' | *[!0-9]*) kb=0 ;; esac
  case "$wall" in '' | *[!0-9.]*) wall=0 ;; esac
  if [ "$rc" = 124 ]; then status="timeout ${limit} s"; fi
  if grep -q "memory allocation\|out of memory" "$work/err.txt"; then status="out of memory"; fi
  if [ "$rc" != 0 ] && [ "$rc" != 124 ] && [ "$status" = ok ]; then status="exit $rc"; fi
  printf '| %s | %s:%s | %s | `%s` | %s | %d | %s |\n' "$label" "$kind" "$n" "$parts" "$*" "$wall" "$((kb / 1024))" "$status"
  echo "$label,$kind,$n,$parts,$*,$wall,$((kb / 1024)),$status" >>"$csv"
}
# The kinds on which the baseline already ran out of time or memory: it is not run on
# their larger sizes.
gave_up=" "
both() { # kind n command...
  run new "$apart" "$@"
  if [ -n "$baseline" ]; then
    case "$gave_up" in
      *" $1 "*) echo "| baseline | $1:$2 | | \`$3\` | | | not run (a smaller one did not finish) |" ;;
      *)
        run baseline "$baseline" "$@"
        case "$(tail -n 1 "$csv")" in *,ok) ;; *) gave_up="$gave_up$1 " ;; esac
        ;;
    esac
  fi
}
for n in 4 6 8 10 12 14 16; do both rack "$n" sequence; done
for n in 4 6 8 10 12; do both cubes "$n" sequence; done
for n in 10 20; do run new "$apart" cubes "$n" partition --first; done
run new "$apart" cubes 20 sequence
