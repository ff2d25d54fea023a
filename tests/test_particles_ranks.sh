#!/usr/bin/env bash
# `sympl run` of a [test_particles] scene: test_particles.csv byte-identical
# for 1 and 2 threads and for 1 and 3 MPI ranks (600 particles: three pieces
# of 256, so that every rank runs one); a scene without [test_particles]
# under mpirun is refused with the reason.
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/mpi_options.sh"
sympl=$1 work=$2 mpi=${3:-OFF}
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cat > belt.toml <<'TOML'
name = "belt-ranks"
system = "outer_solar_system"
methods = ["wh(leapfrog_kdk)"]
dt = 100
t_end = 20000
[test_particles]
grid = {a = {from = 4.5, to = 9.5, count = 30}, e = {from = 0.0, to = 0.2, count = 20}}
indicator = "megno"
TOML
"$sympl" run belt.toml --out t1 --threads 1 > /dev/null
"$sympl" run belt.toml --out t2 --threads 2 > /dev/null
cmp t1/test_particles.csv t2/test_particles.csv
rows=$(($(wc -l < t1/test_particles.csv) - 1))
[ "$rows" -eq 600 ] || { echo "expected 600 rows, got $rows"; exit 1; }
grep -q ',removed,' t1/test_particles.csv || { echo "no particle removed: the test would not see reasons cross ranks"; exit 1; }
if [ "$mpi" = ON ]; then
    for k in 1 3; do
        mpirun "${mpi_options[@]}" -np $k "$sympl" run belt.toml --out r$k --threads 1 > /dev/null
        cmp t1/test_particles.csv r$k/test_particles.csv
    done
    cat > plain.toml <<'TOML'
name = "plain"
system = "harmonic_oscillator"
methods = ["leapfrog_kdk"]
dt = 0.1
t_end = 1
TOML
    set +e
    mpirun "${mpi_options[@]}" -np 2 "$sympl" run plain.toml > out.txt 2> err.txt
    code=$?
    set -e
    [ $code -ne 0 ] || { echo "a plain scene under mpirun was not refused"; exit 1; }
    grep -q "sympl run shares only a \[test_particles\] map among MPI ranks; plain.toml has none" err.txt ||
        { cat err.txt; exit 1; }
    echo "ranks 1 and 3 byte-identical"
fi
echo "test particles: threads 1 and 2 byte-identical"
