#!/bin/sh
# Benchmark of parameter sweeps (not a test): member runs per second of the
# one-at-a-time NBDL sweep (19 members) run serially by the main program,
# by the MPI driver on 1 and on 2 ranks, and the same 19 runs as 19
# separate invocations of the main program on the base deck (the cost of
# the sweep machinery itself). Release build with the Open MPI wrapper.
#   sh dev/bench_sweep.sh [SWEEP_DECK]
set -eu
cd "$(dirname "$0")/.."
deck=${1:-input/sweep_nbdl_oat.inp}
MPI_BUILD="--profile release --flag -DHHNECK_MPI"
FPM_FC=mpifort fpm build $MPI_BUILD > /dev/null 2>&1
hh=$(FPM_FC=mpifort fpm run $MPI_BUILD --runner echo 2>/dev/null | tail -n 1)
sm=$(FPM_FC=mpifort fpm run $MPI_BUILD --example sweep_mpi --runner echo 2>/dev/null | tail -n 1)
base=$(awk '$1 == "BASE" {print $2}' "$deck")
tmp=$(mktemp -d)
now() { date +%s.%N; }
rate() { python3 -c "import sys; n, t = float(sys.argv[1]), float(sys.argv[2]); print(f'{n / t:7.3f} runs/s  ({t:7.2f} s)')" "$1" "$2"; }

set +e
t0=$(now); "$hh" --sweep --h5 "$tmp/serial.h5" < "$deck" > /dev/null 2>&1; t1=$(now)
set -e
n=$(python3 -c "import h5py, sys; print(h5py.File(sys.argv[1])['runs/status'].shape[0])" "$tmp/serial.h5")
serial=$(python3 -c "print($t1 - $t0)")
t0=$(now)
i=0
while [ "$i" -lt "$n" ]; do "$hh" --no-h5 < "$base" > /dev/null 2>&1 || true; i=$((i + 1)); done
t1=$(now); direct=$(python3 -c "print($t1 - $t0)")
set +e
t0=$(now); mpirun --allow-run-as-root --oversubscribe -np 1 "$sm" "$deck" --no-h5 > /dev/null 2>&1; t1=$(now)
one=$(python3 -c "print($t1 - $t0)")
t0=$(now); mpirun --allow-run-as-root --oversubscribe -np 2 "$sm" "$deck" --no-h5 > /dev/null 2>&1; t1=$(now)
two=$(python3 -c "print($t1 - $t0)")
set -e
echo "sweep $deck: $n member runs on $(nproc) cores"
echo "  $n separate runs of the base deck      $(rate "$n" "$direct")"
echo "  serial sweep (hhneck --sweep)          $(rate "$n" "$serial")"
echo "  MPI driver, 1 rank                     $(rate "$n" "$one")"
echo "  MPI driver, 2 ranks                    $(rate "$n" "$two")"
python3 -c "
d, s, o, t = $direct, $serial, $one, $two
print(f'  sweep machinery vs separate runs: {s / d:5.3f}x time; MPI 1 rank vs serial: {o / s:5.3f}x; '
      f'2 ranks vs 1 rank: speed-up {o / t:4.2f} (parallel efficiency {o / t / 2 * 100:4.1f} %)')"
rm -rf "$tmp"
