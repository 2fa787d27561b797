"""Exports hhneck result channels to CSV and to ISO-MME folders, and reads
ISO-MME folders (docs/output-format.md, "Export").

    hhneck-export csv RESULT.h5 [--channels A,B,...] -o OUT.csv
        time and the channels (default all), one row per sample; the header
        row names each column with its unit: "time [s],HEAD_AX [g],...".
        Values as in the result file (the project's axes).
    hhneck-export mme RESULT.h5 -o DIR [--test NAME] [--channels A,B,...]
                     [--position 11] [--fine3 VH]
        an ISO-MME 1.6 folder DIR: DIR/NAME.mme, DIR/Channel/NAME.chn and
        one DIR/Channel/NAME.001, .002, ... per channel, in SAE J211 signs
        with ISO channel codes (the channels that have one: J211_CHANNELS;
        default all of them that the file has). NAME defaults to DIR's name.
    hhneck-export mme-info DIR
        the test attributes and the channels (code, name, unit, samples) of
        an ISO-MME folder.

As a module: read_mme(DIR) -> MmeTest, write_mme(DIR, test), mme_from_result
(RESULT.h5, ...) -> MmeTest, to_j211(channel, values), write_csv(...).
"""
import argparse
import os
import re
import sys
from dataclasses import dataclass, field

import numpy as np

from . import results as hhneck_results

MME_VERSION = "1.6"
KEY_WIDTH = 28                       # "Name of the channel         :" - ISO-MME header lines

# Filter class letter, position 16 of an ISO channel code (ISO/TS 13499).
FILTER_CLASS = {None: "0", 1000: "A", 600: "B", 180: "C", 60: "D"}
FILTER_CFC = {v: k for k, v in FILTER_CLASS.items()}

# The project's channels that have an ISO code, with the sign that turns the
# project's value into SAE J211's: (main location, fine locations 1 and 2,
# physical dimension, direction, J211 sign, CFC or None, where the series is,
# reference system). Project axes: x forward, y left, z up; J211: x forward,
# y right, z down (a half turn about x): vector components y and z, and
# moments and rotations about y and z, change sign. The OC loads are the
# head's on the neck; J211's upper-neck loads are those on the part above
# the section (the neck's on the head), the opposite: so Fx and Mx change
# sign, Fy, Fz, My, Mz keep it (tension and flexion positive in both).
J211_CHANNELS = {
    "HEAD_AXL": ("HEAD", "00", "00", "AC", "X", +1, None, "channels", "local"),
    "HEAD_AYL": ("HEAD", "00", "00", "AC", "Y", -1, None, "channels", "local"),
    "HEAD_AZL": ("HEAD", "00", "00", "AC", "Z", -1, None, "channels", "local"),
    "HEAD_AR": ("HEAD", "00", "00", "AC", "R", +1, None, "channels", "local"),
    "HEAD_OMEGX": ("HEAD", "00", "00", "AV", "X", +1, None, "channels", "global"),
    "HEAD_OMEGY": ("HEAD", "00", "00", "AV", "Y", -1, None, "channels", "global"),
    "HEAD_OMEGZ": ("HEAD", "00", "00", "AV", "Z", -1, None, "channels", "global"),
    "HEAD_ALPHX": ("HEAD", "00", "00", "AA", "X", +1, None, "channels", "global"),
    "HEAD_ALPHY": ("HEAD", "00", "00", "AA", "Y", -1, None, "channels", "global"),
    "HEAD_ALPHZ": ("HEAD", "00", "00", "AA", "Z", -1, None, "channels", "global"),
    "HEAD_THETY": ("HEAD", "00", "00", "AN", "Y", -1, None, "channels", "global"),
    "OC_FX": ("NECK", "UP", "00", "FO", "X", -1, None, "channels", "local"),
    "OC_FY": ("NECK", "UP", "00", "FO", "Y", +1, None, "channels", "local"),
    "OC_FZ": ("NECK", "UP", "00", "FO", "Z", +1, None, "channels", "local"),
    "OC_MX": ("NECK", "UP", "00", "MO", "X", -1, None, "channels", "local"),
    "OC_MY": ("NECK", "UP", "00", "MO", "Y", +1, None, "channels", "local"),
    "OC_MZ": ("NECK", "UP", "00", "MO", "Z", +1, None, "channels", "local"),
    # the filtered histories of /injury/history
    "HEAD_AR_CFC1000": ("HEAD", "00", "00", "AC", "R", +1, 1000, "injury/history/head_ar_cfc1000", "local"),
    "OC_FX_CFC600": ("NECK", "UP", "00", "FO", "X", -1, 600, "injury/history/oc_fx_cfc600", "local"),
    "OC_FZ_CFC600": ("NECK", "UP", "00", "FO", "Z", +1, 600, "injury/history/oc_fz_cfc600", "local"),
    "OC_MY_CFC600": ("NECK", "UP", "00", "MO", "Y", +1, 600, "injury/history/oc_my_cfc600", "local"),
}

# ISO-MME spellings of the project's units
MME_UNITS = {"N m": "Nm", "rad/s^2": "rad/(s*s)", "m/s^2": "m/(s*s)", "m^2/s^2": "m*m/(s*s)"}


def to_j211(channel, values):
    """The project's values of `channel` in SAE J211 signs (J211_CHANNELS)."""
    return J211_CHANNELS[channel][5] * np.asarray(values, dtype=float)


def kinematic_to_j211(v):
    """A kinematic vector (acceleration, angular velocity, a rotation
    vector) from the project's axes (x forward, y left, z up) to J211's
    (x forward, y right, z down)."""
    x, y, z = np.asarray(v, dtype=float)
    return np.array([x, -y, -z])


def neck_load_to_j211(v):
    """An upper-neck force or moment from the project's convention (the
    head's load on the neck, project axes) to J211's (the load on the part
    above the section, J211 axes)."""
    return -kinematic_to_j211(v)


def channel_code(channel, position="11", fine3="VH"):
    """The 16-character ISO code of a project channel (J211_CHANNELS)."""
    loc, f1, f2, dim, d, _, cfc, _, _ = J211_CHANNELS[channel]
    code = position + loc + f1 + f2 + fine3 + dim + d + FILTER_CLASS[cfc]
    if len(code) != 16:
        raise ValueError("channel code %r of %s is not 16 characters (position %r, fine3 %r)"
                         % (code, channel, position, fine3))
    return code


@dataclass
class MmeChannel:
    """One ISO-MME channel: its header lines (key, value) in order, and its
    samples."""
    header: list
    values: np.ndarray

    def get(self, key, default=None):
        """The first header value of `key` (keys compared without padding)."""
        for k, v in self.header:
            if k == key:
                return v
        return default

    @property
    def code(self):
        return self.get("Channel code")

    @property
    def name(self):
        return self.get("Name of the channel")

    @property
    def unit(self):
        return self.get("Unit")

    @property
    def time(self):
        """Sample times [s] from the time of the first sample and the interval."""
        t0 = float(self.get("Time of first sample"))
        dt = float(self.get("Sampling interval"))
        return t0 + dt * np.arange(len(self.values))


@dataclass
class MmeTest:
    """An ISO-MME test: its name (the file names' stem), the .mme header
    lines, the .chn header lines before the channel list, and the channels."""
    name: str
    info: list
    channels: list = field(default_factory=list)
    chn_info: list = field(default_factory=list)

    def get(self, key, default=None):
        for k, v in self.info:
            if k == key:
                return v
        return default

    def channel(self, code):
        """The channel with this code (KeyError when none)."""
        for c in self.channels:
            if c.code == code:
                return c
        raise KeyError("no channel %s in test %s" % (code, self.name))


def _header_line(key, value):
    return "%-*s:%s" % (KEY_WIDTH, key, value)


def _is_number(s):
    try:
        float(s)
        return True
    except ValueError:
        return False


def _read_lines(path):
    """Lines of a text file: UTF-8, else ISO 8859-1 (older ISO-MME files)."""
    with open(path, "rb") as f:
        raw = f.read()
    try:
        s = raw.decode("utf-8")
    except UnicodeDecodeError:
        s = raw.decode("latin-1")
    return s.splitlines()


def _parse_header(lines, path):
    """(key, value) pairs of 'key : value' lines, and the lines after them
    (the first line that is a number ends the header)."""
    header = []
    for k, line in enumerate(lines):
        s = line.strip()
        if not s:
            continue
        if _is_number(s):
            return header, lines[k:]
        if ":" not in line:
            raise ValueError("%s line %d: neither 'key :value' nor a number: %r" % (path, k + 1, line))
        key, value = line.split(":", 1)
        header.append((key.strip(), value.strip()))
    return header, []


def _find(folder, sub, name, ext):
    """folder/sub/name.ext, the extension in either case."""
    for e in (ext, ext.upper()):
        p = os.path.join(folder, sub, name + "." + e)
        if os.path.isfile(p):
            return p
    raise FileNotFoundError("%s: no %s" % (folder, os.path.join(sub, name + "." + ext)))


def read_mme(folder):
    """Read an ISO-MME folder: FOLDER/NAME.mme, FOLDER/Channel/NAME.chn and
    the channel files it lists (NAME.001, ...)."""
    mmes = sorted(f for f in os.listdir(folder) if f.lower().endswith(".mme"))
    if len(mmes) != 1:
        raise ValueError("%s: expected one .mme file, found %d" % (folder, len(mmes)))
    name = mmes[0][:-4]
    info, _ = _parse_header(_read_lines(os.path.join(folder, mmes[0])), mmes[0])
    chn_path = _find(folder, "Channel", name, "chn")
    chn, _ = _parse_header(_read_lines(chn_path), chn_path)
    test = MmeTest(name, info, [], [(k, v) for k, v in chn if not k.startswith("Name of channel")])
    listed = [(k, v) for k, v in chn if k.startswith("Name of channel")]
    n = int(dict(chn).get("Number of channels", len(listed)))
    if n != len(listed):
        raise ValueError("%s: 'Number of channels' is %d but %d channels are named" % (chn_path, n, len(listed)))
    for k, v in listed:
        number = k.split()[-1]
        path = _find(folder, "Channel", name, number)
        header, rest = _parse_header(_read_lines(path), path)
        values = np.array([float(s) for s in rest if s.strip()], dtype=float)
        ch = MmeChannel(header, values)
        ns = ch.get("Number of samples")
        if ns is not None and int(ns) != len(values):
            raise ValueError("%s: 'Number of samples' is %s but the file has %d values" % (path, ns, len(values)))
        code = v.split("/")[0].strip()
        if ch.code is not None and ch.code != code:
            raise ValueError("%s: channel code %s, but the .chn lists %s" % (path, ch.code, code))
        test.channels.append(ch)
    return test


def write_mme(folder, test):
    """Write `test` as the ISO-MME folder `folder` (made if missing)."""
    os.makedirs(os.path.join(folder, "Channel"), exist_ok=True)
    with open(os.path.join(folder, test.name + ".mme"), "w", encoding="utf-8", newline="\r\n") as f:
        for k, v in test.info:
            f.write(_header_line(k, v) + "\n")
    with open(os.path.join(folder, "Channel", test.name + ".chn"), "w", encoding="utf-8", newline="\r\n") as f:
        chn = [(k, v) for k, v in test.chn_info if k != "Number of channels"]
        for k, v in chn:
            f.write(_header_line(k, v) + "\n")
        f.write(_header_line("Number of channels", len(test.channels)) + "\n")
        for i, c in enumerate(test.channels, 1):
            f.write(_header_line("Name of channel %03d" % i, "%s / %s" % (c.code, c.name)) + "\n")
    for i, c in enumerate(test.channels, 1):
        with open(os.path.join(folder, "Channel", "%s.%03d" % (test.name, i)), "w", encoding="utf-8",
                  newline="\r\n") as f:
            for k, v in c.header:
                if k == "Number of samples":
                    v = len(c.values)
                f.write(_header_line(k, v) + "\n")
            for x in c.values:
                f.write(repr(float(x)) + "\n")       # shortest text that reads back the same double


def _uniform_interval(t, path):
    dt = np.diff(t)
    if len(t) < 2 or np.max(np.abs(dt - dt.mean())) > 1e-9 * max(abs(dt.mean()), 1e-300):
        raise ValueError("%s: the samples are not equally spaced in time (ISO-MME needs a sampling interval)" % path)
    return float(dt.mean())


def mme_from_result(path, test_name, channels=None, position="11", fine3="VH"):
    """An MmeTest of the result file's channels in J211 signs. `channels`
    (default: every channel of J211_CHANNELS the file has) must have an
    ISO code; an unknown one raises KeyError naming the ones that do."""
    import h5py
    with h5py.File(path, "r") as f:
        t = np.asarray(f["time"][:], dtype=float)
        have = [c for c, m in J211_CHANNELS.items()
                if (m[7] == "channels" and isinstance(f.get("channels"), h5py.Group) and c in f["channels"])
                or (m[7] != "channels" and m[7] in f)]
        want = have if channels is None else list(channels)
        unknown = [c for c in want if c not in J211_CHANNELS]
        if unknown:
            raise KeyError("no ISO-MME code for %s; channels with one: %s"
                           % (", ".join(unknown), ", ".join(J211_CHANNELS)))
        absent = [c for c in want if c not in have]
        if absent:
            raise KeyError("%s: no channel %s in the file" % (path, ", ".join(absent)))
        dt = _uniform_interval(t, path)
        title = hhneck_results.text(f.attrs.get("title", ""))
        code = hhneck_results.text(f.attrs.get("code", ""))
        out = []
        for c in want:
            m = J211_CHANNELS[c]
            ds = f["channels"][c] if m[7] == "channels" else f[m[7]]
            unit = hhneck_results.text(ds.attrs.get("units", ""))
            values = to_j211(c, ds[:])
            cfc = m[6]
            header = [
                ("Name of the channel", "%s, SAE J211 sign (%s)" % (c, "as hhneck's" if m[5] > 0 else "hhneck's negated")),
                ("Laboratory channel code", c),
                ("Customer channel code", "NOVALUE"),
                ("Channel code", channel_code(c, position, fine3)),
                ("Location", position + m[0] + m[1] + m[2] + fine3),
                ("Direction", {"X": "x-direction", "Y": "y-direction", "Z": "z-direction", "R": "resultant"}[m[4]]),
                ("Reference system", m[8]),
                ("Data source", "calculation"),
                ("Channel frequency class", "NOVALUE" if cfc is None else str(cfc)),
                ("Unit", MME_UNITS.get(unit, unit)),
                ("Sampling interval", repr(dt)),
                ("Time of first sample", repr(float(t[0]))),
                ("Number of samples", len(values)),
                ("Comments", "simulated by %s; unfiltered" % code if cfc is None
                 else "simulated by %s; filtered CFC %d" % (code, cfc)),
            ]
            out.append(MmeChannel(header, values))
    info = [
        ("Data format", "ISO-MME"),
        ("Version", MME_VERSION),
        ("Laboratory name", "NOVALUE"),
        ("Laboratory test ref. number", test_name),
        ("Title", title),
        ("Type of the test", "simulation"),
        ("Number of test objects", "1"),
        ("Comments", "written by hhneck-export from %s; SAE J211 signs (docs/output-format.md)"
         % os.path.basename(path)),
    ]
    return MmeTest(test_name, info, out, [("Instrumentation standard", "SAE J211 (simulation)")])


def write_csv(path, out, channels=None):
    """Channels of a result file as CSV: the header names each column with
    its unit, "time [s],NAME [unit],..."."""
    df = hhneck_results.read_channels(path, channels)
    units = df.attrs["units"]
    table = df.copy()
    table.columns = ["%s [%s]" % (c, units[c]) for c in df.columns]
    table.index.name = "time [s]"
    table.to_csv(out, float_format="%.12g")
    return df


def main(argv=None):
    """Command line (see the module's documentation)."""
    p = argparse.ArgumentParser(prog="hhneck-export", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    c = sub.add_parser("csv", help="channels as CSV")
    c.add_argument("result")
    c.add_argument("--channels", help="comma-separated channel names (default all)")
    c.add_argument("-o", "--output", required=True)
    m = sub.add_parser("mme", help="an ISO-MME folder in SAE J211 signs")
    m.add_argument("result")
    m.add_argument("-o", "--output", required=True, help="folder to write")
    m.add_argument("--test", help="test name (file names; default the folder's name)")
    m.add_argument("--channels", help="comma-separated channel names (default all with an ISO code)")
    m.add_argument("--position", default="11", help="test object and position, code characters 1-2 (default 11)")
    m.add_argument("--fine3", default="VH",
                   help="fine location 3, code characters 11-12 (default VH, 50th percentile human model)")
    i = sub.add_parser("mme-info", help="what an ISO-MME folder holds")
    i.add_argument("folder")
    a = p.parse_args(argv)
    try:
        if a.command == "csv":
            chans = a.channels.split(",") if a.channels else None
            df = write_csv(a.result, a.output, chans)
            print("%s: %d channels, %d samples" % (a.output, df.shape[1], df.shape[0]))
        elif a.command == "mme":
            name = a.test or os.path.basename(os.path.normpath(a.output))
            if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
                raise ValueError("test name %r: use letters, digits, '_', '-' and '.'" % name)
            chans = a.channels.split(",") if a.channels else None
            t = mme_from_result(a.result, name, chans, a.position, a.fine3)
            write_mme(a.output, t)
            print("%s: ISO-MME %s, %d channels" % (a.output, MME_VERSION, len(t.channels)))
        else:
            t = read_mme(a.folder)
            for k, v in t.info:
                print("%-28s:%s" % (k, v))
            for ch in t.channels:
                print("%s  %-10s %6d samples  %s" % (ch.code, ch.unit, len(ch.values), ch.name))
    except (KeyError, ValueError, OSError) as e:
        print("hhneck-export: %s" % (e.args[0] if isinstance(e, KeyError) else e), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
