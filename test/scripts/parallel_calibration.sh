#!/bin/sh
# A calibration on every core gives the listing of one thread: its starting
# points, its cases' runs, their analyses at rest and their ratings run in
# parallel (OpenMP) and are combined in the serial order. A short fit of
# the shipped 12 g calibration with its standing case (the VALUES point and
# one starting point, then Nelder-Mead's simplex and first step, 12 or 13
# evaluations) and the two-case deck (15 g and 12 g) scored once at its
# nominal values, each on one thread and on two (OMP_NUM_THREADS; two
# threads also on one core), are compared line by line.
# Release build: the threads as a user's calibration runs them (the
# checking build runs calibrations in test/unit/test_calibration.pf).
# builds: release
. test/scripts/lib/checks.sh
cut_fit() {   # cut_fit DECK EVALS STARTS: the deck's FIT card cut to EVALS evaluations from STARTS starting points
    sed -e "s/^\(FIT       NELDER    \)[0-9 ]\{14\}/\1$(printf '%-10s%-4s' "$2" "$3")/" "$1"
}
# the shipped 12 g calibration (the controller's) with its 12 g case and its
# standing case (the RETURN and REST cases left out), cut to the VALUES
# point, one starting point and Nelder-Mead's first steps
grep -v '^RETURN\|^REST ' input/calibrate_controller.inp | cut_fit - 10 2 > "$tmp/one_case.inp"
# the two-case deck judges standing by a run of the volunteer state at rest
# (a STANDING case, 2 s, joints within 10 deg) in place of the linear margin,
# which the controller's loops (sampled-data) do not enter
standing=$(printf 'STANDING  %-60s%-10s' input/calibrate_controller_rest.inp 10.0)
cut_fit input/calibrate_nbdl.inp 0 4 | sed -e '/^VALUES/d' | awk -v s="$standing" '{print} /^FIT / {print s}' \
    > "$tmp/two_cases.inp"
for deck in one_case two_cases; do
    check "the $deck deck is cut short (FIT: at most 10 evaluations)" awk \
        '/^FIT / { found = 1; if ($3 + 0 > 10) exit 1 } END { exit !found }' "$tmp/$deck.inp"
    OMP_NUM_THREADS=1 "$HHNECK" --calibrate "$tmp/$deck.inp" > "$tmp/$deck.1" 2> "$tmp/$deck.1.err"
    rc1=$?
    OMP_NUM_THREADS=2 "$HHNECK" --calibrate "$tmp/$deck.inp" > "$tmp/$deck.2" 2> "$tmp/$deck.2.err"
    rc2=$?
    check "$deck: both complete (exit $rc1 and $rc2)" sh -c '[ "$1" -eq 0 ] && [ "$2" -eq 0 ]' sh "$rc1" "$rc2"
    check "$deck: the listing on two threads is the listing on one" cmp "$tmp/$deck.1" "$tmp/$deck.2"
done
# the VALUES point and one start, Nelder-Mead's simplex of 9 points (8
# parameters) and its first iteration (a reflection, and at most one
# expansion or contraction)
n=$(grep -c '^ *\(start\|nelder\) ' "$tmp/one_case.1")
check "one_case: the fit lists its 12 or 13 evaluations (found $n)" sh -c '[ "$1" -ge 12 ] && [ "$1" -le 13 ]' sh "$n"
check "one_case: its best point's 12 g case is rated and its standing case listed" sh -c \
    'grep -q "^CASE .*: MEAN RATING" "$1" && grep -q "^STANDING CASE 1: LARGEST EXCURSION AT REST" "$1"' sh "$tmp/one_case.1"
check "two_cases: both cases are rated" sh -c '[ "$(grep -c "^CASE .*: MEAN RATING" "$1")" -eq 2 ]' sh "$tmp/two_cases.1"
check "two_cases: the nominal values stand at rest (the standing case within its bound) and are run" \
    awk '/^STANDING CASE 1: LARGEST EXCURSION AT REST/ {found = 1; exit !($8 + 0 < $11 + 0)} END {if (!found) exit 1}' \
    "$tmp/two_cases.1"
finish
