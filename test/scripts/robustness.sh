#!/bin/sh
# Never crash, never hang, never leave a wrong file (issue 14), run on the
# executable in $HHNECK from the project root: a full disk (a tiny tmpfs
# when this machine lets us mount one, and an injected ENOSPC in the write
# calls through LD_PRELOAD), directories and other runs in the way, kills
# and signals, devices, FIFOs and directories as input, numbers beyond the
# double range, no free coordinate, huge decks and tables, degenerate
# models, run limits, the command line. One PASS/FAIL line per check (SKIP
# with the reason where the machine cannot do it), then "N passed, N failed".
set -u
cd "$(dirname "$0")/../.."
ROOT=$(pwd)
HHNECK=${HHNECK:-$(fpm run --runner echo 2>/dev/null | tail -n 1)}
case $HHNECK in /*) ;; *) HHNECK=$ROOT/$HHNECK ;; esac
T=$(mktemp -d)
chmod 755 "$T"
npass=0; nfail=0
pass() { echo "PASS  $1"; npass=$((npass + 1)); }
fail() { echo "FAIL  $1"; nfail=$((nfail + 1)); }
skip() { echo "SKIP  $1"; }
check() { if [ "$1" = 0 ]; then pass "$2"; else fail "$2"; fi; }
has() { grep -q -- "$2" "$1"; }
TO=""
command -v timeout > /dev/null 2>&1 && TO="timeout 60"

# decks: a short case, a long one, a stiff one
sed 's/^CONTROL   0.1  /CONTROL   0.005/' input/case6-2.inp > "$T/short.inp"
# (the explicit methods on the discs' damping of the earlier model, a 5 ms
# retardation time: the model deck's 3.33 s puts a mode of 4.9e6 1/s in the
# discs' shear, beyond RK4 at 10 us)
sed 's/^CONTROL .*/CONTROL   0.25      1.0E-5    0.005     RK4/' \
    input/nbdl15g.inp > "$T/long.inp"
echo 'SCALE     EXPLICIT  DISCS     VISCOUS   0.0015' >> "$T/long.inp"
sed 's/^CONTROL .*/CONTROL   0.25      1.0E-4    0.005     DOPRI5    1.0E-4    1.0E-7/' input/nbdl15g.inp > "$T/stiff.inp"
echo 'SCALE     EXPLICIT  DISCS     VISCOUS   0.0015' >> "$T/stiff.inp"
echo 'STIFFEN   1000.0    DISCS' >> "$T/stiff.inp"

# 1. a full disk: exit 4, one located message, no partial file, no "kept in" line
full_disk_checks() {   # $1 rc, $2 stderr, $3 dir, $4 what
    [ "$1" -eq 4 ] && has "$2" 'No space left on device' && has "$2" 'was removed' && \
        ! has "$2" 'HDF5-DIAG' && ! has "$2" 'kept in' && [ "$(wc -l < "$2")" -le 3 ] && \
        [ -z "$(ls "$3")" ]
    check $? "$4: exit 4 ($1), one message naming the OS reason, the partial file removed, no false 'kept in'"
}
if [ "$(id -u)" = 0 ] && mkdir "$T/fs" && mount -t tmpfs -o size=600k tmpfs "$T/fs" 2> /dev/null; then
    $TO "$HHNECK" --h5 "$T/fs/run.h5" < input/nbdl15g.inp > "$T/fs.out" 2> "$T/fs.err"
    full_disk_checks $? "$T/fs.err" "$T/fs" "full disk (a 600 KiB tmpfs)"
    umount "$T/fs"
else
    skip "full disk on a tiny tmpfs: mounting needs root and a system that allows it"
fi
if command -v cc > /dev/null 2>&1 && [ -d /proc/self/fd ]; then
    cat > "$T/enospc.c" <<'EOF'
/* Test shim: writes to a file whose name ends in ".part" fail with ENOSPC
   once HHNECK_TEST_ENOSPC_AFTER bytes have been written to such files. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>
static long long budget = -1, used = 0;
static int full(int fd, size_t n) {
    char p[64], t[4096];
    ssize_t k;
    if (budget == -1) {
        const char *e = getenv("HHNECK_TEST_ENOSPC_AFTER");
        budget = e ? atoll(e) : -2;
    }
    if (budget < 0) return 0;
    snprintf(p, sizeof p, "/proc/self/fd/%d", fd);
    k = readlink(p, t, sizeof t - 1);
    if (k < 6) return 0;
    t[k] = 0;
    if (strcmp(t + k - 5, ".part") != 0) return 0;
    if (used + (long long)n > budget) { errno = ENOSPC; return 1; }
    used += (long long)n;
    return 0;
}
ssize_t write(int fd, const void *b, size_t n) {
    static ssize_t (*real)(int, const void *, size_t);
    if (!real) real = (ssize_t (*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
    return full(fd, n) ? -1 : real(fd, b, n);
}
ssize_t pwrite(int fd, const void *b, size_t n, off_t o) {
    static ssize_t (*real)(int, const void *, size_t, off_t);
    if (!real) real = (ssize_t (*)(int, const void *, size_t, off_t))dlsym(RTLD_NEXT, "pwrite");
    return full(fd, n) ? -1 : real(fd, b, n, o);
}
ssize_t pwrite64(int fd, const void *b, size_t n, off_t o) {
    static ssize_t (*real)(int, const void *, size_t, off_t);
    if (!real) real = (ssize_t (*)(int, const void *, size_t, off_t))dlsym(RTLD_NEXT, "pwrite64");
    return full(fd, n) ? -1 : real(fd, b, n, o);
}
EOF
    if cc -shared -fPIC -o "$T/enospc.so" "$T/enospc.c" -ldl 2> "$T/cc.err"; then
        mkdir "$T/inj"
        HHNECK_TEST_ENOSPC_AFTER=300000 LD_PRELOAD="$T/enospc.so" $TO "$HHNECK" --h5 "$T/inj/run.h5" \
            < input/nbdl15g.inp > "$T/inj.out" 2> "$T/inj.err"
        full_disk_checks $? "$T/inj.err" "$T/inj" "full disk after 300 kB (ENOSPC injected into write/pwrite)"
    else
        skip "full disk by LD_PRELOAD: the shim does not compile here ($(head -n 1 "$T/cc.err"))"
    fi
else
    skip "full disk by LD_PRELOAD: needs a C compiler and /proc/self/fd"
fi

# 2. directories and files in the way: one line, exit 4, no false "kept in"
one_line_exit4() {   # $1 rc, $2 stderr, $3 text, $4 what
    [ "$1" -eq 4 ] && has "$2" "$3" && [ "$(wc -l < "$2")" -eq 1 ] && ! has "$2" 'kept in' && ! has "$2" 'HDF5-DIAG'
    check $? "$4: exit 4 ($1), one line: $(head -c 120 "$2")"
}
"$HHNECK" --h5 "$T/new/dir/run.h5" < "$T/short.inp" > /dev/null 2> "$T/mk.err"
rc=$?
[ "$rc" -eq 0 ] && [ -f "$T/new/dir/run.h5" ] && has "$T/mk.err" "created directory $T/new/dir"
check $? "a missing output directory is created and said so (exit $rc)"
mkdir "$T/isdir.h5"
"$HHNECK" --h5 "$T/isdir.h5" < "$T/short.inp" > /dev/null 2> "$T/isdir.err"
one_line_exit4 $? "$T/isdir.err" 'it is a directory' "--h5 names a directory"
mkdir "$T/p.h5.part"
"$HHNECK" --h5 "$T/p.h5" < "$T/short.inp" > /dev/null 2> "$T/part.err"
one_line_exit4 $? "$T/part.err" 'p.h5.part: it is a directory' "a directory in the way of NAME.part"
: > "$T/afile"
"$HHNECK" --h5 "$T/afile/run.h5" < "$T/short.inp" > /dev/null 2> "$T/afile.err"
one_line_exit4 $? "$T/afile.err" 'is a regular file, not a directory' "a file where the directory should be"
mkdir "$T/ro" && chmod 555 "$T/ro"
if [ "$(id -u)" != 0 ]; then
    "$HHNECK" --h5 "$T/ro/run.h5" < "$T/short.inp" > /dev/null 2> "$T/ro.err"
    one_line_exit4 $? "$T/ro.err" 'cannot create files in its directory' "a read-only directory"
elif command -v setpriv > /dev/null 2>&1 && setpriv --reuid=65534 --regid=65534 --clear-groups \
        sh -c "cd '$ROOT' && test -x '$HHNECK' && test -r '$T/short.inp'" 2> /dev/null; then
    setpriv --reuid=65534 --regid=65534 --clear-groups "$HHNECK" --h5 "$T/ro/run.h5" \
        < "$T/short.inp" > /dev/null 2> "$T/ro.err"
    one_line_exit4 $? "$T/ro.err" 'cannot create files in its directory' "a read-only directory (as an unprivileged user)"
else
    skip "read-only directory: root ignores permissions and no unprivileged user can run $HHNECK here"
fi

# 3. two runs on one result name, without HDF5's file locking: the second stops
#    at once; the first is stopped by SIGTERM and leaves a valid file marked incomplete
HDF5_USE_FILE_LOCKING=FALSE "$HHNECK" --h5 "$T/both.h5" < "$T/long.inp" > "$T/first.out" 2> "$T/first.err" &
first=$!
sleep 2
HDF5_USE_FILE_LOCKING=FALSE "$HHNECK" --h5 "$T/both.h5" < "$T/short.inp" > /dev/null 2> "$T/second.err"
one_line_exit4 $? "$T/second.err" 'another run is writing it' "a second run on the same result name (HDF5 locking off)"
kill -TERM "$first"
wait "$first"
rc=$?
[ "$rc" -eq 5 ] && has "$T/first.err" 'interrupted by signal 15' && has "$T/first.err" "kept in $T/both.h5 (marked incomplete" \
    && [ ! -e "$T/both.h5.part" ] && [ ! -e "$T/both.h5.lock" ] && python3 test/scripts/lib/check_incomplete.py "$T/both.h5" 0.25 > /dev/null
check $? "the first run, stopped by SIGTERM: exit 5 ($rc), its file valid and marked incomplete, lock released"

# 4. a SIGKILL never leaves an older complete result under the name (the
# long run is another deck: --overwrite lets it replace case 6-2's file)
"$HHNECK" --h5 "$T/k.h5" < "$T/short.inp" > /dev/null 2>&1
"$HHNECK" --overwrite --h5 "$T/k.h5" < "$T/long.inp" > /dev/null 2>&1 &
pid=$!
sleep 2
kill -KILL "$pid"
wait "$pid" 2> /dev/null
[ ! -e "$T/k.h5" ] && [ -f "$T/k.h5.part" ] && python3 -c "
import sys, h5py
f = h5py.File(sys.argv[1], 'r')
sys.exit(0 if f.attrs['status'] == 'incomplete' else 1)" "$T/k.h5.part"
check $? "SIGKILL after an earlier complete k.h5: no k.h5 left, k.h5.part says incomplete"
"$HHNECK" --h5 "$T/k.h5" < "$T/short.inp" > /dev/null 2> "$T/k2.err"
rc=$?
[ "$rc" -eq 0 ] && has "$T/k2.err" 'removed the stale lock' && [ -f "$T/k.h5" ] && [ ! -e "$T/k.h5.lock" ]
check $? "the next run takes over the dead run's lock and completes (exit $rc)"

# 5. a signal before the deck is read: exit 5
(sleep 3; cat "$T/short.inp") | "$HHNECK" --check > /dev/null 2> "$T/early.err" &
pid=$!
sleep 1
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 5 ] && has "$T/early.err" 'before the run started'
check $? "SIGTERM while the deck is being read: exit 5 ($rc) and a message"

# 6. inputs that never end or cannot be read: refused at once, located
mkfifo "$T/fifo" 2> /dev/null || true
for inc in /dev/zero /dev/urandom "$T/fifo" "$T/isdir.h5"; do
    [ -e "$inc" ] || { skip "INCLUDE $inc: not on this machine"; continue; }
    printf 'TITLE     X\nINCLUDE   %s\n' "$inc" > "$T/inc.inp"
    $TO "$HHNECK" --check "$T/inc.inp" > /dev/null 2> "$T/inc.err"
    rc=$?
    [ "$rc" -eq 2 ] && has "$T/inc.err" "inc.inp line 2, columns 11-80 (INCLUDE card)"
    check $? "INCLUDE $inc refused at the INCLUDE line (exit $rc): $(cut -c 1-100 "$T/inc.err" | sed 's/.*card): //')"
done
$TO "$HHNECK" --check < /dev/zero > /dev/null 2> "$T/zero.err"
rc=$?
[ "$rc" -eq 2 ] && has "$T/zero.err" 'standard input is a character device'
check $? "hhneck --check < /dev/zero refused at once (exit $rc)"
$TO "$HHNECK" --check < "$T/isdir.h5" > /dev/null 2> "$T/sdir.err"
rc=$?
[ "$rc" -eq 2 ] && has "$T/sdir.err" 'standard input is a directory'
check $? "a directory as standard input refused (exit $rc)"

# 7. numbers beyond the double range, no free coordinate (located, exit 2)
for num in '1.0E+400' '1.0D+999' '-1.0E+309'; do
    sed "s/^CONTROL   0.005     5.0E-5    0.001     /CONTROL   0.005     5.0E-5    $(printf '%-10s' "$num")/" "$T/short.inp" \
        > "$T/ovf.inp"
    "$HHNECK" --check < "$T/ovf.inp" > /dev/null 2> "$T/ovf.err"
    rc=$?
    [ "$rc" -eq 2 ] && has "$T/ovf.err" "columns 31-40 (CONTROL card, field F3 'print interval'): found \"$num\", beyond the range"
    check $? "$num in a field refused before conversion (exit $rc)"
done
"$HHNECK" --rtol 1e400 --check < "$T/short.inp" > /dev/null 2> "$T/rtol.err"
rc=$?
[ "$rc" -eq 1 ] && has "$T/rtol.err" 'rtol needs a tolerance'
check $? "--rtol 1e400 refused as a bad command line (exit $rc)"
{ cat "$T/short.inp"; echo 'LOCK      ALL       TX        TY        TZ        RX        RY        RZ'; } > "$T/zero_dof.inp"
"$HHNECK" --h5 "$T/zero_dof.h5" < "$T/zero_dof.inp" > /dev/null 2> "$T/zdof.err"
rc=$?
[ "$rc" -eq 2 ] && has "$T/zdof.err" '(LOCK card): with this card the model has no free coordinate left' && [ ! -e "$T/zero_dof.h5" ]
check $? "every coordinate locked: refused at the LOCK card (exit $rc), nothing written"

# 8. big inputs: linear, limited, located
awk 'BEGIN { print "TITLE     SPRINGS"; print "CONTROL   0.01      1.0E-4    0.005     DOPRI5";
             print "BODY      A         R         1.0       0.01      0.01      0.01";
             print "BODY      B         A         1.0       0.01      0.01      0.01";
             for (k = 0; k < 64000; k++) { printf "SPRING    S%-8d A         B         1.0\n", k;
                 print "          0.0       0.0       0.01      0.0       0.0       -0.01" } }' > "$T/springs.inp"
t0=$(date +%s)
$TO "$HHNECK" --check "$T/springs.inp" > /dev/null 2> "$T/springs.err"
rc=$?
[ "$rc" -eq 0 ]
check $? "a deck of 64 000 SPRING cards checks (exit $rc, $(($(date +%s) - t0)) s wall in this build)"
awk 'BEGIN { print "TITLE     LINES"; for (k = 0; k < 1000001; k++) print "*" }' > "$T/lines.inp"
$TO "$HHNECK" --check "$T/lines.inp" > /dev/null 2> "$T/lines.err"
rc=$?
[ "$rc" -eq 2 ] && has "$T/lines.err" 'lines.inp line 1000001: the deck has more than 1000000 lines'
check $? "a deck of more than 1 000 000 lines refused at the line (exit $rc)"
yes '*2345678901234567890123456789012345678901234567890123456789012345678901234567890' | head -c 70000000 \
    | $TO "$HHNECK" --check > /dev/null 2> "$T/pipe.err"
rc=$?
[ "$rc" -eq 2 ] && has "$T/pipe.err" 'standard input goes on beyond 67108864 bytes'
check $? "a 70 MB pipe refused at the 64 MiB limit (exit $rc)"
awk 'BEGIN { n = 100000 }
     /^TABLE     IMPACT/ { printf "TABLE     IMPACT    %-10d0.001     1.0\n", n;
         for (j = 0; j < n; j += 3) { line = "          ";
             for (i = j; i < j + 3 && i < n; i++) { t = i * 200.0 / (n - 1);
                 line = line sprintf("%-10.5f%-10.1f", t, (t >= 5 && t <= 15) ? 1600 : 0) }
             print line }
         skip = 1; next }
     skip && /^          / { next }
     { skip = 0; print }' "$T/short.inp" > "$T/table.inp"
$TO "$HHNECK" --h5 "$T/table.h5" < "$T/table.inp" > /dev/null 2> "$T/table.err"
rc=$?
[ "$rc" -eq 0 ] && python3 -c "
import sys, h5py
f = h5py.File(sys.argv[1], 'r')
sys.exit(0 if f.attrs['status'] == 'complete' and f['deck/text'].shape[0] > 33334 else 1)" "$T/table.h5"
check $? "a 100 000-point TABLE runs and its deck is stored as a dataset (exit $rc)"
sed 's/^TABLE     IMPACT    23        /TABLE     IMPACT    100001    /' "$T/short.inp" > "$T/table2.inp"
"$HHNECK" --check < "$T/table2.inp" > /dev/null 2> "$T/table2.err"
rc=$?
[ "$rc" -eq 2 ] && has "$T/table2.err" "(TABLE card, field F2 'number of points'): found 100001; expected an integer in \[1, 100000\]"
check $? "a TABLE of 100 001 points refused at its field (exit $rc)"

# 9. degenerate but valid models: warnings
sed 's/^BODY      C4        C5        0.379     0.0002986 0.0002986 0.0005732/BODY      C4        C5        1.0E-6    1.0E-12   1.0E-12   1.0E-12/' \
    input/head_neck_54dof.inp > "$T/light_model.inp"
sed "s|^INCLUDE   input/head_neck_54dof.inp|INCLUDE   $T/light_model.inp|" "$T/short.inp" > "$T/light.inp"
sed 's/^TABLE     IMPACT    23        0.001     1.0 /TABLE     IMPACT    23        0.001     4.9E-324/' "$T/short.inp" > "$T/scale.inp"
"$HHNECK" --check "$T/light.inp" > /dev/null 2> "$T/light.err"
rc=$?
[ "$rc" -eq 0 ] && has "$T/light.err" 'warning: body C4: mass 1.00E-06 kg, far below' && has "$T/light.err" 'body C4: smallest principal inertia'
check $? "a 1E-6 kg vertebra with 1E-12 inertias: accepted with warnings (exit $rc)"
"$HHNECK" --check < "$T/scale.inp" > /dev/null 2> "$T/scale.err"
rc=$?
[ "$rc" -eq 0 ] && has "$T/scale.err" 'warning: table IMPACT: value scale 4.94E-324 makes its largest value 7.91E-321, zero in effect'
check $? "a table scale of 4.9E-324: accepted with a warning that the table is zero in effect (exit $rc)"

# 10. runs that cannot finish in reasonable time stop (exit 3), files kept, with the cause;
# sampled every 1E-5 s, since how far 6 s of wall time get depends on the
# build and the machine's load (8.6E-5 s for the debug build on a busy
# machine, short of the deck's first 1E-4 s sample)
"$HHNECK" --max-wall 6 --progress --sample 1.0E-5 --h5 "$T/stiff.h5" < "$T/stiff.inp" > "$T/stiff.out" 2> "$T/stiff.err"
rc=$?
[ "$rc" -eq 3 ] && has "$T/stiff.err" 'the wall-time limit of 6 s' && has "$T/stiff.err" 'The fastest mode has' \
    && has "$T/stiff.err" 'about .* to go' && has "$T/stiff.out" 'RUN INCOMPLETE' \
    && python3 test/scripts/lib/check_incomplete.py "$T/stiff.h5" 0.25 > /dev/null
check $? "a stiff deck on DOPRI5 with --max-wall 6 --progress: progress shown, exit 3 ($rc), the fastest mode named, file kept"
# where a wall-time limit stops a run depends on the machine's load; a step
# limit stops it at the same state on every machine: the diagnosis there
"$HHNECK" --max-steps 3000 --no-h5 < "$T/stiff.inp" > /dev/null 2> "$T/stiff3000.err"
rc=$?
# the coordinate the diagnosis names: a vertebra's rotation (the stiffened discs)
coord=$(grep -o 'mostly in C[1-7]\.r[xyz] ' "$T/stiff3000.err" | head -n 1 | cut -c 11-15)
[ "$rc" -eq 3 ] && has "$T/stiff3000.err" 'the step limit of 3000 steps' && [ -n "$coord" ] \
    && has "$T/stiff3000.err" "mostly in $coord (h |lambda| = 3." && has "$T/stiff3000.err" 'held down by stiffness'
check $? "the same deck stopped after 3000 steps: exit 3 ($rc), the step held down by stiffness in a vertebra's rotation ($coord)"
# the remedy fits the run's method: DOPRI5 is pointed to the stiff ROS34PW2;
# the same deck on ROS34PW2 is not pointed to another method
has "$T/stiff3000.err" "(DOPRI5 is explicit). Remedy: the stiff ROS34PW2 (CONTROL F4), or a softer element on $coord" \
    && ! has "$T/stiff3000.err" 'ROS2 '
check $? "its remedy fits DOPRI5: the stiff ROS34PW2, a softer element on $coord, never ROS2"
sed 's/^CONTROL .*/CONTROL   0.25      1.0E-4    0.005     ROS34PW2  1.0E-4    1.0E-7/' "$T/stiff.inp" > "$T/stiffros.inp"
"$HHNECK" --max-steps 20 --no-h5 < "$T/stiffros.inp" > /dev/null 2> "$T/stiffros.err"
rc=$?
[ "$rc" -eq 3 ] && has "$T/stiffros.err" 'the step limit of 20 steps' && has "$T/stiffros.err" 'ROS34PW2 is stable there' \
    && has "$T/stiffros.err" 'Remedy: a looser tolerance (--rtol), a softer element on C[1-7]\.r[xyz]' \
    && has "$T/stiffros.err" 'C[1-7]\.r[xyz] out of the model (LOCK' && ! has "$T/stiffros.err" 'CONTROL F4' \
    && ! has "$T/stiffros.err" 'ROS2 '
check $? "the same deck on ROS34PW2 stopped after 20 steps (exit $rc): its remedy names a looser tolerance, no other method"
{ cat "$T/stiff.inp"; echo 'RUNLIMIT            200'; } > "$T/steps.inp"
"$HHNECK" --no-h5 < "$T/steps.inp" > /dev/null 2> "$T/steps.err"
rc=$?
[ "$rc" -eq 3 ] && has "$T/steps.err" 'the step limit of 200 steps'
check $? "a RUNLIMIT card with a step limit stops the run (exit $rc)"

# 11. the command line a user expects
"$HHNECK" --no-h5 < "$T/short.inp" 2> /dev/null | grep -v 'PAGE\|WALL TIME' | sed 's/stdin:[0-9]*//' | tr -s ' ' > "$T/a.lis"
"$HHNECK" --no-h5 "$T/short.inp" 2> /dev/null | grep -v 'PAGE\|WALL TIME' | sed 's/short\.inp:[0-9]*//' | tr -s ' ' \
    > "$T/b.lis"
cmp -s "$T/a.lis" "$T/b.lis" && [ -s "$T/a.lis" ]
check $? "hhneck DECK gives the listing of hhneck < DECK"
"$HHNECK" --help > "$T/help.txt" 2>&1
rc=$?
missing=""
for opt in --h5 --no-h5 --overwrite --sample --rtol --change --set --check --sweep --include-path HHNECK_PATH \
        --progress --no-progress --max-wall --max-steps --version --help 'exit codes'; do
    grep -q -- "$opt" "$T/help.txt" || missing="$missing $opt"
done
[ "$rc" -eq 0 ] && [ -z "$missing" ] && grep -q '5  interrupted by SIGINT or SIGTERM' "$T/help.txt"
check $? "--help explains every option and the exit codes (exit $rc; missing:${missing:- none})"
"$HHNECK" --frobnicate < "$T/short.inp" > /dev/null 2> "$T/usage.err"
rc=$?
[ "$rc" -eq 1 ] && has "$T/usage.err" 'unknown option "--frobnicate"'
check $? "an unknown option: exit 1 ($rc)"
mkdir "$T/elsewhere"
(cd "$T/elsewhere" && HHNECK_PATH=/nonexistent:$ROOT "$HHNECK" --check "$ROOT/input/case6-1.inp") > /dev/null 2>&1
check $? "from another directory, HHNECK_PATH finds the shipped model deck"
(cd "$T/elsewhere" && "$HHNECK" --check -I "$ROOT" < "$ROOT/input/nbdl15g.inp") > /dev/null 2>&1
check $? "from another directory, -I DIR finds it for a deck on standard input"
(cd "$T/elsewhere" && "$HHNECK" --check < "$ROOT/input/nbdl15g.inp") > /dev/null 2> "$T/nopath.err"
rc=$?
[ "$rc" -eq 2 ] && has "$T/nopath.err" 'stdin line .*(INCLUDE card): file "input/head_neck_54dof.inp" not found (looked for'
check $? "without it, the INCLUDE line says where it looked (exit $rc)"
mkdir -p "$T/proj/models"
printf 'BODY      A         R         1.0       0.01      0.01      0.01\nBODY      B         A         1.0       0.01      0.01      0.01\n' \
    > "$T/proj/models/bodies.inp"
printf 'INCLUDE   bodies.inp\n' > "$T/proj/models/model.inp"
printf 'TITLE     NESTED\nCONTROL   0.01      1.0E-4    0.005     DOPRI5\nINCLUDE   models/model.inp\n' > "$T/proj/case.inp"
(cd "$T/elsewhere" && "$HHNECK" --check "$T/proj/case.inp") > /dev/null 2>&1
check $? "INCLUDE of an included file resolves relative to the including file"

rm -rf "$T"
echo "$npass passed, $nfail failed"
[ "$nfail" -eq 0 ]
