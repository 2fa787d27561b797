#!/bin/sh
# The whole test suite: every test program (the pFUnit suites of test/unit
# and the program tests of test/) in the debug build, then again in a checking
# build that traps invalid operations, division by zero
# and overflow and checks every array bound and pointer, then a look at a
# result file with h5py. Each test program ends with "N passed, N failed".
set -eu
cd "$(dirname "$0")/.."

# fpm's debug profile, without its -fcoarray=single: with it gfortran 12
# writes test module files that it cannot read back once they use pFUnit
DEBUG_FLAGS="-Wall -Wextra -Wimplicit-interface -fPIC -fmax-errors=1 -g -fcheck=bounds -fcheck=array-temps -fbacktrace"
CHECK_FLAGS="-g -O0 -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace -Wall -Wno-unused-dummy-argument -Wno-maybe-uninitialized"

# pFUnit: built once per machine, then the test/unit/*.pf suites turned into
# Fortran with their driver programs
./tools/pfunit.sh ensure
./tools/pfunit.sh generate
PF_INC=$(./tools/pfunit.sh include)
PF_LINK=$(./tools/pfunit.sh link)

echo "== fpm test (debug build: $DEBUG_FLAGS)"
fpm test --flag "$DEBUG_FLAGS $PF_INC" --link-flag "$PF_LINK"
echo "== fpm test (checking build: $CHECK_FLAGS)"
fpm test --flag "$CHECK_FLAGS $PF_INC" --link-flag "$PF_LINK"
echo "== robustness: full disk, files in the way, concurrent runs, signals, endless and huge inputs (debug, checking)"
HHNECK=$(fpm run --flag "$DEBUG_FLAGS $PF_INC" --link-flag "$PF_LINK" --runner echo 2>/dev/null | tail -n 1) sh test/scripts/robustness.sh
HHNECK=$(fpm run --flag "$CHECK_FLAGS $PF_INC" --link-flag "$PF_LINK" --runner echo 2>/dev/null | tail -n 1) sh test/scripts/robustness.sh
echo "== HDF5 results readable by h5py"
tmp=$(mktemp -d)
fpm run -- --h5 "$tmp/case6-2.h5" < input/case6-2.inp > "$tmp/listing.txt"
python3 tools/check_results.py "$tmp/case6-2.h5"
echo "== animations and the ParaView sidecar (docs/animation.md)"
sh test/scripts/animate.sh
echo "== a bad deck: exit code 2, located message on stderr, no result file"
sed 's/^CONTROL   0.1  /CONTROL   -0.1 /' input/case6-2.inp > "$tmp/bad.inp"
set +e
fpm run -- --h5 "$tmp/bad.h5" < "$tmp/bad.inp" > "$tmp/bad.out" 2> "$tmp/bad.err"
rc=$?
set -e
grep -q "stdin line 10, columns 11-20 (CONTROL card, field F1 'end time')" "$tmp/bad.err"
[ "$rc" -eq 2 ] && [ ! -e "$tmp/bad.h5" ] && [ ! -e "$tmp/bad.h5.part" ] && ! grep -q "deck error" "$tmp/bad.out"
echo "PASS  exit code 2, message names line 10 columns 11-20, nothing written"
echo "== a diverging run: exit code 3, listing and HDF5 kept up to the last good step, marked incomplete"
exe=$(fpm run --runner echo 2>/dev/null | tail -n 1)
sed 's/^CONTROL   0.1       5.0E-5    0.001     ADAMS     1.0E-4    1.0E-7/CONTROL   0.1       2.0E-4    0.001     RK4/' \
    input/case6-2.inp > "$tmp/diverge.inp"
set +e
"$exe" --h5 "$tmp/diverge.h5" < "$tmp/diverge.inp" > "$tmp/diverge.out" 2> "$tmp/diverge.err"
rc=$?
set -e
[ "$rc" -eq 3 ] && grep -q "RUN INCOMPLETE" "$tmp/diverge.out" && grep -q "stability limit" "$tmp/diverge.err"
python3 tools/check_incomplete.py "$tmp/diverge.h5" 0.1

echo "== a run stopped by SIGTERM: exit code 5, a valid result file marked incomplete"
sed 's/^CONTROL .*/CONTROL   0.25      1.0E-5    0.005     RK4/' \
    input/nbdl15g.inp > "$tmp/long.inp"
set +e
"$exe" --h5 "$tmp/term.h5" < "$tmp/long.inp" > "$tmp/term.out" 2> "$tmp/term.err" &
pid=$!
sleep 2
kill -TERM "$pid"
wait "$pid"
rc=$?
set -e
[ "$rc" -eq 5 ] && grep -q "interrupted by signal 15" "$tmp/term.err" && [ ! -e "$tmp/term.h5.part" ]
python3 tools/check_incomplete.py "$tmp/term.h5" 0.25

echo "== a run killed outright (SIGKILL): no file under the result name"
set +e
"$exe" --h5 "$tmp/kill.h5" < "$tmp/long.inp" > /dev/null 2>&1 &
pid=$!
sleep 2
kill -KILL "$pid"
wait "$pid"
set -e
[ ! -e "$tmp/kill.h5" ]
echo "PASS  no kill.h5 after SIGKILL (the partial file stays under kill.h5.part)"
echo "== listings of the regression decks against reference/outputs"
HHNECK="$exe" sh test/scripts/listing_references.sh
echo "== a parameter sweep over MPI: 2 ranks give exactly the serial results; diverging members are reported"
# the same compiler wrapper and flags for the serial main program and the MPI
# driver, so that the member runs are the same machine code
MPI_BUILD="--profile release --flag -DHHNECK_MPI"
FPM_FC=mpifort fpm build $MPI_BUILD > "$tmp/mpi_build.log" 2>&1 || { cat "$tmp/mpi_build.log"; exit 1; }
hh=$(FPM_FC=mpifort fpm run $MPI_BUILD --runner echo 2>/dev/null | tail -n 1)
sm=$(FPM_FC=mpifort fpm run $MPI_BUILD --example sweep_mpi --runner echo 2>/dev/null | tail -n 1)
sed 's/^CONTROL .*/CONTROL   0.05      5.0E-5    0.005     RK4/' input/nbdl15g.inp > "$tmp/base.inp"
echo 'SCALE     RK4STABLE DISCS     VISCOUS   0.2' >> "$tmp/base.inp"   # RK4 at 50 us stable again
cat > "$tmp/sweep.inp" <<EOF
TITLE     TEST SWEEP: LATIN HYPERCUBE WITH DIVERGING MEMBERS
BASE      $tmp/base.inp
DESIGN    LHS       12        7
PARAM     DISC_E    FAMILY    DISCS     E         0.5       1500.0    LOG
PARAM     MUSC_K    FAMILY    MUSCLES   M1        0.5       2.0
PARAM     HEAD_M    FIELD3    BODY      HEAD      3.0       4.5
EOF
set +e
"$hh" --sweep --h5 "$tmp/serial.h5" < "$tmp/sweep.inp" > "$tmp/serial.txt" 2> "$tmp/serial.err"
rc_serial=$?
mpirun --allow-run-as-root --oversubscribe -np 2 "$sm" "$tmp/sweep.inp" --h5 "$tmp/mpi.h5" \
    > "$tmp/mpi.txt" 2> "$tmp/mpi.err"
rc_mpi=$?
set -e
nfail=$(grep -c "FAILED (below)" "$tmp/serial.txt" || true)
[ "$rc_serial" -eq 6 ] && [ "$rc_mpi" -eq 6 ] && [ "$nfail" -ge 1 ] && [ "$nfail" -lt 12 ] || {
    echo "FAIL  sweep exit codes serial $rc_serial, MPI $rc_mpi (expected 6), $nfail failed members"
    tail -n 5 "$tmp/serial.err" "$tmp/mpi.err"; exit 1; }
echo "PASS  serial and 2-rank sweeps finish with exit code 6 and list $nfail failed member(s)"
python3 tools/compare_sweeps.py "$tmp/serial.h5" "$tmp/mpi.h5" --expect-failed "$nfail"
rm -rf "$tmp"
echo "== all tests passed"
