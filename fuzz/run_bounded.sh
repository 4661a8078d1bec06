#!/usr/bin/env bash
# Bounded fuzzing: builds the libFuzzer harnesses (clang-14, AddressSanitizer + UndefinedBehaviorSanitizer)
# in build-fuzz/ and runs each for a fixed time, as many at once as there are cores, starting from its seed corpus. Fails on
# any crash, failed check, leak, timeout, excess memory or sanitizer report, and leaves the input that did
# it in build-fuzz/artifacts/: once the bug is fixed, copy that input to fuzz/corpus/<harness>/crash_<what>
# so that the replay under `meson test` keeps it fixed.
#
# Usage: fuzz/run_bounded.sh [SECONDS_PER_HARNESS] [HARNESS...]
#   SECONDS_PER_HARNESS defaults to 60; HARNESS defaults to every directory in fuzz/corpus/.
#   DBRG_FUZZ_BUILD names another build directory; DBRG_FUZZ_TIMEOUT the seconds one input may take
#   (default 10; raise it on a machine busy with other work, where a slow input is not a hang). Inputs the fuzzers find interesting accumulate in
#   <build>/corpus/<harness>/ across runs; the committed seeds are never modified.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
shift $(( $# > 0 ? 1 : 0 ))
build=${DBRG_FUZZ_BUILD:-build-fuzz}
timeout=${DBRG_FUZZ_TIMEOUT:-10}
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then
    for directory in fuzz/corpus/*/; do harnesses+=("$(basename "$directory")"); done
fi

if [ ! -f "$build/build.ninja" ]; then
    # The library is compiled with coverage instrumentation (fuzzer-no-link) so that the fuzzers see into it.
    CC=clang-14 CXX=clang++-14 meson setup "$build" --buildtype=debugoptimized \
        -Dfuzzers=enabled -Dtests=disabled -Dbindings=disabled \
        -Db_sanitize=address,undefined -Db_lundef=false \
        -Dcpp_args=-fsanitize=fuzzer-no-link -Dc_args=-fsanitize=fuzzer-no-link >/dev/null
fi
ninja -C "$build" "${harnesses[@]/#/fuzz/}" >/dev/null

export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=detect_leaks=1
mkdir -p "$build/artifacts" "$build/logs"

# One harness: exit status 0 when it ran its time without a failure.
run_harness() {
    local harness=$1 work="$build/corpus/$1" log="$build/logs/$1.log"
    mkdir -p "$work"
    local dictionary=()
    [ -f "fuzz/dict/$harness.dict" ] && dictionary=("-dict=fuzz/dict/$harness.dict")
    "$build/fuzz/$harness" "$work" "fuzz/corpus/$harness" "${dictionary[@]}" \
        -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$build/artifacts/$harness-" >"$log" 2>&1
}

# Each fuzzer runs on one core: as many at once as there are cores (DBRG_FUZZ_JOBS to choose).
jobs=${DBRG_FUZZ_JOBS:-$(nproc)}
declare -A pid_of
failed=()
for harness in "${harnesses[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
    run_harness "$harness" &
    pid_of[$harness]=$!
done
for harness in "${harnesses[@]}"; do
    log="$build/logs/$harness.log"
    if wait "${pid_of[$harness]}"; then
        runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
        echo "fuzz: $harness: ${runs:-?} inputs in ${seconds} s, no failure (corpus: $(ls "$build/corpus/$harness" | wc -l) inputs)"
    else
        echo "fuzz: $harness FAILED; the end of $log:" >&2
        tail -n 40 "$log" >&2
        failed+=("$harness")
    fi
done
if [ ${#failed[@]} -gt 0 ]; then
    echo "fuzz: failures in ${failed[*]}; the inputs are in $build/artifacts/" >&2
    exit 1
fi
