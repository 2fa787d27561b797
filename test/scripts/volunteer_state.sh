#!/bin/sh
# One model for every subject (issue constraint 4): the volunteer state is
# the model deck with the controller (input/volunteer_controller.inp), and
# the volunteer calibration (input/calibrate_controller.inp) moves the
# controller alone.
# - every parameter of the calibration (its PARAM cards of one name) binds
#   with the controller (hhneck --calibrate --check) and fails to bind when
#   the case and standing decks leave the controller out: every field it
#   writes is a controller card's, none is the model deck's;
# - the same check refuses a calibration with a PARAM on the model deck (a
#   SCALE factor, the disc family, a LIGAMENT card's field), its negative
#   cases, and passes a controller-only one of the same form;
# - every shipped deck of a living subject (the NBDL sleds, the rear and
#   lateral sleds, the occupant scenes, the controller's own rest and return
#   decks) includes the controller right after the model deck; the specimen
#   decks do not.
# builds: release
. test/scripts/lib/checks.sh

cp -r input "$tmp/input"
cp -r reference "$tmp/reference"
cd "$tmp" || exit 1
py_checks - "$HHNECK" <<'PY'
import re
import subprocess
import sys

exe = sys.argv[1]
CTRL = "INCLUDE   input/volunteer_controller.inp"
MODEL = "INCLUDE   input/head_neck_54dof.inp"

def check(ok, what):
    print(("PASS  " if ok else "FAIL  ") + what)

def without_controller(path):
    """a copy of deck `path` without the controller; its name"""
    new = path.replace(".inp", "_nocontrol.inp")
    text = open(path).read()
    open(new, "w").write(text.replace(CTRL + "\n", ""))
    return new

cal = open("input/calibrate_controller.inp").read().splitlines()
decks = [l[10:70].strip() for l in cal if l.startswith("CASE") or l.startswith("STANDING")]
bare = {d: without_controller(d) for d in decks}

def binds(lines, bare_decks):
    """does hhneck --calibrate --check accept the calibration `lines`?"""
    out = []
    for l in lines:
        if l.startswith("VALUES"):
            continue
        if bare_decks and (l.startswith("CASE") or l.startswith("STANDING")):
            d = l[10:70].strip()
            l = l[:10] + bare[d].ljust(60) + l[70:]
        out.append(l)
    r = subprocess.run([exe, "--calibrate", "--check"], input="\n".join(out) + "\n", capture_output=True, text=True)
    return r.returncode == 0, r.stderr.strip()

def off_controller(lines):
    """the names of the PARAMs of calibration `lines` that bind without the
    controller, and of those that do not bind with it"""
    params = [l for l in lines if l.startswith("PARAM")]
    rest = [l for l in lines if not l.startswith("PARAM")]
    names = list(dict.fromkeys(l[10:20].strip() for l in params))
    off, unbound = [], []
    for n in names:
        one = rest + [l for l in params if l[10:20].strip() == n]
        ok_with, msg = binds(one, False)
        ok_without, _ = binds(one, True)
        if not ok_with:
            unbound.append((n, msg))
        if ok_without:
            off.append(n)
    return names, off, unbound

names, off, unbound = off_controller(cal)
check(len(names) >= 4 and not off and not unbound,
      "input/calibrate_controller.inp: its %d parameters (%s) all bind with the controller and none without it%s%s"
      % (len(names), " ".join(names), "; off the controller: %s" % off if off else "",
         "; unbound: %s" % unbound if unbound else ""))
fields = sorted({(l[20:30].strip(), l[30:40].strip()) for l in cal if l.startswith("PARAM")})
check({t for _, t in fields} <= {"ACTIVATE", "FEEDBACK", "SPINDLE"},
      "its PARAM cards write ACTIVATE, FEEDBACK and SPINDLE fields only: %s" % sorted({t for _, t in fields}))

# negative cases: a parameter of the model deck added to the calibration
head = [l for l in cal if not l.startswith("PARAM") and not l.startswith("VALUES")]
first = [l for l in cal if l.startswith("PARAM")][:2]
for card, what in (("PARAM     SIGMA     FIELD4    SCALE     SIGMA     0.4       2.0       LOG", "a SCALE factor"),
                   ("PARAM     DISCE     FAMILY    DISCS     E         0.5       2.0       LOG", "the disc family"),
                   ("PARAM     LIGC2     FIELD5    LIGAMENT  ALLC2C1   1.0E7     1.0E8     LOG", "a LIGAMENT field")):
    names, off, unbound = off_controller(head + first + [card])
    check(off == [card[10:20].strip()] and not unbound,
          "negative case, %s: the check names %s as off the controller (found %s%s)" % (what, card[10:20].strip(), off, unbound or ""))
names, off, unbound = off_controller(head + first + [
    "PARAM     SPF       FIELD2    SPINDLE   FLEXL     0.0       5.0",
    "PARAM     SPF       FIELD2    SPINDLE   FLEXR     0.0       5.0"])
check(not off and not unbound, "a controller-only deck of the same form passes the check (%s)" % off)

# the shipped decks of a living subject include the controller after the model deck
living = ["nbdl8g", "nbdl12g", "nbdl15g", "rear8g", "lateral7g", "scene_frontal", "scene_lateral7g",
          "scene_rear16", "scene_rear16_nohr", "scene_rear24", "volunteer_rest", "rear5g_return",
          "lateral7g_return", "calibrate_controller_rest"]
bad = []
for d in living:
    lines = open("input/%s.inp" % d).read().splitlines()
    if MODEL not in lines or CTRL not in lines or lines.index(CTRL) != lines.index(MODEL) + 1:
        bad.append(d)
check(not bad, "the %d decks of a living subject include the controller right after the model deck%s"
      % (len(living), " (not: %s)" % bad if bad else ""))
specimen = ["case6-1", "case6-2", "case6-5", "hybrid3_flexion"]
has = [d for d in specimen if CTRL in open("input/%s.inp" % d).read()]
check(not has, "the specimen and dummy decks run without it (%s)" % has)
PY
finish
