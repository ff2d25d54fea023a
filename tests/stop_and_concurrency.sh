#!/usr/bin/env bash
# The program under signals and concurrency (issue: nothing lost on faults):
#  1. SIGINT and SIGTERM during a report: exit 128 + signal, no staging
#     directory or temporary left, the previous complete set untouched.
#  2. A second report into the same directory while one runs: exit 2, told
#     which process holds it; the first finishes undisturbed.
#  3. SIGKILL: the staging directory it leaves is removed by the next run.
# Usage: stop_and_concurrency.sh PROGRAM WORKDIR
set -u
program=$1
work=$2
rm -rf "$work" && mkdir -p "$work/out"
fail() { echo "FAIL: $*"; exit 1; }
# About 5 s of work per method on one core: long enough to be interrupted.
cat > "$work/long.toml" <<'TOML'
name = "long"
system = "harmonic_oscillator"
methods = ["leapfrog_kdk", "blanes_moan_s6"]
t_end = 3e6
dt = 0.01
TOML
cat > "$work/short.toml" <<'TOML'
name = "short"
system = "harmonic_oscillator"
methods = ["leapfrog_kdk"]
t_end = 10
dt = [0.1, 0.05]
TOML
echo "old summary" > "$work/out/summary.md"
echo "old csv" > "$work/out/work_precision.csv"

wait_for_staging() {
    for _ in $(seq 100); do
        compgen -G "$work/out/.sympl-staging-*" > /dev/null && return 0
        sleep 0.05
    done
    fail "no staging directory appeared"
}

for signal in INT TERM; do
    "$program" report "$work/long.toml" --out "$work/out" --no-plots > /dev/null 2> "$work/err" &
    pid=$!
    wait_for_staging
    sleep 0.3
    kill -s "$signal" "$pid"
    wait "$pid"
    rc=$?
    expected=$((128 + $(kill -l "$signal")))
    [ "$rc" -eq "$expected" ] || fail "SIG$signal: exit $rc, expected $expected"
    grep -q "stopped by SIG$signal" "$work/err" || fail "SIG$signal: stderr says: $(cat "$work/err")"
    compgen -G "$work/out/.sympl-staging-*" > /dev/null && fail "SIG$signal left a staging directory"
    compgen -G "$work/out/.*.sympl-part-*" > /dev/null && fail "SIG$signal left a temporary"
    [ "$(cat "$work/out/summary.md")" = "old summary" ] || fail "SIG$signal changed summary.md"
    [ "$(cat "$work/out/work_precision.csv")" = "old csv" ] || fail "SIG$signal changed work_precision.csv"
    echo "SIG$signal: exit $rc, previous outputs kept, no temporaries"
done

"$program" report "$work/long.toml" --out "$work/out" --no-plots > /dev/null 2>&1 &
first=$!
wait_for_staging
"$program" report "$work/short.toml" --out "$work/out" --no-plots > /dev/null 2> "$work/err"
rc=$?
[ "$rc" -eq 2 ] || fail "second report into a busy directory: exit $rc, expected 2"
grep -q "is being written by another sympl (process $first)" "$work/err" || fail "second report says: $(cat "$work/err")"
echo "concurrent: the second run was refused: $(cat "$work/err")"

kill -s KILL "$first"
wait "$first" 2> /dev/null
compgen -G "$work/out/.sympl-staging-*" > /dev/null || fail "SIGKILL left no staging directory (test set-up)"
"$program" report "$work/short.toml" --out "$work/out" --no-plots > /dev/null 2> "$work/err" || fail "run after SIGKILL: $(cat "$work/err")"
compgen -G "$work/out/.sympl-staging-*" > /dev/null && fail "the staging directory of the killed run is still there"
grep -q "short" "$work/out/work_precision.csv" || fail "the run after SIGKILL wrote no new set"
echo "SIGKILL: its staging directory was removed by the next run, which committed a new set"
rm -rf "$work"
