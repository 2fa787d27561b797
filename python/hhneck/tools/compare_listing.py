"""Compare a listing with its reference (reference/outputs/CASE.txt).

    hhneck-compare-listing LISTING REFERENCE [--rtol 5e-3]

Line by line, the text with every number taken out must be the same, and
every number must agree with the reference within a tolerance that is set
by the physics of the number, not by its roundoff:

* a channel's value (a column of a time-history table, the maximum or
  minimum of a row of the peaks table) within rtol of the channel's
  largest magnitude in the reference, plus one unit of its last printed
  digit. A channel's scale is at least NOISE_FLOOR of its group's scale
  (the largest channel of the same unit in the peaks table): an
  out-of-plane channel of a sagittal run, zero but for roundoff
  (3.956E-13 N m against a flexion moment of 28.3 N m), is measured
  against its group, not against its own noise;
* a channel's value may also differ by the listing's resolution (RESOLUTION
  of its group's scale, docs/output-format.md): a value at the resolution
  prints as itself on one machine and as 0 on another;
* the time of an extreme (the peaks table, or a number followed by MS)
  within TIME_TOL ms, unless the extreme is noise -- its magnitude at or
  below ROUNDOFF of its group's scale, where its time is where the
  roundoff happened to peak and depends on the machine -- or its value
  agrees with the reference within a tenth of its tolerance (a flat
  extreme, or two near-equal extremes far apart in time: either time is
  the extreme's time to within roundoff);
* any other number within rtol of the largest magnitude on its line plus
  one unit of its last digit.

Lines that depend on the build or the machine are skipped: the page headers
(version, date), the end-of-run statistics (steps, evaluations, wall time)
and the energy-balance residual (its row in the peaks table and its column
of the energy table: a channel at the level of the integration tolerance,
checked by test_stability). Prints one PASS or FAIL line; exit 1 on a
difference.
"""
import argparse
import re
import sys

NUM = re.compile(r"(?<![\w.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[EeDd][-+]?\d+)?(?![\w.])")
SKIP = ("HHNECK ", "END OF RUN", "ENERGY BALANCE", "WALL TIME", "E_BALANCE")
RESIDUALS = ("E_BALANCE",)   # columns at the integration tolerance's level, not compared (test_stability checks them)
N = NUM.pattern
# a row of the peaks table: channel, unit (may hold spaces: "N m"), max, time, min, time
PEAKS_ROW = re.compile(r"^\s+(\S+)\s+(.*?)\s+(%s)\s+(%s)\s+(%s)\s+(%s)\s*$" % (N, N, N, N))
RTOL = 5e-3        # of a channel's (or a line's) largest magnitude
TIME_TOL = 2.0     # ms: a flat extreme may move by a few samples with the roundoff
NOISE_FLOOR = 1e-4  # a channel's scale is at least this fraction of its group's
ROUNDOFF = 1e-8    # an extreme at or below this fraction of its group's scale is noise
RESOLUTION = 1e-6  # the listing prints a value below this fraction of its group's scale as 0 (hn_listing)


def number(tok):
    return float(tok.replace("D", "E").replace("d", "e"))


def ulp(tok):
    """One unit of the last printed digit of a number's text."""
    parts = re.split(r"[EeDd]", tok)
    exp = int(parts[1]) if len(parts) > 1 else 0
    dec = len(parts[0].split(".")[1]) if "." in parts[0] else 0
    return 10.0 ** (exp - dec)


class Layout:
    """What each line of a reference listing holds: the peaks-table rows
    (channel, unit), the time-history rows (the channel of each number),
    and every channel's scale and its group's."""

    def __init__(self, lines):
        self.peaks = {}       # line index -> channel name
        self.columns = {}     # line index -> channel name of each number (None: the time)
        self.unit = {}        # channel -> unit (from the peaks table)
        self.scale = {}       # channel -> largest magnitude in the reference
        in_peaks = False
        names = None
        for i, line in enumerate(lines):
            if "SUMMARY OF PEAKS" in line:
                in_peaks, names = True, None
                continue
            if "INJURY CRITERIA" in line:
                in_peaks = False
            words = line.split()
            if words[:1] == ["TIME"] and i + 1 < len(lines) and lines[i + 1].split()[:1] == ["(MS)"]:
                names = [None] + words[1:]
                continue
            if in_peaks:
                m = PEAKS_ROW.match(line)
                if m and not NUM.fullmatch(m.group(1)):
                    name = m.group(1)
                    self.peaks[i] = name
                    self.unit[name] = m.group(2).strip()
                    self.grow(name, max(abs(number(m.group(3))), abs(number(m.group(5)))))
                continue
            if "TIME HISTORY" in line:
                names = None                  # a new table: its header follows
            toks = NUM.findall(line)
            if names and len(toks) == len(names) and NUM.sub("", line).strip() == "":
                self.columns[i] = names       # a row of the table: the time and one number per channel
                for name, tok in zip(names[1:], toks[1:]):
                    self.grow(name, abs(number(tok)))
        self.group = {}
        for name, u in self.unit.items():
            self.group[u] = max(self.group.get(u, 0.0), self.scale.get(name, 0.0))

    def grow(self, name, v):
        self.scale[name] = max(self.scale.get(name, 0.0), v)

    def group_scale(self, name):
        """The largest channel of the unit of `name` (0 when not in the peaks table)."""
        return self.group.get(self.unit.get(name), 0.0)

    def channel_scale(self, name):
        """The scale a value of channel `name` is measured against."""
        return max(self.scale.get(name, 0.0), NOISE_FLOOR * self.group_scale(name))

    def tolerance(self, name, rtol):
        """What a value of channel `name` may differ by (but for its last printed digit)."""
        return rtol * self.channel_scale(name) + RESOLUTION * self.group_scale(name)

    def is_noise(self, name, v):
        """An extreme of channel `name` at roundoff level against its group."""
        return abs(v) <= ROUNDOFF * self.group_scale(name)


def deviations(a, b, i, layout, rtol):
    """(deviation in units of the tolerance, which number) of each number
    compared on line i (a: the listing's line, b: the reference's)."""
    ta, tb = NUM.findall(a), NUM.findall(b)
    va, vb = [number(t) for t in ta], [number(t) for t in tb]
    out = []
    if i in layout.peaks:
        name = layout.peaks[i]
        for k in (len(tb) - 4, len(tb) - 2):  # max, min (the last four numbers; a unit may hold one: s^2)
            tol = layout.tolerance(name, rtol) + ulp(tb[k])
            out.append((abs(va[k] - vb[k]) / tol, k))
            if layout.is_noise(name, vb[k]) or abs(va[k] - vb[k]) <= 0.1 * tol:
                continue                      # a noise extreme, or a flat one: its time is not compared
            out.append((abs(va[k + 1] - vb[k + 1]) / max(TIME_TOL, ulp(tb[k + 1])), k + 1))
        return out
    if i in layout.columns:
        for k, name in enumerate(layout.columns[i]):
            if name in RESIDUALS:
                continue
            tol = (layout.tolerance(name, rtol) if name else 0.0) + ulp(tb[k])
            out.append((abs(va[k] - vb[k]) / tol, k))
        return out
    scale = max([abs(v) for v in vb] + [0.0])
    times = {k for k, m in enumerate(NUM.finditer(b)) if b[m.end():m.end() + 3] == " MS"}
    for k in range(len(tb)):
        tol = rtol * scale + ulp(tb[k])
        if k in times:
            tol = max(tol, TIME_TOL)
            if k > 0 and abs(va[k - 1] - vb[k - 1]) <= 0.1 * (rtol * scale + ulp(tb[k - 1])):
                continue                      # the extreme's value agrees: either time is its time
        out.append((abs(va[k] - vb[k]) / tol if tol > 0 else 0.0, k))
    return out


def compare(new, ref, rtol=RTOL):
    """(ok, text) for two listings given as lists of lines."""
    if len(new) != len(ref):
        return False, "%d lines, reference %d" % (len(new), len(ref))
    layout = Layout(ref)
    worst, where = 0.0, ""
    for i, (a, b) in enumerate(zip(new, ref)):
        if any(s in b for s in SKIP):
            continue
        if " ".join(NUM.sub("#", a).split()) != " ".join(NUM.sub("#", b).split()):
            return False, "line %d differs in its text:\n  %s\n  %s" % (i + 1, a.strip(), b.strip())
        ta, tb = NUM.findall(a), NUM.findall(b)
        for dev, k in deviations(a, b, i, layout, rtol):
            if dev > worst:
                worst, where = dev, "line %d: %s against %s" % (i + 1, ta[k], tb[k])
    if worst > 1.0:
        return False, "%s (%.1f times the tolerance)" % (where, worst)
    return True, "largest deviation %.2f of the tolerance%s" % (worst, ", " + where if where else "")


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-compare-listing", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("listing", help="the listing to check")
    p.add_argument("reference", help="its reference (reference/outputs/CASE.txt)")
    p.add_argument("--rtol", type=float, default=RTOL, help="relative tolerance (default %g)" % RTOL)
    args = p.parse_args(argv)
    new, ref = (open(f).read().splitlines() for f in (args.listing, args.reference))
    ok, text = compare(new, ref, args.rtol)
    if ok:
        print("PASS  %s matches %s (%s)" % (args.listing, args.reference, text))
        return 0
    print("FAIL  %s: %s" % (args.listing, text))
    return 1


if __name__ == "__main__":
    sys.exit(main())
