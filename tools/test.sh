#!/bin/sh
# The whole test suite (docs/testing.md):
#   1. every test program -- the pFUnit suites of test/unit/*.pf and the
#      program tests test/*.f90 -- in a debug build,
#   2. the same again in a checking build that traps invalid operations,
#      division by zero and overflow and checks every array bound and
#      pointer (skipped with --no-checking-build),
#   3. every whole-program check test/scripts/*.sh, with HHNECK set to the
#      debug build's executable.
# Each test program and script ends its output with "N passed, N failed";
# the last line is the total over all of them. Exit code 1 on any failure.
#   tools/test.sh NAME [FILTER]   only the test program NAME (a suite
#                                 test/unit/NAME.pf or test/NAME.f90) in the
#                                 debug build; with FILTER only its tests whose
#                                 name contains FILTER
set -u
cd "$(dirname "$0")/.."

checking=yes
only=
case "${1:-}" in
    --no-checking-build) checking=no ;;
    test_*) only=$1 ;;
    "") ;;
    *) echo "usage: tools/test.sh [--no-checking-build | NAME [FILTER]]" >&2; exit 1 ;;
esac

# fpm's debug profile, without its -fcoarray=single: with it gfortran 12
# writes test module files that it cannot read back once they use pFUnit
DEBUG_FLAGS="-Wall -Wextra -Wimplicit-interface -fPIC -fmax-errors=1 -g -fcheck=bounds -fcheck=array-temps -fbacktrace"
CHECK_FLAGS="-g -O0 -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace -Wall -Wno-unused-dummy-argument -Wno-maybe-uninitialized"

# pFUnit: built once per machine (a few minutes), then the test/unit/*.pf
# suites turned into Fortran with their driver programs
./tools/pfunit.sh ensure || exit 1
./tools/pfunit.sh generate || exit 1
PF_INC=$(./tools/pfunit.sh include)
PF_LINK=$(./tools/pfunit.sh link)

if [ -n "$only" ]; then
    if [ $# -ge 2 ]; then
        exec fpm test "$only" --flag "$DEBUG_FLAGS $PF_INC" --link-flag "$PF_LINK" -- "$2"
    fi
    exec fpm test "$only" --flag "$DEBUG_FLAGS $PF_INC" --link-flag "$PF_LINK"
fi

log=$(mktemp)
trap 'rm -f "$log" "$log.rc"' EXIT
failed_steps=0

# step TITLE COMMAND...: run the command, its output to the terminal and
# to the log; count it when it ends non-zero
step() {
    echo "== $1"
    shift
    { "$@" 2>&1; echo $? > "$log.rc"; } | tee -a "$log"
    [ "$(cat "$log.rc")" -eq 0 ] || failed_steps=$((failed_steps + 1))
}

step "fpm test (debug build: $DEBUG_FLAGS)" \
    fpm test --flag "$DEBUG_FLAGS $PF_INC" --link-flag "$PF_LINK"
if [ "$checking" = yes ]; then
    step "fpm test (checking build: $CHECK_FLAGS)" \
        fpm test --flag "$CHECK_FLAGS $PF_INC" --link-flag "$PF_LINK"
fi

# the whole-program checks run the debug build's executable
HHNECK=$(fpm run --flag "$DEBUG_FLAGS $PF_INC" --runner echo 2>/dev/null | tail -n 1)
export HHNECK
for script in test/scripts/*.sh; do
    step "$script" sh "$script"
done

passed=$(sed -n 's/^\([0-9][0-9]*\) passed, [0-9][0-9]* failed$/\1/p' "$log" | awk '{s += $1} END {print s + 0}')
failed=$(sed -n 's/^[0-9][0-9]* passed, \([0-9][0-9]*\) failed$/\1/p' "$log" | awk '{s += $1} END {print s + 0}')
programs=$(grep -c '^[0-9][0-9]* passed, [0-9][0-9]* failed$' "$log")
if [ "$failed_steps" -gt 0 ] && [ "$failed" -eq 0 ]; then
    # a test program that stopped before its closing line
    echo "FAIL  $failed_steps step(s) ended with an error before reporting a failed check (see above)"
    failed=$failed_steps
fi
echo "== total over $programs test programs and scripts: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
