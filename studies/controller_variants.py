#!/usr/bin/env python3
"""What does each part of the volunteer state's controller
(input/volunteer_controller.inp) do on every case it is judged on?

    python3 studies/controller_variants.py [--out FILE]

The controller has three parts: bracing (the ACTIVATE cards' base
activation of the four groups, flexors and extensors of each side), the
muscles' stretch loops (SPINDLE cards) and the head-orientation loops about
the lab's x, y and z axes (FEEDBACK cards). Each variant is the shipped
controller deck edited in a scratch copy of input/ (nothing is refitted):

  shipped              the deck as it is (its values fitted to NBDL 12 g)
  no head loops        FEEDBACK gains (kp, kd; ki on the continuation) zero
  no stretch loops     SPINDLE gains (kp, kd, ki) zero
  bracing only         both zero
  loops, no bracing    the ACTIVATE cards' base activation zero
  no controller        the model deck alone (its held reflex, the specimen
                       state's muscles)

Each is scored on the cases the volunteer state answers to: NBDL 12 g
(calibration) and 15 g (prediction), CORA-style and ISO/TS 18571 as
hhneck-compare-nbdl rates them (hhneck.ratings.compare); 10 s at rest and
pushed (input/volunteer_rest.inp and the three other pushes of
test/scripts/controller.sh), the head's largest rotation from its start;
the rear 5 g and lateral 7 g half-sines (input/rear5g_return.inp,
input/lateral7g_return.inp), the head's peak rotation and its rotation at
600 ms. The head's rotation from its start is the angle of S(t) S(0)^T from
the result file's body rotations. A run that ends early (the head falls
past the model's ranges) is marked with the time it reached.

Release build ($HHNECK, else fpm's release build). Takes about two minutes.
Its answer is written in docs/validation.md ("The controller's parts").
"""
import argparse
import os
import shutil
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from hhneck import ratings, run  # noqa: E402
from hhneck.paths import project_path  # noqa: E402
from hhneck.results import rotation_from_start  # noqa: E402
from hhneck.validation.controller_variants import PUSHES, edited, pushed_rest, without_controller  # noqa: E402

VARIANTS = ("shipped", "no head loops", "no stretch loops", "bracing only", "loops, no bracing", "no controller")


def write_variant(tmp, name):
    """A scratch input/ for variant `name`; its directory."""
    d = os.path.join(tmp, name.replace(" ", "_").replace(",", ""))
    shutil.copytree(project_path("input"), os.path.join(d, "input"))
    os.symlink(project_path("reference"), os.path.join(d, "reference"))
    path = os.path.join(d, "input", "volunteer_controller.inp")
    lines = open(path).read().splitlines()
    flags = {"no head loops": dict(feedback=False), "no stretch loops": dict(spindle=False),
             "bracing only": dict(feedback=False, spindle=False), "loops, no bracing": dict(bracing=False)}
    if name == "no controller":
        for deck in os.listdir(os.path.join(d, "input")):
            p = os.path.join(d, "input", deck)
            if deck.endswith(".inp"):
                text = open(p).read()
                open(p, "w").write(without_controller(text))
    elif name != "shipped":
        open(path, "w").write("\n".join(edited(lines, **flags[name])) + "\n")
    rest = open(os.path.join(d, "input", "volunteer_rest.inp")).read()
    for push, text in pushed_rest(rest).items():
        open(os.path.join(d, "input", "volunteer_rest_%s.inp" % push), "w").write(text)
    return d


def runs(d):
    """The variant's scores: a dict of the table's columns."""
    def go(deck):
        r = run.run_deck(os.path.join("input", deck + ".inp"), h5=os.path.join(d, deck + ".h5"), cwd=d,
                         check=False)
        return r.h5 if r.h5 and os.path.exists(r.h5) else None
    out = {}
    for sev in ("12g", "15g"):
        h5 = go("nbdl" + sev)
        chans, _, overall, _, _, _ = ratings.compare(sev, h5)
        out[sev] = (overall, float(np.mean([c["iso"] for c in chans if c["rated"]])))
    rest = []
    for deck in ["volunteer_rest"] + ["volunteer_rest_" + p for p, _, _ in PUSHES]:
        t, a = rotation_from_start(go(deck))
        rest.append((a.max(), t[-1]))
    out["rest"] = rest
    for deck in ("rear5g_return", "lateral7g_return"):
        t, a = rotation_from_start(go(deck))
        out[deck] = (a.max(), a[-1], t[-1])
    return out


def g3(v):
    """v to three significant digits, trailing zeros kept (0.440, 45.0)."""
    return ("%#.3g" % v).rstrip(".")


def table(results):
    """The Markdown table of every variant's scores."""
    def ended(t, end):
        return "" if t > end - 1e-3 else " (ends at %s s)" % g3(t)
    lines = ["| controller | NBDL 12 g CORA / ISO (calibration) | NBDL 15 g CORA / ISO (prediction) | "
             "largest rotation in 10 s at rest, pushed (5, 5) / (−5, −5) / (10, 0) / (10, 10) deg/s (deg) | "
             "rear 5 g: peak, at 600 ms (deg) | lateral 7 g: peak, at 600 ms (deg) |",
             "|---|---|---|---|---|---|"]
    for name, r in results.items():
        rest = " / ".join("%s%s" % (g3(a), ended(t, 10.0)) for a, t in r["rest"])
        ret = ["%s, %s%s" % (g3(pk), g3(end), ended(t, 0.6)) for pk, end, t in (r["rear5g_return"],
                                                                                r["lateral7g_return"])]
        lines.append("| %s | %.3f / %.3f | %.3f / %.3f | %s | %s | %s |" % (
            name, r["12g"][0], r["12g"][1], r["15g"][0], r["15g"][1], rest, ret[0], ret[1]))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", help="also write the table to this file")
    a = ap.parse_args(argv)
    tmp = tempfile.mkdtemp(prefix="hhneck-controller-variants-")
    results = {}
    for name in VARIANTS:
        results[name] = runs(write_variant(tmp, name))
        print("%s done" % name, file=sys.stderr, flush=True)
    text = table(results)
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text + "\n")
    shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
