#!/bin/sh
# The layers of src/ hold: every `use` of a module of the project (and
# every submodule's parent) names a module in the same folder or in a
# folder above it in the order of the folder table of docs/architecture.md
# (the one place the order is written); the table's module lists are the
# modules of each folder. Also shown to fail: a copy of the tree with one
# upward `use` added. And the element families plug in: no file of src/,
# app/ or test/ outside src/elements/ (the families and their registry)
# names a family's number (`fam` and an underscore: the registry's
# constants); it looks families up by name or calls
# their bindings (shown to fail on a copy with one added). Run from the
# project root.
set -u
pass=0; fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

check() {   # check SRC_DIR DOC: prints one line per upward edge or mismatch, exit 1 on any
    python3 - "$1" "$2" <<'PY'
import os, re, sys
src, doc = sys.argv[1], sys.argv[2]
order, listed = [], {}
for line in open(doc, encoding='utf-8'):
    m = re.match(r'\|\s*`src/([a-z_]+)/`\s*\|[^|]*\|(.*)\|\s*$', line)
    if m:
        order.append(m.group(1))
        listed[m.group(1)] = set(re.findall(r'`(hn_\w+)`', m.group(2)))
bad = 0
if not order:
    print('no folder table in ' + doc); sys.exit(1)
folder_of, uses = {}, []
for folder in sorted(os.listdir(src)):
    d = os.path.join(src, folder)
    if not os.path.isdir(d):
        continue
    if folder not in order:
        print(f'src/{folder}/ is not in the folder table of the architecture document'); bad += 1
    for name in sorted(os.listdir(d)):
        if not name.lower().endswith(('.f90', '.f')):
            continue
        text = open(os.path.join(d, name), encoding='utf-8').read()
        for m in re.finditer(r'^\s*module\s+(?!procedure\b)(\w+)\s*$', text, re.M | re.I):
            folder_of[m.group(1).lower()] = folder
        for m in re.finditer(r'^\s*submodule\s*\(\s*(\w+)\s*\)\s*(\w+)', text, re.M | re.I):
            folder_of[m.group(2).lower()] = folder
            uses.append((folder, name, m.group(1).lower()))
        for m in re.finditer(r'^\s*use\s*(?:,\s*non_intrinsic\s*)?(?:::)?\s*(\w+)', text, re.M | re.I):
            uses.append((folder, name, m.group(1).lower()))
for folder in order:
    have = {m for m, f in folder_of.items() if f == folder}
    if folder in listed and listed[folder] != have:
        print(f'src/{folder}/: the table lists {sorted(listed[folder] - have)} not there, '
              f'misses {sorted(have - listed[folder])}'); bad += 1
for folder, name, used in uses:
    target = folder_of.get(used)
    if target is None or folder not in order or target not in order:
        continue    # an intrinsic or external module (hdf5, mpi, ...)
    if order.index(target) > order.index(folder):
        print(f'src/{folder}/{name} uses {used} of src/{target}/, a layer above'); bad += 1
sys.exit(1 if bad else 0)
PY
}

if check src docs/architecture.md > "$tmp/report" 2>&1; then
    echo "PASS  every use in src/ names a module of its own layer or one below (order of docs/architecture.md)"
    pass=$((pass + 1))
else
    echo "FAIL  upward uses or a table that does not match the code:"
    sed 's/^/      /' "$tmp/report"
    fail=$((fail + 1))
fi

# the check must fail on a tree with one upward use: hn_kinds (base) using hn_run (run)
cp -r src "$tmp/src"
awk '{ print } /^module hn_kinds$/ { print "    use hn_run, only: run_state_t" }' src/base/hn_kinds.f90 \
    > "$tmp/src/base/hn_kinds.f90"
if check "$tmp/src" docs/architecture.md > "$tmp/report2" 2>&1; then
    echo "FAIL  the check passed a tree where base/hn_kinds uses run/hn_run"
    fail=$((fail + 1))
elif grep -q 'src/base/hn_kinds.f90 uses hn_run of src/run/' "$tmp/report2"; then
    echo "PASS  an upward use (base/hn_kinds using run/hn_run) is found and named"
    pass=$((pass + 1))
else
    echo "FAIL  the check failed on the bad tree without naming the upward use:"
    sed 's/^/      /' "$tmp/report2"
    fail=$((fail + 1))
fi
num='fam''_'   # a family number's prefix (split, so that this file does not hold it)
numbers_outside() {   # numbers_outside ROOT: files under ROOT/{src,app,test} outside src/elements naming one
    (cd "$1" && grep -rl "$num" src app test 2>/dev/null | grep -v '^src/elements/' | sort)
}
found=$(numbers_outside .)
if [ -z "$found" ]; then
    echo "PASS  no file outside src/elements/ names a family number ${num}*"
    pass=$((pass + 1))
else
    echo "FAIL  files outside src/elements/ name a family number ${num}* (look the family up by name, or add a binding):"
    echo "$found" | sed 's/^/      /'
    fail=$((fail + 1))
fi
# the check must fail on a tree where run/hn_run names the limits' number
mkdir -p "$tmp/numtree"
cp -r src app test "$tmp/numtree/"
echo "! ${num}limits" >> "$tmp/numtree/src/run/hn_run.f90"
if [ "$(numbers_outside "$tmp/numtree")" = "src/run/hn_run.f90" ]; then
    echo "PASS  a family number named outside src/elements/ (run/hn_run) is found"
    pass=$((pass + 1))
else
    echo "FAIL  the family-number check did not find exactly the file that names one"
    fail=$((fail + 1))
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
