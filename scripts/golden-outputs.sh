#!/usr/bin/env bash
# Write the JSON and pictures of the shipped examples into one folder, so that a
# refactoring can show they stay byte-identical: run it before and after, then
# `diff -r BEFORE AFTER`. Each command runs twice, with `--json` and as text. Timings
# (the "seconds" of the stats, the text's "time:" lines) are removed; everything else
# is kept as printed.
#
# usage: scripts/golden-outputs.sh OUT_DIR [APART_BINARY]
set -euo pipefail
out=${1:?usage: scripts/golden-outputs.sh OUT_DIR [APART_BINARY]}
bin=${2:-target/release/apart}
mkdir -p "$out"
ex=examples

strip() {
  python3 -c '
import json, sys
def clean(v):
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items() if k not in ("seconds", "elapsed", "phases")}
    if isinstance(v, list):
        return [clean(x) for x in v]
    return v
print(json.dumps(clean(json.load(sys.stdin)), indent=1, sort_keys=False))
'
}

run() { # name, then the arguments of apart
  local name=$1
  shift
  local code=0
  "$bin" --json -q "$@" >"$out/$name.raw" 2>"$out/$name.err" || code=$?
  echo "$code" >"$out/$name.exit"
  if strip <"$out/$name.raw" >"$out/$name.json" 2>/dev/null; then rm "$out/$name.raw"; fi
  code=0
  "$bin" "$@" >"$out/$name.txt" 2>"$out/$name.txt.err" || code=$?
  echo "$code" >"$out/$name.txt.exit"
  sed -i -E '/^ *time: /d; s/[0-9]+(\.[0-9]+)? (ms|s)\b/T/g' "$out/$name.txt" "$out/$name.txt.err"
  sed -i "s#$out#OUT#g" "$out/$name.txt" "$out/$name.txt.err" "$out/$name.err"
}

for a in split-star split-star-3 dovetail-and-cap hinge linked-rings peg-in-the-hole ring-and-cone tray-of-cubes cad-pin-in-hole cad-seams; do
  run "check-$a" check "$ex/$a"
  run "partition-$a" partition "$ex/$a" --all --svg "$out/partition-$a.svg" --png "$out/partition-$a.png"
  run "sequence-$a" sequence "$ex/$a" --svg "$out/sequence-$a.svg" --png "$out/sequence-$a.png"
done
run partition-dir-split-star partition "$ex/split-star" --direction 1,1,1
run partition-first-tray partition "$ex/tray-of-cubes" --first
run partition-tol-cad-pin partition "$ex/cad-pin-in-hole" --tolerance auto
run sequence-html-dovetail sequence "$ex/dovetail-and-cap" --html "$out/sequence-dovetail.html" --glb "$out/sequence-dovetail.glb"
run separate-dovetail separate "$ex/dovetail-and-cap" tenon slot
run separate-files separate "$ex/sheet-metal/cube.off" "$ex/sheet-metal/channel.off"
run place-cube place "$ex/sheet-metal/cube.off" "$ex/sheet-metal/cube.off" --svg "$out/place-cube.svg" --png "$out/place-cube.png"
run place-channel place "$ex/sheet-metal/channel.off" "$ex/sheet-metal/complex.off" --weight 0.5
run stack-channel stack "$ex/sheet-metal/channel.off" --count 15 --weight 0.5 --png "$out/stack-channel.png" --svg "$out/stack-channel.svg"
run stack-triangle stack "$ex/sheet-metal/triangle.off" --count 6
echo "wrote $(ls "$out" | wc -l) files to $out"
