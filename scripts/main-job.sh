#!/usr/bin/env bash
# The main job: the benchmarks, then the verification matrix and the V&V report with them.
#
#   scripts/main-job.sh            # full sizes (work-precision at four mesh levels x three CFLs)
#   scripts/main-job.sh --quick    # the benchmarks at their small CI sizes; verify is the same
#
# Writes out/verification/ (results.json, junit.xml, index.html, report.md, ...) and
# out/verification/benchmarks/ (the impact-bench CSV, SVG and Markdown). Runs from any folder.
# Exit status: verify's (0 when every failing check is a declared known failure and none
# passes unexpectedly, 1 on an unexpected FAIL or an XPASS, 2 bad input), written after the
# report; when verify passes but the benchmarks failed (a stability run that blew up
# silently), the benchmarks' status, so a failure is never hidden. The report is written in
# both cases, with whatever the benchmarks managed to write. A build error stops at once.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

quick=()
if [[ "${1:-}" == "--quick" ]]; then
    quick=(--quick)
    shift
fi
if [[ $# -gt 0 ]]; then
    echo "usage: scripts/main-job.sh [--quick]" >&2
    exit 2
fi

out=out/verification
bench="$out/benchmarks"
rm -rf "$bench"   # no stale results from an earlier run in the report
mkdir -p "$bench"

# One optimised build of the binaries (the release profile, as `.ci/run`'s tests use), then
# run them from target/release. --workspace, not -p: a package selection can resolve the
# dependencies' features apart from `cargo test --workspace --release` and rebuild them.
echo "== build: impact-bench and impact (release)"
cargo build --release --workspace --bins
target_dir="$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')"

echo "== benchmarks: impact-bench all ${quick[*]:-} --out $bench"
bench_status=0
"$target_dir/release/impact-bench" all "${quick[@]}" --out "$bench" || bench_status=$?
if [[ $bench_status -ne 0 ]]; then
    echo "main-job: the benchmarks failed (status $bench_status); the report shows what they wrote" >&2
fi

echo "== verify: the matrix and the V&V report"
verify_status=0
"$target_dir/release/impact" verify --report --out "$out" --benchmarks "$bench" || verify_status=$?

echo "== report: $out/index.html, $out/report.md"
if [[ $verify_status -ne 0 ]]; then
    exit "$verify_status"
fi
exit "$bench_status"
