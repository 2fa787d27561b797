"""Draw the model's prediction corridor (app/mpi/corridor_mpi.F90) against the
volunteers' corridors.

    hhneck-plot-corridor PREFIX OUT.png

reads PREFIX_nbdl15g.csv and PREFIX_nbdl12g.csv (model mean and SD, volunteer
mean and SD of each rated head channel, CFC 60) and draws one row per
severity; prints the share of 30-250 ms in which the volunteers' mean lies
inside the model's mean +- 1 SD.
"""
import argparse
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

CH = [("HEAD_AX", "head x-acceleration (g)"), ("HEAD_AZ", "head z-acceleration (g)"),
      ("HEAD_ALPHY", "angular acceleration (rad/s²)"), ("HEAD_OMEGY", "angular velocity (rad/s)"),
      ("HEAD_THETY", "rotation (deg)")]


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-plot-corridor", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("prefix", help="the corridor driver's output prefix (PREFIX_nbdl15g.csv, PREFIX_nbdl12g.csv)")
    p.add_argument("png", help="plot to write")
    args = p.parse_args(argv)
    prefix, out = args.prefix, args.png
    fig, axes = plt.subplots(2, 5, figsize=(22, 8))
    for row, sev in enumerate(("15g", "12g")):
        d = np.genfromtxt("%s_nbdl%s.csv" % (prefix, sev), delimiter=",", names=True)
        t = d["time_ms"]
        w = (t >= 30) & (t <= 250)
        for ax, (ch, label) in zip(axes[row], CH):
            mm, ms = d[ch + "_model_mean"], d[ch + "_model_sd"]
            vm, vs = d[ch + "_vol_mean"], d[ch + "_vol_sd"]
            ax.fill_between(t, vm - vs, vm + vs, color="tab:blue", alpha=0.25, label="volunteers mean ± 1 SD")
            ax.plot(t, vm, color="tab:blue", lw=1.2)
            ax.fill_between(t, mm - ms, mm + ms, color="tab:red", alpha=0.3, label="model mean ± 1 SD")
            ax.plot(t, mm, color="tab:red", lw=1.5)
            inside = np.mean(np.abs(vm[w] - mm[w]) <= ms[w])
            print("%s %-10s volunteer mean inside the model band %.1f %% of 30-250 ms" % (sev, ch, 100 * inside))
            ax.set_title("%s %s: %.0f %% inside" % (sev.replace("g", " g"), label, 100 * inside), fontsize=9)
            ax.set_xlim(0, 300)
            ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=80)
    return 0


if __name__ == "__main__":
    sys.exit(main())
