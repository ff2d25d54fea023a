#!/usr/bin/env bash
# The program under hostile input (docs/reliability.md; issue "hostile
# input"): one or more inputs of each class the issue names, each run as a
# user would run it. For every case:
#  - it ends by itself within its time (no hang) and not by a signal (no
#    crash: exit < 128), with the exit status expected (2: bad input);
#  - without sanitizers, its address space is capped at 6 GiB (the 4 GiB
#    run budget, memory_budget_bytes, and the program itself): an
#    allocation the checks should have refused up front ends in bad_alloc,
#    an abort, and fails the case;
#  - its error is the expected one (a pattern naming the value or key), at
#    most 4 KiB a line and 64 KiB in all (the first 20 unknown names of a
#    scene are told, then their count), every line printable (no NUL, ESC
#    or other control character but the newline);
#  - files it did not make are untouched (a user's files beside the
#    outputs, the targets of planted symlinks): their checksums before and
#    after.
# Usage: hostile_inputs.sh PROGRAM WORKDIR SANITIZED(ON|OFF)
set -u
program=$1
work=$2
sanitized=${3:-OFF}
rm -rf "$work" && mkdir -p "$work"
cd "$work" || exit 1
failures=0
cases=0
fail() { echo "FAIL [$1]: $2"; failures=$((failures + 1)); }

# run_case NAME EXPECTED_EXIT PATTERN TIMEOUT_S ARGS...: the program with ARGS.
run_case() {
    local name=$1 expected=$2 pattern=$3 limit=$4
    shift 4
    cases=$((cases + 1))
    local status
    if [ "$sanitized" = ON ]; then
        timeout -s KILL "$limit" "$program" "$@" > "out.$cases" 2> "err.$cases"
        status=$?
    else
        prlimit --as=$((6 * 1024 * 1024 * 1024)) timeout -s KILL "$limit" "$program" "$@" > "out.$cases" 2> "err.$cases"
        status=$?
    fi
    if [ $status -ge 124 ]; then
        fail "$name" "ended by a signal or the time limit ($status); stderr: $(head -c 600 "err.$cases")"
        return
    fi
    [ $status -eq "$expected" ] || fail "$name" "exit $status, expected $expected; stderr: $(head -c 600 "err.$cases")"
    if [ -n "$pattern" ]; then
        grep -Eq -- "$pattern" "err.$cases" || fail "$name" "no /$pattern/ in: $(head -c 600 "err.$cases")"
    fi
    local size longest
    size=$(wc -c < "err.$cases")
    longest=$(awk '{ if (length($0) > n) n = length($0) } END { print n + 0 }' "err.$cases")
    [ "$size" -le 65536 ] || fail "$name" "$size bytes of messages (over 64 KiB)"
    [ "$longest" -le 4096 ] || fail "$name" "a line of $longest characters (over 4 KiB)"
    # Every byte printable or a newline (UTF-8 above 0x7f allowed, C1 controls not).
    # -a: grep would take a file with a NUL for binary and not match in it.
    if LC_ALL=C grep -a -q -P '[\x00-\x09\x0b-\x1f\x7f]' "err.$cases"; then
        fail "$name" "a control character in the messages"
    fi
    if LC_ALL=C grep -a -q -P '\xc2[\x80-\x9f]' "err.$cases"; then
        fail "$name" "a C1 control character in the messages"
    fi
}

scene() { cat > "$1"; }

# --- Recursion without a bound: method names nested 5000 deep. --------------
nest() {  # nest OPEN INNER CLOSE COUNT
    local open=$1 inner=$2 close=$3 n=$4 s=""
    s=$(printf "%${n}s" | sed "s/ /$open/g")$inner$(printf "%${n}s" | sed "s/ /$close/g")
    printf '%s' "$s"
}
for wrap in "logh(" "compensated(" "tao(" "wh(" "cartesian_split("; do
    name="deep_${wrap%(}"
    printf 'system = "kepler"\nmethods = ["%s"]\ndt = 0.01\nt_end = 1\n' \
        "$(nest "$wrap" leapfrog_kdk ")" 5000)" > "$name.toml"
    run_case "$name" 2 "nest|deep" 60 run "$name.toml"
done
printf 'system = "kepler"\nmethods = ["%s"]\ndt = 0.01\nt_end = 1\n' \
    "$(nest "extrapolated(" leapfrog_kdk ", 2)" 5000)" > deep_extrapolated.toml
run_case deep_extrapolated 2 "nest|deep" 60 run deep_extrapolated.toml

# --- Memory a scene sizes: refused up front with the figures. ----------------
scene gauss_big.toml <<'TOML'
system = "fpu_beta"
parameters = {n = 20000}
methods = ["gauss_6"]
dt = 0.1
t_end = 1
TOML
run_case gauss_6_on_20000_masses 2 "GiB" 60 run gauss_big.toml
scene grid_big.toml <<'TOML'
system = "henon_heiles"
parameters = {energy = 0.125}
methods = ["blanes_moan_s6"]
dt = 0.05
t_end = 1000
[ensemble]
grid = {q2 = {from = -0.4, to = 0.6, count = 3000}, p2 = {from = -0.5, to = 0.5, count = 3000}}
indicator = "megno"
TOML
run_case ensemble_grid_of_9e6_points 2 "expected|refus|limit" 60 ensemble grid_big.toml
ln -s /dev/zero zero_states
scene states_zero.toml <<'TOML'
system = "henon_heiles"
methods = ["leapfrog_kdk"]
dt = 0.05
t_end = 10
[ensemble]
states = "zero_states"
TOML
run_case states_file_naming_dev_zero 2 "zero_states" 60 ensemble states_zero.toml

ln -s /dev/zero zero_elements
scene elements_zero.toml <<'TOML'
system = "outer_solar_system"
methods = ["wh(saba_2)"]
dt = 100
t_end = 2000
[test_particles]
elements = "zero_elements"
indicator = "megno"
TOML
run_case elements_file_naming_dev_zero 2 "zero_elements: the orbital elements file is a character device" 60 run elements_zero.toml

# --- Files of the wrong kind. -------------------------------------------------
scene ok.toml <<'TOML'
name = "ok"
system = "harmonic_oscillator"
methods = ["leapfrog_kdk"]
dt = 0.01
t_end = 10
checkpoint = {every_steps = 100, file = "state/ok"}
TOML
mkdir -p state/ok.leapfrog_kdk
run_case checkpoint_that_is_a_directory 2 "state/ok" 60 run ok.toml --resume
rm -rf state
scene belt_checkpointed.toml <<'TOML'
system = "outer_solar_system"
methods = ["wh(saba_2)"]
dt = 100
t_end = 2000
checkpoint = {every_steps = 100, file = "state/belt"}
[test_particles]
grid = {a = {from = 6.0, to = 9.0, count = 4}, e = {from = 0.0, to = 0.2, count = 2}}
indicator = "megno"
TOML
mkdir -p state/belt.test-particles-rank-0
run_case rank_file_that_is_a_directory 2 "state/belt.test-particles-rank-0" 60 run belt_checkpointed.toml --resume
rm -rf state

# --- The user's files: never removed, never written through a symlink. -------
mkdir -p mine
echo "the user's notes" > mine/.notes.part-2024
echo "the user's lock target" > victim_lock
echo "the user's trajectory target" > victim_trajectory
ln -s ../victim_lock mine/.sympl.lock
scene here.toml <<'TOML'
name = "here"
system = "harmonic_oscillator"
methods = ["leapfrog_kdk"]
dt = 0.01
t_end = 10
[output]
directory = "mine"
trajectory_every = 100
TOML
before=$(md5sum mine/.notes.part-2024 victim_lock victim_trajectory)
run_case planted_lock_symlink 2 "sympl.lock is a symlink; expected the lock file" 60 run here.toml
rm mine/.sympl.lock
run_case output_beside_the_users_files 0 "" 60 run here.toml
# The output directory the current one: the user's files there stay too.
mkdir -p dot && cd dot || exit 1
echo "the user's notes" > .notes.part-2024
sed 's/directory = "mine"/directory = "."/' ../here.toml > here.toml
run_case output_into_the_current_directory 0 "" 60 run here.toml
[ "$(cat .notes.part-2024)" = "the user's notes" ] || fail output_into_the_current_directory ".notes.part-2024 changed"
[ -f here_leapfrog_kdk_trajectory.csv ] || fail output_into_the_current_directory "no trajectory written"
cd .. || exit 1
mkdir -p tstate
ln -s ../victim_trajectory tstate/traj.leapfrog_kdk.trajectory
scene traj.toml <<'TOML'
name = "traj"
system = "harmonic_oscillator"
methods = ["leapfrog_kdk"]
dt = 0.01
t_end = 10
checkpoint = {every_steps = 100, file = "tstate/traj"}
[output]
directory = "out_traj"
trajectory_every = 10
TOML
run_case planted_trajectory_symlink 2 "symlink|trajectory" 60 run traj.toml
after=$(md5sum mine/.notes.part-2024 victim_lock victim_trajectory)
[ "$before" = "$after" ] || fail user_files "a file the program did not make changed: $after"

# --- Nonsense refused, not answered. -----------------------------------------
scene at_rest.toml <<'TOML'
system = "outer_solar_system"
methods = ["wh(saba_2)"]
dt = 100
t_end = 200000
[initial]
q = [0, 0, 0, 5.2, 0, 0, 9.5, 0, 0, 19.2, 0, 0, 30.1, 0, 0, 39.5, 0, 0]
p = [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]
[test_particles]
grid = {a = {from = 6.0, to = 9.0, count = 4}, e = {from = 0.0, to = 0.2, count = 2}}
indicator = "megno"
TOML
run_case test_particles_with_planets_at_rest 2 "inside the star; expected planets on bound orbits" 120 run at_rest.toml

# --- Messages: bounded, printable, naming the key. ---------------------------
scene per_period.toml <<'TOML'
system = "harmonic_oscillator"
methods = ["leapfrog_kdk"]
dt = {per_period = 1e-320}
t_end = 10
TOML
run_case dt_from_a_subnormal_per_period 2 "per_period" 60 run per_period.toml
scene slow_light.toml <<'TOML'
system = "charged_uniform"
parameters = {speed_of_light = 0.5}
methods = ["boris"]
dt = 0.01
t_end = 10
TOML
run_case speed_of_light_below_the_start 2 "speed_of_light" 60 run slow_light.toml
printf 'system = "harmonic_oscillator"\nmethods = ["leap\\u001b[31mfrog\\nkdk"]\ndt = 0.01\nt_end = 1\n' > escapes.toml
run_case escape_and_newline_in_a_name 2 "leap" 60 run escapes.toml
printf 'system = "harmonic_oscillator"\nmethods = ["leap\0frog"]\ndt = 0.01\nt_end = 1\n' > nul.toml
run_case nul_byte_in_a_scene 2 "nul.toml" 60 run nul.toml
printf 'system = "harmonic_oscillator"\nmethods = ["%s"]\ndt = 0.01\nt_end = 1\n' \
    "$(head -c 1000000 /dev/zero | tr '\0' x)" > long_name.toml
run_case a_1_MB_unknown_name 2 "xxxx" 60 run long_name.toml
{
    printf 'system = "harmonic_oscillator"\nmethods = ['
    for k in $(seq 999); do printf '"%s%d", ' "$(head -c 1000 /dev/zero | tr '\0' y)" "$k"; done
    printf '"leapfrog_kdk"]\ndt = 0.01\nt_end = 1\n'
} > many_names.toml
run_case a_thousand_unknown_names 2 "yyyy" 60 run many_names.toml

echo "$cases hostile inputs, $failures failure(s)"
[ "$failures" -eq 0 ] && echo "hostile inputs: all refused cleanly"
