"""Work-precision plot from the CSV of `fpm run --example work_precision`:
error in head rotation against wall time and against dynamics evaluations,
one panel per case, one line per integrator.

    hhneck-plot-work-precision docs/work_precision.csv docs/work_precision.png
"""
import argparse
import csv
import sys
from collections import defaultdict

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"RK4": "o-", "ABM4": "s-", "DOPRI5": "^-", "ADAMS": "v-", "ROS2": "D-", "ROS34PW2": "*-"}


def read_rows(path):
    """The CSV's rows as dicts, and the cases in their order of appearance."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    cases = []
    for r in rows:
        if r["case"] not in cases:
            cases.append(r["case"])
    return rows, cases


def curves(rows, case):
    """{method: [(wall_s, evals, err_theta_deg)]} of the successful runs of a case with a positive error."""
    lines = defaultdict(list)
    for r in rows:
        if r["case"] == case and r["status"] == "ok" and float(r["err_theta_deg"]) > 0:
            lines[r["method"]].append((float(r["wall_s"]), int(r["evals"]), float(r["err_theta_deg"])))
    return lines


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-plot-work-precision", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("csv", help="the CSV written by `fpm run --example work_precision`")
    p.add_argument("png", help="plot to write")
    args = p.parse_args(argv)
    rows, cases = read_rows(args.csv)
    if not cases:
        p.error("%s has no rows" % args.csv)
    fig, axes = plt.subplots(2, len(cases), figsize=(5 * len(cases), 8), squeeze=False)
    for j, case in enumerate(cases):
        for m, pts in curves(rows, case).items():
            pts.sort()
            axes[0][j].loglog([q[0] for q in pts], [q[2] for q in pts], STYLE.get(m, "x-"), label=m)
            pts.sort(key=lambda q: q[1])
            axes[1][j].loglog([q[1] for q in pts], [q[2] for q in pts], STYLE.get(m, "x-"), label=m)
        for i, xl in enumerate(["wall time (s)", "dynamics evaluations"]):
            ax = axes[i][j]
            ax.axhline(0.1, color="grey", lw=0.8, ls=":")
            ax.set_xlabel(xl)
            ax.set_ylabel("max error in head rotation (deg)")
            ax.set_title(case)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)
    print("wrote", args.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
