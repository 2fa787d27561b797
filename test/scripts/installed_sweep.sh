#!/bin/sh
# An installed hhneck runs a sweep outside the project: the sweep's BASE
# deck and the INCLUDE files of both decks are found as a single run finds
# INCLUDE files (next to the including file, the working directory, then
# -I DIR and HHNECK_PATH), by the serial sweep and by the sweep driver
# (the fpm example sweep_mpi, app/mpi/sweep_mpi.F90, built without MPI
# next to the executable). Each
# sweep has 2 members of a few milliseconds of the NBDL 15 g deck.
. test/scripts/lib/checks.sh
project=$(pwd)
sm=$(dirname "$HHNECK")/../example/sweep_mpi

run=$tmp/run          # an empty working directory outside the project
decks=$tmp/decks      # where a user keeps his own decks
mkdir -p "$run" "$decks"

# 1. the shipped case deck as BASE, its end time swept: 2 members of 1 and 2 ms
cat > "$run/sweep.inp" <<'DECK'
TITLE     INSTALLED SWEEP: THE SHIPPED NBDL DECK, 2 SHORT MEMBERS
BASE      input/nbdl15g.inp
DESIGN    FACTORIAL 2
PARAM     TEND      FIELD1    CONTROL             0.001     0.002
DECK
cd "$run" || exit 1

"$HHNECK" --sweep --no-h5 sweep.inp > plain.txt 2> plain.err
rc=$?
check "without -I or HHNECK_PATH the sweep deck is refused (exit 2, got $rc)" [ "$rc" -eq 2 ]
check "the message names the BASE card and says how to find the shipped decks" \
    grep -q 'sweep.inp line 2, columns 11-80 (BASE card): file "input/nbdl15g.inp" not found.*-I DIR or HHNECK_PATH' \
    plain.err

"$HHNECK" --sweep --no-h5 -I "$project" sweep.inp > dash_i.txt 2> dash_i.err
rc=$?
check "with -I PROJECT the sweep runs both members (exit 0, got $rc)" [ "$rc" -eq 0 ]
check "with -I PROJECT: all 2 member runs complete" grep -q 'all 2 member runs complete' dash_i.err
[ "$rc" -eq 0 ] || tail -n 3 dash_i.err

HHNECK_PATH="$tmp/nothing-here:$project" "$HHNECK" --sweep --no-h5 < sweep.inp > env.txt 2> env.err
rc=$?
check "with HHNECK_PATH (2 directories) the sweep on standard input runs (exit 0, got $rc)" [ "$rc" -eq 0 ]
check "with HHNECK_PATH: all 2 member runs complete" grep -q 'all 2 member runs complete' env.err
[ "$rc" -eq 0 ] || tail -n 3 env.err
check "the members are the same with -I and with HHNECK_PATH" \
    sh -c 'grep "^ *[12]  0 " dash_i.txt > a.rows; grep "^ *[12]  0 " env.txt > b.rows; [ -s a.rows ] && cmp -s a.rows b.rows'

# 2. the user's own base deck next to his sweep deck, including the model
#    deck from the directory of the shipped decks (-I PROJECT/input)
sed -n '/^TITLE/,$p' "$project/input/nbdl15g.inp" |
    sed -e 's/^CONTROL .*/CONTROL   0.002     1.0E-4    0.001     ROS34PW2  1.0E-3    1.0E-5/' \
        -e 's|^INCLUDE   input/|INCLUDE   |' -e '/^H5FILE/d' > "$decks/short_base.inp"
cat > "$decks/sweep.inp" <<'DECK'
TITLE     INSTALLED SWEEP: MY BASE DECK, THE SHIPPED MODEL DECK
BASE      short_base.inp
DESIGN    FACTORIAL 2
PARAM     HEAD_M    BODY      HEAD      MASS      0.9       1.1
DECK
"$HHNECK" --sweep --no-h5 -I "$project/input" "$decks/sweep.inp" > own.txt 2> own.err
rc=$?
check "a BASE deck next to the sweep deck, its INCLUDEs through -I PROJECT/input (exit 0, got $rc)" [ "$rc" -eq 0 ]
[ "$rc" -eq 0 ] || tail -n 3 own.err
"$HHNECK" --sweep --no-h5 "$decks/sweep.inp" > own_plain.txt 2> own_plain.err
rc=$?
check "the same without -I: the base deck's INCLUDE line is named (exit 2, got $rc)" \
    sh -c '[ "$1" -eq 2 ] && grep -q "short_base.inp line [0-9]*, columns 11-80 (INCLUDE card): file \"head_neck_54dof.inp\" not found" own_plain.err' \
    sh "$rc"

# 3. the sweep driver (example/sweep_mpi) finds them the same way
if [ -x "$sm" ]; then
    "$sm" sweep.inp --no-h5 -I "$project" > sm.txt 2> sm.err
    rc=$?
    check "sweep_mpi with -I PROJECT runs both members (exit 0, got $rc)" [ "$rc" -eq 0 ]
    [ "$rc" -eq 0 ] || tail -n 3 sm.err
    HHNECK_PATH=$project "$sm" sweep.inp --no-h5 > sm_env.txt 2> sm_env.err
    rc=$?
    check "sweep_mpi with HHNECK_PATH runs both members (exit 0, got $rc)" [ "$rc" -eq 0 ]
    "$sm" sweep.inp --no-h5 > sm_plain.txt 2> sm_plain.err
    rc=$?
    check "sweep_mpi without either refuses the sweep deck (exit 2, got $rc)" [ "$rc" -eq 2 ]
    check "sweep_mpi gives the serial program's member rows" \
        sh -c 'grep "^ *[12]  0 " sm.txt > c.rows; cmp -s a.rows c.rows'
    # members long enough for gradual underflow in the elements: a complete
    # sweep ends without gfortran's note of the floating-point flags raised
    sed -e 's/0\.001     0\.002/0.1       0.15/' sweep.inp > long.inp
    "$sm" long.inp --no-h5 -I "$project" > sm_long.txt 2> sm_long.err
    rc=$?
    check "sweep_mpi with 100 and 150 ms members completes (exit 0, got $rc)" [ "$rc" -eq 0 ]
    check "... and prints no note of raised floating-point flags on stderr" \
        sh -c '! grep -q "floating-point exceptions are signalling" sm_long.err'
else
    echo "note: no sweep_mpi next to $HHNECK (fpm build builds it); its checks are left out"
fi
cd "$project" || exit 1
finish
