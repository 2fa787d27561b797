#!/usr/bin/env python3
"""Work-precision plot from the CSV of `fpm run --example work_precision`:
error in head rotation against wall time and against dynamics evaluations,
one panel per case, one line per integrator.

    python3 tools/plot_work_precision.py docs/work_precision.csv docs/work_precision.png
"""
import csv
import sys
from collections import defaultdict

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
cases = []
for r in rows:
    if r["case"] not in cases:
        cases.append(r["case"])
style = {"RK4": "o-", "ABM4": "s-", "DOPRI5": "^-", "ADAMS": "v-", "ROS2": "D-", "ROS34PW2": "*-"}
fig, axes = plt.subplots(2, len(cases), figsize=(5 * len(cases), 8), squeeze=False)
for j, case in enumerate(cases):
    lines = defaultdict(list)
    for r in rows:
        if r["case"] == case and r["status"] == "ok" and float(r["err_theta_deg"]) > 0:
            lines[r["method"]].append((float(r["wall_s"]), int(r["evals"]), float(r["err_theta_deg"])))
    for m, pts in lines.items():
        pts.sort()
        axes[0][j].loglog([p[0] for p in pts], [p[2] for p in pts], style.get(m, "x-"), label=m)
        pts.sort(key=lambda p: p[1])
        axes[1][j].loglog([p[1] for p in pts], [p[2] for p in pts], style.get(m, "x-"), label=m)
    for i, xl in enumerate(["wall time (s)", "dynamics evaluations"]):
        ax = axes[i][j]
        ax.axhline(0.1, color="grey", lw=0.8, ls=":")
        ax.set_xlabel(xl)
        ax.set_ylabel("max error in head rotation (deg)")
        ax.set_title(case)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print("wrote", sys.argv[2])
