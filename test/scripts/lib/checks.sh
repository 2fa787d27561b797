# Shared by the whole-program checks test/scripts/*.sh (sourced, not run):
# counts checks, prints one "PASS  what" or "FAIL  what" line per check and
# the closing "N passed, N failed" line. Run from the project root; the
# executable is $HHNECK (default: fpm's debug build, built if needed), made
# an absolute path; the Python package is the project's own (python/ first
# on PYTHONPATH, whatever copy pip installed).
HHNECK=${HHNECK:-$(fpm run hhneck --runner echo 2>/dev/null | tail -n 1)}
case $HHNECK in /*) ;; *) HHNECK=$(pwd)/$HHNECK ;; esac   # usable after a cd
PYTHONPATH=$(pwd)/python${PYTHONPATH:+:$PYTHONPATH}
export PYTHONPATH
npass=0
nfail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

pass() { echo "PASS  $*"; npass=$((npass + 1)); }
fail() { echo "FAIL  $*"; nfail=$((nfail + 1)); }

# check WHAT COMMAND...: PASS when the command succeeds
check() {
    what=$1
    shift
    if "$@"; then pass "$what"; else fail "$what"; fi
}

# py_checks SCRIPT ARGS...: a Python checker that prints PASS/FAIL lines;
# its lines are counted here (a checker that dies without one FAIL line
# counts as one failure)
py_checks() {
    out=$(python3 "$@" 2>&1)
    rc=$?
    printf '%s\n' "$out" | grep -E '^(PASS|FAIL)  ' || true
    np=$(printf '%s\n' "$out" | grep -c '^PASS  ' || true)
    nf=$(printf '%s\n' "$out" | grep -c '^FAIL  ' || true)
    npass=$((npass + np))
    nfail=$((nfail + nf))
    if [ "$rc" -ne 0 ] && [ "$nf" -eq 0 ]; then
        printf '%s\n' "$out" | tail -n 5
        fail "python3 $* stopped (exit $rc)"
    fi
}

# finish: the closing line; non-zero on any failure
finish() {
    echo "$npass passed, $nfail failed"
    [ "$nfail" -eq 0 ]
}
