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
rm -rf "$tmp"
echo "== all tests passed"
