#!/usr/bin/env python3
"""Checks a result file left by a run that stopped early: readable, marked
incomplete with a message, samples up to the stop and all finite. Prints
one PASS or FAIL line per check and exits non-zero on any failure.
    check_incomplete.py FILE T_END"""
import sys
import h5py
import numpy as np


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 1
    f = h5py.File(argv[1], "r")
    t_end = float(argv[2])
    status = text(f.attrs["status"])
    msg = text(f.attrs["message"])
    t = f["time"][:]
    failures = 0

    def check(ok, what):
        nonlocal failures
        print(("PASS  " if ok else "FAIL  ") + what)
        failures += 0 if ok else 1

    check(status == "incomplete", "result file marked incomplete (status '%s')" % status)
    check(len(msg) > 0, "result file carries the stop message: %s" % msg)
    check(len(t) > 1 and t[-1] < t_end,
          "samples up to the stop: %d to t = %.4f s (end time %g s)" % (len(t), t[-1] if len(t) else -1, t_end))
    check(bool(np.all(np.diff(t) > 0)), "sample times increase")
    check(all(np.all(np.isfinite(f["channels"][k][:])) for k in f["channels"]), "every channel finite")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
