#!/usr/bin/env python3
"""Copies /time and every channel of a result file into a compact reference
file: /time (nt,), /channels (nt, nch) with attributes `names` and `units`
(space separated), and the code, title and status attributes.
    extract_reference.py IN OUT"""
import sys
import h5py
import numpy as np

src = h5py.File(sys.argv[1], "r")
names = sorted(src["channels"].keys())
data = np.stack([src["channels"][n][:] for n in names], axis=1)
units = [src["channels"][n].attrs["units"] for n in names]
units = [u.decode() if isinstance(u, bytes) else str(u) for u in units]
with h5py.File(sys.argv[2], "w") as dst:
    for k in ("code", "title", "status"):
        dst.attrs[k] = src.attrs[k]
    dst.create_dataset("time", data=src["time"][:])
    d = dst.create_dataset("channels", data=data, compression="gzip", shuffle=True)
    d.attrs["names"] = np.bytes_(" ".join(names))
    d.attrs["units"] = np.bytes_(" ".join(u.replace(" ", "_") for u in units))
