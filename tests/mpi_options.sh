# Sourced by the test scripts that start mpirun: its options here, in the
# array mpi_options (more ranks than cores; as root, Open MPI needs
# --allow-run-as-root).
mpi_options=(--oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi_options+=(--allow-run-as-root)
