#!/bin/sh
# Regenerates the reference outputs of every case deck ON PURPOSE, after a
# change that is meant to change results (say why in the commit). The
# regression check (test/scripts/regression.sh) never writes them.
#   reference/outputs/CASE.txt   the listing (release build, the deck's sampling;
#                                CASE_all: the full listing, PRINT ALL, of case
#                                CASE: test/scripts/lib/reference_listings.sh)
#                                at rtol 1e-7 (--rtol: atol 1e-10), so that a
#                                build or machine with other roundoff, and so
#                                other step sequences, agrees far inside the
#                                tolerance of hhneck-compare-listing (at the
#                                decks' own rtol 1e-3 or 1e-4 the listings of
#                                an FMA build differ by 1.4 to 40 times it)
#   reference/outputs/CASE.h5    /time and /channels every 1 ms, computed at
#                                rtol 1e-8 (atol 1e-11) so that builds with
#                                other roundoff agree far inside the tolerance
set -eu
cd "$(dirname "$0")/.."
fpm build --profile release >&2          # its progress must not go into a listing
hhneck=$(fpm run --profile release --runner echo 2>/dev/null | tail -n 1)
tmp=$(mktemp -d)
. test/scripts/lib/reference_listings.sh
for c in $REFERENCE_LISTINGS; do
    echo "regenerating reference/outputs/$c" >&2
    reference_listing "$hhneck" "$c" > "reference/outputs/$c.txt"
    case $c in *_all) continue ;; esac      # the same run as CASE: no result file of its own
    "$hhneck" --sample 1.0E-3 --rtol 1.0E-8 --h5 "$tmp/$c.h5" < "input/$c.inp" > /dev/null
    python3 dev/extract_reference.py "$tmp/$c.h5" "reference/outputs/$c.h5"
done
rm -rf "$tmp"
