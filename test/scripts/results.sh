#!/bin/sh
# The HDF5 result file of case 6-2 has the documented layout, read by h5py.
# Results are never lost: a variant deck that INCLUDEs case 6-2 writes a
# file named after itself, so base and variant run one after the other keep
# both files; a run whose file holds another deck's results is refused
# before it starts (exit 4, the file kept) unless --overwrite is given; the
# same deck run again replaces its own file. --set KEY=VALUE runs as the
# --change card it stands for.
. test/scripts/lib/checks.sh

"$HHNECK" --h5 "$tmp/case6-2.h5" < input/case6-2.inp > "$tmp/listing.txt" 2> "$tmp/err.txt"
check "case 6-2 runs to the end (exit code 0)" [ $? -eq 0 ]
py_checks test/scripts/lib/check_results.py "$tmp/case6-2.h5"

# attr FILE NAME: a root attribute of a result file
attr() {
    python3 -c 'import sys, h5py; print(h5py.File(sys.argv[1], "r").attrs[sys.argv[2]])' "$1" "$2"
}
base="CASE 6-2 FOREHEAD PENDULUM IMPACT (RECONSTRUCTED FORCE PULSE)"
w=$tmp/names
mkdir -p "$w/input"
cp input/case6-2.inp input/head_neck_54dof.inp "$w/input/"
cat > "$w/input/heavy.inp" <<'DECK'
TITLE     CASE 6-2, HEAD 10 % HEAVIER
INCLUDE   input/case6-2.inp
CHANGE    HEADM     BODY      HEAD      MASS      SCALE     1.1
DECK
cd "$w" || exit 1
"$HHNECK" input/case6-2.inp > base.lis 2> base.err
check "the base deck input/case6-2.inp writes case6-2.h5 (its H5FILE card; exit $?)" [ -f case6-2.h5 ]
check "the file records the deck: title and deck file case6-2.inp" \
    [ "$(attr case6-2.h5 title)|$(attr case6-2.h5 deck_file)" = "$base|case6-2.inp" ]
"$HHNECK" input/heavy.inp > heavy.lis 2> heavy.err
rc=$?
ok=no; [ "$rc" -eq 0 ] && [ -f heavy.h5 ] && [ "$(attr heavy.h5 deck_file)" = heavy.inp ] && ok=yes
check "the variant input/heavy.inp (INCLUDE input/case6-2.inp) runs (exit $rc) and writes heavy.h5, named after itself" [ "$ok" = yes ]
check "base and variant run one after the other keep both files: case6-2.h5 still the base's" \
    [ "$(attr case6-2.h5 title)" = "$base" ]
cksum case6-2.h5 > before.sum
"$HHNECK" < input/heavy.inp > stdin.lis 2> stdin.err
rc=$?
check "the variant from standard input (the INCLUDEd H5FILE, case6-2.h5, holds the base's results): refused, exit 4 (got $rc)" \
    [ "$rc" -eq 4 ]
check "the message names the file, both decks and --overwrite" \
    grep -q "the result file case6-2.h5 holds the results of another deck (\"$base\", case6-2.inp), not of this one (\"CASE 6-2, HEAD 10 % HEAVIER\", stdin); nothing was run and the file is kept: give --overwrite" stdin.err
check "refused before the run starts: no listing, the file unchanged" \
    sh -c '[ ! -s stdin.lis ] && cksum case6-2.h5 | cmp -s - before.sum && [ ! -e case6-2.h5.part ]'
"$HHNECK" --overwrite < input/heavy.inp > stdin.lis 2> stdin.err
rc=$?
ok=no; [ "$rc" -eq 0 ] && [ "$(attr case6-2.h5 title)" = "CASE 6-2, HEAD 10 % HEAVIER" ] && ok=yes
check "with --overwrite the variant replaces it (exit $rc, the file now the variant's)" [ "$ok" = yes ]
"$HHNECK" input/heavy.inp > heavy.lis 2> heavy.err
rc=$?
ok=no; [ "$rc" -eq 0 ] && grep -q "removed the older result file heavy.h5" heavy.err && ok=yes
check "the same deck run again replaces its own file (exit $rc)" [ "$ok" = yes ]
"$HHNECK" --h5 heavy.h5 input/case6-2.inp > /dev/null 2> other.err
rc=$?
check "another deck given --h5 onto heavy.h5: refused too, exit 4 (got $rc)" [ "$rc" -eq 4 ]
sed 's/^TITLE .*/TITLE     A COPY OF CASE 6-2 UNDER ANOTHER NAME/' input/case6-2.inp > input/copy.inp
"$HHNECK" input/copy.inp > /dev/null 2> copy.err
rc=$?
check "a copy with its own title and the base's H5FILE card: refused, exit 4 (got $rc)" [ "$rc" -eq 4 ]
echo "not a result file" > notes.h5
"$HHNECK" --h5 notes.h5 input/heavy.inp > /dev/null 2> notes.err
rc=$?
ok=no; [ "$rc" -eq 4 ] && grep -q "is not a result file of hhneck" notes.err && grep -q "not a result file" notes.h5 && ok=yes
check "a file that is not a result file: refused, exit 4 (got $rc), kept" [ "$ok" = yes ]
printf 'TITLE     CASE 6-2 WITH ITS OWN FILE\nINCLUDE   input/case6-2.inp\nH5FILE    own.h5\n' > input/own.inp
"$HHNECK" input/own.inp > /dev/null 2> own.err
rc=$?
ok=no; [ "$rc" -eq 0 ] && [ -f own.h5 ] && ok=yes
check "a variant with an H5FILE card of its own writes that file (exit $rc)" [ "$ok" = yes ]

# --set KEY=VALUE is the CHANGE card it stands for: the same run, channel
# for channel, as with the equivalent --change; the listings differ only in
# the date, the wall time and the option's name
same_run() {
    python3 - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
a, b = (h5py.File(f, "r") for f in sys.argv[1:3])
ok = all(np.array_equal(a["channels"][n][()], b["channels"][n][()]) for n in a["channels"]) and \
    [c.replace(b"--set 1", b"--change 1") for c in a["deck/changes"][()]] == list(b["deck/changes"][()])
sys.exit(0 if ok and len(a["deck/changes"][()]) == 1 else 1)
PY
}
listing() {
    grep -v 'PAGE\|WALL TIME' "$1" | sed 's/--set[: ]1/--change 1/; s/--change:1/--change 1/' | tr -s ' '
}
"$HHNECK" --set 'BODY.HEAD.MASS*=1.1' --h5 set.h5 input/case6-2.inp > set.lis 2> set.err
rc=$?
"$HHNECK" --change 'CHANGE    SET1      BODY      HEAD      MASS      SCALE     1.1' --h5 change.h5 \
    input/case6-2.inp > change.lis 2> change.err
rc2=$?
ok=no; [ "$rc" -eq 0 ] && [ "$rc2" -eq 0 ] && same_run set.h5 change.h5 && ok=yes
check "--set BODY.HEAD.MASS*=1.1 runs (exit $rc) as --change 'CHANGE SET1 BODY HEAD MASS SCALE 1.1': every channel equal" \
    [ "$ok" = yes ]
listing set.lis > set.cmp
listing change.lis > change.cmp
check "... the same listing but for the option's name, noted 'SET1: mass of HEAD ... (--set 1)'" \
    sh -c 'cmp -s set.cmp change.cmp && grep -q "SET1: mass of HEAD 3.84700E+0 -> 4.23170E+0 kg  (--set 1)" set.lis'
"$HHNECK" --set CONTROL.F5=2.0E-5 --h5 set5.h5 input/case6-2.inp > /dev/null 2>&1
rc=$?
"$HHNECK" --change 'CHANGE    SET1      FIELD5    CONTROL             SET       2.0E-5' --h5 change5.h5 \
    input/case6-2.inp > /dev/null 2>&1
ok=no; [ "$rc" -eq 0 ] && same_run set5.h5 change5.h5 && ok=yes
check "--set CONTROL.F5=2.0E-5 (a field of a card) is the FIELD5 change too (exit $rc)" [ "$ok" = yes ]
"$HHNECK" --set BODY.HEAD.MAS=4.2 input/case6-2.inp > /dev/null 2> badkey.err
rc=$?
check "a bad key: exit 1 (got $rc), the option and the characters at fault named" \
    grep -q '^hhneck: --set 1, characters 11-13 of "BODY.HEAD.MAS=4.2": found "MAS"; expected Fn' badkey.err
"$HHNECK" --set 'FAMILY.DISCS.E=1.2' --set CONTROL.F5=1E-5x input/case6-2.inp > /dev/null 2> badvalue.err
rc=$?
check "a family property set, not scaled: exit 1 (got $rc), the '=' named" \
    grep -q "^hhneck: --set 1, characters 15-15 of \"FAMILY.DISCS.E=1.2\": found \"=\"; a family's property is scaled" \
    badvalue.err
"$HHNECK" --set CONTROL.F5=1E-5x input/case6-2.inp > /dev/null 2> badvalue.err
rc=$?
check "a bad value: exit 1 (got $rc), its characters named" \
    grep -q '^hhneck: --set 1, characters 12-16 of "CONTROL.F5=1E-5x": found "1E-5x"; expected a real number' badvalue.err
"$HHNECK" --change 'CHANGE    M         BODY      HEAD      MASS      SCALE     1.0' --set BODY.HEAD2.MASS=4.2 \
    input/case6-2.inp > /dev/null 2> badbody.err
rc=$?
ok=no; [ "$rc" -eq 2 ] && grep -q "^hhneck: deck error: --set 1, columns 31-40 (CHANGE card, field F3 'target'): found \"HEAD2\".*(--set 1 stands for the card 'CHANGE    SET1      BODY      HEAD2     MASS      SET       4.2')" badbody.err && ok=yes
check "a body the deck lacks: a deck error located as --set 1 with its card image, exit 2 (got $rc)" [ "$ok" = yes ]
cd - > /dev/null || exit 1
finish
