"""Sensitivity report of a sweep result file: a plot and a Markdown table.

    hhneck-plot-sensitivity SWEEP.h5 OUT.png [--markdown OUT.md]

The plot shows, for the head rotation, angular acceleration and upper-neck
loads, how much each parameter moves them (OAT elasticities or standardised
regression coefficients, as the sweep computed them), parameters ranked by
their largest effect. The table gives every output against every parameter.
"""
import argparse
import sys

import h5py
import matplotlib
import numpy as np

from .results import text, text_list

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SHOWN = ["THETA_PEAK", "ALPHA_PEAK", "OC_TENSION", "OC_SHEAR", "OC_FLEX", "OC_EXT", "NIJ", "HIC15"]


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-plot-sensitivity", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("sweep", help="sweep result file (hhneck --sweep --h5 SWEEP.h5)")
    p.add_argument("png", help="plot to write")
    p.add_argument("--markdown", metavar="MD", help="also write the table of every output against every parameter")
    args = p.parse_args(argv)
    f = h5py.File(args.sweep, "r")
    names = text_list(f["params/name"][()])
    what = text_list(f["params/what"][()])
    outs = text_list(f["runs/output_names"][()])
    units = text_list(f["runs/output_units"][()])
    coef = f["sensitivity/coefficient"][()]          # (nout, np)
    valid = f["sensitivity/valid"][()] == 1
    r2 = f["sensitivity/r2"][()]
    method = text(f["sensitivity"].attrs["method"])
    status = f["runs/status"][()]
    design = text(f.attrs["design"])
    title = text(f.attrs["title"])

    shown = [outs.index(o) for o in SHOWN if o in outs]
    c = np.where(valid, coef, np.nan)
    order = np.argsort(-np.nanmax(np.abs(c[shown]), axis=0))
    fig, ax = plt.subplots(figsize=(10, 0.45 * len(names) + 2.5))
    h = 0.8 / len(shown)
    for j, k in enumerate(shown):
        y = np.arange(len(names)) + (j - len(shown) / 2 + 0.5) * h
        ax.barh(y, c[k, order], height=h, label=f"{outs[k]} ({units[k]})")
    ax.set_yticks(np.arange(len(names)))
    ax.set_yticklabels([f"{names[i]}\n{what[i]}" for i in order], fontsize=8)
    ax.invert_yaxis()
    ax.axvline(0, color="k", lw=0.6)
    ax.set_xlabel("elasticity (% output per % parameter)" if design == "OAT"
                  else "standardised regression coefficient")
    nfail = int(np.count_nonzero(status))
    ax.set_title(f"{title}\n{design}: {len(status)} members, {nfail} failed; {method}", fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(axis="x", alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)
    print(f"wrote {args.png}")

    if args.markdown:
        md = args.markdown
        with open(md, "w") as out:
            out.write(f"| parameter | {' | '.join(outs)} |\n|---|{'---|' * len(outs)}\n")
            for p in range(len(names)):
                cells = [f"{coef[k, p]:.3f}" if valid[k, p] else "n/a" for k in range(len(outs))]
                out.write(f"| {names[p]} ({what[p]}) | {' | '.join(cells)} |\n")
            if design != "OAT":
                out.write(f"| R^2 | {' | '.join(f'{x:.3f}' for x in r2)} |\n")
        print(f"wrote {md}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
