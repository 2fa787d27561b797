#!/bin/sh
# Sizes of the Fortran sources: no source file of src/, app/ or test/ over
# 900 lines and no procedure over 150 lines, counted from its `subroutine`,
# `function` or `module procedure` line to its `end` line (a contained
# procedure counts inside its host, and on its own). The pFUnit suites'
# generated *_suite.F90 files are not sources. Also shown to fail: a tree
# with a file of 901 lines and a function of 151 lines. This check
# runs no executable: HHNECK is not needed.
HHNECK=${HHNECK:-none}
. test/scripts/lib/checks.sh

max_file=900
max_proc=150

sizes() {   # sizes ROOT: one line per file or procedure over its limit, exit 1 on any
    python3 - "$1" "$max_file" "$max_proc" <<'PY'
import os, re, sys
root, max_file, max_proc = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
prefix = r'(?:(?:pure|impure|elemental|recursive|non_recursive|module)\s+|' \
         r'(?:integer|real|logical|complex|character|type|class)\s*(?:\([^)]*\))?\s+)*'
start = re.compile(r'^\s*' + prefix + r'(subroutine|function)\s+(\w+)', re.I)
mproc = re.compile(r'^\s*module\s+procedure\s+(\w+)\s*$', re.I)
end = re.compile(r'^\s*end\s*(subroutine|function|procedure)\b', re.I)
bad = 0
for top in ('src', 'app', 'test'):
    for d, _, names in os.walk(os.path.join(root, top)):
        for name in sorted(names):
            if not name.lower().endswith(('.f90', '.pf')) or name.endswith('_suite.F90'):
                continue
            path = os.path.join(d, name)
            rel = os.path.relpath(path, root)
            lines = open(path, encoding='utf-8').read().split('\n')
            if lines and lines[-1] == '':
                lines.pop()
            if len(lines) > max_file:
                print(f'{rel}: {len(lines)} lines (at most {max_file})'); bad += 1
            stack = []
            for n, line in enumerate(lines, 1):
                code = line.split('!')[0]
                m = start.match(code) or mproc.match(code)
                if m and not re.match(r'^\s*end\b', code, re.I):
                    stack.append((m.groups()[-1], n))
                elif end.match(code) and stack:
                    proc, first = stack.pop()
                    if n - first + 1 > max_proc:
                        print(f'{rel}:{first}: procedure {proc} is {n - first + 1} lines (at most {max_proc})'); bad += 1
sys.exit(1 if bad else 0)
PY
}

if sizes . > "$tmp/report" 2>&1; then
    pass "no Fortran source over $max_file lines, no procedure over $max_proc"
else
    cat "$tmp/report"
    fail "Fortran sources or procedures over their size limits"
fi

# a tree with a file of 901 lines holding a subroutine of 150 lines (allowed)
# and a function of 151 lines (too long)
mkdir -p "$tmp/tree/src/base"
{
    echo 'module hn_long'
    echo 'contains'
    echo '    pure subroutine fits(x)'
    i=0; while [ $i -lt 148 ]; do echo '        x = x + 1'; i=$((i + 1)); done
    echo '    end subroutine fits'
    echo '    pure integer function too_long(x) result(y)'
    i=0; while [ $i -lt 149 ]; do echo '        y = x'; i=$((i + 1)); done
    echo '    end function too_long'
    i=0; while [ $i -lt 597 ]; do echo '    ! filler'; i=$((i + 1)); done
    echo 'end module hn_long'
} > "$tmp/tree/src/base/hn_long.f90"
sizes "$tmp/tree" > "$tmp/report2" 2>&1
if grep -q 'src/base/hn_long.f90: 901 lines' "$tmp/report2" &&
    grep -q 'hn_long.f90:153: procedure too_long is 151 lines' "$tmp/report2" &&
    ! grep -q 'procedure fits' "$tmp/report2"; then
    pass "a file of 901 lines and a function of 151 lines are named, a subroutine of 150 lines is not"
else
    cat "$tmp/report2"
    fail "the check did not name exactly the file of 901 lines and the function of 151 lines"
fi

finish
