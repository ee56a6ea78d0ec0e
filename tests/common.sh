# Sourced by the test scripts (after they read their arguments): strict
# unset variables, a scratch directory $work removed on exit, MPI allowed as
# root and oversubscribed, fail=0, and xdmf_times FILE (each time of an
# XDMF file with how often it occurs).
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
fail=0

xdmf_times() { grep -o 'Time Value="[^"]*"' "$1" | sort | uniq -c | awk '{print $1, $3}' | sort -u; }
