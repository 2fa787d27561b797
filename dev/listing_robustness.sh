#!/bin/sh
# The listing references (test/scripts/listing_references.sh) on builds
# whose roundoff differs from the release build that wrote them: the
# release profile with -march=native (fused multiply-add where the
# processor has it, so other roundoff in nearly every expression) and fpm's
# debug profile (-O0). Each deck runs at --rtol 1.0E-7 as the references
# were written, and must match within hhneck-compare-listing's tolerance.
# A few minutes: two builds. Not part of tools/test.sh (the builds take
# longer than the check); run it after a change of compare_listing.py, of
# the references or of the integrators.
#   dev/listing_robustness.sh
set -u
cd "$(dirname "$0")/.."
. test/scripts/lib/reference_listings.sh
pass=0; fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for build in native debug; do
    case $build in
        native) args="--profile release --flag -march=native" ;;
        debug) args="" ;;
    esac
    # shellcheck disable=SC2086
    fpm build $args >&2 || { echo "FAIL  the $build build"; fail=$((fail + 1)); continue; }
    # shellcheck disable=SC2086
    exe=$(fpm run $args --runner echo 2>/dev/null | tail -n 1)
    for c in $REFERENCE_LISTINGS; do
        reference_listing "$exe" "$c" > "$tmp/$c.txt" 2> /dev/null
        printf '%s build: ' "$build"
        if python3 -m hhneck.tools.compare_listing "$tmp/$c.txt" "reference/outputs/$c.txt"; then
            pass=$((pass + 1))
        else
            fail=$((fail + 1))
        fi
    done
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
