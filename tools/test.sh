#!/bin/sh
# The whole test suite (docs/testing.md):
#   1. every test program -- the pFUnit suites of test/unit/*.pf and the
#      program tests test/*.f90 -- in a checking build that traps invalid
#      operations, division by zero and overflow and checks every array
#      bound and pointer (in the debug build instead with
#      --no-checking-build: the checking build's run-time checks include
#      every one of the debug build's, so the programs are built and run
#      once),
#   2. every whole-program check test/scripts/*.sh, with HHNECK set to the
#      checking build's executable (the debug build's with
#      --no-checking-build; the release build's for a script with a line
#      "# builds: release"),
#   3. the Python tests of the tools, test/python (pytest, one run per file
#      test/python/test_*.py, each a job of the pool below), with HHNECK
#      set to the release build's executable.
# The scripts and the Python tests run with this checkout's Python
# environment .venv (tools/setup.sh) first on PATH: its python3 imports
# this checkout's package, and the console commands (hhneck-animate, ...)
# are this checkout's.
# The test programs of a build run $TEST_JOBS at a time (default: the
# number of cores), and so do the scripts with the Python tests beside
# them; each one's output is shown whole when all are done.
# Each test program and script ends its output with "N passed, N failed";
# the last line is the total over all of them. Exit code 1 on any failure.
#   tools/test.sh NAME [FILTER]   only the test program NAME (a suite
#                                 test/unit/NAME.pf or test/NAME.f90) in the
#                                 debug build; with FILTER only its tests whose
#                                 name contains FILTER
set -u
cd "$(dirname "$0")/.."
if [ -x .venv/bin/python3 ]; then
    PATH=$(pwd -P)/.venv/bin:$PATH
    export PATH
fi

checking=yes
only=
case "${1:-}" in
    --no-checking-build) checking=no ;;
    test_*) only=$1 ;;
    "") ;;
    *) echo "usage: tools/test.sh [--no-checking-build | NAME [FILTER]]" >&2; exit 1 ;;
esac
TEST_JOBS=${TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
times=build/test_times    # seconds per test program in the last run
script_times=build/script_times    # seconds per script (and build) and of the Python tests in the last run

# the order of a first run (no build/test_times, build/script_times yet,
# as from a clean clone): typical seconds of the slowest test programs
# and of the slowest scripts and Python test files, so that none of them
# starts last and leaves a core idle at the end of a step
TYPICAL_TEST_TIMES="test_scene 31 test_free_bodies 25 test_calibration 23 test_nz_springs 16
    test_stiffened 14 test_feedback 10 test_cases 8"
TYPICAL_SCRIPT_TIMES="test/scripts/mpi_sweep.sh 85 test/scripts/new_nbdl_case.sh 61
    test/scripts/readme_commands.sh 38 test/scripts/robustness.sh 25 test/scripts/regression.sh 20 test/scripts/hot_path_allocations.sh 5 test/scripts/two_clones.sh 21
    test/scripts/activation_groups.sh 20 test/scripts/parallel_calibration.sh 30 test/scripts/animate.sh 16
    test/scripts/results.sh 15 test/scripts/listing_references.sh 15 test/scripts/deck_writers.sh 15
    test/scripts/api_docs.sh 11 test/python/test_commands.py 45 test/python/test_calibration_iso.py 45
    test/python/test_segments.py 45 test/python/test_model_deck.py 37 test/python/test_upper_cervical.py 20
    test/python/test_catalogue.py 10 test/python/test_import_anywhere.py 8 test/python/test_specimens.py 8"
# fpm's debug profile, without its -fcoarray=single: with it gfortran 12
# writes test module files that it cannot read back once they use pFUnit
DEBUG_FLAGS="-Wall -Wextra -Wimplicit-interface -fPIC -fmax-errors=1 -g -fcheck=bounds -fcheck=array-temps -fbacktrace"
CHECK_FLAGS="-g -O0 -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace -Wall -Wno-unused-dummy-argument -Wno-maybe-uninitialized"

# pFUnit: built once per machine (a few minutes), then the test/unit/*.pf
# suites turned into Fortran with their driver programs
start=$(date +%s)
./tools/pfunit.sh ensure || exit 1
./tools/pfunit.sh generate || exit 1
echo "== pFUnit ready ($(($(date +%s) - start)) s)"
PF_INC=$(./tools/pfunit.sh include)
PF_LINK=$(./tools/pfunit.sh link)
# gold links the test programs when the machine has it (binutils): fpm
# puts every test module into each test program, about 70 MB of objects
# with their debug information, and gold links one in half of ld's time
# (0.5 s of processor time, not 1 s; about 130 links in the two builds)
if ld.gold --version > /dev/null 2>&1; then
    PF_LINK="$PF_LINK -fuse-ld=gold"
fi

if [ -n "$only" ]; then
    if [ $# -ge 2 ]; then
        exec fpm test "$only" --flag "$DEBUG_FLAGS $PF_INC" --link-flag "$PF_LINK" -- "$2"
    fi
    exec fpm test "$only" --flag "$DEBUG_FLAGS $PF_INC" --link-flag "$PF_LINK"
fi

[ -x .venv/bin/python3 ] ||
    echo "test.sh: no .venv (tools/setup.sh makes it): the Python tests use the machine's python3" >&2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
log=$work/log
failed_steps=0

# step TITLE COMMAND...: run the command, its output to the terminal and
# to the log; count it when it ends non-zero
step() {
    echo "== $1"
    shift
    t0=$(date +%s)
    { "$@" 2>&1; echo $? > "$work/rc"; } | tee -a "$log"
    [ "$(cat "$work/rc")" -eq 0 ] || failed_steps=$((failed_steps + 1))
    echo "   ($(($(date +%s) - t0)) s)"
}

# run_tests FLAGS: build every test program with FLAGS, run them
# TEST_JOBS at a time, then show each one's output. A program that stops
# without its closing line is reported as one failed check.
run_tests() {
    fpm test --flag "$1 $PF_INC" --link-flag "$PF_LINK" --runner true || return 1
    # the slowest first (their times from the last run, else these), so
    # that no long program starts last
    fpm test --flag "$1 $PF_INC" --link-flag "$PF_LINK" --runner echo 2>/dev/null | grep '/test/' |
        awk -v known="$times" -v typical="$TYPICAL_TEST_TIMES" 'BEGIN {
                n = split(typical, f, " ")
                for (i = 1; i < n; i += 2) t[f[i]] = f[i + 1]
                while ((getline line < known) > 0) { split(line, f, " "); t[f[2]] = f[1] }
            }
            { name = $0; sub(".*/", "", name); print (name in t ? t[name] : 0), $0 }' |
        sort -rn | cut -d' ' -f2- > "$work/exes"
    out=$work/out
    rm -rf "$out"
    mkdir -p "$out"
    # shellcheck disable=SC2016
    xargs -P "$TEST_JOBS" -n 1 sh -c \
        'n=$(basename "$1"); t=$(date +%s); "$1" >> "$0/$n.out" 2>&1; echo $? > "$0/$n.rc";
         echo "$(($(date +%s) - t)) $n" > "$0/$n.time"; echo "   $n done ($(($(date +%s) - t)) s)"' \
        "$out" < "$work/exes"
    cat "$out"/*.time > "$times" 2>/dev/null
    status=0
    while read -r exe; do
        n=$(basename "$exe")
        echo "-- $n"
        cat "$out/$n.out"
        if [ "$(cat "$out/$n.rc")" -ne 0 ]; then
            status=1
            if ! grep -a -q '^[0-9][0-9]* passed, [0-9][0-9]* failed$' "$out/$n.out"; then
                echo "FAIL  $n stopped before its closing line (exit code $(cat "$out/$n.rc"))"
                echo "0 passed, 1 failed"
            fi
        fi
    done < "$work/exes"
    return $status
}

if [ "$checking" = yes ]; then
    step "test programs, checking build ($CHECK_FLAGS)" run_tests "$CHECK_FLAGS"
else
    step "test programs, debug build ($DEBUG_FLAGS)" run_tests "$DEBUG_FLAGS"
fi

# the whole-program checks run the checking build's executable when that
# build runs (else the debug build's); a script with a line "# builds:
# release" runs on fpm's release build (the README's run).
# The executables are built first, one build at a time; then the scripts
# and the Python tests (on the release build's executable: they test the
# tools over the program as a user runs it) run TEST_JOBS at a
# time, the slowest first (their times from the last run, in
# $script_times), each in its own process with its own temporary folders,
# and their outputs are shown whole, in the order of the list below.
exe_of() {
    case $1 in
        debug) fpm run --flag "$DEBUG_FLAGS $PF_INC" --runner echo 2>/dev/null | tail -n 1 ;;
        checking) fpm run --flag "$CHECK_FLAGS $PF_INC" --runner echo 2>/dev/null | tail -n 1 ;;
        release) fpm run --profile release --runner echo 2>/dev/null | tail -n 1 ;;
    esac
}
run_checks() {
    jobs=$work/jobs
    rm -rf "$jobs"
    mkdir -p "$jobs"
    n=0
    for script in test/scripts/*.sh test/python/test_*.py; do
        builds=release
        case $script in *.sh) builds=$(sed -n 's/^# builds: *//p' "$script" | head -n 1) ;; esac
        builds=${builds:-debug checking}     # a script's default: both (below)
        for build in $builds; do
            case $build in
                # a script for both builds runs in the checking build alone when
                # that build runs: its checks include every one of the debug
                # build's, and with no trapped exception the two compute alike
                debug) case " $builds " in *" checking "*) [ "$checking" = no ] || continue ;; esac ;;
                release) ;;
                checking) [ "$checking" = yes ] || continue ;;
                *) echo "$script: unknown build '$build'" >&2; continue ;;
            esac
            [ -f "$jobs/exe.$build" ] || exe_of "$build" > "$jobs/exe.$build"
            n=$((n + 1))
            if [ "${script%.py}" != "$script" ]; then
                title="$script (pytest)"
                command="python3 -m pytest -q -p no:cacheprovider $script"
            else
                title="$script ($build build)"
                command="sh $script"
            fi
            echo "$title" > "$jobs/$n.title"
            printf 'HHNECK=%s; export HHNECK; exec %s\n' "$(cat "$jobs/exe.$build")" "$command" > "$jobs/$n.sh"
        done
    done
    # shellcheck disable=SC2016
    ls "$jobs" | sed -n 's/\.sh$//p' |
        awk -v known="$script_times" -v dir="$jobs" -v typical="$TYPICAL_SCRIPT_TIMES" 'BEGIN {
                n = split(typical, f, " ")
                for (i = 1; i < n; i += 2) d[f[i]] = f[i + 1]
                while ((getline line < known) > 0) { i = index(line, " "); t[substr(line, i + 1)] = substr(line, 1, i - 1) }
            }
            { getline title < (dir "/" $0 ".title"); file = title; sub(/ .*/, "", file)
              print (title in t ? t[title] : (file in d ? d[file] : 0)), $0 }' |
        sort -rn | cut -d' ' -f2 |
        xargs -P "$TEST_JOBS" -n 1 sh -c \
            't=$(date +%s); sh "$0/$1.sh" >> "$0/$1.out" 2>&1; echo $? > "$0/$1.rc";
             echo "$(($(date +%s) - t)) $(cat "$0/$1.title")" > "$0/$1.time"; echo "   $(cat "$0/$1.title") done ($(($(date +%s) - t)) s)"' \
            "$jobs"
    cat "$jobs"/*.time > "$script_times" 2>/dev/null
    status=0
    k=0
    while [ "$k" -lt "$n" ]; do
        k=$((k + 1))
        echo "-- $(cat "$jobs/$k.title") ($(cut -d' ' -f1 "$jobs/$k.time") s)"
        cat "$jobs/$k.out"
        if [ "$(cat "$jobs/$k.rc")" -ne 0 ]; then
            status=1
            if ! grep -a -q '^[0-9][0-9]* passed, [0-9][0-9]* failed$' "$jobs/$k.out"; then
                echo "FAIL  $(cat "$jobs/$k.title") stopped before its closing line (exit code $(cat "$jobs/$k.rc"))"
                echo "0 passed, 1 failed"
            fi
        fi
    done
    return $status
}
step "whole-program checks (test/scripts) and the Python tests (test/python)" run_checks

summary='^[0-9][0-9]* passed, [0-9][0-9]* failed$'
passed=$(grep -a "$summary" "$log" | awk '{s += $1} END {print s + 0}')
failed=$(grep -a "$summary" "$log" | awk '{s += $3} END {print s + 0}')
programs=$(grep -a -c "$summary" "$log")
if [ "$failed_steps" -gt 0 ] && [ "$failed" -eq 0 ]; then
    # a build that failed
    echo "FAIL  $failed_steps step(s) ended with an error before reporting a failed check (see above)"
    failed=$failed_steps
fi
echo "== total over $programs test programs and scripts: $passed passed, $failed failed ($(($(date +%s) - start)) s)"
[ "$failed" -eq 0 ]
