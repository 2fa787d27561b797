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
        with ISO channel codes (the channels that have one: J211_CHANNELS,
        and the lower neck from a LOADCELL card at the T1 section; default
        all of them that the file has). NAME defaults to DIR's name. The
        channels of the file left out (no defensible code) are listed.
    hhneck-export mme-info DIR
        the test attributes and the channels (code, name, unit, samples) of
        an ISO-MME folder.

As a module: read_mme(DIR) -> MmeTest, write_mme(DIR, test), mme_from_result
(RESULT.h5, ...) -> MmeTest, to_j211(channel, values), write_csv(...),
parse_code(CODE) -> dict of its eight elements, iso_channels(RESULT.h5) ->
(coded, left_out).

Sources. The code structure (16 characters: test object, position, main
location, fine locations 1-3, physical dimension, direction, filter class)
and every element used here (ISO_ELEMENTS) are those of the ISO/TS 13499
channel-code list RED B version 1.6.2 (2020-06-17), as transcribed in the
code list of the pyisomme project (github.com/jonaskeller14/pyisomme,
pyisomme/channel_codes.xml): NECK with fine location 1 UP / LO for the
upper / lower neck load cell, THSP (thoracic spine) with fine location 1
01 for T1, EKIN (kinetic energy, numerical simulation), fine location 3 VH
(50th percentile human male, human models), dimensions AC AV AA AN DS FO
MO EN, filter classes 0 A B. The header fields are those of ISO-MME 1.6
test and channel files (ISO/TS 13499 RED A) as public ISO-MME 1.6 files
spell them ("Data format edition number", "Laboratory test ref. number",
"Name of test object 1", ...; "Channel code", "Reference system",
"Channel frequency class", "First global maximum value", "Data status",
...); a field hhneck has no value for is NOVALUE, as the format allows.
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
    # T1 (the HEADNECK card's lower body), in R: the thoracic spine's first vertebra
    "T1_AX": ("THSP", "01", "00", "AC", "X", +1, None, "channels", "global"),
    "T1_AY": ("THSP", "01", "00", "AC", "Y", -1, None, "channels", "global"),
    "T1_AZ": ("THSP", "01", "00", "AC", "Z", -1, None, "channels", "global"),
    "T1_THETX": ("THSP", "01", "00", "AN", "X", +1, None, "channels", "global"),
    "T1_THETY": ("THSP", "01", "00", "AN", "Y", -1, None, "channels", "global"),
    "T1_THETZ": ("THSP", "01", "00", "AN", "Z", -1, None, "channels", "global"),
    "T1_DX": ("THSP", "01", "00", "DS", "X", +1, None, "channels", "global"),
    "T1_DY": ("THSP", "01", "00", "DS", "Y", -1, None, "channels", "global"),
    "T1_DZ": ("THSP", "01", "00", "DS", "Z", -1, None, "channels", "global"),
    # the model's kinetic energy (a scalar: no direction)
    "E_KINETIC": ("EKIN", "00", "00", "EN", "0", +1, None, "channels", "global"),
    # the filtered histories of /injury/history
    "HEAD_AR_CFC1000": ("HEAD", "00", "00", "AC", "R", +1, 1000, "injury/history/head_ar_cfc1000", "local"),
    "OC_FX_CFC600": ("NECK", "UP", "00", "FO", "X", -1, 600, "injury/history/oc_fx_cfc600", "local"),
    "OC_FZ_CFC600": ("NECK", "UP", "00", "FO", "Z", +1, 600, "injury/history/oc_fz_cfc600", "local"),
    "OC_MY_CFC600": ("NECK", "UP", "00", "MO", "Y", +1, 600, "injury/history/oc_my_cfc600", "local"),
}

# The lower-neck load cell: a LOADCELL card (docs/deck-format.md) whose body
# is the child of the root body (the section between T1 and the vertebra
# above it); its J211 channels NAME_JFX ... NAME_JMZ are already in J211
# signs (the load on the part above the section).
LOWER_NECK = {"JFX": ("FO", "X"), "JFY": ("FO", "Y"), "JFZ": ("FO", "Z"),
              "JMX": ("MO", "X"), "JMY": ("MO", "Y"), "JMZ": ("MO", "Z")}

# The elements of ISO/TS 13499 channel codes used here, with the code
# list's descriptions (RED B 1.6.2; see the module's docstring).
ISO_ELEMENTS = {
    "main location": {"HEAD": "Head", "NECK": "Neck", "THSP": "Thoracic Spine", "EKIN": "Kinetic Energy"},
    "fine location 1": {"00": "Not defined", "UP": "Upper", "LO": "Lower", "01": "1."},
    "fine location 2": {"00": "Not defined"},
    "fine location 3": {"VH": "50th Percentile Human Male", "VF": "5th Percentile Human Female",
                        "VM": "95th Percentile Human Male", "H3": "Hybrid III Mid-Sized Adult Male Dummy"},
    "physical dimension": {"AC": "Acceleration", "AV": "Angular Velocity", "AA": "Angular Acceleration",
                           "AN": "Angle", "DS": "Displacement", "FO": "Force", "MO": "Moment", "EN": "Energy"},
    "direction": {"X": "Longitudinal", "Y": "Lateral", "Z": "Vertical", "R": "Resultant", "0": "Undefined/other"},
    "filter class": {"0": "Unfiltered", "A": "CFC 1000", "B": "CFC 600", "C": "CFC 180", "D": "CFC 60"},
}
CODE_FIELDS = (("test object and position", 0, 2), ("main location", 2, 6), ("fine location 1", 6, 8),
               ("fine location 2", 8, 10), ("fine location 3", 10, 12), ("physical dimension", 12, 14),
               ("direction", 14, 15), ("filter class", 15, 16))


def parse_code(code):
    """The eight elements of a 16-character ISO channel code, {element:
    characters}; ValueError when it is not 16 characters or an element is
    not one of the code list's (ISO_ELEMENTS; the test object and position
    is two digits or capitals)."""
    if len(code) != 16:
        raise ValueError("channel code %r: %d characters, not 16" % (code, len(code)))
    out = {name: code[a:b] for name, a, b in CODE_FIELDS}
    if not re.fullmatch(r"[0-9A-Z]{2}", out["test object and position"]):
        raise ValueError("channel code %r: test object and position %r" % (code, out["test object and position"]))
    for name, value in out.items():
        if name in ISO_ELEMENTS and value not in ISO_ELEMENTS[name]:
            raise ValueError("channel code %r: %s %r is not in the code list's %s"
                             % (code, name, value, ", ".join(ISO_ELEMENTS[name])))
    return out


# Channels of a result file left out of the ISO-MME export, with why (a
# pattern on the name, first match wins; see docs/output-format.md).
LEFT_OUT = (
    (r"HEAD_A[XYZ]$|HEAD_A[XYZ]S$", "the head-axes channel HEAD_A?L carries the head acceleration code"),
    (r"HEAD_D[XYZ]$|HT1_|OCT1_|HEADL_", "a motion relative to T1 or a rotation decomposition: no code"),
    (r".*_(RX|RY|RZ|PX|PY|PZ)$", "a joint's relative rotation: no code for a vertebral joint"),
    (r"E_|W_", "an energy-balance term: no code (the code list's energies are EKIN, EINT, EXWO, ETOT)"),
    (r"L_", "a joint-limit generalized force: no code"),
)


def _left_out_reason(name, elements, cells):
    if name in elements or name.rsplit("_", 1)[0] in elements or name[2:] in elements:
        return "a disc, ligament or muscle load or a muscle's activation: no code for a model element"
    for cell, reason in cells.items():
        if name.startswith(cell + "_"):
            return reason
    for pattern, reason in LEFT_OUT:
        if re.match(pattern, name):
            return reason
    return "no defensible ISO code"


def load_cells(f):
    """{name: body} of the LOADCELL cards of an open result file's deck (/deck/text)."""
    if "deck/text" not in f:
        return {}
    out = {}
    for card in f["deck/text"][()]:
        card = card.decode() if isinstance(card, bytes) else str(card)
        if card.startswith("LOADCELL"):
            out[card[10:20].strip()] = card[20:30].strip()
    return out


def iso_channels(path):
    """(coded, left_out) of a result file: coded {channel: ISO-code tuple as
    in J211_CHANNELS} for every channel the export writes, left_out
    {channel: why} for every channel of /channels without a code."""
    import h5py
    with h5py.File(path, "r") as f:
        names = hhneck_results.text_list(f["channels"].attrs["names"]) if "names" in f["channels"].attrs \
            else sorted(f["channels"].keys())
        bodies = hhneck_results.text_list(f["model"].attrs["bodies"]) if "model" in f else []
        parent = np.asarray(f["model/parent"][:], dtype=int) if "model" in f else np.zeros(0, dtype=int)
        cells = load_cells(f)
        elements = set()
        if "model/elements" in f:
            for g in f["model/elements"].values():
                elements.update(hhneck_results.text(n) for n in g["name"][:])
        history = {c for c, m in J211_CHANNELS.items() if m[7] != "channels" and m[7] in f}
    coded = {c: m for c, m in J211_CHANNELS.items() if (m[7] == "channels" and c in names) or c in history}
    root = [k + 1 for k in range(len(parent)) if parent[k] == 0]
    reasons = {}
    for cell, body in cells.items():
        k = bodies.index(body) + 1 if body in bodies else 0
        if k and parent[k - 1] in root:
            for suffix, (dim, d) in LOWER_NECK.items():
                if cell + "_" + suffix in names:
                    coded[cell + "_" + suffix] = ("NECK", "LO", "00", dim, d, +1, None, "channels", "local")
            reasons[cell] = ("a LOADCELL's loads in its frame body's axes: its J211 channels %s_J* carry the "
                             "lower-neck code" % cell)
        elif body == "HEAD":
            reasons[cell] = "a LOADCELL at the head: the OC_ channels carry the upper-neck code"
        else:
            reasons[cell] = "a LOADCELL at %s: the code list has no neck section between the upper and lower neck" \
                % body
    left = {n: _left_out_reason(n, elements, reasons) for n in names if n not in coded}
    return coded, left


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


def channel_code(channel, position="11", fine3="VH", entry=None):
    """The 16-character ISO code of a project channel (J211_CHANNELS, or
    the table entry given)."""
    loc, f1, f2, dim, d, _, cfc, _, _ = entry or J211_CHANNELS[channel]
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
    left_out: dict = field(default_factory=dict)   # channels of the source without a code, with why

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


def _novalue(v):
    return "NOVALUE" if v is None or v == "" else v


def mme_from_result(path, test_name, channels=None, position="11", fine3="VH"):
    """An MmeTest of the result file's channels in J211 signs. `channels`
    (default: every channel with an ISO code, iso_channels) must have one;
    an unknown one raises KeyError naming the ones that do. The test's
    .left_out lists the file's channels without a code, with why."""
    import h5py
    coded, left = iso_channels(path)
    want = list(coded) if channels is None else list(channels)
    unknown = [c for c in want if c not in coded]
    if unknown:
        absent = [c for c in unknown if c in J211_CHANNELS]
        if absent and len(absent) == len(unknown):
            raise KeyError("%s: no channel %s in the file" % (path, ", ".join(absent)))
        raise KeyError("no ISO-MME code for %s; channels with one: %s"
                       % (", ".join(c for c in unknown if c not in J211_CHANNELS), ", ".join(coded)))
    with h5py.File(path, "r") as f:
        t = np.asarray(f["time"][:], dtype=float)
        dt = _uniform_interval(t, path)
        title = hhneck_results.text(f.attrs.get("title", ""))
        code = hhneck_results.text(f.attrs.get("code", ""))
        mass = float(np.sum(f["model/mass"][:])) if "model/mass" in f else None
        out = []
        for c in want:
            m = coded[c]
            ds = f["channels"][c] if m[7] == "channels" else f[m[7]]
            unit = hhneck_results.text(ds.attrs.get("units", ""))
            values = m[5] * np.asarray(ds[:], dtype=float)
            cfc = m[6]
            iso = channel_code(c, position, fine3, m)
            kmax, kmin = int(np.argmax(values)), int(np.argmin(values))
            header = [
                ("Name of the channel", "%s, SAE J211 sign (%s)" % (c, "as hhneck's" if m[5] > 0 else "hhneck's negated")),
                ("Laboratory channel code", c),
                ("Customer channel code", "NOVALUE"),
                ("Channel code", iso),
                ("Test object number", "1"),
                ("Data source", "calculation"),
                ("Reference channel", "implicit"),
                ("Location", position + m[0] + m[1] + m[2] + fine3),
                ("Direction", {"X": "x-direction", "Y": "y-direction", "Z": "z-direction", "R": "resultant",
                               "0": "NOVALUE"}[m[4]]),
                ("Reference system", m[8]),
                ("Transducer type", "NOVALUE"),
                ("Transducer id", "NOVALUE"),
                ("Pre-filter type", "NOVALUE"),
                ("Cut off frequency", "NOVALUE"),
                ("Channel frequency class", "NOVALUE" if cfc is None else str(cfc)),
                ("Channel amplitude class", "NOVALUE"),
                ("Unit", MME_UNITS.get(unit, unit)),
                ("Dimension", m[3]),
                ("Sampling interval", repr(dt)),
                ("Bit resolution", "NOVALUE"),
                ("Time of first sample", repr(float(t[0]))),
                ("Number of samples", len(values)),
                ("First global maximum value", repr(float(values[kmax]))),
                ("Time of maximum value", repr(float(t[kmax]))),
                ("First global minimum value", repr(float(values[kmin]))),
                ("Time of minimum value", repr(float(t[kmin]))),
                ("Data status", "ok"),
                ("Comments", "simulated by %s; unfiltered" % code if cfc is None
                 else "simulated by %s; filtered CFC %d" % (code, cfc)),
            ]
            out.append(MmeChannel(header, values))
    info = [("Data format edition number", MME_VERSION)]
    info += [(k, "NOVALUE") for k in ("Laboratory name", "Laboratory contact name", "Laboratory contact phone",
                                       "Laboratory contact fax", "Laboratory contact email")]
    info.append(("Laboratory test ref. number", test_name))
    info += [(k, "NOVALUE") for k in ("Customer name", "Customer test ref. number", "Customer project ref. number",
                                       "Customer order number", "Customer cost unit", "Customer test engineer name",
                                       "Customer test engineer phone", "Customer test engineer fax",
                                       "Customer test engineer email")]
    info += [
        ("Title", _novalue(title)),
        ("Medium No./number of media", "1/1"),
        ("Timestamp", "NOVALUE"),
        ("Type of the test", "simulation"),
        ("Subtype of the test", "NOVALUE"),
        ("Regulation", "NOVALUE"),
        ("Reference temperature", "NOVALUE"),
        ("Relative air humidity", "NOVALUE"),
        ("Date of the test", "NOVALUE"),
        ("Number of test objects", "1"),
        ("Name of test object 1", "hhneck head-neck model (%s)" % (code or "hhneck")),
        ("Velocity test object 1", "NOVALUE"),
        ("Mass test object 1", "NOVALUE" if mass is None else "%.6g" % mass),
        ("Driver position object 1", "NOVALUE"),
        ("Impact side test object 1", "NOVALUE"),
        ("Type of test object 1", "human model"),
        ("Class of test object 1", "NOVALUE"),
        ("Code of test object 1", fine3),
        ("Ref. number of test object 1", "NOVALUE"),
        ("Comments", "written by hhneck-export from %s; SAE J211 signs (docs/output-format.md)"
         % os.path.basename(path)),
    ]
    test = MmeTest(test_name, info, out, [("Instrumentation standard", "SAE J211 (simulation)")])
    test.left_out = left
    return test


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
            if chans is None and t.left_out:
                print("left out, %d channels without an ISO code:" % len(t.left_out))
                by_reason = {}
                for n, why in t.left_out.items():
                    by_reason.setdefault(why, []).append(n)
                for why, names in by_reason.items():
                    print("  %s: %s" % (why, " ".join(names)))
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
