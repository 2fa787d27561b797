#!/usr/bin/env python3
"""Compare the model's NBDL 15 g run with the seven volunteer runs.

    python3 tools/compare_nbdl.py [RESULT.h5] [--out DIR]

Without RESULT.h5 it runs `fpm run --profile release -- --h5 ... <
input/nbdl15g.inp` first. Volunteer data: reference/nbdl_15g (raw runs,
every 0.5 ms). Every volunteer run and the model are filtered CFC 60 (SAE
J211/1, as the library does). For each channel it reports the model's peak
and time against the mean and SD of the runs' peaks, the fraction of the
window 30-250 ms in which the model lies within mean +- 1 SD, and a
CORA-style rating (method in docs/validation.md). Writes a table on stdout,
DIR/validation_table.md and DIR/validation_nbdl.png (default DIR: docs).
"""
import os
import subprocess
import sys
import tempfile

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

G = 9.80665
WINDOW = (30.0, 250.0)   # ms


def cfc(x, cls, dt):
    """SAE J211/1 Appendix C filter, forward then backward, started from rest."""
    wd = 2 * np.pi * cls * 2.0775
    wa = np.tan(wd * dt / 2)
    den = 1 + np.sqrt(2) * wa + wa ** 2
    a0 = wa ** 2 / den
    a1, a2 = 2 * a0, a0
    b1 = -2 * (wa ** 2 - 1) / den
    b2 = (-1 + np.sqrt(2) * wa - wa ** 2) / den

    def one(u):
        v = np.empty_like(u)
        u1 = u2 = v1 = v2 = u[0]
        for n in range(len(u)):
            v[n] = a0 * u[n] + a1 * u1 + a2 * u2 + b1 * v1 + b2 * v2
            u2, u1, v2, v1 = u1, u[n], v1, v[n]
        return v

    return one(one(np.asarray(x, float))[::-1])[::-1]


def runs(name):
    d = np.genfromtxt(os.path.join("reference", "nbdl_15g", name + ".csv"), delimiter=",", names=True)
    t = d["time_ms"]
    cols = [c for c in d.dtype.names if c.startswith("run_")]
    return t, np.array([d[c] for c in cols]), cols


def volunteer_channels():
    """Each channel as (t_ms, runs[nrun, nt]) filtered CFC 60."""
    out = {}
    t, ax, cols = runs("Head_XAccel")
    dt = (t[1] - t[0]) * 1e-3
    f = lambda a: np.array([cfc(r, 60, dt) for r in a])
    out["head x-acceleration (g)"] = (t, f(ax))
    out["head z-acceleration (g)"] = (t, f(runs("Head_ZAccel")[1]))
    alpha = f(runs("Head_YrotAccel")[1])
    out["head angular acceleration (rad/s2)"] = (t, alpha)
    rot = f(runs("Head_YrotDisp")[1])
    # angular velocity: derivative of the filtered rotation (no drift, unlike
    # integrating the angular acceleration)
    out["head angular velocity (rad/s)"] = (t, np.gradient(np.radians(rot), dt, axis=1))
    out["head rotation (deg)"] = (t, rot)
    hx = f(runs("Head_XDisp")[1]) - f(runs("T1_XDisp")[1])
    hz = f(runs("Head_ZDisp")[1]) - f(runs("T1_ZDisp")[1])
    out["head x-displacement rel. T1 (mm)"] = (t, hx)
    out["head z-displacement rel. T1 (mm)"] = (t, hz)
    return out, cols


MODEL = {
    "head x-acceleration (g)": "HEAD_AX",
    "head z-acceleration (g)": "HEAD_AZ",
    "head angular acceleration (rad/s2)": "HEAD_ALPHY",
    "head angular velocity (rad/s)": "HEAD_OMEGY",
    "head rotation (deg)": "HEAD_THETY",
    "head x-displacement rel. T1 (mm)": "HEAD_DX",
    "head z-displacement rel. T1 (mm)": "HEAD_DZ",
}


def peak(t, x, sign):
    m = (t >= WINDOW[0]) & (t <= WINDOW[1])
    i = np.argmax(sign * x[m])
    return x[m][i], t[m][i]


def cora(t, model, mean, sd):
    """Corridor rating C and cross-correlation rating X (docs/validation.md)."""
    m = (t >= WINDOW[0]) & (t <= WINDOW[1])
    y, r, s = model[m], mean[m], sd[m]
    floor = 0.05 * np.max(np.abs(r))
    inner = np.maximum(s, floor)
    outer = np.maximum(3 * s, 3 * floor)
    d = np.abs(y - r)
    c = np.where(d <= inner, 1.0, np.where(d >= outer, 0.0, ((outer - d) / (outer - inner)) ** 2))
    C = c.mean()
    dt = t[1] - t[0]
    maxlag = int(round(30.0 / dt))
    best, lag = -2, 0
    for k in range(-maxlag, maxlag + 1):
        a = np.roll(y, k)
        lo, hi = max(0, k), len(y) + min(0, k)
        if hi - lo < 10:
            continue
        rho = np.corrcoef(a[lo:hi], r[lo:hi])[0, 1]
        if rho > best:
            best, lag = rho, k
    shift = abs(lag) * dt
    EP = 1.0 if shift <= 2.0 else max(0.0, (30.0 - shift) / (30.0 - 2.0))
    EV = ((1 + best) / 2) ** 2
    a_m, a_r = np.sum(y ** 2), np.sum(r ** 2)
    ES = min(a_m, a_r) / max(a_m, a_r)
    X = (EP + EV + ES) / 3
    return C, X, 0.5 * C + 0.5 * X, lag * dt


def main():
    args = [a for a in sys.argv[1:]]
    outdir = "docs"
    if "--out" in args:
        k = args.index("--out")
        outdir = args[k + 1]
        del args[k:k + 2]
    if args:
        h5 = args[0]
    else:
        h5 = os.path.join(tempfile.mkdtemp(), "nbdl15g.h5")
        with open("input/nbdl15g.inp") as deck:
            subprocess.run(["fpm", "run", "--profile", "release", "--", "--h5", h5], stdin=deck,
                           stdout=subprocess.DEVNULL, check=True)
    f = h5py.File(h5, "r")
    tm = f["time"][:] * 1e3
    dtm = (tm[1] - tm[0]) * 1e-3
    vol, cols = volunteer_channels()
    rows = []
    fig, axes = plt.subplots(2, 4, figsize=(18, 8))
    for ax, (label, (t, data)) in zip(axes.flat, vol.items()):
        model = cfc(f["channels"][MODEL[label]][:], 60, dtm)
        mi = np.interp(t, tm, model)
        mean, sd = data.mean(axis=0), data.std(axis=0, ddof=1)
        m = (t >= WINDOW[0]) & (t <= WINDOW[1])
        sign = 1.0 if np.max(mean[m]) >= -np.min(mean[m]) else -1.0
        pk = np.array([peak(t, r, sign) for r in data])
        mp, mt = peak(t, mi, sign)
        inside = np.mean(np.abs(mi[m] - mean[m]) <= sd[m])
        C, X, score, lag = cora(t, mi, mean, sd)
        rows.append(dict(label=label, mp=mp, mt=mt, pm=pk[:, 0].mean(), ps=pk[:, 0].std(ddof=1),
                         tmn=pk[:, 1].mean(), tsd=pk[:, 1].std(ddof=1),
                         ok_peak=abs(mp - pk[:, 0].mean()) <= pk[:, 0].std(ddof=1),
                         ok_time=abs(mt - pk[:, 1].mean()) <= 10.0, inside=inside, C=C, X=X, score=score, lag=lag))
        for r in data:
            ax.plot(t, r, color="0.6", lw=0.6)
        ax.fill_between(t, mean - sd, mean + sd, color="tab:blue", alpha=0.25, label="volunteer mean ± 1 SD")
        ax.plot(t, mean, color="tab:blue", lw=1.2)
        ax.plot(tm, model, color="tab:red", lw=2.2, label="model")
        ax.set_xlim(0, 300)
        ax.set_title(label, fontsize=10)
        ax.set_xlabel("time (ms)")
        ax.grid(alpha=0.3)
    axes.flat[0].legend(fontsize=8)
    axes.flat[-1].axis("off")
    axes.flat[-1].text(0.0, 0.5, "NBDL 15 g frontal sled\n7 volunteer runs (thin grey),\nmean ± 1 SD (band),\n"
                       "model (thick red);\nall CFC 60", fontsize=11, va="center")
    fig.tight_layout()
    os.makedirs(outdir, exist_ok=True)
    fig.savefig(os.path.join(outdir, "validation_nbdl.png"), dpi=100)
    lines = ["| channel | model peak | at (ms) | volunteers peak (mean ± SD) | at (ms) | peak within 1 SD | time within 10 ms | "
             "time inside mean ± 1 SD | corridor C | cross-corr. X | CORA-style | lag (ms) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %.1f | %.0f | %.1f ± %.1f | %.0f ± %.0f | %s | %s | %.0f %% | %.2f | %.2f | %.2f | %+.0f |" % (
            r["label"], r["mp"], r["mt"], r["pm"], r["ps"], r["tmn"], r["tsd"], "yes" if r["ok_peak"] else "no",
            "yes" if r["ok_time"] else "no", 100 * r["inside"], r["C"], r["X"], r["score"], r["lag"]))
    overall = np.mean([r["score"] for r in rows])
    lines.append("")
    lines.append("Overall CORA-style rating (mean of the channels): **%.2f**; peaks within 1 SD: %d of %d; "
                 "peak times within 10 ms: %d of %d." % (overall, sum(r["ok_peak"] for r in rows), len(rows),
                                                         sum(r["ok_time"] for r in rows), len(rows)))
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(outdir, "validation_table.md"), "w") as out:
        out.write(text + "\n")


if __name__ == "__main__":
    main()
