#!/usr/bin/env bash
# A checkpointed `sympl run` killed with SIGKILL at random moments and resumed
# (--resume) until it finishes gives outputs byte-identical to an
# uninterrupted run: the printed summary (final states to 17 digits, energy
# and final errors, step and force counts) and every trajectory CSV, for a
# table, a compensated table, a force-gradient table and a classic stepper (RK4).
# Usage: kill_and_resume.sh PROGRAM WORKDIR
set -u
program=$1
work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
cat > scene.toml <<'TOML'
name = "resume"
system = "kepler"
parameters = {eccentricity = 0.6}
methods = ["blanes_moan_s6", "compensated(leapfrog_kdk)", "chin_4a", "rk4"]
t_end = 20000
dt = 0.01
checkpoint = {every_steps = 20000, file = "state/resume"}
[output]
trajectory_every = 100
final_state = true
directory = "out"
TOML
start=$(date +%s%N)
"$program" run scene.toml > whole.txt || fail "the uninterrupted run failed"
whole_ms=$(( ($(date +%s%N) - start) / 1000000 ))
RANDOM=20261122  # the kill times are random, in the same pattern in every run of the test
# Kill times scale with how long the whole run takes on this build (a
# sanitizer build is ten times slower): between 1/20 and 1/20 + 1/8 of it.
kill_after() {
    local ms=$(( whole_ms / 20 + RANDOM % (whole_ms / 8 + 1) ))
    printf '%d.%03d' $((ms / 1000)) $((ms % 1000))
}
mkdir whole && mv out/*.csv whole/ || fail "no trajectories"
[ -z "$(ls -A state)" ] || fail "a finished run left checkpoints: $(ls state)"

"$program" run scene.toml > /dev/null 2>&1 &
pid=$!
sleep "$(kill_after)"
kill -s KILL "$pid" 2> /dev/null
wait "$pid" 2> /dev/null
kills=1
while true; do
    "$program" run scene.toml --resume > resumed.txt 2> err.txt &
    pid=$!
    sleep "$(kill_after)"
    if kill -s KILL "$pid" 2> /dev/null; then
        wait "$pid" 2> /dev/null
        kills=$((kills + 1))
        [ "$kills" -lt 200 ] || fail "never finished after $kills kills"
    else
        wait "$pid" || fail "a resumed run failed: $(cat err.txt)"
        break
    fi
done
cmp whole.txt resumed.txt || { diff whole.txt resumed.txt; fail "the summaries differ"; }
for f in whole/*.csv; do
    cmp "$f" "out/$(basename "$f")" || fail "$(basename "$f") differs"
done
[ -z "$(ls -A state)" ] || fail "checkpoints left after the resumed run finished: $(ls -A state)"
echo "killed $kills times with SIGKILL (whole run: $whole_ms ms) and resumed: summary and $(ls whole | wc -l) trajectories byte-identical"
