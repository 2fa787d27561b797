#!/bin/sh
# The model deck's two activation histories (ACTIVATE FLEX for the flexors,
# ACTIVATE EXT for the extensors; docs/validation.md): in the NBDL 15 g run
# every Hill muscle starts at the bracing level of the history its HILL card
# names and moves with the other muscles of that history, and the two
# histories set to the same values give the run of one history for all
# muscles, channel for channel: each history's activation is a state of the
# equations, so the two runs integrate one more, equal, component; at
# --rtol 1.0E-7 every channel agrees within 1e-4 of its range (1.5e-5 at
# most) plus 1e-9 (the out-of-plane channels are roundoff, 1e-17); the
# energy balance's residual, a measure of the integration error itself, is
# left out.
. test/scripts/lib/checks.sh

"$HHNECK" --h5 "$tmp/shipped.h5" < input/nbdl15g.inp > /dev/null 2>&1
py_checks - "$tmp/shipped.h5" input/head_neck_54dof.inp <<'PY'
import sys
import h5py
import numpy as np
sys.path.insert(0, "python")
from hhneck.deck_fields import field, is_card
c = h5py.File(sys.argv[1], "r")["channels"]
deck = open(sys.argv[2]).read().splitlines()
u0 = {field(l, 1): float(field(l, 2)) for l in deck if is_card(l, "ACTIVATE")}
hist = {field(l, 1): field(l, 6) for l in deck if is_card(l, "HILL")}
def check(ok, what):
    print(("PASS  " if ok else "FAIL  ") + what)
check(sorted(u0) == ["EXT", "FLEX"] and sorted(set(hist.values())) == ["EXT", "FLEX"],
      "the model deck has the histories FLEX and EXT and its HILL cards use both")
for h in ("FLEX", "EXT"):
    group = [m for m in hist if hist[m] == h]
    a = [c["A_" + m][:] for m in group]
    check(all(abs(x[0] - u0[h]) <= 1e-12 for x in a),
          "%s: %s start at the bracing level %g" % (h, " ".join(group), u0[h]))
    check(all(np.array_equal(x, a[0]) for x in a), "%s: its muscles' activations are one history" % h)
    check(np.ptp(a[0]) > 0.05, "%s: the reflex moves it (by %.3g)" % (h, np.ptp(a[0])))
check(not np.array_equal(c["A_SCML"][:], c["A_SPLCL"][:]), "the flexors and the extensors follow different histories")
PY

# the same values on both cards against one history for every muscle
mkdir "$tmp/two" "$tmp/one"
for d in two one; do
    mkdir "$tmp/$d/input"
    cp input/nbdl15g.inp input/nbdl15g_t1.inp "$tmp/$d/input/"
done
python3 - "$tmp" <<'PY'
import sys
sys.path.insert(0, "python")
from hhneck.deck_fields import field, is_card, set_field
lines = open("input/head_neck_54dof.inp").read().splitlines()
flex = next(l for l in lines if is_card(l, "ACTIVATE") and field(l, 1) == "FLEX")
two = [set_field(flex, 1, "EXT") if is_card(l, "ACTIVATE") and field(l, 1) == "EXT" else l for l in lines]
one, skip = [], 0
for l in lines:
    if skip:
        skip -= 1
        continue
    if is_card(l, "ACTIVATE") and field(l, 1) == "EXT":
        skip = 1  # the card and its continuation
        continue
    one.append(set_field(l, 6, "FLEX") if is_card(l, "HILL") else l)
open(sys.argv[1] + "/two/input/head_neck_54dof.inp", "w").write("\n".join(two) + "\n")
open(sys.argv[1] + "/one/input/head_neck_54dof.inp", "w").write("\n".join(one) + "\n")
PY
for d in two one; do
    (cd "$tmp/$d" && "$HHNECK" --rtol 1.0E-7 --h5 run.h5 < input/nbdl15g.inp > /dev/null 2>&1)
done
check "one history FLEX for every muscle has no ACTIVATE EXT card" sh -c "! grep -q '^ACTIVATE  EXT' '$tmp/one/input/head_neck_54dof.inp'"
check "FLEX and EXT with the same values: every channel equals the run of one history" python3 - "$tmp/two/run.h5" "$tmp/one/run.h5" <<'PY'
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
