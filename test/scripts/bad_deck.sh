#!/bin/sh
# A bad deck (a negative end time on the CONTROL card): exit code 2, a
# message on stderr that names the line and columns, no result file.
. test/scripts/lib/checks.sh

sed 's/^CONTROL   0.1  /CONTROL   -0.1 /' input/case6-2.inp > "$tmp/bad.inp"
"$HHNECK" --h5 "$tmp/bad.h5" < "$tmp/bad.inp" > "$tmp/bad.out" 2> "$tmp/bad.err"
rc=$?
check "a bad deck ends with exit code 2 (got $rc)" [ "$rc" -eq 2 ]
check "the message names stdin line 10, columns 11-20, the CONTROL card's end time" \
    grep -q "stdin line 10, columns 11-20 (CONTROL card, field F1 'end time')" "$tmp/bad.err"
check "no result file" [ ! -e "$tmp/bad.h5" ]
check "no partial result file" [ ! -e "$tmp/bad.h5.part" ]
check "the error goes to stderr, not into the listing" sh -c "! grep -q 'deck error' '$tmp/bad.out'"
finish
