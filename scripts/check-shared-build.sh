#!/usr/bin/env bash
# Checks that the README's two commands share one build: after the binary's build
# (`cargo run --release` builds exactly this), `cargo test --workspace --release`
# must compile only what tests add (test-only crates, test harnesses, examples) and
# reuse every library and binary the first build made (the same files, not copies). A test-only dependency that
# turns on a feature of a shared crate (a different feature set is a different
# artifact) makes it compile that crate and every crate above it a second time; this
# names them.
#
#   scripts/check-shared-build.sh
#
# Uses the normal target folder (`CARGO_TARGET_DIR` if set). Exit code 0 when nothing
# is compiled twice, 1 otherwise. Needs Python 3 for the JSON of cargo's messages.
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cargo build --release --locked --message-format=json >"$work/bin.json"
cargo test --workspace --release --locked --no-run --message-format=json >"$work/test.json"

python3 - "$work/bin.json" "$work/test.json" <<'EOF'
import json, sys

def artifacts(path):
    for line in open(path):
        if line.startswith("{"):
            m = json.loads(line)
            if m.get("reason") == "compiler-artifact":
                yield m

# The binary's build: its packages and the files it made (their names carry a hash of
# the features and dependencies, so a warm target folder holding both variants still
# tells them apart).
binary, files = set(), set()
for m in artifacts(sys.argv[1]):
    binary.add(m["package_id"])
    files.update(m["filenames"])
twice = []
for m in artifacts(sys.argv[2]):
    kinds = set(m["target"]["kind"])
    if m["profile"]["test"] or m["package_id"] not in binary:
        continue
    if kinds & {"example", "test", "bench"} or files.intersection(m["filenames"]):
        continue
    name = m["package_id"].split("#")[-1]
    feats = ",".join(m["features"]) or "no features"
    twice.append(f"  {name} {m['target']['name']} ({'/'.join(sorted(kinds))}; {feats})")
if twice:
    print("built a second time by `cargo test --workspace --release` (other features")
    print("than in the binary's build, or a dependency built a second time):")
    print("\n".join(sorted(twice)))
    print("find the feature with: cargo tree -e features -i CRATE (and --workspace)")
    sys.exit(1)
print(f"one shared build: the test build compiled none of the binary's "
      f"{len(binary)} packages again")
EOF
