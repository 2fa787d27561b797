#!/usr/bin/env python3
"""Checks a result file left by a run that stopped early: readable, marked
incomplete with a message, samples up to the stop and all finite.
    check_incomplete.py FILE T_END"""
import sys
import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
t_end = float(sys.argv[2])
status = f.attrs["status"]
status = status.decode() if isinstance(status, bytes) else str(status)
msg = f.attrs["message"]
msg = msg.decode() if isinstance(msg, bytes) else str(msg)
t = f["time"][:]
ok = status == "incomplete" and len(msg) > 0 and len(t) > 1 and t[-1] < t_end and np.all(np.diff(t) > 0)
ok = ok and all(np.all(np.isfinite(f["channels"][k][:])) for k in f["channels"])
print(("PASS  " if ok else "FAIL  ") + "incomplete result file: status %s, %d samples to t = %.4f s, message: %s"
      % (status, len(t), t[-1] if len(t) else -1, msg))
sys.exit(0 if ok else 1)
