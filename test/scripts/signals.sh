#!/bin/sh
# A run stopped by SIGTERM: exit code 5, a valid result file marked
# incomplete. A run killed outright (SIGKILL): no file under the result name.
. test/scripts/lib/checks.sh

# NBDL at RK4 with a 10 us step: long enough to be stopped after 2 s
# (the discs' damping of the earlier model, 5 ms: the model deck's 3.33 s
# puts a mode of 4.9e6 1/s in the discs' shear, beyond RK4 at 10 us)
sed 's/^CONTROL .*/CONTROL   0.25      1.0E-5    0.005     RK4/' \
    input/nbdl15g.inp > "$tmp/long.inp"
echo 'SCALE     EXPLICIT  DISCS     VISCOUS   0.0015' >> "$tmp/long.inp"

"$HHNECK" --h5 "$tmp/term.h5" < "$tmp/long.inp" > "$tmp/term.out" 2> "$tmp/term.err" &
pid=$!
sleep 2
kill -TERM "$pid"
wait "$pid"
rc=$?
check "SIGTERM: exit code 5 (got $rc)" [ "$rc" -eq 5 ]
check "SIGTERM: stderr says interrupted by signal 15" grep -q "interrupted by signal 15" "$tmp/term.err"
check "SIGTERM: the partial file is renamed to the result name" [ ! -e "$tmp/term.h5.part" ]
py_checks test/scripts/lib/check_incomplete.py "$tmp/term.h5" 0.25

"$HHNECK" --h5 "$tmp/kill.h5" < "$tmp/long.inp" > /dev/null 2>&1 &
pid=$!
sleep 2
kill -KILL "$pid"
wait "$pid" 2> /dev/null
check "SIGKILL: no file under the result name (the partial file stays kill.h5.part)" [ ! -e "$tmp/kill.h5" ]
finish
