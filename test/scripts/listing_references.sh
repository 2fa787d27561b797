#!/bin/sh
# The listings of the regression decks against their references
# (reference/outputs/CASE.txt, written by dev/regenerate_references.sh):
# same text, numbers within hhneck-compare-listing's tolerance. The
# default listings, and case 6-2's full listing (PRINT ALL: every table;
# test/scripts/lib/reference_listings.sh). Run from the project root; the
# executable in $HHNECK.
# Each deck runs with its own integrator at --rtol 1.0E-7, as the
# references were written: another build or machine has other roundoff and
# so another step sequence, and at the decks' own tolerances (1e-3, 1e-4)
# that moves the listings by up to 40 times the compare tolerance (an FMA
# build, -march=native), by 0.10 of it at 1e-7. compare_listing.py takes a
# channel at roundoff level against its unit's largest for noise, so the
# time of a noise peak is never compared. dev/listing_robustness.sh
# builds with other roundoff (-march=native, -O0) and runs this comparison.
# A change of an input far below physics but far above one ulp (the head's
# mass by 2.6e-8 of itself; one ulp cannot be written in ten columns) must
# pass too.
# builds: release
set -u
HHNECK=${HHNECK:-$(fpm run --profile release --runner echo 2>/dev/null | tail -n 1)}
case $HHNECK in /*) ;; *) HHNECK=$(pwd)/$HHNECK ;; esac   # usable after a cd
PYTHONPATH=$(pwd)/python${PYTHONPATH:+:$PYTHONPATH}   # the project's own package
export PYTHONPATH
tmp=$(mktemp -d)
pass=0; fail=0
compare() {
    if python3 -m hhneck.tools.compare_listing "$1" "$2"; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
    fi
}
. test/scripts/lib/reference_listings.sh
for c in $REFERENCE_LISTINGS; do
    reference_listing "$HHNECK" "$c" > "$tmp/$c.txt" 2> /dev/null
    compare "$tmp/$c.txt" "reference/outputs/$c.txt"
done
# the head's mass 3.847 kg -> 3.8470001 kg (2.6e-8 of itself)
mkdir -p "$tmp/input"
cp input/*.inp "$tmp/input/"
sed 's/^\(BODY      HEAD      C1        \)3\.847     /\13.8470001 /' input/head_neck_54dof.inp \
    > "$tmp/input/head_neck_54dof.inp"
if cmp -s input/head_neck_54dof.inp "$tmp/input/head_neck_54dof.inp"; then
    echo "FAIL  the change of the head's mass was not made"
    fail=$((fail + 1))
else
    (cd "$tmp" && "$HHNECK" --no-h5 --rtol 1.0E-7 < input/nbdl15g.inp > nbdl15g_ulp.txt 2> /dev/null)
    compare "$tmp/nbdl15g_ulp.txt" reference/outputs/nbdl15g.txt
fi
rm -rf "$tmp"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
