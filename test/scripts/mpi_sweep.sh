#!/bin/sh
# A parameter sweep over MPI: 2 ranks give exactly the serial results (bit
# for bit), and diverging members are reported. Serial program and MPI
# driver come from the same build with mpifort and the same flags, so that
# the member runs are the same machine code ($HHNECK is not used); -O1, not
# the release profile: its compile takes a third of the release build's and
# the members are short.
. test/scripts/lib/checks.sh

MPI_FLAGS="-O1 -DHHNECK_MPI"
if ! FPM_FC=mpifort fpm build --flag "$MPI_FLAGS" > "$tmp/mpi_build.log" 2>&1; then
    tail -n 20 "$tmp/mpi_build.log"
    fail "-O1 build with mpifort"
    finish
    exit 1
fi
hh=$(FPM_FC=mpifort fpm run --flag "$MPI_FLAGS" --runner echo 2>/dev/null | tail -n 1)
sm=$(FPM_FC=mpifort fpm run --flag "$MPI_FLAGS" --example sweep_mpi --runner echo 2>/dev/null | tail -n 1)
sed 's/^CONTROL .*/CONTROL   0.05      5.0E-5    0.005     RK4/' input/nbdl15g.inp > "$tmp/base.inp"
echo 'SCALE     RK4STABLE DISCS     VISCOUS   0.2' >> "$tmp/base.inp"   # RK4 at 50 us stable again
cat > "$tmp/sweep.inp" <<DECK
TITLE     TEST SWEEP: LATIN HYPERCUBE WITH DIVERGING MEMBERS
BASE      $tmp/base.inp
DESIGN    LHS       12        7
PARAM     DISC_E    FAMILY    DISCS     E         0.5       1.0E4     LOG
PARAM     MUSC_K    FAMILY    MUSCLES   M1        0.5       2.0
PARAM     HEAD_M    FIELD3    BODY      HEAD      3.0       4.5
DECK
"$hh" --sweep --h5 "$tmp/serial.h5" < "$tmp/sweep.inp" > "$tmp/serial.txt" 2> "$tmp/serial.err"
rc_serial=$?
mpirun --allow-run-as-root --oversubscribe -np 2 "$sm" "$tmp/sweep.inp" --h5 "$tmp/mpi.h5" \
    > "$tmp/mpi.txt" 2> "$tmp/mpi.err"
rc_mpi=$?
nfailed=$(grep -c "FAILED (below)" "$tmp/serial.txt" || true)
check "serial sweep ends with exit code 6: members failed (got $rc_serial)" [ "$rc_serial" -eq 6 ]
check "2-rank sweep ends with exit code 6: members failed (got $rc_mpi)" [ "$rc_mpi" -eq 6 ]
check "some but not all of the 12 members diverge ($nfailed listed as failed)" \
    sh -c '[ "$1" -ge 1 ] && [ "$1" -lt 12 ]' sh "$nfailed"
[ "$nfail" -eq 0 ] || tail -n 5 "$tmp/serial.err" "$tmp/mpi.err"
py_checks -m hhneck.tools.compare_sweeps "$tmp/serial.h5" "$tmp/mpi.h5" --expect-failed "$nfailed"
finish
