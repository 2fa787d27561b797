#!/bin/sh
# The volunteer state's activation histories (input/volunteer_controller.inp:
# ACTIVATE FLEXL, FLEXR, EXTL, EXTR; its GROUP cards move the model deck's
# Hill muscles into them; docs/deck-format.md, GROUP): in the NBDL 15 g
# run every Hill muscle of the model deck is in one of the four, starts at
# the bracing level u0 of its history's ACTIVATE card and is moved by the
# loops; the frontal pulse is symmetric, so each left muscle's activation
# is its right mirror's (within 1e-6: roundoff of the out-of-plane
# motion), and the flexors and the extensors differ. Then the right
# histories merged into the left ones (every GROUP card naming FLEXR or
# EXTR names FLEXL or EXTL instead, and the right histories' ACTIVATE,
# FEEDBACK and SPINDLE cards left out) give the same run, channel for
# channel: each history's activation is a state of the equations, and the
# two runs integrate two equal components or one; at --rtol 1.0E-7 every
# channel agrees within 1e-4 of its range plus 1e-9 (the out-of-plane
# channels are roundoff); the energy balance's residual, a measure of the
# integration error itself, is left out.
# Release build: the runs are the NBDL 15 g deck's, which the checking build
# runs end to end in test/unit/test_cases.pf.
# builds: release
. test/scripts/lib/checks.sh

"$HHNECK" --h5 "$tmp/shipped.h5" < input/nbdl15g.inp > /dev/null 2>&1
py_checks - "$tmp/shipped.h5" input/head_neck_54dof.inp input/volunteer_controller.inp <<'PY'
import sys
import h5py
import numpy as np
sys.path.insert(0, "python")
from hhneck.decks import field, is_card
c = h5py.File(sys.argv[1], "r")["channels"]
model = open(sys.argv[2]).read().splitlines()
ctrl = open(sys.argv[3]).read().splitlines()
u0 = {field(l, 1): float(field(l, 2)) for l in ctrl if is_card(l, "ACTIVATE")}
hill = [field(l, 1) for l in model if is_card(l, "HILL")]
group = {field(l, 1): field(l, 2) for l in ctrl if is_card(l, "GROUP")}
def check(ok, what):
    print(("PASS  " if ok else "FAIL  ") + what)
check(sorted(u0) == ["EXTL", "EXTR", "FLEXL", "FLEXR"], "the controller deck has the histories FLEXL FLEXR EXTL EXTR")
check(sorted(group) == sorted(hill) and set(group.values()) == set(u0),
      "its GROUP cards put each of the model deck's %d Hill muscles into one of them" % len(hill))
for h in sorted(u0):
    members = [m for m in hill if group.get(m) == h]
    a = [c["A_" + m][:] for m in members]
    check(len(a) > 0 and all(abs(x[0] - u0[h]) <= 1e-12 for x in a),
          "%s: %s start at the bracing level %g" % (h, " ".join(members), u0[h]))
    check(len(a) > 0 and min(np.ptp(x) for x in a) > 0.01,
          "%s: the loops move each muscle (by %.3g at least)" % (h, min(np.ptp(x) for x in a) if a else 0))
pairs = [(m, m[:-1] + "R") for m in hill if m.endswith("L") and m[:-1] + "R" in hill]
worst = max(np.abs(c["A_" + l][:] - c["A_" + r][:]).max() for l, r in pairs)
check(len(pairs) == len(hill) // 2 and worst < 1e-6,
      "the symmetric pulse: each of %d left muscles' activation is its right mirror's (largest difference %.2g)"
      % (len(pairs), worst))
check(not np.array_equal(c["A_SCML"][:], c["A_SPLCL"][:]), "the flexors and the extensors follow different histories")
PY

# the right histories merged into the left ones against the four
mkdir "$tmp/four" "$tmp/two"
for d in four two; do
    mkdir "$tmp/$d/input"
    cp input/nbdl15g.inp input/nbdl15g_t1.inp input/head_neck_54dof.inp "$tmp/$d/input/"
done
cp input/volunteer_controller.inp "$tmp/four/input/"
python3 - "$tmp/two/input/volunteer_controller.inp" <<'PY'
import sys
sys.path.insert(0, "python")
from hhneck.decks import field, is_card, set_field
merge = {"FLEXR": "FLEXL", "EXTR": "EXTL"}
out, skip = [], False
for l in open("input/volunteer_controller.inp").read().splitlines():
    if not l.startswith((" ", "*")):
        skip = any(is_card(l, k) and field(l, 1) in merge for k in ("ACTIVATE", "FEEDBACK", "SPINDLE"))
    if skip:
        continue
    out.append(set_field(l, 2, merge[field(l, 2)]) if is_card(l, "GROUP") and field(l, 2) in merge else l)
open(sys.argv[1], "w").write("\n".join(out) + "\n")
PY
for d in four two; do
    (cd "$tmp/$d" && "$HHNECK" --rtol 1.0E-7 --h5 run.h5 < input/nbdl15g.inp > /dev/null 2>&1)
done
check "the merged deck has no right history" sh -c "! grep -qE '^(ACTIVATE|FEEDBACK|SPINDLE)  (FLEXR|EXTR) ' '$tmp/two/input/volunteer_controller.inp'"
check "two histories merged: every channel equals the run of four" python3 - "$tmp/four/run.h5" "$tmp/two/run.h5" <<'PY'
import sys
import h5py
import numpy as np
a, b = (h5py.File(f, "r")["channels"] for f in sys.argv[1:3])
def same(n):
    x, y = a[n][:], b[n][:]
    return n == "E_BALANCE" or np.abs(x - y).max() <= 1e-4*np.ptp(x) + 1e-9   # (out-of-plane channels: roundoff)
sys.exit(0 if sorted(a) == sorted(b) and len(a) > 100 and all(same(n) for n in a) else 1)
PY
finish
