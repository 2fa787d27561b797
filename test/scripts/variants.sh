#!/bin/sh
# A variant deck (its own TITLE, a shipped case deck INCLUDEd, CHANGE
# cards) and CHANGE cards from the command line (--change): the included
# deck's title is a second title line on every page of the listing and
# /deck/subtitles in the result file; each --change card is echoed with the
# deck, noted with the deck's changes as "--change N" (listing and
# /deck/changes) and located so in a message; a deck without either keeps
# its one-line title. Runs of 2 ms of the NBDL 15 g deck.
. test/scripts/lib/checks.sh

tend='CHANGE    TEND      FIELD1    CONTROL             SET       0.002'
c7ry='CHANGE    C7LIM     FIELD5    LIMIT     C7        SCALE     2.0       RY'
cat > "$tmp/variant.inp" <<DECK
TITLE     NBDL 15 G, DISCS 20 % STIFFER (A VARIANT DECK)
INCLUDE   input/nbdl15g.inp
CHANGE    E12       FAMILY    DISCS     E         SCALE     1.2
$tend
DECK

"$HHNECK" --h5 "$tmp/variant.h5" --change "$c7ry" "$tmp/variant.inp" > "$tmp/variant.lis" 2> "$tmp/variant.err"
rc=$?
check "the variant deck with a --change card runs (exit 0, got $rc)" [ "$rc" -eq 0 ]
[ "$rc" -eq 0 ] || tail -n 3 "$tmp/variant.err"
pages=$(grep -c ' PAGE  *[0-9]*$' "$tmp/variant.lis")
subs=$(grep -c '^ INCLUDES: NBDL 15 G FRONTAL SLED, T1 DRIVEN BY THE MEAN OF 7 VOLUNTEER RUNS$' "$tmp/variant.lis")
check "every page (of $pages) has the included deck's title as its second title line ($subs)" \
    sh -c '[ "$1" -gt 1 ] && [ "$1" -eq "$2" ]' sh "$pages" "$subs"
check "the first title line is the variant's own" \
    sh -c 'sed -n 3p "$1" | grep -qx " NBDL 15 G, DISCS 20 % STIFFER (A VARIANT DECK)"' sh "$tmp/variant.lis"
check "pages stay within 60 lines with the second title line" \
    sh -c 'awk "/ PAGE +[0-9]+\$/ {if (n > m) m = n; n = 0} {n++} END {exit !(m <= 61)}" "$1"' sh "$tmp/variant.lis"
check "the deck echo shows the --change card after the deck's cards" \
    grep -q '  --change:1  *CHANGE    C7LIM     FIELD5    LIMIT     C7        SCALE     2.0       RY$' "$tmp/variant.lis"
check "the listing notes the --change card with the deck's changes" \
    grep -q '^     C7LIM: LIMIT C7 RY field F5 5.00000E-2 -> 1.00000E-1  (--change 1)$' "$tmp/variant.lis"
check "the listing notes the deck's own changes too" \
    grep -q '^     E12: every element of DISCS, E x 1.20000E+0  (.*variant.inp line 3)$' "$tmp/variant.lis"
cat > "$tmp/read.py" <<'PY'
import sys
import h5py
with h5py.File(sys.argv[1], 'r') as f:
    subs = [s.decode() for s in f['/deck/subtitles'][()]]
    changes = [s.decode() for s in f['/deck/changes'][()]]
    src = [s.decode().strip() for s in f['/deck/source'][()]]
    print('title=' + f.attrs['title'])
    print('subtitles=' + '|'.join(subs))
    print('changes=' + '|'.join(changes))
    print('sources=' + str(src.count('--change')))
PY
python3 "$tmp/read.py" "$tmp/variant.h5" > "$tmp/variant.h5.txt" 2>&1
check "the result file keeps the variant's title" \
    grep -qx 'title=NBDL 15 G, DISCS 20 % STIFFER (A VARIANT DECK)' "$tmp/variant.h5.txt"
check "the result file keeps the included deck's title in /deck/subtitles" \
    grep -qx 'subtitles=NBDL 15 G FRONTAL SLED, T1 DRIVEN BY THE MEAN OF 7 VOLUNTEER RUNS' "$tmp/variant.h5.txt"
check "/deck/changes holds the --change card's note" grep -q '^changes=.*(--change 1)' "$tmp/variant.h5.txt"
check "/deck/source names the --change card" grep -qx 'sources=1' "$tmp/variant.h5.txt"

# the shipped deck with --change alone: one title line, no subtitles
"$HHNECK" --h5 "$tmp/plain.h5" --change "$tend" --change "$c7ry" input/nbdl15g.inp > "$tmp/plain.lis" 2> "$tmp/plain.err"
rc=$?
check "the shipped deck with 2 --change cards runs (exit 0, got $rc)" [ "$rc" -eq 0 ]
check "its header has the one title line" \
    sh -c 'sed -n 4p "$1" | grep -q "^=====" && ! grep -q "^ INCLUDES: " "$1"' sh "$tmp/plain.lis"
check "its result file has no /deck/subtitles" \
    python3 -c "import h5py, sys; sys.exit('/deck/subtitles' in h5py.File('$tmp/plain.h5', 'r'))"
check "both --change cards are noted, in their order" \
    sh -c 'grep -n "(--change [12])\$" "$1" | grep -q "TEND.*--change 1" &&
           grep "(--change [12])\$" "$1" | tail -n 1 | grep -q "C7LIM.*--change 2"' sh "$tmp/plain.lis"

# errors
"$HHNECK" --check --change "$tend" --change 'CHANGE    C7LIM     FIELD5    LIMIT     C7        SCALE     2.0' \
    input/nbdl15g.inp > /dev/null 2> "$tmp/bad.err"
rc=$?
check "an ambiguous --change card is a deck error (exit 2, got $rc)" [ "$rc" -eq 2 ]
rx=$(grep -n '^LIMIT     C7        RX' input/head_neck_54dof.inp | cut -d: -f1)
check "located at --change 2, with the candidates and what tells them apart" \
    grep -q "^hhneck: deck error: --change 2 (CHANGE C7LIM): found 3 LIMIT cards named C7 (.*line $rx .* RX, line $((rx + 1)) RY, line $((rx + 2)) RZ); expected the coordinate too, in F7" \
    "$tmp/bad.err"
"$HHNECK" --sweep --change "$tend" input/sweep_nbdl_oat.inp > /dev/null 2> "$tmp/sweep.err"
rc=$?
check "--change with --sweep is a usage error (exit 1, got $rc)" [ "$rc" -eq 1 ]
"$HHNECK" --help > "$tmp/help.txt" 2>&1
check "--help names --change" grep -q "^  --change 'CARD' " "$tmp/help.txt"
finish
