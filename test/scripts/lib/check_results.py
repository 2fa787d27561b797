#!/usr/bin/env python3
"""Opens a result file with h5py and checks the documented layout
(docs/output-format.md): status, time, channels, bodies, coordinates, a
text `units` attribute (read as str) on every dataset of /time, /channels,
/bodies, /coordinates, /model and /injury, the labelled injury criteria,
and schema version 2: an integer schema_version, lists (bodies,
coordinates, channel names and units, columns, Nij modes) as arrays of
UTF-8 strings that h5py reads as str, element names as UTF-8 strings.
    check_results.py FILE"""
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
check(f.attrs["status"] == "complete", "status attribute is the text 'complete' (a str)")
sv = f.attrs.get("schema_version")
check(isinstance(sv, np.integer) and sv.shape == () and sv == 2, "schema_version is the integer 2 (%r)" % (sv,))


def str_list(obj, name):
    """The attribute as a list of str when it is a 1-D array of UTF-8 strings, else None."""
    a = obj.attrs[name]
    t = obj.attrs.get_id(name).get_type()
    if not (isinstance(a, np.ndarray) and a.ndim == 1 and isinstance(t, h5py.h5t.TypeStringID)
            and t.get_cset() == h5py.h5t.CSET_UTF8 and all(isinstance(x, str) for x in a)):
        return None
    return list(a)


nb = f["model/mass"].shape[0]
bodies = str_list(f["model"], "bodies")
check(bodies is not None and len(bodies) == nb and all(bodies), "/model bodies: %d UTF-8 str (%s)"
      % (nb, " ".join(bodies or [])))
coords = str_list(f["model"], "coordinates")
check(coords is not None and len(coords) == f["coordinates/x"].shape[1], "/model coordinates: one str per column")
check(str_list(f["coordinates/x"], "columns") == coords and str_list(f["coordinates/xd"], "columns") == coords
      and set(str_list(f["coordinates/x"], "column_units")) <= {"m", "rad"},
      "/coordinates/x and xd: columns and column_units as str arrays")
names = str_list(f["channels"], "names")
units = str_list(f["channels"], "units")
check(names is not None and sorted(names) == sorted(f["channels"]) and units is not None
      and units == [f["channels"][n].attrs["units"] for n in names],
      "/channels names (%d) are the channels, units theirs, as str arrays" % len(names or []))
lig = f["model/elements/ligaments/name"]
check(h5py.check_string_dtype(lig.dtype) is not None and h5py.check_string_dtype(lig.dtype).encoding == "utf-8"
      and all(n and n == n.strip() for n in lig.asstr()[:]),
      "element names are UTF-8 strings without padding (%d ligaments)" % lig.shape[0])
check(nt > 1 and np.all(np.diff(f["time"][:]) > 0), "time increases (%d samples)" % nt)
check(all(f["channels"][k].shape == (nt,) for k in f["channels"]), "every channel has one value per sample")
check(f["bodies/position"].shape == (nt, nb, 3), "bodies/position (nt, nb, 3) in h5py order")
check(f["bodies/rotation"].shape == (nt, nb, 3, 3), "bodies/rotation (nt, nb, 3, 3) in h5py order")
check(np.all(np.isfinite(f["coordinates/x"][:])), "coordinates finite")
missing = []
def needs_units(name, obj):
    if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiu":
        u = obj.attrs.get("units")
        if not isinstance(u, str) or not u:
            missing.append(name)
for group in ("time", "channels", "bodies", "coordinates", "model", "injury"):
    if isinstance(f[group], h5py.Dataset):
        needs_units(group, f[group])
    else:
        f[group].visititems(lambda n, o, g=group: needs_units(g + "/" + n, o))
check(not missing, "a text 'units' attribute on every numeric dataset (%s)" % (", ".join(missing[:5]) or "none missing"))
inj = f["injury"]
if "note" in inj.attrs:
    check(isinstance(inj.attrs["note"], str), "injury criteria not computed: " + inj.attrs["note"])
else:
    modes = str_list(inj["nij"], "modes")
    check(modes == ["NTE", "NTF", "NCE", "NCF"] and inj["nij/value"].shape == (4,),
          "Nij labelled by mode (a str array): " + ", ".join("%s %.3g" % (m, v) for m, v in zip(modes, inj["nij/value"][:])))
    hic = inj["hic15/value"][()]
    t1, t2 = inj["hic15/t_start"][()], inj["hic15/t_end"][()]
    check(hic >= 0 and 0 <= t2 - t1 <= 0.015 + 1e-9 and inj["hic15/t_start"].attrs["units"] == "s",
          "HIC15 %.3g over a labelled window of %.3g ms" % (hic, 1000 * (t2 - t1)))
lines = [s.decode().rstrip() for s in f["deck/text"][:]]
check(len(lines) > 0 and lines[0].startswith("TITLE"), "the deck is stored as /deck/text (%d cards)" % len(lines))
print("%d passed, 0 failed" % ok)
