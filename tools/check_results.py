#!/usr/bin/env python3
"""Opens a result file with h5py and checks the documented layout
(docs/output-format.md): status, time, channels, bodies, coordinates."""
import sys
import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
ok = 0
def check(cond, what):
    global ok
    print(("PASS  " if cond else "FAIL  ") + what)
    if not cond:
        sys.exit(1)
    ok += 1
nt = f["time"].shape[0]
check(f.attrs["status"] in (b"complete", "complete"), "status attribute is 'complete'")
check(nt > 1 and np.all(np.diff(f["time"][:]) > 0), "time increases (%d samples)" % nt)
check(all(f["channels"][k].shape == (nt,) for k in f["channels"]), "every channel has one value per sample")
nb = f["model/mass"].shape[0]
check(f["bodies/position"].shape == (nt, nb, 3), "bodies/position (nt, nb, 3) in h5py order")
check(f["bodies/rotation"].shape == (nt, nb, 3, 3), "bodies/rotation (nt, nb, 3, 3) in h5py order")
check(np.all(np.isfinite(f["coordinates/x"][:])), "coordinates finite")
print("%d passed, 0 failed" % ok)
