#!/bin/sh
# Every deck the tools write is a deck the program takes: each card
# within 80 columns, comment cards too (a long path in a comment goes on
# continuation comment cards, hhneck.decks), and `hhneck --check`
# passes on it, with the tools' files under a directory path of more than 120
# characters. A data card that a long path would push beyond column 80 (an
# INCLUDE or CASE card naming a file there) is refused with a message naming
# the line. The shipped decks are what their writers write
# (hhneck.validation.model_deck from reference/model_parameters.csv, hhneck.validation.case_decks,
# hhneck.validation.nbdl_tables).
# make_nbdl_tables.py --data with a long data folder: new_nbdl_case.sh.
. test/scripts/lib/checks.sh
root=$(pwd)

# within80 FILE...: no line of the files is longer than 80 characters
within80() {
    over80=$(awk 'length > 80 { print FILENAME ": line " FNR ": " length " columns" }' "$@")
    [ -z "$over80" ] || { echo "$over80" >&2; return 1; }
}

# written FILE SHIPPED: FILE within 80 columns and the same as SHIPPED
written() {
    within80 "$1" && cmp "$1" "$2"
}

# valid DIR DECK: hhneck --check passes on DECK read from standard input in
# the working directory DIR (where its relative INCLUDEs are found); its
# message shown when it does not
valid() {
    (cd "$1" && "$HHNECK" --check < "$2") > "$tmp/check.out" 2>&1 || { cat "$tmp/check.out"; return 1; }
}

# The unit checks of the helper every writer uses.
py_checks - <<'PY'
import sys
sys.path.insert(0, "python")
from hhneck.decks import CardError, check_cards, comment_cards, field_text, set_field

def check(ok, what):
    print(("PASS  " if ok else "FAIL  ") + what)

def joined(cards):
    return "".join(c[2:] for c in cards)

path = "/" + "/".join("level%02d_of_the_folders" % k for k in range(9))
path = (path + "/runs")[:200]
cards = comment_cards(path)
check(len(path) == 200 and len(cards) > 1 and all(len(c) <= 80 and c.startswith("* ") for c in cards)
      and joined(cards) == path,
      "comment_cards: a 200-character path on %d comment cards within 80 columns, joined the path again"
      % len(cards))
check(all(c.endswith("/") for c in cards[:-1]), "comment_cards: the path is broken after a '/'")
flat = "x" * 200
cards = comment_cards(flat)
check([len(c) for c in cards] == [80, 80, 46] and joined(cards) == flat,
      "comment_cards: a text without a blank or '/' broken at column 80 exactly")
text = "the runs in %s (T1 tables by python3 -m hhneck.validation.nbdl_tables --data)." % path
cards = comment_cards(text)
check(all(len(c) <= 80 and not c.endswith(" ") for c in cards) and joined(cards) == text,
      "comment_cards: a sentence around the path, no card ending in a blank, joined the sentence again")
short = "Time in ms (scale 0.001 s)."
check(comment_cards(short) == ["* " + short] and comment_cards("y" * 78) == ["* " + "y" * 78],
      "comment_cards: a text that fits gives the one card '* ' + text")
ok = ["TITLE     A", "*" + "z" * 79]
check(check_cards(ok) is ok, "check_cards: cards of 80 columns pass")
try:
    check_cards(ok + ["INCLUDE   " + "/d" * 40], "deck.inp")
    check(False, "check_cards: a card beyond column 80 refused")
except ValueError as e:
    check(isinstance(e, CardError) and "deck.inp, line 3: the INCLUDE card has 90 columns" in str(e),
          "check_cards: a card of 90 columns refused, naming the deck, the line, the card and its length (%s)"
          % str(e)[:60])
try:
    set_field("SCALE     SIGMA     MUSCLES   F0        1.0", 4, "1.23456e-05")
    check(False, "set_field: a value wider than its field refused")
except CardError as e:
    check("field F4 of SCALE" in str(e) and field_text("1.2345e-05") == "1.2345e-05",
          "set_field: a value of 11 characters refused (it would shift the fields after it); 10 fit")
PY

# a directory path of more than 120 characters
long=$tmp/the_first_directory_level_with_a_long_name/the_second_directory_level_with_a_long_name
long=$long/the_third_level_where_the_tools_write
mkdir -p "$long/proj/input"
check "the long directory path has ${#long} characters (at least 120)" [ ${#long} -ge 120 ]

# The input/ writers run in a project directory under the long path: the
# shipped decks again, each valid with the others it includes.
# (HHNECK_ROOT: that directory is the project the package writes into,
# hhneck.paths)
ln -s "$root/reference" "$long/proj/reference"
ln -s "$root/fpm.toml" "$long/proj/fpm.toml"
cp input/nbdl15g.inp input/nbdl12g.inp input/nbdl8g.inp input/volunteer_controller.inp "$long/proj/input/"
(cd "$long/proj" && export HHNECK_ROOT="$long/proj" &&
     python3 -m hhneck.validation.model_deck --output input/head_neck_54dof.inp &&
     python3 -m hhneck.validation.case_decks && python3 -m hhneck.validation.nbdl_tables)
check "hhneck.validation.model_deck, hhneck.validation.case_decks and hhneck.validation.nbdl_tables run (exit $?)" [ $? -eq 0 ]
for f in head_neck_54dof case6-1 case6-2 case6-5 hybrid3_flexion nbdl15g_t1 nbdl12g_t1 nbdl8g_t1; do
    check "input/$f.inp as written: within 80 columns, the shipped deck" written "$long/proj/input/$f.inp" "input/$f.inp"
done
for f in case6-1 case6-2 case6-5 hybrid3_flexion nbdl15g nbdl12g nbdl8g; do
    check "input/$f.inp with the written decks it includes: hhneck --check passes" valid "$long/proj" "input/$f.inp"
done

# hhneck.validation.model_deck's other postures, and --fit with a listing under the
# long path (the shipped values: the shipped deck)
for opt in "--posture straight" "--posture seated-held" "--t1-slope 20 --lordosis 10"; do
    # shellcheck disable=SC2086
    python3 -m hhneck.validation.model_deck $opt > "$long/proj/input/head_neck_54dof.inp"
    check "hhneck.validation.model_deck $opt: within 80 columns" within80 "$long/proj/input/head_neck_54dof.inp"
    check "hhneck.validation.model_deck $opt: hhneck --check passes on case 6-2 with it" valid "$long/proj" input/case6-2.inp
done
# a calibration listing's PARAM lines, in the order of the calibration's
# PARAM cards, with the values of the shipped model deck
python3 - input/head_neck_54dof.inp input/calibrate_nbdl.inp "$long/fit listing.txt" <<'PY'
import sys
sys.path.insert(0, "python")
from hhneck.decks import field, is_card
deck = open(sys.argv[1]).read().splitlines()
par = {field(l, 1): field(l, 4) for l in deck if is_card(l, "SCALE")}
for hist, s in (("FLEX", "F"), ("EXT", "E")):
    a = [l for l in deck if is_card(l, "ACTIVATE", hist)][0]
    par.update({"BRACE" + s: field(a, 2), "REFLEX" + s: field(a, 3), "DELAY" + s: field(a, 5)})
names = [field(l, 1) for l in open(sys.argv[2]).read().splitlines() if is_card(l, "PARAM")]
open(sys.argv[3], "w").write("".join("PARAM %-10s= %s\n" % (n, par[n]) for n in names))
PY
python3 -m hhneck.validation.model_deck --fit "$long/fit listing.txt" > "$long/proj/input/head_neck_54dof.inp"
check "hhneck.validation.model_deck --fit LISTING (shipped values): the shipped deck" \
    cmp -s "$long/proj/input/head_neck_54dof.inp" input/head_neck_54dof.inp

# The tools that write decks into a temporary directory to run them: valid
# decks in a short directory; in the long one, valid where no card names a
# file there, else refused with the line named (t1_drive_effect.py and
# fit_axial_damping.py then write nothing).
mkdir "$tmp/t1" "$long/t1"
check "t1_drive_effect.py: every variant's deck and T1 tables within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$tmp/t1" "$long/t1" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
from hhneck.decks import CardError
import t1_drive_effect as t
hhneck, short, long = sys.argv[1:4]
bad = []
for sev in ("15g", "12g"):
    for k, (label, held, z) in enumerate(t.VARIANTS + [("z CFC 30", (), 30)]):
        for d in (short, long) if z is None else (short,):
            path = os.path.join(d, "d%s_%d.inp" % (sev, k))
            t.deck_variant(sev, held, z, path)
            files = [path] + ([path + ".t1"] if z is not None else [])
            if any(len(l) > 80 for f in files for l in open(f).read().splitlines()):
                bad.append("%s beyond column 80" % path)
            r = subprocess.run([hhneck, "--check"], stdin=open(path), capture_output=True, text=True)
            if r.returncode:
                bad.append("%s: %s" % (path, r.stderr.strip()))
try:
    t.deck_variant("15g", (), 60, os.path.join(long, "z60.inp"))
    bad.append("a T1 table under the long path named on the INCLUDE card: written")
except CardError as e:
    if "line" not in str(e) or "INCLUDE card" not in str(e) or os.path.exists(os.path.join(long, "z60.inp.t1")):
        bad.append("the long INCLUDE card: %s; files %s" % (e, os.listdir(long)))
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY

check "controller_variants.py: every variant's decks within 80 columns, hhneck --check passes, the edits as named" \
    python3 - "$HHNECK" "$tmp/cv" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
import controller_variants as cv
hhneck, tmp = sys.argv[1:3]
os.makedirs(tmp)
bad = []
shipped = open("input/volunteer_controller.inp").read().splitlines()
for name in cv.VARIANTS:
    d = cv.write_variant(tmp, name)
    ctl = open(os.path.join(d, "input", "volunteer_controller.inp")).read().splitlines()
    nbdl = open(os.path.join(d, "input", "nbdl15g.inp")).read()
    changed = {l[:8] for a, l in zip(shipped, ctl) if a != l and not l.startswith(" ")}
    want = {"shipped": set(), "no head loops": {"FEEDBACK"}, "no stretch loops": {"SPINDLE "},
            "bracing only": {"FEEDBACK", "SPINDLE "}, "loops, no bracing": {"ACTIVATE"}, "no controller": set()}[name]
    if changed != want or ("volunteer_controller.inp" in nbdl) == (name == "no controller"):
        bad.append("%s: cards changed %s, controller included %s" % (name, sorted(changed), "volunteer_controller" in nbdl))
    # the pushed rest decks and the return deck are written alike for every variant: checked once
    more = ["rear5g_return"] + ["volunteer_rest_" + p for p, _, _ in cv.PUSHES] if name == "shipped" else []
    for deck in ["nbdl15g", "volunteer_rest"] + more:
        path = os.path.join(d, "input", deck + ".inp")
        if any(len(l) > 80 for f in (path, os.path.join(d, "input", "volunteer_controller.inp"))
               for l in open(f).read().splitlines()):
            bad.append("%s beyond column 80" % path)
        r = subprocess.run([hhneck, "--check"], stdin=open(path), cwd=d, capture_output=True, text=True)
        if r.returncode:
            bad.append("%s: %s" % (path, r.stderr.strip()))
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY

check "probe_x_trough.py: every probe's deck, model deck and T1 tables within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$tmp/probe" "$long/probe" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
from hhneck.decks import CardError
import probe_x_trough as p
hhneck, short, long = sys.argv[1:4]
os.makedirs(short)
os.makedirs(long)
model = open(p.MODEL).read()
bad = []
for sev in ("15g", "12g"):
    for k, (label, edit_model, edit_deck) in enumerate(p.PROBES):
        deck = p.probe_deck(k, sev, model, edit_model, edit_deck, short)
        if any(len(l) > 80 for l in deck.splitlines()):
            bad.append("probe %d beyond column 80" % k)
        r = subprocess.run([hhneck, "--check"], input=deck, capture_output=True, text=True)
        if r.returncode:
            bad.append("%s %s: %s" % (sev, label, r.stderr.strip()))
for f in os.listdir(short):
    if any(len(l) > 80 for l in open(os.path.join(short, f)).read().splitlines()):
        bad.append("%s beyond column 80" % f)
try:
    p.probe_deck(0, "15g", model, None, None, long)
    bad.append("a model deck under the long path named on the INCLUDE card: passed")
except CardError as e:
    if "line" not in str(e) or "INCLUDE card" not in str(e):
        bad.append("the long INCLUDE card: %s" % e)
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY

check "predict_nbdl8g.py --fit LISTING (under the long path): the 8 g deck and its model deck within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$long/fit listing.txt" "$tmp" "$long" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
from hhneck.decks import CardError
import predict_nbdl8g as p
hhneck, listing, short, long = sys.argv[1:5]
model = open("input/head_neck_54dof.inp").read()
inc = os.path.join(short, "model_2.inp")
deck = p.fit_deck(model, listing, p.bindings(), inc)
bad = [f for f, text in (("deck", deck), ("model", open(inc).read()))
       if any(len(l) > 80 for l in text.splitlines())]
r = subprocess.run([hhneck, "--check"], input=deck, capture_output=True, text=True)
if r.returncode:
    bad.append(r.stderr.strip())
if open(inc).read() != model:
    bad.append("the shipped values did not give the shipped model deck")
try:
    p.fit_deck(model, listing, p.bindings(), os.path.join(long, "model_2.inp"))
    bad.append("a model deck under the long path named on the INCLUDE card: passed")
except CardError as e:
    if "line" not in str(e) or "INCLUDE card" not in str(e):
        bad.append("the long INCLUDE card: %s" % e)
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY

mkdir "$tmp/fits" "$long/fits"
check "fit_axial_damping.py: the calibration decks and their case and model decks within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$tmp/fits" "$long/fits" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
from hhneck.decks import CardError
import fit_axial_damping as f
hhneck, short, long = sys.argv[1:4]
model = open(f.MODEL).read()
runs = f.fit_decks(model, short)
bad = ["%s beyond column 80" % n for n in os.listdir(short)
       if any(len(l) > 80 for l in open(os.path.join(short, n)).read().splitlines())]
checks = [(["--calibrate", "--check"], path + ".inp") for _, path in runs]
checks += [(["--check"], os.path.join(short, "nbdl%s.inp" % s)) for s in ("15g", "12g")]
for opts, path in checks:
    r = subprocess.run([hhneck] + opts, stdin=open(path), capture_output=True, text=True, timeout=120)
    if r.returncode:
        bad.append("%s: %s" % (path, r.stderr.strip()))
if len(runs) != len(f.FITS):
    bad.append("%d calibration decks for %d fits" % (len(runs), len(f.FITS)))
try:
    f.fit_decks(model, long)
    bad.append("case decks under the long path named on CASE cards: written")
except CardError as e:
    if "line" not in str(e) or os.listdir(long):
        bad.append("the long CASE or INCLUDE card: %s; files %s" % (e, os.listdir(long)))
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY

check "cross_severity.py: the scoring decks of a listing under the long path, written there, within 80 columns, hhneck --calibrate --check passes" \
    python3 - "$HHNECK" "$long/fit listing.txt" "$long" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
from hhneck.decks import CardError, write_deck
import cross_severity as c
hhneck, listing, long = sys.argv[1:4]
# the shipped values clipped into the study's PARAM ranges (the calibration
# refuses VALUES outside them; the model deck's VBEND and its histories'
# delays now lie outside this earlier study's ranges)
from hhneck.decks import field, is_card
ranges = {field(l, 1): (float(field(l, 5)), float(field(l, 6)))
          for l in open("input/calibrate_nbdl.inp").read().splitlines() if is_card(l, "PARAM")}
values = ["%.6g" % min(max(float(v), ranges[n][0]), ranges[n][1]) for n, v in c.params(listing)]
bad = []
for sev in ("15g", "12g"):
    path = os.path.join(long, "score%s.inp" % sev)
    write_deck(path, c.score_deck(sev, values))
    if any(len(l) > 80 for l in open(path).read().splitlines()):
        bad.append("%s beyond column 80" % path)
    r = subprocess.run([hhneck, "--calibrate", "--check"], stdin=open(path), capture_output=True, text=True,
                       timeout=120)
    if r.returncode:
        bad.append("%s: %s" % (path, r.stderr.strip()))
try:
    c.score_deck("15g", values[:-1] + ["0.123456789"])
    bad.append("a value of 11 characters on a VALUES card: passed")
except CardError:
    pass
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY
check "feedback_nbdl.py: the decks with the feedback cards, the muscles-only and the loop-free calibration decks within 80 columns, hhneck --check and --calibrate --check pass" \
    python3 - "$HHNECK" <<'PY'
import subprocess, sys
sys.path[:0] = ["python", "studies"]
import feedback_nbdl as f
hhneck = sys.argv[1]
bad = []
decks = [(["--check"], f.variant(sev, f.feedback_cards())) for sev in ("8g", "12g", "15g")]
decks.append((["--calibrate", "--check"], f.muscles_only_deck()))
decks.append((["--calibrate", "--check"], f.without_loops()))
for opts, text in decks:
    if any(len(l) > 80 for l in text.splitlines()):
        bad.append("a card beyond column 80 in: %s" % text.splitlines()[0])
    r = subprocess.run([hhneck] + opts, input=text, capture_output=True, text=True, timeout=120)
    if r.returncode:
        bad.append("%s: %s" % (text.splitlines()[0], r.stderr.strip()))
names = [l[10:20].strip() for l in decks[-2][1].splitlines() if l.startswith("PARAM")]
if any(n in names for n in f.PASSIVE) or "KPE" not in names:
    bad.append("the muscles-only deck's parameters: %s" % names)
control = decks[-1][1].splitlines()
if any(l[10:20].strip() in f.LOOPS for l in control if l.startswith("PARAM")) or \
        any("_feedback" in l for l in control if l.startswith("CASE")):
    bad.append("the control deck keeps a loop: %s" % [l for l in control if l[:5] in ("PARAM", "CASE ")])
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY
check "rest_motion.py: the model copy and the rest decks (no loops, the head loops, the stretch loops) within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$tmp" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
import rest_motion as r
hhneck, short = sys.argv[1:3]
model = os.path.join(short, "model_rest.inp")
r.model_copy(0.35, model)
bad = []
if not any(l.startswith("SCALE     NZBEND") and "0.35" in l for l in open(model).read().splitlines()):
    bad.append("the model copy does not set NZBEND to 0.35")
if r.SPINDLES.count("SPINDLE") != 2:
    bad.append("expected the two SPINDLE cards of input/nbdl12g_spindle.inp: %r" % r.SPINDLES)
for text in (r.REST.format(model=model), r.REST.format(model=model) + r.LOOPS,
             r.REST.format(model=model) + r.SPINDLES):
    if any(len(l) > 80 for l in text.splitlines()):
        bad.append("a card beyond column 80: %s" % text.splitlines()[0])
    p = subprocess.run([hhneck, "--check"], input=text, capture_output=True, text=True, timeout=120)
    if p.returncode:
        bad.append(p.stderr.strip())
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY
check "spindle_segmental.py: the muscles-and-loops calibration deck and the rest deck with the loops within 80 columns, hhneck --check and --calibrate --check pass; a partial fit keeps the starting point's other values" \
    python3 - "$HHNECK" "$tmp" <<'PY'
import os, subprocess, sys
sys.path[:0] = ["python", "studies"]
import spindle_segmental as s
import rest_motion as r
from feedback_nbdl import reduced_deck
hhneck, short = sys.argv[1:3]
bad = []
muscles = reduced_deck(s.CALIBRATION, s.PASSIVE, "NBDL CALIBRATION: 12 G, THE MUSCLES AND THEIR STRETCH LOOPS ONLY")
rest = r.REST.format(model="input/head_neck_54dof.inp") + "\n".join(s.spindle_cards()) + "\n"
for opts, text in ((["--calibrate", "--check"], muscles), (["--check"], rest)):
    if any(len(l) > 80 for l in text.splitlines()):
        bad.append("a card beyond column 80 in: %s" % text.splitlines()[0])
    p = subprocess.run([hhneck] + opts, input=text, capture_output=True, text=True, timeout=120)
    if p.returncode:
        bad.append("%s: %s" % (text.splitlines()[0], p.stderr.strip()))
names = [l[10:20].strip() for l in muscles.splitlines() if l.startswith("PARAM")]
if any(n in names for n in s.PASSIVE) or not all(n in names for n in s.LOOPS):
    bad.append("the muscles-and-loops deck's parameters: %s" % names)
if len(s.spindle_cards()) != 2:
    bad.append("expected the two SPINDLE cards of %s" % s.CASE)
start = os.path.join(short, "start.txt")
open(start, "w").write("PARAM SIGMA = 1.0\nPARAM AXIAL = 1.4\n")
point = dict(s.fitted_values(s.merged(start, [("SIGMA", 0.5)], short)))
if point != {"SIGMA": 0.5, "AXIAL": 1.4}:
    bad.append("merged: %s" % point)
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY
check "spindle_gain.py: its calibration deck, whole and with the muscles alone, within 80 columns and hhneck --calibrate --check passes; the one-point deck scores the VALUES point only (F2 0, the rest of the FIT card kept); the VALUES point is fit B's with g = 0" \
    python3 - "$HHNECK" <<'PY'
import subprocess, sys
sys.path[:0] = ["python", "studies"]
import spindle_gain as g
import spindle_segmental as s
from feedback_nbdl import reduced_deck
hhneck = sys.argv[1]
bad = []
whole = open(g.CALIBRATION).read()
muscles = reduced_deck(g.CALIBRATION, s.PASSIVE, g.MUSCLES_TITLE)
for text in (whole, muscles, g.one_point(whole)):
    if any(len(l) > 80 for l in text.splitlines()):
        bad.append("a card beyond column 80 in: %s" % text.splitlines()[0])
    p = subprocess.run([hhneck, "--calibrate", "--check"], input=text, capture_output=True, text=True, timeout=120)
    if p.returncode:
        bad.append("%s: %s" % (text.splitlines()[0], p.stderr.strip()))
fit = [l for l in g.one_point(whole).splitlines() if l.startswith("FIT")]
if fit != ["FIT       NELDER    0         300       13        5.0       1.0       0.05"]:
    bad.append("one_point's FIT card: %s" % fit)
values = dict(g.deck_values(g.CALIBRATION))
if len(values) != 21 or values["GAINE"] != 0.0 or values["GAINF"] != 0.0 or values["KPSE"] != 5.92:
    bad.append("the VALUES point: %s" % values)
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY
check "neck_inertia.py: the Kang and Stemper decks with its CHANGE cards (the neck's masses and inertias, each coupling) within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$tmp" <<'PY'
import os, sys
sys.path[:0] = ["python", "studies", "test/scripts/lib"]
import neck_inertia as n
from hhneck.validation import specimens
from study_decks import deck_problems
hhneck, short = sys.argv[1:3]
work = os.path.join(short, "neck_inertia")
os.makedirs(work, exist_ok=True)
bad = []
cards = n.mass_changes(0.5) + [c for _, c in n.COUPLINGS]
if len(n.mass_changes(0.5)) != 14:
    bad.append("expected a MASS and an INERTIA card for each of C7 ... C1: %s" % n.mass_changes(0.5))
for deck in (specimens.kang_deck(work, "side"), specimens.kang_deck(work, "front"), specimens.stemper_deck(work)):
    n.with_changes(deck, cards)
    bad += deck_problems(hhneck, open(deck).read(), work, deck)
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY
check "kang_t3_potting.py: the T3-potted Kang decks (T3, T2 below T1; T3 driven and held where T1 was; the cell below T2) within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$tmp" <<'PY'
import os, sys
sys.path[:0] = ["python", "studies", "test/scripts/lib"]
import kang_t3_potting as k
from study_decks import deck_problems
hhneck, short = sys.argv[1:3]
bad = []
for direction, driven in (("side", "TY"), ("front", "TX")):
    work = os.path.join(short, "t3_" + direction)
    deck = k.t3_deck(work, direction)
    model = open(os.path.join(work, "t3_model.inp")).read()
    text = open(deck).read()
    bodies = [(l[10:20].strip(), l[20:30].strip()) for l in model.splitlines() if l.startswith("BODY")]
    if bodies[:4] != [("T3", "R"), ("T2", "T3"), ("T1", "T2"), ("C7", "T1")] or len(bodies) != 11:
        bad.append("%s: bodies %s" % (direction, bodies))
    if model.count("\nNZSPRING  T2") != 3 or model.count("\nNZSPRING  T1") != 3:
        bad.append("%s: three thoracic springs on each of T2 and T1 expected" % direction)
    pres = [l.split()[1:4] for l in text.splitlines() if l.startswith("PRESCRIB")]
    if sorted(p[0] for p in pres) != ["T3"] * 6 or [p[1] for p in pres if p[2] == "ACCEL"] != [driven]:
        bad.append("%s: PRESCRIB cards %s" % (direction, pres))
    if "LOADCELL  T1CELL    T2" not in text or "INCLUDE   t3_model.inp" not in text:
        bad.append("%s: the cell below T2 and the T3 model deck expected" % direction)
    bad += ["t3_model.inp: a card beyond column 80: %r" % l for l in model.splitlines() if len(l) > 80]
    bad += deck_problems(hhneck, text, work, deck)
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY

check "kang_early_coupling.py: its Kang front decks (CHANGE cards; the upper two discs' Ix, Iy and J, and nothing else, scaled in its model copy) within 80 columns, hhneck --check passes" \
    python3 - "$HHNECK" "$tmp" <<'PY'
import os, sys
sys.path[:0] = ["python", "studies", "test/scripts/lib"]
import kang_early_coupling as k
from hhneck.validation import segments
from study_decks import deck_problems
hhneck, short = sys.argv[1:3]
bad = []
shipped = open(os.path.join(segments.ROOT, "input", "head_neck_54dof.inp")).read().splitlines()
for n, (label, cards, upper) in enumerate(k.VARIANTS):
    work = os.path.join(short, "early_%d" % n)
    os.makedirs(work, exist_ok=True)
    text = open(k.front_deck(work, cards, upper)).read()
    if upper != 1.0:
        changed = [(a, b) for a, b in zip(shipped, open(os.path.join(work, "upper_model.inp")).read().splitlines())
                   if a != b]
        if len(changed) != 2:
            bad.append("%s: %d model lines changed, expected the 2 discs' second continuation cards" % (label, len(changed)))
        for a, b in changed:
            fa, fb = [float(a[i:i + 10]) for i in (20, 30, 40)], [float(b[i:i + 10]) for i in (20, 30, 40)]
            if any(abs(y - upper * x) > 1e-3 * abs(upper * x) for x, y in zip(fa, fb)) or a[:20] != b[:20] or a[50:] != b[50:]:
                bad.append("%s: %r -> %r" % (label, a, b))
    bad += deck_problems(hhneck, text, work, label)
sys.exit("\n".join(bad) or None)   # the failures, if any, on stderr
PY

finish
