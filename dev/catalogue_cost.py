#!/usr/bin/env python3
"""Where the whole catalogue's time goes (docs/performance.md, "The
catalogue's cost"): hhneck-catalogue run once in this process with
counters around its parts, in processor time (user + system) of this
process and of the program runs it waits for:

- the program runs (the hhneck executable's processes, their CPU time);
- importing the ISO/TS 18571 package (objective-rating-metrics with its
  dynamic time warping, dtwalign, which imports numba, scipy.stats,
  seaborn and matplotlib.pyplot);
- the ISO/TS 18571 ratings (hhneck.ratings.rate: the package's four scores),
  how many and the CPU time of each;
- the figures (matplotlib, written with the final report);
- the rest of Python (reading data and result files, filtering, the
  CORA-style ratings, the report).

    python3 dev/catalogue_cost.py [--exe HHNECK] [--quick]

Release build ($HHNECK, else fpm's release build); one job at a time
(--jobs 1), so that the parts add up in one process."""
import argparse
import os
import resource
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from hhneck import ratings  # noqa: E402
from hhneck.validation import catalogue, segments  # noqa: E402


def cpu_self():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


class Timer:
    """Adds the CPU time of this process spent in the wrapped function and
    counts the calls that returned something (a figure's path, a rating)."""
    def __init__(self, f):
        self.f, self.cpu, self.calls = f, 0.0, 0

    def __call__(self, *args, **kwargs):
        c0 = cpu_self()
        result = None
        try:
            result = self.f(*args, **kwargs)
            return result
        finally:
            self.cpu += cpu_self() - c0
            self.calls += result is not None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", help="the hhneck executable (default $HHNECK, else fpm's release build)")
    ap.add_argument("--quick", action="store_true", help="the catalogue's quick form")
    a = ap.parse_args(argv)
    exe = a.exe or segments.default_executable()
    c0 = cpu_self()
    importing = Timer(ratings._package_class)
    importing.f()                       # the first call imports the package
    importing.cpu = cpu_self() - c0
    rate = ratings.rate = Timer(ratings.rate)
    figure = catalogue.figure = Timer(catalogue.figure)
    case_figure = catalogue._case_figure = Timer(catalogue._case_figure)
    work = tempfile.mkdtemp(prefix="hhneck-catalogue-cost-")
    s0, k0, w0 = cpu_self(), cpu_children(), time.perf_counter()
    args = ["--exe", exe, "--jobs", "1", "--out", work, "--report", os.path.join(work, "catalogue.md")]
    rc = catalogue.main(args + (["--quick"] if a.quick else []))
    s1, k1, w1 = cpu_self(), cpu_children(), time.perf_counter()
    py = s1 - s0
    figs = figure.cpu + case_figure.cpu
    rows = [("program runs (hhneck processes)", k1 - k0, ""),
            ("importing the ISO/TS 18571 package", importing.cpu, "once"),
            ("ISO/TS 18571 ratings", rate.cpu, "%d ratings, %.3f s each" % (rate.calls, rate.cpu / max(rate.calls, 1))),
            ("figures", figs, "%d written" % (figure.calls + case_figure.calls)),
            ("the rest of Python", py - rate.cpu - figs, "")]
    total = importing.cpu + py + (k1 - k0)
    print("| part | CPU (s) | share | |\n|---|---|---|---|")
    for name, t, note in rows:
        print("| %s | %.2f | %.0f %% | %s |" % (name, t, 100 * t / total, note))
    print("| **whole catalogue** | **%.2f** | 100 %% | wall %.1f s, one job; exit %d |" % (total, w1 - w0, rc))
    return rc


if __name__ == "__main__":
    sys.exit(main())
