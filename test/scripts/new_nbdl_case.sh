#!/bin/sh
# A deck for volunteer runs that are not shipped, built the way a user would
# (tools/make_nbdl_tables.py --data DIR --name NAME) from a copy of a shipped
# data set, must be the shipped case: the same T1 tables as input/nbdl12g_t1.inp
# and input/nbdl15g_t1.inp (the rotation unit chosen by the rule: radians for
# the 12 g files, degrees for the 15 g ones), the same head channels when run
# as input/nbdl12g.inp, and tools/compare_nbdl.py --data gives the same table
# as the shipped 12 g comparison.
. test/scripts/lib/checks.sh

cp -r reference/nbdl_12g "$tmp/runs12"
cp -r reference/nbdl_15g "$tmp/runs15"
python3 tools/make_nbdl_tables.py --data "$tmp/runs12" --name trial12 --into "$tmp" 2> "$tmp/unit12.txt"
python3 tools/make_nbdl_tables.py --data "$tmp/runs15" --name trial15 --into "$tmp" 2> "$tmp/unit15.txt"
for s in 12 15; do
    grep -v '^\*' "input/nbdl${s}g_t1.inp" > "$tmp/shipped$s.txt"
    grep -v '^\*' "$tmp/trial${s}_t1.inp" > "$tmp/new$s.txt"
    check "$s g: the T1 tables from a copy of the runs equal the shipped ones" cmp -s "$tmp/shipped$s.txt" "$tmp/new$s.txt"
done
check "12 g: the T1 rotation read as radians" grep -q "read as rad" "$tmp/unit12.txt"
check "15 g: the T1 rotation read as degrees" grep -q "read as deg" "$tmp/unit15.txt"

"$HHNECK" --h5 "$tmp/new.h5" < "$tmp/trial12.inp" > /dev/null 2>&1
"$HHNECK" --h5 "$tmp/shipped.h5" < input/nbdl12g.inp > /dev/null 2>&1
check "the new deck gives the shipped 12 g deck's head and condyle channels" python3 - "$tmp/new.h5" "$tmp/shipped.h5" <<'PY'
import sys
import h5py
import numpy as np
a, b = (h5py.File(f, "r")["channels"] for f in sys.argv[1:3])
names = ("HEAD_AX", "HEAD_AZ", "HEAD_ALPHY", "HEAD_OMEGY", "HEAD_THETY", "OC_FX", "OC_FZ", "OC_MY")
sys.exit(0 if all(np.array_equal(a[n][:], b[n][:]) for n in names) else 1)
PY
python3 tools/compare_nbdl.py --data new="$tmp/runs12" --case new --h5 new="$tmp/new.h5" --out "$tmp/o1" \
    | sed 's/NBDL new/NBDL 12 g/; s/rating new/rating 12 g/' > "$tmp/t1.md"
python3 tools/compare_nbdl.py --case 12g --h5 12g="$tmp/shipped.h5" --out "$tmp/o2" > "$tmp/t2.md"
check "compare_nbdl.py --data rates the new case" grep -q "Overall CORA-style rating 12 g" "$tmp/t1.md"
check "and prints the shipped 12 g comparison" cmp -s "$tmp/t1.md" "$tmp/t2.md"
finish
