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
    rotation_angle(trace) -> angle
        the angle [deg] of a rotation matrix from its trace.
    rotation_from_start(path, body="HEAD") -> (t, angle)
        times [s] and a body's rotation from its start [deg]: the angle of
        S(t) S(0)^T from the file's body rotations.
    schema_version(f) -> int
        a file's schema_version (1 for files written before it existed).
    read_results(path, channels=None) -> Results
        all three at once: .channels, .bodies, .injury (the DataFrames
        above), .title, .schema_version, .path.
    read_sweep(path) -> DataFrame
        a sweep result file (hhneck --sweep, docs/sweeps.md): one row per
        member run, indexed by run number (1-based, index name "run"): the
        parameter values (one column per parameter, its name), the 31
        summary outputs (one column each), then status, message, rank,
        wall [s], evaluations, t_reached [s]. Units of every column in
        df.attrs["units"]; df.attrs["parameters"] and ["outputs"] list the
        column names of each kind, df.attrs["what"] the parameters'
        targets ("BODY HEAD MASS"); also title, design, base,
        schema_version, source.
    read_sensitivity(path) -> DataFrame
        a sweep's sensitivities: one row per parameter, one column per
        output, NaN where none could be computed; df.attrs["method"],
        df.attrs["r2"] (output -> R^2), df.attrs["units"] (all "1").

A sweep file given to read_channels (or a single run's result file given
to read_sweep) raises FileKindError saying which reader it needs.

Command line: hhneck-results RESULT.h5 (python3 -m hhneck.results) prints
the title, bodies, channel count and the injury criteria; given a sweep
file, the design, members and sensitivity table.
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


class FileKindError(ValueError):
    """A file of another kind than the reader reads (a sweep file given to
    read_channels, a run's result file given to read_sweep)."""


def file_kind(f):
    """'sweep' (a sweep result file: /runs and /sensitivity), 'result' (a
    run's result file or a reference file: /time and /channels), or None."""
    if "runs" in f and "params" in f:
        return "sweep"
    if "time" in f and "channels" in f:
        return "result"
    return None


def _expect(f, path, kind):
    """Raise FileKindError unless the open file `f` is of `kind`."""
    found = file_kind(f)
    if found == kind:
        return
    if found == "sweep":
        raise FileKindError("%s is a sweep result file (hhneck --sweep): read it with "
                            "hhneck.results.read_sweep (or read_sensitivity)" % path)
    if found == "result":
        raise FileKindError("%s is a run's result file, not a sweep's: read it with "
                            "hhneck.results.read_channels (or read_results)" % path)
    raise FileKindError("%s is neither a hhneck result file (/time, /channels) nor a sweep file "
                        "(/params, /runs); its top level holds: %s" % (path, ", ".join(sorted(f.keys())) or "nothing"))


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
        _expect(f, path, "result")
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
        _expect(f, path, "result")
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


def rotation_angle(trace):
    """The angle [deg] of a rotation matrix (or of each of an array of them)
    from its trace: cos(angle) = (trace - 1) / 2, clipped against roundoff."""
    return np.degrees(np.arccos(np.clip((np.asarray(trace) - 1.0) / 2.0, -1.0, 1.0)))


def rotation_from_start(path, body="HEAD"):
    """Times [s] and the rotation of `body` from its start [deg]: the angle
    of S(t) S(0)^T, S the body's rotation matrix (/bodies/rotation), from
    the trace: cos(angle) = (tr(S(t) S(0)^T) - 1) / 2."""
    with h5py.File(path, "r") as f:
        _expect(f, path, "result")
        names = text_list(f["model"].attrs["bodies"])
        if body not in names:
            raise KeyError("%s: no body %s (bodies: %s)" % (path, body, " ".join(names)))
        r = f["bodies/rotation"][:, names.index(body)]      # [t, j, i] is S_ij
        t = np.asarray(f["time"][:], dtype=float)
    return t, rotation_angle(np.sum(r * r[0], axis=(1, 2)))      # tr(S(t) S(0)^T)


PEAKS = ("nic", "tension", "compression", "shear", "flexion_moment", "extension_moment")


def read_injury(path):
    """The injury criteria of /injury, one row per criterion."""
    rows = []
    with h5py.File(path, "r") as f:
        _expect(f, path, "result")
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


def _column_units(ds, n, fallback):
    """The units of each of the n columns of a sweep dataset: its
    column_units list, else `fallback` (files written before it existed)."""
    if "column_units" in ds.attrs:
        return text_list(ds.attrs["column_units"])
    return list(fallback) if fallback is not None else [""] * n


def _param_units_from_what(what):
    """Units of a parameter from its target ("FAMILY ...", "BODY HEAD MASS":
    a scale factor; "CONTROL  F1": that field's units) for sweep files
    written without column_units."""
    w = what.split()
    if w and w[0] in ("FAMILY", "BODY"):
        return "1"
    return "units of %s %s" % (w[0], w[-1]) if len(w) >= 2 else ""


def read_sweep(path):
    """The member runs of a sweep result file, one row each, with units
    (module docstring)."""
    with h5py.File(path, "r") as f:
        _expect(f, path, "sweep")
        names = text_list(f["params/name"][()])
        what = text_list(f["params/what"][()])
        outs = text_list(f["runs/output_names"][()])
        inputs = np.asarray(f["runs/inputs"][()], dtype=float).reshape(-1, len(names))
        outputs = np.asarray(f["runs/outputs"][()], dtype=float).reshape(-1, len(outs))
        punits = _column_units(f["runs/inputs"], len(names), [_param_units_from_what(w) for w in what])
        ounits = _column_units(f["runs/outputs"], len(outs),
                               ["1" if u == "-" else u for u in text_list(f["runs/output_units"][()])])
        status = np.asarray(f["runs/status"][()], dtype=int)
        extra = {"status": (status, "1"),
                 "message": (np.array([text(m) for m in f["runs/message"][()]], dtype=object), ""),
                 "rank": (np.asarray(f["runs/rank"][()], dtype=int), "1"),
                 "wall": (np.asarray(f["runs/wall"][()], dtype=float), "s"),
                 "evaluations": (np.asarray(f["runs/evaluations"][()], dtype=int), "1"),
                 "t_reached": (np.asarray(f["runs/t_reached"][()], dtype=float), "s")}
        attrs = {"title": text(f.attrs.get("title", "")), "design": text(f.attrs.get("design", "")),
                 "base": text(f.attrs.get("base", "")), "schema_version": schema_version(f),
                 "source": str(path)}
    clash = [n for n in names if n in outs or n in extra]
    if clash:
        raise ValueError("%s: parameter name(s) %s equal an output or run column's name" % (path, ", ".join(clash)))
    data, units = {}, {}
    for k, n in enumerate(names):
        data[n], units[n] = inputs[:, k], punits[k]
    for k, n in enumerate(outs):
        data[n], units[n] = outputs[:, k], ounits[k]
    for n, (v, u) in extra.items():
        data[n], units[n] = v, u
    df = pd.DataFrame(data, index=pd.Index(np.arange(1, len(status) + 1), name="run"))
    df.attrs.update(attrs, units=units, parameters=names, outputs=outs, what=dict(zip(names, what)))
    return df


def read_sensitivity(path):
    """The sensitivities of a sweep result file: parameters x outputs, NaN
    where none could be computed; attrs method, r2, units."""
    with h5py.File(path, "r") as f:
        _expect(f, path, "sweep")
        names = text_list(f["params/name"][()])
        outs = text_list(f["runs/output_names"][()])
        coef = np.asarray(f["sensitivity/coefficient"][()], dtype=float).reshape(len(outs), len(names))
        valid = np.asarray(f["sensitivity/valid"][()]).reshape(len(outs), len(names)) == 1
        r2 = np.asarray(f["sensitivity/r2"][()], dtype=float)
        method = text(f["sensitivity"].attrs.get("method", ""))
    df = pd.DataFrame(np.where(valid, coef, np.nan).T, index=pd.Index(names, name="parameter"), columns=outs)
    df.attrs.update(method=method, r2=dict(zip(outs, r2.tolist())), units={o: "1" for o in outs})
    return df


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
    p.add_argument("result", help="hhneck HDF5 result file (or a sweep result file)")
    path = p.parse_args(argv).result
    with h5py.File(path, "r") as f:
        kind = file_kind(f)
    if kind == "sweep":
        sw = read_sweep(path)
        print("%s (sweep, %s design, schema version %d)" % (sw.attrs["title"], sw.attrs["design"],
                                                             sw.attrs["schema_version"]))
        print("%d members (%d failed), parameters: %s" % (len(sw), int((sw["status"] != 0).sum()),
                                                          ", ".join(sw.attrs["parameters"])))
        print(read_sensitivity(path).to_string(float_format=lambda x: "%.3f" % x))
        return 0
    res = read_results(path)
    ch = res.channels
    print("%s (schema version %d)" % (res.title, res.schema_version))
    print("%d channels, %d samples from %g s to %g s" % (ch.shape[1], ch.shape[0], ch.index[0], ch.index[-1]))
    print(res.bodies.to_string())
    print(res.injury.attrs.get("note") or res.injury.to_string())
    return 0


if __name__ == "__main__":
    sys.exit(main())
