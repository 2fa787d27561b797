#!/usr/bin/env python3
"""Copies /time and every channel of a result file into a compact reference
file: /time (nt,), /channels (nt, nch) with attributes `names` and `units`
(arrays of nch UTF-8 strings, channels in name order), and the code, title
and status attributes, and schema_version 2 (docs/output-format.md). Files
before schema version 2 had `names` and `units` as one space-separated
text each (units with '_' for blanks); hhneck.results reads both
(test/scripts/regression.sh).
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
    dst.attrs["schema_version"] = np.int32(2)
    d.attrs["names"] = np.array(names, dtype=h5py.string_dtype("utf-8"))
    d.attrs["units"] = np.array(units, dtype=h5py.string_dtype("utf-8"))
