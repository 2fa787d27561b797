#!/bin/sh
# An installed hhneck checks a calibration deck outside the project: its
# CASE decks and its DATA directories of volunteer runs are found as INCLUDE
# files are (next to the calibration deck, the working directory, then
# -I DIR and HHNECK_PATH); a DATA directory found nowhere is named with its
# card and the places looked in. Only --check (a fit runs for an hour).
. test/scripts/lib/checks.sh
project=$(pwd)
run=$tmp/run          # an empty working directory outside the project
mine=$tmp/mine        # a user's own calibration deck beside his data
mkdir -p "$run" "$mine"
cd "$run" || exit 1

"$HHNECK" --calibrate "$project/input/calibrate_nbdl.inp" --check > plain.txt 2> plain.err
rc=$?
check "without -I the shipped calibration deck is refused from another directory (exit 2, got $rc)" [ "$rc" -eq 2 ]
check "the message names the DATA card, the directory and where it was looked for" \
    grep -q 'calibrate_nbdl.inp line [0-9]* (DATA card): directory "reference/nbdl_15g" not found (looked for .*input/reference/nbdl_15g, reference/nbdl_15g' \
    plain.err

"$HHNECK" -I "$project" --calibrate "$project/input/calibrate_nbdl.inp" --check > dash_i.txt 2> dash_i.err
rc=$?
check "with -I PROJECT the shipped calibration deck is valid (exit 0, got $rc)" \
    sh -c '[ "$1" -eq 0 ] && grep -q "calibration deck is valid" dash_i.err' sh "$rc"
[ "$rc" -eq 0 ] || tail -n 3 dash_i.err

HHNECK_PATH="$tmp/nothing-here:$project" "$HHNECK" --calibrate "$project/input/calibrate_nbdl.inp" --check \
    > env.txt 2> env.err
rc=$?
check "with HHNECK_PATH (2 directories) it is valid too (exit 0, got $rc)" [ "$rc" -eq 0 ]

# a user's deck with its data next to it: found beside the deck, whatever
# the working directory
cp -r "$project/reference/nbdl_15g" "$mine/my15g"
sed -e 's|^DATA      reference/nbdl_15g|DATA      my15g|' "$project/input/calibrate_nbdl.inp" > "$mine/cal.inp"
check "the copied deck names its own data directory" grep -q '^DATA      my15g' "$mine/cal.inp"
"$HHNECK" -I "$project" --calibrate "$mine/cal.inp" --check > own.txt 2> own.err
rc=$?
check "a DATA directory next to the calibration deck is found from elsewhere (exit 0, got $rc)" [ "$rc" -eq 0 ]
[ "$rc" -eq 0 ] || tail -n 3 own.err

# a DATA card naming a file, not a directory
sed -e 's|^DATA      reference/nbdl_15g|DATA      cal.inp|' "$mine/cal.inp" > "$mine/bad.inp"
sed -i -e 's|^DATA      my15g|DATA      cal.inp|' "$mine/bad.inp"
"$HHNECK" -I "$project" --calibrate "$mine/bad.inp" --check > bad.txt 2> bad.err
rc=$?
check "a DATA card naming a regular file is refused (exit 2, got $rc)" [ "$rc" -eq 2 ]
check "... saying it is a regular file and a directory was expected" \
    grep -q 'bad.inp line [0-9]* (DATA card): ".*cal.inp" is a regular file; expected a directory' bad.err
finish
