#!/bin/sh
# The volunteer state's controller fitted to the NBDL 12 g volunteers on the
# current model deck (issue constraint 4: the controller's bracing and gains
# are the only parameters fitted to volunteers):
#   1. hhneck --calibrate < input/calibrate_controller.inp -> the listing FIT;
#   2. its PARAM values (and the TIE values, the fields a parameter shares
#      left and right) written into input/volunteer_controller.inp, whose
#      header then says they are fitted and by what;
#   3. reference/controller_parameters.csv: every value of the controller
#      deck, the fitted ones with status fitted, stage controller.
# dev/fit_model.sh runs this as its last stage. Deterministic: the fit starts
# from the calibration deck's VALUES point, not from the controller deck's
# values, so a second run gives the same deck.
# Usage: dev/fit_controller.sh [FIT]   (default fit_controller.txt; about 20
# minutes on two cores). It rewrites input/volunteer_controller.inp and
# reference/controller_parameters.csv in place.
#        dev/fit_controller.sh --listing FIT   steps 2 and 3 alone, from the
# listing FIT of an earlier run of step 1.
set -e
cd "$(dirname "$0")/.."
if [ "$1" = --listing ]; then
    fit=$2
    [ -f "$fit" ] || { echo "fit_controller.sh: no listing $fit" >&2; exit 1; }
else
    fit=${1:-fit_controller.txt}
    exe=$(fpm run --profile release --runner echo 2>/dev/null | tail -1)
    case $exe in /*) ;; *) exe=$PWD/$exe ;; esac
    "$exe" --calibrate < input/calibrate_controller.inp > "$fit"
fi
python3 - "$fit" <<'PY'
import re
import sys

fit = open(sys.argv[1]).read().splitlines()
cal = open("input/calibrate_controller.inp").read().splitlines()
deck_path = "input/volunteer_controller.inp"
deck = open(deck_path).read().splitlines()

def field(line, n):
    """field n (1-7) of a card image"""
    return line[10 + 10*(n - 1):20 + 10*(n - 1)].strip()

# the fitted values: the PARAM lines, then each TIE line (card, item, field)
value = {}
tie = {}
for l in fit:
    m = re.match(r"PARAM (.{10}) = (\S+)", l)
    if m:
        value[m.group(1).strip()] = m.group(2)
    m = re.match(r"TIE   (.{10}) = (\S+)\s+(\S+)\s+(\S+)\s+F(\d+)", l)
    if m:
        tie[(m.group(3), m.group(4), int(m.group(5)))] = m.group(2)
if not value:
    sys.exit("fit_controller.sh: no PARAM line in %s: the calibration did not finish" % sys.argv[1])

def field_text(v):
    """the listing's number v in at most 9 columns (a field is 10 wide, one
    blank between fields): the same number where it can be (0.00476348 as
    .00476348), else rounded to the most digits that fit"""
    x = float(v)
    for text in ("%.6g" % x, v):
        short = text.replace("0.", ".", 1) if text.lstrip("-").startswith("0.") else text
        for t in (text, short):
            if len(t) <= 9 and float(t) == x:
                return t
    for digits in range(6, 0, -1):
        for t in ("%.*g" % (digits, x), "%.*E" % (digits - 1, x)):
            t = t.replace("E+0", "E+").replace("E-0", "E-")
            if len(t) <= 9:
                return t
    sys.exit("fit_controller.sh: %s does not fit in 9 columns" % v)

def locate(key, item, n):
    """the index of the controller deck line holding field n of card key named item (name.text: F2 or F3 text)"""
    name, _, other = item.partition(".")
    hits = [i for i, l in enumerate(deck) if l[:8].strip() == key and field(l, 1) == name
            and (not other or other in (field(l, 2), field(l, 3)))]
    if len(hits) != 1:
        sys.exit("fit_controller.sh: %d %s cards named %s in %s; expected one" % (len(hits), key, item, deck_path))
    return hits[0], hits[0] + (n - 1)//7

fitted = {}     # (card, F1, F3, field) -> parameter name
seen = set()
for l in cal:
    if not l.startswith("PARAM "):
        continue
    name, n, key, item = field(l, 1), int(field(l, 2)[5:]), field(l, 3), field(l, 4)
    v = value[name] if name not in seen else tie[(key, item, n)]
    v = field_text(v)
    seen.add(name)
    card, i = locate(key, item, n)
    other = item.partition(".")[2]
    c = 10 + 10*((n - 1) % 7)
    deck[i] = (deck[i].ljust(c + 10)[:c] + v.ljust(10) + deck[i][c + 10:]).rstrip()
    fitted[(key, field(deck[card], 1), other, n)] = name

# the header: what is fitted and by what
head = [i for i, l in enumerate(deck) if l.startswith("* The gains are") or l.startswith("* The bracing levels u0")]
end = head[0]
while deck[end + 1].startswith("* ") and not deck[end + 1].startswith("*  "):
    end += 1
deck[head[0]:end + 1] = [
    "* The bracing levels u0 (= u1) and the loops' pitch gains and stretch gains",
    "* are FITTED to the NBDL 12 g volunteers by dev/fit_controller.sh",
    "* (input/calibrate_controller.inp; left and right share each value), the",
    "* only parameters fitted to volunteers; the loops about x and z are chosen",
    "* (a frontal pulse does not move them) so that the head returns after a",
    "* lateral push; every value is in reference/controller_parameters.csv.",
    "* test/scripts/controller.sh checks rest and return."]
open(deck_path, "w").write("\n".join(deck) + "\n")

# the table: every value of the controller deck
units = {("ACTIVATE", 2): "1", ("ACTIVATE", 3): "1", ("ACTIVATE", 4): "s", ("ACTIVATE", 5): "s",
         ("FEEDBACK", 4): "1/rad", ("FEEDBACK", 5): "s/rad", ("FEEDBACK", 6): "s",
         ("FEEDBACK", 8): "1/(rad s)",
         ("SPINDLE", 2): "1/lopt", ("SPINDLE", 3): "s/lopt", ("SPINDLE", 4): "s", ("SPINDLE", 7): "1/(lopt s)"}
what = {("ACTIVATE", 2): "bracing level u0 (excitation at the start)",
        ("ACTIVATE", 3): "excitation after the start, u1 = u0 (no open-loop reflex)",
        ("FEEDBACK", 4): "vestibular loop gain kp on the head's rotation",
        ("FEEDBACK", 5): "vestibular loop gain kd on the head's angular velocity",
        ("FEEDBACK", 6): "vestibular loop delay (vestibulocollic latency)",
        ("FEEDBACK", 8): "vestibular loop gain ki on the time integral of the head's rotation",
        ("SPINDLE", 2): "stretch loop gain kp on each muscle's stretch",
        ("SPINDLE", 3): "stretch loop gain kd on each muscle's rate of lengthening",
        ("SPINDLE", 4): "stretch loop delay (stretch reflex latency)",
        ("SPINDLE", 7): "stretch loop gain ki on the time integral of each muscle's stretch"}
cont = {1: ("tau_act", "s", "activation time constant", "sourced", "S5"),
        2: ("tau_deact", "s", "deactivation time constant", "sourced", "S5")}
rows = ["name,value,unit,status,source,stage,description"]
for i, l in enumerate(deck):
    key = l[:8].strip()
    if key not in ("ACTIVATE", "FEEDBACK", "SPINDLE"):
        continue
    hist = field(l, 1)
    label = hist + ("." + field(l, 3) if key == "FEEDBACK" else "")
    more = deck[i + 1] if i + 1 < len(deck) and not deck[i + 1][:10].strip() else ""
    for n in (2, 3, 4, 5, 6, 7, 8):
        text = field(l, n) if n <= 7 else field(more, n - 7)
        if (key, n) not in what or not text:
            continue
        if n == 4 and key == "ACTIVATE" or n == 5 and key == "ACTIVATE":
            continue
        name = "%s.%s.%s" % (key.lower(), label, {2: "u0", 3: "u1", 4: "kp", 5: "kd", 6: "delay", 8: "ki"}[n]
                             if key != "SPINDLE" else {2: "kp", 3: "kd", 4: "delay", 7: "ki"}[n])
        k = (key, hist, field(l, 3) if key == "FEEDBACK" else "", n)
        if k in fitted:
            status, source, stage = "fitted", "S6", "controller"
            desc = "%s, %s (PARAM %s of input/calibrate_controller.inp)" % (what[(key, n)], hist, fitted[k])
        elif "delay" in name:
            status, source, stage, desc = "sourced", "S10", "", what[(key, n)]
        elif (key, n) in (("SPINDLE", 7), ("FEEDBACK", 8)):
            status, source, stage = "assumed", "", ""
            desc = what[(key, n)] + " (chosen: the column holds its posture at rest)"
        else:
            status, source, stage = "assumed", "", ""
            desc = what[(key, n)] + " (chosen: the head returns after a lateral push)"
        rows.append('%s,%s,%s,%s,%s,%s,"%s"' % (name, text, units[(key, n)], status, source, stage, desc))
    if key == "ACTIVATE":
        c = deck[i + 1]
        for n, (nm, unit, desc, status, source) in cont.items():
            rows.append('activate.%s.%s,%s,%s,%s,%s,,"%s"' % (hist, nm, field(c, n), unit, status, source, desc))
open("reference/controller_parameters.csv", "w").write("\n".join(rows) + "\n")
print("fit_controller.sh: %d fitted values written into %s and reference/controller_parameters.csv"
      % (len(fitted), deck_path))
PY
