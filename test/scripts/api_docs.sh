#!/bin/sh
# The API pages (docs/ford.md, FORD from the !> and !! comments of src/)
# build without a FORD warning or error, with one page for every module
# and submodule of src/ and pages for public procedures that carry their
# source comments; a private procedure has none. FORD is the pinned version
# tools/setup.sh installs into .venv (tools/test.sh puts it on PATH).
# This check runs no executable: HHNECK is not needed.
HHNECK=${HHNECK:-none}
. test/scripts/lib/checks.sh

ford=$(command -v ford || echo .venv/bin/ford)
if [ ! -x "$ford" ]; then
    fail "FORD is installed (tools/setup.sh installs it into .venv)"
    finish
    exit 1
fi

start=$(date +%s)
"$ford" --output_dir "$tmp/api" docs/ford.md > "$tmp/ford.log" 2>&1
rc=$?
took=$(( $(date +%s) - start ))
check "FORD builds the pages (exit $rc, $took s)" [ "$rc" -eq 0 ]
# FORD writes warnings (a comment line it takes for a metadata key, a
# missing entity) and errors on stdout or stderr, wrapped over lines
if grep -qiE '(warning|error)' "$tmp/ford.log"; then
    fail "FORD writes no warning or error"
    grep -iE -A1 '(warning|error)' "$tmp/ford.log" | head -n 20
else
    pass "FORD writes no warning or error"
fi

# one page per module and submodule: the names declared in src/, lower case
find src -name '*.f90' -exec sed -n \
    -e 's/^ *module  *\([A-Za-z0-9_]*\) *\(!.*\)\{0,1\}$/\1/p' \
    -e 's/^ *submodule *([^)]*) *\([A-Za-z0-9_]*\).*/\1/p' {} + |
    tr 'A-Z' 'a-z' | sort > "$tmp/modules.src"
ls "$tmp/api/module" 2>/dev/null | sed -n 's/\.html$//p' | sort > "$tmp/modules.api"
nsrc=$(wc -l < "$tmp/modules.src")
check "src/ declares modules (found $nsrc)" [ "$nsrc" -gt 50 ]
if cmp -s "$tmp/modules.src" "$tmp/modules.api"; then
    pass "one page for each of the $nsrc modules and submodules of src/, none else"
else
    fail "one page for each module of src/ (< without a page, > without a module):"
    diff "$tmp/modules.src" "$tmp/modules.api" | grep '^[<>]' | head -n 20
fi

# public procedures: a page with the first words of the comment above them
# in the source and of one argument's trailing comment
# doc_page NAME FILE PHRASE: PHRASE is in FILE (the source) and in NAME's page
doc_page() {
    if grep -qF "$3" "$2" && grep -qF "$3" "$tmp/api/proc/$1.html" 2>/dev/null; then
        pass "$1 ($2) has a page with its comment \"$3\""
    else
        fail "$1 ($2) has a page with its comment \"$3\""
    fi
}
doc_page cfc_filter src/analysis/hn_filters.f90 "Zero-phase CFC filtering of x sampled at dt into y"
doc_page runlimit_card src/deck/hn_deck_control.f90 "the deck: card images, located field access"
doc_page read_case src/deck/hn_deck.f90 "Read the deck in file"
doc_page body_kinematics src/core/hn_kinematics.f90 "Body-level kinematics of the whole tree, parents first"
doc_page body_kinematics src/core/hn_kinematics.f90 "active coordinates [m, rad]"
check "the private h5file_card (hn_deck_control) has no page (the public ones have)" \
    test -e "$tmp/api/proc/runlimit_card.html" -a ! -e "$tmp/api/proc/h5file_card.html"
check "the module page hn_deck_control lists its public runlimit_card" \
    grep -qs 'runlimit_card' "$tmp/api/module/hn_deck_control.html"
finish
