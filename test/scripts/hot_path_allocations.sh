#!/bin/sh
# The hot path's heap allocations, counted: the fpm example
# hot_path_allocations (example/hot_path_allocations.f90) runs N + 1 calls
# of one path on the shipped NBDL 15 g model -- a dynamics evaluation on
# the GAUSS, CHOLESKY or ABA path, or a structured Jacobian -- and a shim
# preloaded into it (LD_PRELOAD, compiled here with the machine's C
# compiler) counts every malloc, calloc and realloc. The allocations per
# call are the difference between N = 1010 and N = 10, over 1000:
# - the ABA path, the shipped decks' SOLVER ABA, allocates nothing;
# - the others allocate at most what docs/performance.md ("One dynamics
#   evaluation") records (GAUSS 13, CHOLESKY 14, the structured Jacobian
#   42 per call: array temporaries of the composite-rigid-body a_ij, the
#   dense solve and the discs' tangents), so that a new allocation in the
#   hot path fails here.
# builds: release
. test/scripts/lib/checks.sh

hp=$(dirname "$HHNECK")/../example/hot_path_allocations
cat > "$tmp/count.c" <<'C'
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <fcntl.h>
#include <unistd.h>
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
static unsigned long count = 0;
void *malloc(size_t n) { __atomic_add_fetch(&count, 1, __ATOMIC_RELAXED); return __libc_malloc(n); }
void *calloc(size_t a, size_t b) { __atomic_add_fetch(&count, 1, __ATOMIC_RELAXED); return __libc_calloc(a, b); }
void *realloc(void *p, size_t n) { __atomic_add_fetch(&count, 1, __ATOMIC_RELAXED); return __libc_realloc(p, n); }
__attribute__((destructor)) static void report(void) {
    const char *f = getenv("HHNECK_MALLOC_COUNT");
    char buf[32];
    int fd, k;
    if (!f || (fd = open(f, O_WRONLY | O_CREAT | O_TRUNC, 0644)) < 0) return;
    k = snprintf(buf, sizeof buf, "%lu\n", count);
    if (write(fd, buf, k) != k) { /* the check then finds no count */ }
    close(fd);
}
C
if ! cc -shared -fPIC -O2 -o "$tmp/count.so" "$tmp/count.c" 2> "$tmp/cc.err"; then
    fail "the counting shim compiles (cc: $(head -n 1 "$tmp/cc.err"))"
    finish
    exit 1
fi
check "the example hot_path_allocations is built beside the program" [ -x "$hp" ]

# allocations PATH N: the program's heap allocations for N + 1 calls
allocations() {
    rm -f "$tmp/count"
    HHNECK_MALLOC_COUNT="$tmp/count" LD_PRELOAD="$tmp/count.so" "$hp" "$1" "$2" > "$tmp/out" 2>&1 &&
        cat "$tmp/count"
}
for p in ABA:0 GAUSS:13 CHOLESKY:14 JACOBIAN:42; do
    path=${p%%:*}
    most=${p#*:}
    a=$(allocations "$path" 10)
    b=$(allocations "$path" 1010)
    if [ -z "$a" ] || [ -z "$b" ]; then
        fail "$path: the program ran with the shim ($(tail -n 1 "$tmp/out"))"
        continue
    fi
    per=$(( (b - a) / 1000 ))
    check "$path: $per heap allocations per call ($a for 11 calls, $b for 1011; at most $most)" \
        [ "$(( b - a ))" -le "$(( most * 1000 ))" ]
done
finish
