# Shared by the tests of commands that run many members (sweep.sh,
# calibrate.sh), sourced after `set -u` with their arguments DEMVV WORK_DIR
# [MPIRUN]: sets demvv, work (emptied), launch_np2 (two MPI ranks, empty
# without MPIRUN) and the helpers fail and one_line.
demvv=$1
work=$2
mpirun=${3:-}
launch_np2="${mpirun:+$mpirun --oversubscribe -np 2}"
[ -n "$mpirun" ] && [ "$(id -u)" -eq 0 ] && launch_np2="$mpirun --allow-run-as-root --oversubscribe -np 2"
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
one_line() { [ "$(wc -l < "$1")" -eq 1 ] || fail "$2: the error is not one line: $(cat "$1")"; }
