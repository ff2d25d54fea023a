#!/usr/bin/env bash
# `sympl ensemble` with checkpoints, killed by SIGKILL mid-run and resumed
# (--resume) at another thread count, and under MPI with one rank killed
# (which ends the job) and resumed at another rank count: ensemble.csv
# byte-identical to an uninterrupted run's, and no checkpoint left once the
# ensemble is complete.
# Usage: ensemble_kill_and_resume.sh PROGRAM WORKDIR [MPI ON|OFF]
set -u
source "$(cd "$(dirname "$0")" && pwd)/kill_and_resume_helpers.sh"
sympl=$1 work=$2 mpi=${3:-OFF}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
# 120 orbits of 10000 steps; a checkpoint after every 8 orbits of a rank.
cat > orbits.toml <<'TOML'
name = "resumed-orbits"
system = "kepler"
methods = ["blanes_moan_s6"]
dt = 0.01
t_end = 100
checkpoint = {every_steps = 80000, file = "state/orbits"}
[ensemble]
grid = {eccentricity = {from = 0.05, to = 0.9, count = 120}}
indicator = "megno"
TOML
"$sympl" ensemble orbits.toml --out whole --threads 2 > /dev/null || fail "the uninterrupted run failed"
[ -z "$(ls -A state)" ] || fail "a complete ensemble left checkpoints: $(ls state)"
"$sympl" ensemble orbits.toml --out threads --threads 2 > /dev/null 2>&1 &
pid=$!
wait_for_file $pid "state/orbits.ensemble-rank-[0-9]*" || fail "threads: the run ended before it saved a checkpoint"
kill_now $pid
saved=$(ls state | wc -l)
[ "$saved" -gt 0 ] || fail "threads: killed too late, no checkpoint left to resume from"
"$sympl" ensemble orbits.toml --out threads --threads 1 --resume > /dev/null || fail "threads: the resumed run failed"
cmp whole/ensemble.csv threads/ensemble.csv || fail "threads: ensemble.csv differs after the resume"
[ -z "$(ls -A state)" ] || fail "threads: checkpoints left: $(ls state)"
echo "killed at 2 threads after $saved checkpoint file(s), resumed at 1: ensemble.csv byte-identical"
if [ "$mpi" = ON ]; then
    mpirun "${mpi_options[@]}" -np 3 "$sympl" ensemble orbits.toml --out ranks --threads 1 > /dev/null 2>&1 &
    job=$!
    wait_for_file $job "state/orbits.ensemble-rank-[0-9]*" || fail "ranks: the job ended before it saved a checkpoint"
    kill_one_rank $job || fail "ranks: no rank process under mpirun $job"
    saved=$(ls state | wc -l)
    [ "$saved" -gt 0 ] || fail "ranks: killed too late, no checkpoint left to resume from"
    mpirun "${mpi_options[@]}" -np 2 "$sympl" ensemble orbits.toml --out ranks --threads 1 --resume > /dev/null ||
        fail "ranks: the resumed job failed"
    cmp whole/ensemble.csv ranks/ensemble.csv || fail "ranks: ensemble.csv differs after the resume"
    [ -z "$(ls -A state)" ] || fail "ranks: checkpoints left: $(ls state)"
    echo "one of 3 ranks killed after $saved checkpoint file(s), resumed on 2 ranks: ensemble.csv byte-identical"
fi
echo "ensemble killed and resumed: byte-identical"
