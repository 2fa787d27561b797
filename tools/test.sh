#!/bin/sh
# The whole test suite: every test program in the default (debug) build, then
# again in a checking build that traps invalid operations, division by zero
# and overflow and checks every array bound and pointer, then a look at a
# result file with h5py. Each test program ends with "N passed, N failed".
set -eu
cd "$(dirname "$0")/.."

CHECK_FLAGS="-g -O0 -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace -Wall -Wno-unused-dummy-argument -Wno-maybe-uninitialized"

echo "== fpm test (debug profile)"
fpm test
echo "== fpm test (checking build: $CHECK_FLAGS)"
fpm test --flag "$CHECK_FLAGS"
echo "== HDF5 results readable by h5py"
tmp=$(mktemp -d)
fpm run -- --h5 "$tmp/case6-2.h5" < input/case6-2.inp > "$tmp/listing.txt"
python3 tools/check_results.py "$tmp/case6-2.h5"
echo "== a bad deck: exit code 2, located message on stderr, no result file"
sed 's/^CONTROL   0.1  /CONTROL   -0.1 /' input/case6-2.inp > "$tmp/bad.inp"
set +e
fpm run -- --h5 "$tmp/bad.h5" < "$tmp/bad.inp" > "$tmp/bad.out" 2> "$tmp/bad.err"
rc=$?
set -e
grep -q "stdin line 10, columns 11-20 (CONTROL card, field F1 'end time')" "$tmp/bad.err"
[ "$rc" -eq 2 ] && [ ! -e "$tmp/bad.h5" ] && [ ! -e "$tmp/bad.h5.part" ] && ! grep -q "deck error" "$tmp/bad.out"
echo "PASS  exit code 2, message names line 10 columns 11-20, nothing written"
rm -rf "$tmp"
echo "== all tests passed"
