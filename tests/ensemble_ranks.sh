#!/usr/bin/env bash
# `sympl ensemble`: ensemble.csv byte-identical for 1 and 4 threads and for
# 1 and 3 MPI ranks; a grid point below the potential is an `invalid` row;
# a scene error exits 2 and writes nothing.
set -euo pipefail
sympl=$1 work=$2 mpi=${3:-OFF}
source "$(cd "$(dirname "$0")" && pwd)/mpi_options.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cat > chaos.toml <<'TOML'
name = "small-chaos"
system = "henon_heiles"
parameters = {energy = 0.125}
methods = ["blanes_moan_s6"]
dt = 0.05
t_end = 200
[ensemble]
grid = {q2 = {from = -0.4, to = 0.6, count = 13}, p2 = {from = -0.4, to = 0.4, count = 11}}
indicator = "megno"
TOML
"$sympl" ensemble chaos.toml --out t1 --threads 1 > /dev/null
"$sympl" ensemble chaos.toml --out t4 --threads 4 > /dev/null
cmp t1/ensemble.csv t4/ensemble.csv
rows=$(($(wc -l < t1/ensemble.csv) - 1))
[ "$rows" -eq 143 ] || { echo "expected 143 rows, got $rows"; exit 1; }
grep -q '^0,-0.4,-0.4,invalid,.*below the potential' t1/ensemble.csv || { echo "no invalid row for (q2, p2) = (-0.4, -0.4)"; exit 1; }
grep -q ',stable,' t1/ensemble.csv
if [ "$mpi" = ON ]; then
    for k in 1 3; do
        mpirun "${mpi_options[@]}" -np $k "$sympl" ensemble chaos.toml --out r$k --threads 1 > /dev/null
        cmp t1/ensemble.csv r$k/ensemble.csv
    done
    echo "ranks 1 and 3 byte-identical"
fi
# A scene error: exit 2, the message names the key, nothing written.
sed 's/indicator = "megno"/indicator = "lyapunov"/' chaos.toml > bad.toml
set +e
"$sympl" ensemble bad.toml --out bad 2> err.txt
code=$?
set -e
[ $code -eq 2 ] || { echo "exit $code for a bad indicator"; exit 1; }
grep -q "bad.toml:9:.*indicator = 'lyapunov'; expected \"megno\" or \"none\"" err.txt || { cat err.txt; exit 1; }
[ ! -e bad/ensemble.csv ]
echo "threads 1 and 4 byte-identical; invalid rows; scene errors"
