# Sourced by the kill-and-resume scripts (ensemble, test-particle map): a run
# killed once it has saved a checkpoint, alone or as one rank of an MPI job.

# The script's verdict on a check that did not hold.
fail() { echo "FAIL: $*"; exit 1; }

# Until a file matching the glob $2 exists (0), or the process $1 has ended (1).
wait_for_file() {
    while kill -0 "$1" 2> /dev/null; do
        compgen -G "$2" > /dev/null && return 0
        sleep 0.002
    done
    return 1
}

# SIGKILL to the process $1, reaped.
kill_now() {
    kill -s KILL "$1"
    wait "$1" 2> /dev/null
}

# One rank of the mpirun job $1 killed (Open MPI then ends the job), the job
# reaped; 1 when the job has no rank process.
kill_one_rank() {
    local rank
    rank=$(pgrep -P "$1" | head -n 1)
    [ -n "$rank" ] || return 1
    kill -s KILL "$rank"
    wait "$1" 2> /dev/null
    return 0
}

# mpirun's options, in the array mpi_options.
source "$(dirname "${BASH_SOURCE[0]}")/mpi_options.sh"
