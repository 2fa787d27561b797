#!/bin/sh
# A bad deck (a negative end time on the CONTROL card): exit code 2, a
# message on stderr that names the line and columns, no result file. The
# mistakes that once passed --check and then cost the run: two elements of
# one name in an included deck, a second NEUTRAL card, an INITIAL card on a
# prescribed coordinate, a fixed-step run of 1E8 steps, a fixed-step run
# beyond its step limit; numbers across a field boundary (12.5 over F3/F4
# once read as 12 and 0.5), refused with the exact located message in
# --check and in a run, while a CHANGE that fills its field edge to edge
# passes; a calibration deck checked, not run.
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

# two DISC cards named C2C1 (the model deck included by the NBDL deck)
mkdir -p "$tmp/input"
sed 's/^DISC      C1HD /DISC      C2C1 /' input/head_neck_54dof.inp > "$tmp/input/head_neck_54dof.inp"
cp input/nbdl15g_t1.inp input/volunteer_controller.inp "$tmp/input/"
sed 's/^H5FILE .*/H5FILE    twice.h5/' input/nbdl15g.inp > "$tmp/input/twice.inp"
( cd "$tmp" && "$HHNECK" --check input/twice.inp ) > /dev/null 2> "$tmp/twice.err"
rc=$?
check "two DISC cards of one name: --check ends with exit code 2 (got $rc)" [ "$rc" -eq 2 ]
# the lines of the cards named, as the decks hold them
inc=$(grep -n '^INCLUDE   input/head_neck_54dof.inp' input/nbdl15g.inp | cut -d: -f1)
first=$(grep -n '^DISC      C2C1 ' input/head_neck_54dof.inp | cut -d: -f1)
second=$(grep -n '^DISC      C1HD ' input/head_neck_54dof.inp | cut -d: -f1)
check "the message names the second DISC card and the first" \
    grep -q "head_neck_54dof.inp line $second (included from input/twice.inp line $inc), columns 11-20 (DISC card, element name): found \"C2C1\" again.*the DISC card at input/head_neck_54dof.inp line $first" "$tmp/twice.err"
( cd "$tmp" && "$HHNECK" input/twice.inp ) > /dev/null 2>&1
rc=$?
check "the run is refused as a deck error before it starts (exit code 2, got $rc)" [ "$rc" -eq 2 ]

# a second NEUTRAL card of C7 RY; an INITIAL card on the prescribed T1 TX
awk '{print} /^HOLD/ {print "NEUTRAL   C7        RY        20.0"; print "NEUTRAL   C7        RY        21.0"}' \
    input/nbdl15g.inp > "$tmp/neutral.inp"
"$HHNECK" --check < "$tmp/neutral.inp" > /dev/null 2> "$tmp/neutral.err"
rc=$?
check "two NEUTRAL cards of C7 RY: exit code 2 (got $rc)" [ "$rc" -eq 2 ]
check "the message names both NEUTRAL cards" grep -q 'stdin line 17, columns 11-30 (NEUTRAL card.*the NEUTRAL card at stdin line 16' "$tmp/neutral.err"
awk '{print} /^HOLD/ {print "INITIAL   T1        TX        0.0       1.0"}' input/nbdl15g.inp > "$tmp/initial.inp"
"$HHNECK" --check < "$tmp/initial.inp" > /dev/null 2> "$tmp/initial.err"
rc=$?
check "an INITIAL card on a prescribed coordinate: exit code 2 (got $rc)" [ "$rc" -eq 2 ]
hold=$(grep -n '^HOLD' input/nbdl15g.inp | cut -d: -f1)
prescrib=$(grep -n '^PRESCRIB  T1        TX' input/nbdl15g.inp | cut -d: -f1)
check "the message names the PRESCRIB card and the INITIAL card" \
    grep -q "stdin line $((prescrib + 1)), columns 11-30 (PRESCRIB card.*the INITIAL card at stdin line $((hold + 1))" "$tmp/initial.err"

# RK4 with a 1E-9 s step over 0.1 s: named by --check with the step count
sed 's/^CONTROL .*/CONTROL   0.1       1.0E-9    0.005     RK4/' input/nbdl15g.inp > "$tmp/rk4.inp"
"$HHNECK" --check < "$tmp/rk4.inp" > /dev/null 2> "$tmp/rk4.err"
rc=$?
check "RK4 over 1E8 steps: --check still accepts the deck (got $rc)" [ "$rc" -eq 0 ]
check "and warns with the CONTROL card, the step count and the wall time" \
    grep -q "warning: stdin line 9, columns 21-30 (CONTROL card, field F2 'step'): RK4 takes  1.00E+08 fixed steps.* of wall time" "$tmp/rk4.err"
"$HHNECK" --check --max-steps 100000 < "$tmp/rk4.inp" > /dev/null 2> "$tmp/rk4limit.err"
rc=$?
check "beyond --max-steps: refused by --check, exit code 2 (got $rc)" [ "$rc" -eq 2 ]
check "the refusal names the step limit" grep -q "more than its step limit of 100000" "$tmp/rk4limit.err"

# numbers across a field boundary: exit 2 with the located message, in
# --check and in a run (nothing written)
# straddled FILE WHAT CARD MESSAGE: the nbdl15g deck with CARD after its HOLD card
straddled() {
    awk -v card="$3" '{print} /^HOLD/ {print card}' input/nbdl15g.inp > "$tmp/$1.inp"
    "$HHNECK" --check < "$tmp/$1.inp" > /dev/null 2> "$tmp/$1.check"
    rc=$?
    check "$2: --check refuses it, exit code 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$2: --check names line and columns, both fields and the spill" \
        [ "$(cat "$tmp/$1.check")" = "hhneck: deck error: $4" ]
    "$HHNECK" --h5 "$tmp/$1.h5" < "$tmp/$1.inp" > /dev/null 2> "$tmp/$1.err"
    rc=$?
    check "$2: a run refuses it, exit code 2 (got $rc), the same message, no result file" \
        sh -c "[ $rc -eq 2 ] && cmp -s '$tmp/$1.check' '$tmp/$1.err' && [ ! -e '$tmp/$1.h5' ]"
}
straddled across "12.5 over the F3/F4 boundary of INITIAL" 'INITIAL   C7        RY                12.5' \
    "stdin line 16, columns 39-42 (INITIAL card, fields F3 'initial value' and F4): found \"12.5\" across the boundary of F3 (columns 31-40) and F4 (columns 41-50) with no blank between: the number spills into columns 41-42 of F4; expected each number inside its own field's ten columns"
straddled back "a rate spilling back into F3" 'INITIAL   C7        RY        0.0     -12.5' \
    "stdin line 16, columns 39-43 (INITIAL card, fields F3 'initial value' and F4): found \"-12.5\" across the boundary of F3 (columns 31-40) and F4 (columns 41-50) with no blank between: the number spills into columns 39-40 of F3; expected each number inside its own field's ten columns"
straddled long "a long number spilling over F3" 'INITIAL   C7        RY        1.23456789012' \
    "stdin line 16, columns 31-43 (INITIAL card, fields F3 'initial value' and F4): found \"1.23456789012\" across the boundary of F3 (columns 31-40) and F4 (columns 41-50) with no blank between: the number spills into columns 41-43 of F4; expected each number inside its own field's ten columns"
# a FIELD change writes ten columns edge to edge (1.23457E+0) against F4's 5.0: a whole field, accepted
"$HHNECK" --check --change 'CHANGE    I3        FIELD3    INITIAL   C3        SET       1.23456789' \
    input/rest_spindle.inp > /dev/null 2> "$tmp/whole.err"
rc=$?
check "a CHANGE that fills F3 edge to edge beside F4's 5.0: --check passes (exit $rc)" [ "$rc" -eq 0 ]

# a calibration deck is checked, not run
"$HHNECK" --calibrate --check input/calibrate_nbdl.inp > "$tmp/cal.out" 2> "$tmp/cal.err"
rc=$?
check "--calibrate --check: exit code 0 (got $rc)" [ "$rc" -eq 0 ]
check "and says the calibration deck is valid, without a fit history" \
    sh -c "grep -q 'calibration deck is valid' '$tmp/cal.err' && [ ! -s '$tmp/cal.out' ]"
finish
