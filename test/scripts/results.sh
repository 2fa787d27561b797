#!/bin/sh
# The HDF5 result file of case 6-2 has the documented layout, read by h5py.
. test/scripts/lib/checks.sh

"$HHNECK" --h5 "$tmp/case6-2.h5" < input/case6-2.inp > "$tmp/listing.txt" 2> "$tmp/err.txt"
check "case 6-2 runs to the end (exit code 0)" [ $? -eq 0 ]
py_checks test/scripts/lib/check_results.py "$tmp/case6-2.h5"
finish
