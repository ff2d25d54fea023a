#!/usr/bin/env bash
# `sympl run` of a checkpointed [test_particles] map, killed by SIGKILL
# mid-run and resumed (--resume) at another thread count, and under MPI with
# one of 3 ranks killed (which ends the job) and resumed on 2 ranks:
# test_particles.csv byte-identical to an uninterrupted run's, and no
# checkpoint left once the map is complete.
# Usage: test_particles_kill_and_resume.sh PROGRAM WORKDIR [MPI ON|OFF]
set -u
source "$(cd "$(dirname "$0")" && pwd)/kill_and_resume_helpers.sh"
sympl=$1 work=$2 mpi=${3:-OFF}
rm -rf "$work" && mkdir -p "$work/state" && cd "$work" || exit 1
# 2048 particles (8 pieces of 256) over 1000 steps; each piece saved as it ends.
cat > belt.toml <<'TOML'
name = "resumed-belt"
system = "outer_solar_system"
methods = ["wh(leapfrog_kdk)"]
dt = 100
t_end = 100000
checkpoint = {every_steps = 1, file = "state/belt"}
[test_particles]
grid = {a = {from = 5.5, to = 9.5, count = 64}, e = {from = 0.0, to = 0.15, count = 32}}
indicator = "megno"
TOML
"$sympl" run belt.toml --out whole --threads 2 > /dev/null || fail "the uninterrupted run failed"
[ -z "$(ls -A state)" ] || fail "a complete map left checkpoints: $(ls state)"
"$sympl" run belt.toml --out threads --threads 2 > /dev/null 2>&1 &
pid=$!
wait_for_file $pid "state/belt.test-particles-rank-[0-9]*" || fail "threads: the run ended before it saved a checkpoint"
kill_now $pid
[ -e threads/test_particles.csv ] && fail "threads: killed too late, the map was already written"
"$sympl" run belt.toml --out threads --threads 1 --resume > /dev/null || fail "threads: the resumed run failed"
cmp whole/test_particles.csv threads/test_particles.csv || fail "threads: test_particles.csv differs after the resume"
[ -z "$(ls -A state)" ] || fail "threads: checkpoints left: $(ls state)"
echo "killed at 2 threads, resumed at 1: test_particles.csv byte-identical"
if [ "$mpi" = ON ]; then
    mpirun "${mpi_options[@]}" -np 3 "$sympl" run belt.toml --out ranks --threads 1 > /dev/null 2>&1 &
    job=$!
    wait_for_file $job "state/belt.test-particles-rank-[0-9]*" || fail "ranks: the job ended before it saved a checkpoint"
    kill_one_rank $job || fail "ranks: no rank process under mpirun $job"
    [ -e ranks/test_particles.csv ] && fail "ranks: killed too late, the map was already written"
    mpirun "${mpi_options[@]}" -np 2 "$sympl" run belt.toml --out ranks --threads 1 --resume > /dev/null ||
        fail "ranks: the resumed job failed"
    cmp whole/test_particles.csv ranks/test_particles.csv || fail "ranks: test_particles.csv differs after the resume"
    [ -z "$(ls -A state)" ] || fail "ranks: checkpoints left: $(ls state)"
    echo "one of 3 ranks killed, resumed on 2 ranks: test_particles.csv byte-identical"
fi
echo "test-particle map killed and resumed: byte-identical"
