"""Sensitivity report of a sweep result file: a plot and a Markdown table.

    hhneck-plot-sensitivity SWEEP.h5 OUT.png [--markdown OUT.md]

    hhneck-plot-sensitivity SWEEP.h5 OUT.png --direction lateral

The plot shows how much each parameter moves the outputs of the sweep's
direction of motion (OAT elasticities or standardised regression
coefficients, as the sweep computed them), parameters ranked by their
largest effect:

    sagittal (frontal, rear): THETA_PEAK, ALPHA_PEAK, the upper-neck
        OC_TENSION, OC_SHEAR, OC_FLEX, OC_EXT, and the criteria NIJ, HIC15, NIC
    lateral: HEAD_RX_PEAK, OMEGA_X_PEAK, ALPHA_RES, OC_TENSION, OC_FY_PEAK,
        OC_MX_PEAK, OC_M_RES, and the criteria HIC15, NIC

The direction is the one whose head rotation is larger in the completed
members (median |HEAD_RX_PEAK| against median |HEAD_RY_PEAK|) unless
--direction names it. An output with no sensitivity (roundoff in every
member, or none computed) is left out and named under the plot. The table
gives every output against every parameter.
"""
import argparse
import sys

import h5py
import matplotlib
import numpy as np

from ..results import text, text_list

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SHOWN = {"sagittal": ["THETA_PEAK", "ALPHA_PEAK", "OC_TENSION", "OC_SHEAR", "OC_FLEX", "OC_EXT",
                      "NIJ", "HIC15", "NIC"],
         "lateral": ["HEAD_RX_PEAK", "OMEGA_X_PEAK", "ALPHA_RES", "OC_TENSION", "OC_FY_PEAK", "OC_MX_PEAK",
                     "OC_M_RES", "HIC15", "NIC"]}


def sweep_direction(outs, outputs, status):
    """'lateral' when the median |HEAD_RX_PEAK| of the completed members
    exceeds their median |HEAD_RY_PEAK|, else 'sagittal'. outputs: (nrun,
    nout) in the order of the names `outs`."""
    ok = np.asarray(status) == 0
    if not ok.any() or "HEAD_RX_PEAK" not in outs or "HEAD_RY_PEAK" not in outs:
        return "sagittal"
    rx = np.median(np.abs(outputs[ok, outs.index("HEAD_RX_PEAK")]))
    ry = np.median(np.abs(outputs[ok, outs.index("HEAD_RY_PEAK")]))
    return "lateral" if rx > ry else "sagittal"


def shown_outputs(outs, valid, direction):
    """(shown, left_out): the direction's outputs (SHOWN) that have a
    sensitivity to at least one parameter, and those that have none.
    valid: (nout, np) booleans."""
    shown, left = [], []
    for o in SHOWN[direction]:
        if o not in outs:
            continue
        (shown if valid[outs.index(o)].any() else left).append(o)
    return shown, left


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-plot-sensitivity", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("sweep", help="sweep result file (hhneck --sweep --h5 SWEEP.h5)")
    p.add_argument("png", help="plot to write")
    p.add_argument("--markdown", metavar="MD", help="also write the table of every output against every parameter")
    p.add_argument("--direction", choices=("auto", "sagittal", "lateral"), default="auto",
                   help="the outputs plotted: the sagittal or lateral set (default auto: from the head rotations)")
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
    outputs = np.asarray(f["runs/outputs"][()], dtype=float).reshape(len(status), len(outs))
    design = text(f.attrs["design"])
    title = text(f.attrs["title"])
    f.close()

    direction = sweep_direction(outs, outputs, status) if args.direction == "auto" else args.direction
    shown_names, left_out = shown_outputs(outs, valid, direction)
    if not shown_names:
        print("hhneck-plot-sensitivity: no output of the %s set has a sensitivity (%s): nothing to plot"
              % (direction, ", ".join(left_out)), file=sys.stderr)
        return 1
    shown = [outs.index(o) for o in shown_names]
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
    ax.set_title(f"{title}\n{design}: {len(status)} members, {nfail} failed; {method}; {direction} outputs",
                 fontsize=9)
    if left_out:
        fig.text(0.01, 0.005, "no sensitivity (left out): " + ", ".join(left_out), fontsize=7)
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(axis="x", alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)
    print(f"wrote {args.png} ({direction}: {', '.join(shown_names)})")

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
