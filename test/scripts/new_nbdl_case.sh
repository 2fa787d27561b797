#!/bin/sh
# A deck for volunteer runs that are not shipped, built the way a user would
# (python3 -m hhneck.validation.nbdl_tables --data DIR --name NAME) from a copy of a shipped
# data set, must be the shipped case: the same T1 tables as input/nbdl12g_t1.inp
# and input/nbdl15g_t1.inp (the rotation unit chosen by the rule: radians for
# the 12 g files, degrees for the 15 g ones), the same head channels when run
# as input/nbdl12g.inp, and hhneck-compare-nbdl --data gives the same table
# as the shipped 12 g comparison. Runs that lack a channel or differ in form
# (no T1 rotation or z file, no head angular acceleration, another sampling
# step, another time origin, a broken file) are taken the way the tools
# document, or refused with a message that names the file.
# It checks the tools' workflow, whose whole NBDL runs the user makes with
# the release build (the debug and checking builds run NBDL in test_cases):
# builds: release
. test/scripts/lib/checks.sh

cp -r reference/nbdl_12g "$tmp/runs12"
cp -r reference/nbdl_15g "$tmp/runs15"
python3 -m hhneck.validation.nbdl_tables --data "$tmp/runs12" --name trial12 --into "$tmp" 2> "$tmp/unit12.txt"
python3 -m hhneck.validation.nbdl_tables --data "$tmp/runs15" --name trial15 --into "$tmp" 2> "$tmp/unit15.txt"
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
python3 -m hhneck.tools.compare_nbdl --data new="$tmp/runs12" --case new --h5 new="$tmp/new.h5" --out "$tmp/o1" \
    | sed 's/NBDL new/NBDL 12 g/; s/rating new/rating 12 g/' > "$tmp/t1.md"
python3 -m hhneck.tools.compare_nbdl --case 12g --h5 12g="$tmp/shipped.h5" --out "$tmp/o2" > "$tmp/t2.md"
check "compare_nbdl.py --data rates the new case" grep -q "Overall CORA-style rating 12 g" "$tmp/t1.md"
check "and prints the shipped 12 g comparison" cmp -s "$tmp/t1.md" "$tmp/t2.md"

# No T1 rotation or z file: the deck holds T1's RY and TZ; the run is the
# shipped 12 g deck with those two PRESCRIB cards made CONSTANT.
cp -r reference/nbdl_12g "$tmp/xonly"
rm "$tmp/xonly/T1_YrotDisp.csv" "$tmp/xonly/T1_ZAccel.csv"
python3 -m hhneck.validation.nbdl_tables --data "$tmp/xonly" --name xonly --into "$tmp" 2> "$tmp/xonly.err"
check "no T1 rotation or z file: the deck holds RY and TZ" sh -c \
    "grep -q '^PRESCRIB  T1        RY        CONSTANT' '$tmp/xonly.inp' && grep -q '^PRESCRIB  T1        TZ        CONSTANT' '$tmp/xonly.inp'"
check "and says so on stderr" sh -c "grep -q 'T1_YrotDisp.csv not in' '$tmp/xonly.err' && grep -q 'T1_ZAccel.csv not in' '$tmp/xonly.err'"
sed -e 's/^PRESCRIB  T1        TZ .*/PRESCRIB  T1        TZ        CONSTANT/' \
    -e 's/^PRESCRIB  T1        RY .*/PRESCRIB  T1        RY        CONSTANT/' input/nbdl12g.inp > "$tmp/held.inp"
"$HHNECK" --h5 "$tmp/xonly.h5" < "$tmp/xonly.inp" > /dev/null 2>&1
"$HHNECK" --h5 "$tmp/held.h5" < "$tmp/held.inp" > /dev/null 2>&1
check "and runs as the 12 g deck with T1 driven in x only" python3 - "$tmp/xonly.h5" "$tmp/held.h5" <<'PY'
import sys
import h5py
import numpy as np
a, b = (h5py.File(f, "r")["channels"] for f in sys.argv[1:3])
sys.exit(0 if all(np.array_equal(a[n][:], b[n][:]) for n in ("HEAD_AX", "HEAD_AZ", "HEAD_THETY", "T1_THETY")) else 1)
PY

# No head angular acceleration file: the rating is the mean of the other
# four rated channels, each as in the full comparison.
cp -r reference/nbdl_12g "$tmp/noalpha"
rm "$tmp/noalpha/Head_YrotAccel.csv"
python3 -m hhneck.tools.compare_nbdl --data na="$tmp/noalpha" --case na --h5 na="$tmp/shipped.h5" --out "$tmp/o3" > "$tmp/t3.md"
check "no head angular acceleration file: rated over the four channels the runs have" python3 - "$tmp/t2.md" "$tmp/t3.md" <<'PY'
import re
import sys
full, part = (open(f).read() for f in sys.argv[1:3])
rows = dict(re.findall(r"^\| (head [^|]*?) \|(?: [^|]* \|){2} \*\*([0-9.]+)\*\*", full, re.M))
four = [float(rows[k]) for k in ("head x-acceleration (g)", "head z-acceleration (g)",
                                 "head angular velocity (rad/s)", "head rotation (deg)")]
m = re.search(r"mean of the 4 rated head channels the runs have; not in them: head angular acceleration "
              r"\(rad/s2\)\): \*\*([0-9.]+)\*\*.*Peaks within 1 SD: \d+ of 5", part)
sys.exit(0 if m and abs(float(m.group(1)) - sum(four) / 4) <= 0.001 else 1)
PY

# Another sampling step (every third sample: 1.5 ms): tables every 1 ms.
mkdir "$tmp/coarse"
for f in reference/nbdl_12g/*.csv; do awk 'NR == 1 || NR % 3 == 2' "$f" > "$tmp/coarse/${f##*/}"; done
python3 -m hhneck.validation.nbdl_tables --data "$tmp/coarse" --name coarse --into "$tmp" 2> /dev/null
check "runs sampled every 1.5 ms give tables every 1 ms (0-298 ms)" \
    grep -q '^TABLE     T1XACC           299     0.001' "$tmp/coarse_t1.inp"

# A time origin 40 ms earlier than the source's: a warning says how far to
# shift; the shipped runs get none.
mkdir "$tmp/early"
for f in reference/nbdl_12g/*.csv; do
    awk -F, 'BEGIN { OFS = "," } NR == 1 { print; next } { $1 = $1 - 40; print }' "$f" > "$tmp/early/${f##*/}"
done
python3 -m hhneck.validation.nbdl_tables --data "$tmp/early" --name early --into "$tmp" 2> "$tmp/early.err"
check "a pulse 40 ms early: the warning says to shift time_ms by +40 ms" \
    grep -q "first passes -1 g at 12.0 ms.*shift the runs' time_ms by +40 ms" "$tmp/early.err"
check "the shipped runs: no such warning" sh -c "! grep -q 'first passes' '$tmp/unit12.txt' '$tmp/unit15.txt'"
cp -r reference/nbdl_12g "$tmp/still"
awk -F, 'BEGIN { OFS = "," } NR == 1 { print; next } { for (i = 2; i <= NF; i++) $i = 0; print }' \
    reference/nbdl_12g/T1_XAccel.csv > "$tmp/still/T1_XAccel.csv"
python3 -m hhneck.validation.nbdl_tables --data "$tmp/still" --name still --into "$tmp" 2> "$tmp/still.err"
rc=$?
check "no sled pulse in the T1 x-acceleration: refused (exit $rc)" sh -c \
    "[ $rc -ne 0 ] && grep -q 'never passes -1 g' '$tmp/still.err' && [ ! -e '$tmp/still.inp' ]"

# Broken data: refused with the file's name, never a Python traceback.
cp -r reference/nbdl_12g "$tmp/broken"
rm "$tmp/broken/T1_XAccel.csv"
python3 -m hhneck.validation.nbdl_tables --data "$tmp/broken" --name broken --into "$tmp" 2> "$tmp/b1.err"
rc=$?
check "no T1 x-acceleration file: refused (exit $rc), naming the file" sh -c \
    "[ $rc -ne 0 ] && grep -q 'T1_XAccel.csv not found' '$tmp/b1.err' && ! grep -q Traceback '$tmp/b1.err'"
cp reference/nbdl_12g/T1_XAccel.csv "$tmp/broken/"
sed -i '5s/,[^,]*,/,,/' "$tmp/broken/Head_ZAccel.csv"
python3 -m hhneck.tools.compare_nbdl --data b="$tmp/broken" --case b --h5 b="$tmp/shipped.h5" --out "$tmp/o4" \
    > /dev/null 2> "$tmp/b2.err"
rc=$?
check "an empty value in a run: refused (exit $rc), naming the file" sh -c \
    "[ $rc -ne 0 ] && grep -q 'Head_ZAccel.csv: a run has an empty or non-numeric value' '$tmp/b2.err' && ! grep -q Traceback '$tmp/b2.err'"

# A data folder path of more than 120 characters: the comments that name it
# (or its last directory) go on continuation comment cards, every card within
# 80 columns, nothing of the path lost, and the deck is valid. An --into
# directory too long for the INCLUDE card, or a name too long for the H5FILE
# card: refused, naming the line, and nothing written.
long=$tmp/volunteer_runs_kept_in_a_deep_folder/of_the_sled_tests_at_twelve_g
data=$long/the_runs_1607_to_1617_copied_from_the_shipped_twelve_g_set
mkdir -p "$long"
cp -r reference/nbdl_12g "$data"
check "the data folder path has ${#data} characters (at least 120)" [ ${#data} -ge 120 ]
python3 -m hhneck.validation.nbdl_tables --data "$data" --name long12 --into "$tmp" 2> "$tmp/long.err"
check "its decks written (exit $?)" [ $? -eq 0 ]
check "every card of both decks within 80 columns" \
    sh -c "[ -z \"\$(awk 'length > 80' '$tmp/long12.inp' '$tmp/long12_t1.inp')\" ]"
"$HHNECK" --check < "$tmp/long12.inp" > "$tmp/long.check" 2>&1
check "hhneck --check passes on the deck, with its T1 tables (exit $?)" [ $? -eq 0 ]
check "the comments hold the whole path (deck: the runs, --data and --deck; tables: the runs' folder)" \
    python3 - "$tmp/long12.inp" "$tmp/long12_t1.inp" "$data" "$tmp" <<'PY'
import os
import sys
deck, tables = (open(f).read().splitlines() for f in sys.argv[1:3])
data, into = sys.argv[3:5]
text = lambda lines: "".join(l[2:] for l in lines if l.startswith("* "))
def wrapped(lines, wanted):
    """Each wanted text in the comment cards' text joined, and on no one card."""
    return all(w in text(lines) and not any(w in l for l in lines) for w in wanted)
sys.exit(0 if wrapped(deck, ["in %s (T1 tables" % data, "--data X=%s" % data])
         and "--deck X=%s/long12.inp" % into in text(deck)
         and wrapped(tables, ["runs of %s (n = 10)" % os.path.basename(data)]) else 1)
PY
check "its T1 tables equal the shipped 12 g ones" sh -c \
    "grep -v '^\*' '$tmp/long12_t1.inp' | cmp -s - '$tmp/shipped12.txt'"
python3 -m hhneck.validation.nbdl_tables --data "$data" --name long12 --into "$long" 2> "$tmp/into.err"
rc=$?
check "an --into directory too long for the INCLUDE card: refused (exit $rc), naming the line, nothing written" sh -c \
    "[ $rc -ne 0 ] && grep -q 'long12.inp, line [0-9]*: the INCLUDE card has [0-9]* columns' '$tmp/into.err' &&
     ! grep -q Traceback '$tmp/into.err' && [ ! -e '$long/long12.inp' ] && [ ! -e '$long/long12_t1.inp' ]"
name=runs_of_a_volunteer_series_with_a_name_long_enough_to_pass_column_80
python3 -m hhneck.validation.nbdl_tables --data "$data" --name "$name" --into "$tmp" 2> "$tmp/name.err"
rc=$?
check "a name too long for the H5FILE card: refused (exit $rc), naming the line, nothing written" sh -c \
    "[ $rc -ne 0 ] && grep -q 'line [0-9]*: the H5FILE card has [0-9]* columns' '$tmp/name.err' &&
     ! grep -q Traceback '$tmp/name.err' && [ ! -e '$tmp/$name.inp' ] && [ ! -e '$tmp/${name}_t1.inp' ]"
finish
