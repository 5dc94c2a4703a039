#!/usr/bin/env bash
# Instruction counts of the gungraun benches (benches/benches/instructions.rs) against the committed baseline
# benches/baselines/instructions.json: fails when a count grew by more than the baseline's tolerance (2 %).
#
#   scripts/instructions-check.sh            run the benches and compare
#   scripts/instructions-check.sh --update   run the benches and rewrite the baseline
#
# Needs valgrind and gungraun-runner 0.20.0 (`cargo install gungraun-runner --version 0.20.0 --locked`).
# Counts are deterministic on one machine and toolchain; the baseline records rustc and valgrind versions.
set -euo pipefail
cd "$(dirname "$0")/.."

runner_version=0.20.0
command -v valgrind >/dev/null || { echo "error: valgrind is not installed" >&2; exit 1; }
if ! gungraun-runner --version 2>/dev/null | grep -qF "$runner_version"; then
  echo "error: gungraun-runner $runner_version is not on PATH" >&2
  echo "       cargo install gungraun-runner --version $runner_version --locked" >&2
  exit 1
fi

target_dir=$(cargo metadata --format-version 1 --no-deps | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
counts="$target_dir/instructions-counts.jsonl"
mkdir -p "$target_dir"
cargo bench -p benches --bench instructions -- --output-format=json >"$counts"
cargo run --release -q -p benches --example instructions_check -- benches/baselines/instructions.json "$counts" "$@"
