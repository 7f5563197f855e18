#!/usr/bin/env bash
# The main job: the benchmarks, the verification matrix and the V&V report with them.
#
#   scripts/main-job.sh            # full sizes (work-precision at four mesh levels x three CFLs)
#   scripts/main-job.sh --quick    # the benchmarks at their small CI sizes; verify is the same
#
# Writes out/verification/ (results.json, junit.xml, index.html, report.md, ...) and
# out/verification/benchmarks/ (the impact-bench CSV, SVG and Markdown). Runs from any folder.
# Order: first the untimed work side by side on the cores (the matrix, `impact verify` on
# impact and CalculiX, beside
# the stability benchmark and the work-precision references, `impact-bench references`), then
# the timed benchmarks alone (throughput, work-precision: nothing else of this job runs while
# they time), then the uncertainty studies (scripts/uq-study.py), then the report (`impact report`). The benchmarks' results are those of
# `impact-bench all`: work-precision reads the references this binary wrote (the same bits).
# Exit status: verify's (0 when every failing check is a declared known failure and none
# passes unexpectedly, 1 on an unexpected FAIL or an XPASS, 2 bad input), written after the
# report; when verify passes but the benchmarks failed (a stability run that blew up
# silently), the benchmarks' status, so a failure is never hidden; 2 when the report cannot be
# written. The report is written in both cases, with whatever the benchmarks managed to
# write. A build error stops at once.
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
# The venv (the independent Python FE the matrix compares with, the uncertainty studies) is set
# up beside the build, so that the matrix finds it on a fresh clone (mostly downloads: it
# costs the build little).
venv_log="$(mktemp)"
scripts/setup-venv.sh > "$venv_log" 2>&1 &
venv_pid=$!
echo "== build: impact-bench and impact (release), the venv beside it"
cargo build --release --workspace --bins
venv_status=0
wait "$venv_pid" || venv_status=$?
if [[ $venv_status -ne 0 ]]; then
    cat "$venv_log" >&2
    echo "main-job: scripts/setup-venv.sh failed (status $venv_status): the matrix's Python comparisons and the uncertainty studies will say so" >&2
fi
rm -f "$venv_log"
target_dir="$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')"

bench_bin="$target_dir/release/impact-bench"
bench_status=0
bench() { "$bench_bin" "$@" "${quick[@]}" --out "$bench" || { local s=$?; [[ $bench_status -ne 0 ]] || bench_status=$s; }; }

echo "== untimed, side by side: the matrix (impact verify), the stability benchmark and the work-precision references"
matrix_out="$(mktemp)"
trap 'rm -f "$matrix_out"' EXIT
# The matrix's table goes to a file and is printed when it is done (its progress lines, on
# stderr, show as it goes).
# CalculiX runs the cases its adapter lists beside impact (issue 38), when ccx is installed or
# installable here (scripts/setup-calculix.sh); otherwise the matrix is impact's alone, said.
codes=(--code impact)
if scripts/setup-calculix.sh; then
    codes+=(--code calculix)
else
    echo "main-job: ccx is not installed: the matrix runs impact alone (the report shows no CalculiX rows)" >&2
fi
"$target_dir/release/impact" verify "${codes[@]}" --out "$out" > "$matrix_out" &
verify_pid=$!
bench stability
bench references
verify_status=0
wait "$verify_pid" || verify_status=$?
cat "$matrix_out"

echo "== timed, alone: impact-bench throughput and work-precision ${quick[*]:-} --out $bench"
bench throughput
bench work-precision
if [[ $bench_status -ne 0 ]]; then
    echo "main-job: the benchmarks failed (status $bench_status); the report shows what they wrote" >&2
fi

# The uncertainty studies (issue 27): the paper case's Table 1 rows under both couplings and its
# Table 2 impulses, each at the sample size that converges (verification/uq/paper-{plastic,
# elastic}{,-surface}.yaml, table2-{plastic,elastic}.yaml), after the timed benchmarks so that
# they do not disturb them; the Python package is built into the venv first (maturin reuses
# target/release). A failed study leaves the report's section saying so; the job's status
# is then at least 1.
echo "== uncertainty studies: scripts/uq-study.py --out $out/uq"
uq_status=0
{ [[ $venv_status -eq 0 ]] && PATH="$PWD/.venv/bin:$PATH" .venv/bin/pip install --quiet --no-build-isolation ./python \
    && .venv/bin/python scripts/uq-study.py --out "$out/uq" --jobs "$(nproc)"; } || uq_status=$?
if [[ $uq_status -ne 0 ]]; then
    echo "main-job: the uncertainty studies failed (status $uq_status)" >&2
    rm -f "$out/uq/uq.md"
    [[ $bench_status -ne 0 ]] || bench_status=1
fi

echo "== report: $out/index.html, $out/report.md"
"$target_dir/release/impact" report --from "$out" --benchmarks "$bench" || exit 2
if [[ $verify_status -ne 0 ]]; then
    exit "$verify_status"
fi
exit "$bench_status"
