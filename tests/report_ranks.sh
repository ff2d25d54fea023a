#!/usr/bin/env bash
# `sympl report` under mpirun: the (scene, method, dt) runs are spread over
# the ranks and rank 0 writes the same outputs as one process, timings aside
# (work_precision.csv's seconds columns, and what is read off them).
set -euo pipefail
sympl=$1 work=$2
source "$(cd "$(dirname "$0")" && pwd)/mpi_options.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cat > hh.toml <<'TOML'
name = "small-hh"
system = "henon_heiles"
parameters = {energy = 0.125, q2 = 0.1}
methods = ["leapfrog_kdk", "blanes_moan_s6", "rk4", "odeint_rk4"]
dt = {from = 0.2, to = 0.02, count = 4}
t_end = 20
TOML
"$sympl" report hh.toml --no-plots --out one > /dev/null
mpirun "${mpi_options[@]}" -np 3 "$sympl" report hh.toml --no-plots --out three > three.txt
# Columns 11-13 are the wall times.
for d in one three; do cut -d, -f1-10,14- "$d/work_precision.csv" > "$d.csv"; done
rows=$(($(wc -l < one.csv) - 1))
[ "$rows" -eq 16 ] || { echo "expected 16 runs, got $rows"; exit 1; }
cmp one.csv three.csv
grep -q "dealt round-robin over 3 MPI ranks" three/summary.md || { echo "summary.md does not say how the runs were timed"; exit 1; }
grep -q "small-hh" three.txt
# Only rank 0 writes: one table per measure (final and energy error) on stdout.
[ "$(grep -c '^small-hh ' three.txt)" -eq 10 ] || { cat three.txt; exit 1; }
# Rank 0 cannot write: every rank ends with exit 2 (none is left waiting for it).
set +e
timeout 120 mpirun "${mpi_options[@]}" -np 3 "$sympl" report hh.toml --no-plots --out /proc/no-such 2> err.txt
code=$?
set -e
[ $code -eq 2 ] || { echo "exit $code when rank 0 cannot write"; cat err.txt; exit 1; }
grep -q "rank 0 of 3.*/proc/no-such" err.txt || { cat err.txt; exit 1; }
echo "report over 3 ranks: same outputs as one process"
