#!/bin/sh
# Regression: every case deck with reference outputs in reference/outputs
# (written on purpose by dev/regenerate_references.sh, never by this check)
# run again as they were made -- the program of the README's run (release
# build), every channel every 1 ms (--sample 1.0E-3) at rtol 1e-8 and atol
# 1e-11 (--rtol 1.0E-8) with the deck's integrator -- and compared with
# them: every channel at every sample must agree within 1e-4 of the
# channel's largest reference magnitude (at least 1e-4 of the largest
# channel of its unit, so that roundoff-only channels are not measured
# against their own noise: the out-of-plane channels of the sagittal cases
# are about 1e-9 of their unit's largest and differ between builds by as
# much as they are large). 1e-4 is far above the 1e-8 tolerance (builds
# with other optimization have other roundoff and so other step sequences)
# and far below any change of the model or the method. E_BALANCE is zero
# to the tolerance and checked by test/unit/test_stability.pf. The same
# decks run end to end in the checking build in test/unit/test_cases.pf.
# builds: release
. test/scripts/lib/checks.sh

CASES="case6-1 case6-2 case6-5 nbdl15g hybrid3_flexion"
for c in $CASES; do
    "$HHNECK" --no-progress --sample 1.0E-3 --rtol 1.0E-8 --h5 "$tmp/$c.h5" < "input/$c.inp" > "$tmp/$c.txt" 2> "$tmp/$c.err"
    rc=$?
    check "$c runs at rtol 1e-8 (exit $rc)" [ "$rc" -eq 0 ]
done
py_checks - "$tmp" $CASES <<'PY'
import sys

import numpy as np
from hhneck.results import read_channels
from hhneck.tools.compare_listing import NOISE_FLOOR   # a channel's scale: at least this of its unit's largest

REL_TOL = 1.0e-4        # of a channel's largest reference magnitude
tmp = sys.argv[1]
for case in sys.argv[2:]:
    ref = read_channels("reference/outputs/%s.h5" % case)
    try:
        new = read_channels("%s/%s.h5" % (tmp, case))
    except (OSError, KeyError) as e:
        print("FAIL  %s matches its reference outputs [no result file: %s]" % (case, e))
        continue
    units = new.attrs["units"]
    missing = [n for n in ref.columns if n not in new.columns]
    same_grid = len(new.index) == len(ref.index) and np.max(np.abs(new.index.values - ref.index.values)) < 1e-9
    if missing or not same_grid:
        print("FAIL  %s matches its reference outputs [%s]" % (
            case, "channels not in the run: " + " ".join(missing[:5]) if missing else
            "%d samples against the reference's %d" % (len(new.index), len(ref.index))))
        continue
    peak = ref.abs().max()
    unit_peak = {}
    for n in ref.columns:
        unit_peak[units[n]] = max(unit_peak.get(units[n], 0.0), peak[n])
    worst, worst_dev = "none", 0.0
    for n in ref.columns:
        if n == "E_BALANCE":
            continue
        scale = max(peak[n], NOISE_FLOOR * unit_peak[units[n]])
        diff = np.max(np.abs(new[n].values - ref[n].values))
        dev = diff if scale < 1e-9 else diff / scale
        if not dev <= worst_dev:        # a NaN is the worst
            worst, worst_dev = n, dev
    print("%s  %s matches its reference outputs [%d channels; largest deviation in %s: %.2e of its range]" % (
        "PASS" if worst_dev <= REL_TOL else "FAIL", case, len(ref.columns), worst, worst_dev))
PY
finish
