#!/usr/bin/env python3
"""The effect of each measured T1 motion on the head: runs the NBDL decks with
T1 driven by x only, x + sagittal rotation, and x + z + rotation (the decks as
shipped), and prints a Markdown table of the overall CORA-style rating and the
head peaks (tools/compare_nbdl.py) for both severities.

    python3 tools/t1_drive_effect.py        (release build; about 30 s)
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_nbdl import compare, s3  # noqa: E402

VARIANTS = [
    ("x only", {"TZ": "PRESCRIB  T1        TZ        CONSTANT", "RY": "PRESCRIB  T1        RY        CONSTANT"}),
    ("x + rotation", {"TZ": "PRESCRIB  T1        TZ        CONSTANT"}),
    ("x + z + rotation (shipped)", {}),
]


def deck_variant(sev, repl, path):
    out = []
    for line in open("input/nbdl%s.inp" % sev):
        key = line[20:22] if line.startswith("PRESCRIB  T1") else None
        out.append((repl[key] + "\n") if key in repl else line)
    open(path, "w").write("".join(out))


def main():
    tmp = tempfile.mkdtemp()
    rows = ["| severity | T1 driven by | rating | x-acc. (g) | z dip (g) | z rebound (g) | ang. acc. (rad/s²) "
            "| ang. vel. (rad/s) | rotation (deg) |", "|---|---|---|---|---|---|---|---|---|"]
    for sev in ("15g", "12g"):
        for label, repl in VARIANTS:
            deck = os.path.join(tmp, "d.inp")
            deck_variant(sev, repl, deck)
            h5 = os.path.join(tmp, "r.h5")
            with open(deck) as f:
                subprocess.run(["fpm", "run", "--profile", "release", "--", "--h5", h5], stdin=f,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            chans, peaks, overall, _, _, _ = compare(sev, h5)
            rows.append("| %s | %s | %.3f | %s |" % (sev.replace("g", " g"), label, overall, " | ".join(
                "%s (%+.2f SD)" % (s3(p["mp"]), p["z"]) for p in peaks)))
        rows.append("| %s | volunteers (mean ± SD) | | %s |" % (sev.replace("g", " g"), " | ".join(
            "%s ± %s" % (s3(p["pm"]), s3(p["ps"])) for p in peaks)))
    print("\n".join(rows))


if __name__ == "__main__":
    main()
