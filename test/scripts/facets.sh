#!/bin/sh
# The facet joints' include deck: input/facets.inp is what
# studies/facets.py --write-deck writes from reference/facet_parameters.csv
# (byte for byte, every card within 80 columns); a stiffness row of the
# table changed changes the deck, and a change that names no row is
# refused; a deck of the model deck with it INCLUDEd after passes
# `hhneck --check` and runs, with the twelve facets' force channels
# (finite, never negative) and their penetrations in mm.
. test/scripts/lib/checks.sh
root=$(pwd)

py_checks - "$tmp" <<'PY'
import os, sys
sys.path[:0] = ["studies", "python"]
import facets
tmp = sys.argv[1]
out = os.path.join(tmp, "facets.inp")
facets.write_deck(out)
same = open(out).read() == open("input/facets.inp").read()
print(("PASS" if same else "FAIL") + "  input/facets.inp is what studies/facets.py --write-deck writes")
long = [k + 1 for k, line in enumerate(open(out)) if len(line.rstrip("\n")) > 80]
print(("PASS" if not long else "FAIL") + "  every card within 80 columns %s" % (long or ""))
n = sum(1 for line in open(out) if line.startswith("FACET "))
print(("PASS" if n == 12 else "FAIL") + "  a left and a right facet at six joints (%d cards)" % n)
facets.CHANGED["facet.modulus"] = 20.0
cards = "\n".join(facets.facet_cards())
print(("PASS" if "2.114e+06" in cards else "FAIL") + "  the modulus doubled doubles k at C2-C3 (2.11E6 N/m)")
facets.CHANGED.clear()
facets.CHANGED["facet.nosuch"] = 1.0
try:
    facets.table()
    print("FAIL  a change of no row of the table is refused")
except KeyError as e:
    print("PASS  a change of no row of the table is refused (%s)" % e)
PY

printf 'TITLE     MODEL AND INCLUDE\nCONTROL   0.002     1.0E-4    0.001     ROS34PW2  1.0E-3    1.0E-5\nINCLUDE   input/head_neck_54dof.inp\nINCLUDE   input/facets.inp\n' > "$tmp/with.inp"
check "the model deck with input/facets.inp passes hhneck --check" sh -c "'$HHNECK' --check < '$tmp/with.inp' > '$tmp/check.out' 2>&1"
check "and runs 2 ms" sh -c "'$HHNECK' --no-progress --h5 '$tmp/with.h5' < '$tmp/with.inp' > '$tmp/with.lst' 2>&1"
py_checks - "$tmp/with.h5" <<'PY'
import sys
import numpy as np
sys.path[:0] = ["python"]
from hhneck.results import read_channels
df = read_channels(sys.argv[1])
names = [c for c in df.columns if c.startswith("FC") and c.endswith("_N")]
print(("PASS" if len(names) == 12 else "FAIL") + "  twelve facet force channels NAME_N (%d)" % len(names))
v = df[names].values
ok = np.all(np.isfinite(v)) and np.all(v >= 0)
print(("PASS" if ok else "FAIL") + "  facet forces finite and never negative (largest %.3g N)" % np.max(v))
print(("PASS" if df[[n[:-2] + "_D" for n in names]].attrs["units"][names[0][:-2] + "_D"] == "mm" else "FAIL")
      + "  penetrations NAME_D in mm")
PY
finish
