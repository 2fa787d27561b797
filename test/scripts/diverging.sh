#!/bin/sh
# A diverging run (case 6-2 with RK4 beyond its stability limit): exit code
# 3, listing and HDF5 file kept up to the last good step, marked incomplete.
. test/scripts/lib/checks.sh

sed 's/^CONTROL .*/CONTROL   0.1       2.0E-4    0.001     RK4/' \
    input/case6-2.inp > "$tmp/diverge.inp"
"$HHNECK" --h5 "$tmp/diverge.h5" < "$tmp/diverge.inp" > "$tmp/diverge.out" 2> "$tmp/diverge.err"
rc=$?
check "a diverging run ends with exit code 3 (got $rc)" [ "$rc" -eq 3 ]
check "the listing ends with RUN INCOMPLETE" grep -q "RUN INCOMPLETE" "$tmp/diverge.out"
check "stderr names the stability limit" grep -q "stability limit" "$tmp/diverge.err"
py_checks test/scripts/lib/check_incomplete.py "$tmp/diverge.h5" 0.1
finish
