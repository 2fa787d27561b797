"""Reads hhneck result files (docs/output-format.md) into pandas.

    read_channels(path, channels=None) -> DataFrame
        one column per channel (in the file's order, or the order asked),
        indexed by time in seconds (index name "time"); the units of each
        column in df.attrs["units"] (a dict), and df.attrs["title"],
        df.attrs["schema_version"], df.attrs["source"]. Reads result files
        (/channels/NAME datasets) of every schema version and the compact
        reference files of dev/extract_reference.py (/channels as one
        (nt, nch) dataset).
    read_bodies(path) -> DataFrame
        one row per body, in tree order, indexed by body name: number
        (1-based), parent (name, "R" for the inertial frame), parent_number
        (0 = R), mass [kg], Ixx Iyy Izz Ixy Ixz Iyz [kg m^2].
    read_injury(path) -> DataFrame
        one row per criterion (HIC15, HIC36, NIJ_NTE ... NIJ_NCF, NIC,
        TENSION, COMPRESSION, SHEAR, FLEXION_MOMENT, EXTENSION_MOMENT) with
        columns value, units, time, t_start, t_end [s] (NaN where a
        criterion has no such time); empty, with df.attrs["note"] saying
        why, when the run computed none.
    schema_version(f) -> int
        a file's schema_version (1 for files written before it existed).
    read_results(path, channels=None) -> Results
        all three at once: .channels, .bodies, .injury (the DataFrames
        above), .title, .schema_version, .path.

Command line: hhneck-results RESULT.h5 (python3 -m hhneck.results) prints
the title, bodies, channel count and the injury criteria.
"""
import argparse
import sys
from dataclasses import dataclass

import h5py
import numpy as np
import pandas as pd


def text(v):
    """An h5py string (bytes or str, possibly blank-padded) as str."""
    if isinstance(v, bytes):
        v = v.decode("utf-8")
    return str(v).strip()


def text_list(v):
    """A list attribute as a list of str: an array of strings (schema 2) or
    one blank-separated text (earlier files)."""
    if isinstance(v, (str, bytes)):
        return text(v).split()
    return [text(x) for x in np.ravel(v)]


def schema_version(f):
    """The schema_version attribute of an open file (1 when absent)."""
    v = f.attrs.get("schema_version")
    return 1 if v is None else int(np.ravel(v)[0])


def _channel_order(g):
    """Channel names of a /channels group: its `names` attribute, else its
    datasets in name order."""
    if "names" in g.attrs:
        return text_list(g.attrs["names"])
    return sorted(g.keys())


def read_channels(path, channels=None):
    """Channels of a result (or reference) file as a DataFrame indexed by
    time [s]; units in df.attrs["units"]. `channels`: names to read, in
    that order (default all); an unknown name raises KeyError naming it."""
    with h5py.File(path, "r") as f:
        time = np.asarray(f["time"][:], dtype=float)
        c = f["channels"]
        if isinstance(c, h5py.Dataset):            # a reference file: (nt, nch)
            names = text_list(c.attrs["names"])
            units_all = [u.replace("_", " ") if schema_version(f) < 2 else u
                         for u in text_list(c.attrs["units"])]
            data_all = np.asarray(c[:], dtype=float)
            column = {n: data_all[:, k] for k, n in enumerate(names)}
            unit = dict(zip(names, units_all))
        else:
            names = _channel_order(c)
            column, unit = {}, {}
        want = names if channels is None else list(channels)
        missing = [n for n in want if n not in names and not (isinstance(c, h5py.Group) and n in c)]
        if missing:
            raise KeyError("%s: no channel %s (the file has %d channels)" % (path, ", ".join(missing), len(names)))
        data = {}
        for n in want:
            if isinstance(c, h5py.Dataset):
                data[n] = column[n]
            else:
                data[n] = np.asarray(c[n][:], dtype=float)
                unit[n] = text(c[n].attrs.get("units", ""))
        df = pd.DataFrame(data, index=pd.Index(time, name="time"), columns=want)
        df.attrs["units"] = {n: unit[n] for n in want}
        df.attrs["title"] = text(f.attrs.get("title", ""))
        df.attrs["schema_version"] = schema_version(f)
        df.attrs["source"] = str(path)
    return df


def read_bodies(path):
    """The model's bodies: number, parent, mass and centroidal inertia."""
    with h5py.File(path, "r") as f:
        m = f["model"]
        names = text_list(m.attrs["bodies"])
        parent = np.asarray(m["parent"][:], dtype=int)
        mass = np.asarray(m["mass"][:], dtype=float)
        inertia = np.asarray(m["inertia"][:], dtype=float)      # (nb, 3, 3), symmetric
    df = pd.DataFrame({
        "number": np.arange(1, len(names) + 1),
        "parent": ["R" if p == 0 else names[p - 1] for p in parent],
        "parent_number": parent,
        "mass": mass,
        "Ixx": inertia[:, 0, 0], "Iyy": inertia[:, 1, 1], "Izz": inertia[:, 2, 2],
        "Ixy": inertia[:, 0, 1], "Ixz": inertia[:, 0, 2], "Iyz": inertia[:, 1, 2],
    }, index=pd.Index(names, name="body"))
    df.attrs["units"] = {"mass": "kg", "Ixx": "kg m^2", "Iyy": "kg m^2", "Izz": "kg m^2",
                         "Ixy": "kg m^2", "Ixz": "kg m^2", "Iyz": "kg m^2"}
    return df


PEAKS = ("nic", "tension", "compression", "shear", "flexion_moment", "extension_moment")


def read_injury(path):
    """The injury criteria of /injury, one row per criterion."""
    rows = []
    with h5py.File(path, "r") as f:
        inj = f["injury"]
        if "note" in inj.attrs:
            df = pd.DataFrame(columns=["value", "units", "time", "t_start", "t_end"])
            df.attrs["note"] = text(inj.attrs["note"])
            return df

        def scalar(ds):
            return float(np.ravel(ds[()])[0])

        for hic in ("hic15", "hic36"):
            g = inj[hic]
            rows.append((hic.upper(), scalar(g["value"]), text(g["value"].attrs["units"]), np.nan,
                         scalar(g["t_start"]), scalar(g["t_end"])))
        g = inj["nij"]
        for k, mode in enumerate(text_list(g.attrs["modes"])):
            rows.append(("NIJ_" + mode, float(g["value"][k]), text(g["value"].attrs["units"]),
                         float(g["time"][k]), np.nan, np.nan))
        for p in PEAKS:
            g = inj[p]
            rows.append((p.upper(), scalar(g["value"]), text(g["value"].attrs["units"]), scalar(g["time"]),
                         np.nan, np.nan))
    df = pd.DataFrame(rows, columns=["criterion", "value", "units", "time", "t_start", "t_end"])
    return df.set_index("criterion")


@dataclass
class Results:
    """A result file read whole: channels (read_channels), bodies
    (read_bodies), injury (read_injury), title, schema_version, path."""
    channels: pd.DataFrame
    bodies: pd.DataFrame
    injury: pd.DataFrame
    title: str
    schema_version: int
    path: str


def read_results(path, channels=None):
    """The channels (all, or those named), bodies and injury criteria of a
    result file, with units (read_channels, read_bodies, read_injury)."""
    ch = read_channels(path, channels)
    return Results(ch, read_bodies(path), read_injury(path), ch.attrs["title"], ch.attrs["schema_version"],
                   str(path))


def main(argv=None):
    """Print a summary of a result file."""
    p = argparse.ArgumentParser(prog="hhneck-results",
                                description="Summary of a hhneck result file: title, bodies, channels, injury criteria.")
    p.add_argument("result", help="hhneck HDF5 result file")
    res = read_results(p.parse_args(argv).result)
    ch = res.channels
    print("%s (schema version %d)" % (res.title, res.schema_version))
    print("%d channels, %d samples from %g s to %g s" % (ch.shape[1], ch.shape[0], ch.index[0], ch.index[-1]))
    print(res.bodies.to_string())
    print(res.injury.attrs.get("note") or res.injury.to_string())
    return 0


if __name__ == "__main__":
    sys.exit(main())
