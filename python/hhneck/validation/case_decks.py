"""Writes the pulse-driven case decks of input/:
  case6-1.inp, case6-2.inp, case6-5.inp  forehead pendulum impacts on the seated
      cadaver, force pulses RECONSTRUCTED (the paper's records are not public);
  hybrid3_flexion.inp  the Hybrid III neck pendulum flexion input (49 CFR
      572.33) applied to the human model.
See reference/cases.md.   python3 -m hhneck.validation.case_decks (writes into the project, hhneck.paths)
"""
import argparse
import math
import sys

from ..decks import CardError, card, held, number_text, write_decks
from ..paths import project_path

def table(name, pts, tscale="0.001", vscale="1.0"):
    out = [card("TABLE", name, "%d" % len(pts), tscale, vscale, strip=False)]
    for i in range(0, len(pts), 3):
        out.append(card("", *[number_text(round(x, d)) for (t, v) in pts[i:i + 3] for x, d in ((t, 4), (v, 3))]))
    return out

def halfsine(t0, dur, peak, dt=0.5):
    n = int(round(dur / dt))
    return [(0.0, 0.0)] + [(t0 + k * dt, peak * math.sin(math.pi * k / n)) for k in range(n + 1)] + [(200.0, 0.0)]

def triangle(t0, rise, fall, peak):
    return [(0.0, 0.0), (t0, 0.0), (t0 + rise, peak), (t0 + rise + fall, 0.0), (200.0, 0.0)]

CASES = {
    "6-1": ("half-sine, peak 1.0 kN, 16 ms (soft padded impactor face)", halfsine(5.0, 16.0, 1000.0)),
    "6-2": ("half-sine, peak 1.6 kN, 10 ms (medium padding)", halfsine(5.0, 10.0, 1600.0)),
    "6-5": ("triangle, peak 2.5 kN, rise 2 ms, fall 4 ms (stiff face)", triangle(5.0, 2.0, 4.0, 2500.0)),
}


def case_decks():
    """{path: card images} of the decks this module writes."""
    decks = {}   # path: card images, written together at the end
    for case, (pulse, pts) in CASES.items():
        L = [
            "* SEATED CADAVER, FRONTAL PENDULUM IMPACT TO THE FOREHEAD, CASE %s" % case,
            "* RECONSTRUCTED INPUT: the force records of the cadaver tests used in the",
            "* 1978 paper are not public. This pulse is a reconstruction of the kind of",
            "* forehead impact the paper describes (reference/cases.md):",
            "*   %s" % pulse,
            "* T1 (torso) is held fixed; the force acts on the forehead, horizontally",
            "* rearward in R, from t = 5 ms. Written by hhneck.validation.case_decks.",
            card("TITLE", "CASE %s FOREHEAD PENDULUM IMPACT (RECONSTRUCTED FORCE PULSE)" % case),
            "*         end (s)   step (s)  print (s) method    rtol      atol",
            "CONTROL   0.1       5.0E-5    0.001     ROS34PW2  1.0E-4    1.0E-7",
            "OUTPUT    1.0E-4",
            card("H5FILE", "case%s.h5" % case),
            "HOLD      POSTURE",
            "INCLUDE   input/head_neck_54dof.inp",
        ]
        L += [held("T1", q) for q in ("TX", "TY", "TZ", "RX", "RY", "RZ")]
        L += ["* impact force [N] against time [ms]"] + table("IMPACT", pts)
        L += [
            "*         body      frame     table     direction x, y, z",
            "FORCE     HEAD      R         IMPACT    -1.0      0.0       0.0",
            "*         point of application, head frame from its mass centre (m)",
            "          0.095     0.0       0.030",
        ]
        decks["input/case%s.inp" % case] = L

    # ---------------------------------------------------------------- Hybrid III
    G = 9.80665
    V0 = 23.0 * 0.3048                      # impact speed 23.0 ft/s (572.33)
    pend = [(0.0, 0.0), (2.0, 25.0), (10.0, 25.0), (20.0, 20.1), (30.0, 15.5)]   # mid-corridor, g
    dv = sum(0.5 * (a0 + a1) * G * (t1 - t0) * 1e-3 for (t0, a0), (t1, a1) in zip(pend, pend[1:]))
    tail = 2 * (V0 - dv) / (15.5 * G) * 1e3  # linear fall to 0 so that the speed change is V0
    pend += [(30.0 + tail, 0.0), (300.0, 0.0)]
    L = [
        "* HYBRID III 50TH NECK PENDULUM TEST, FLEXION (49 CFR 572.33), AS A FURTHER",
        "* CHECK OF THE HUMAN HEAD/NECK MODEL: the dummy's pendulum input applied to",
        "* the human model of this code (not a model of the dummy's rubber neck).",
        "* The neck base (T1) moves with the pendulum: impact speed 23.0 ft/s",
        "* (%.3f m/s) and the mid-corridor deceleration of 572.33: 25 g at 10 ms," % V0,
        "* 20.1 g at 20 ms, 15.5 g at 30 ms, then a linear fall to 0 at %.1f ms so" % (30 + tail),
        "* that the speed change equals the impact speed (reference/cases.md).",
        "* In the test the head hangs below the pendulum: gravity points away from",
        "* the torso, so the GRAVITY card reverses it in the model's upright frame.",
        "* Corridors (reference-data.md): head rotation 64-78 deg at 57-64 ms; OC",
        "* moment 65-80 lbf ft (88-108 N m) at 47-58 ms, back to 0 at 97-107 ms.",
        "* Written by hhneck.validation.case_decks.",
        "TITLE     HYBRID III NECK PENDULUM FLEXION INPUT (49 CFR 572.33), HUMAN MODEL",
        "*         end (s)   step (s)  print (s) method    rtol      atol",
        "CONTROL   0.15      5.0E-5    0.002     ROS34PW2  1.0E-4    1.0E-7",
        "OUTPUT    1.0E-4",
        "H5FILE    hybrid3_flexion.h5",
        "GRAVITY   0.0       0.0       9.80665",
        "HOLD      POSTURE",
        "INCLUDE   input/head_neck_54dof.inp",
        "*         body      coord     kind      table     x0 (m)    v0 (m/s)",
        card("PRESCRIB", "T1", "TX", "ACCEL", "PENDULUM", "0.0", "%.4f" % V0),
    ]
    L += [held("T1", q) for q in ("TY", "TZ", "RX", "RY", "RZ")]
    L += ["* pendulum acceleration [g] against time [ms] (a deceleration: negative)"]
    L += table("PENDULUM", [(t, a) for (t, a) in pend], vscale="-9.80665")
    decks["input/hybrid3_flexion.inp"] = L
    return decks


def main(argv=None):
    argparse.ArgumentParser(prog="python3 -m hhneck.validation.case_decks",
                            description=__doc__.split("   python3 -m")[0].strip(),
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args(argv)
    try:
        # the project's input/ (hhneck.paths), whatever the working directory;
        # none written if a card passes column 80
        write_decks({project_path(k): v for k, v in case_decks().items()})
    except CardError as e:
        sys.exit("python3 -m hhneck.validation.case_decks: %s" % e)
    return 0


if __name__ == "__main__":
    sys.exit(main())
