"""The specimen sled cases of the catalogue. Now: Stemper et al. 2004, rear
impact at 1.8 m/s (head-neck specimens potted at T1, README of
shared/data/pmhs_neck, "Case 1").

Set-up (decisions of the README's "Ambiguities" named by number):
* the model deck (input/head_neck_54dof.inp) as shipped, T1 the potted
  body: its x-acceleration is the source's pulse (the 1.8 m/s curve, t = 0
  at the pulse start, forward, the corridors' time base), its other five
  coordinates held;
* gravity downward, 9.81 m/s^2 (1: the PMHS were upright in 1 g);
* muscles passive: both activation histories of the model deck set to zero
  (u0 = u1 = 0, by CHANGE cards); the specimens' muscles were left attached
  (README), so their passive Hill-type force-length and damping stay;
* the start posture held as the labs held it until the pulse (positioning
  cables, or the FE set-up's settling, 2): the model has no support element
  yet, so HOLD POSTURE's constant generalized forces stand in for it
  (SUPPORT = "HOLD"); SUPPORT = "NONE" runs without (the muscle-free neck
  then sags under gravity from t = 0);
* the model's posture as shipped (its C7 neutral angle gives the T1 slope;
  the source's 25 deg T1 anterior angle is not imposed).

Channels (their signs as the README derives them): segment angles
C2-C3 ... C6-C7 = -(change of the upper body's RY relative to the lower)
(extension positive), head-T1 angle = -(change of HEAD_THETY - T1_THETY),
retraction = HEAD_DX [mm] (head mass centre relative to T1, R's x, from the
start). Reference: each corridor outline's midline (hhneck.specimen_data),
rated by ISO/TS 18571 over the times the corridor covers (0.3-126 ms), no
offsets.

API: stemper_deck, run_stemper (-> {channel: (t_ms, model)}), rate_stemper.
"""
import os
import subprocess
import tempfile

import numpy as np

from . import iso18571, segments, specimen_data

STEMPER_CHANNELS = ["seg_angle_C%d_C%d" % (k, k + 1) for k in range(2, 7)] + ["head_T1_angle",
                                                                               "head_T1_retraction"]


def stemper_deck(workdir, support="HOLD", muscles="PASSIVE", data_dir=segments.DATA_DIR):
    """Write the Stemper 1.8 m/s deck and its two-column pulse table into
    workdir; returns the deck's path. support: HOLD or NONE; muscles:
    PASSIVE (activation zero) or REFLEX (the model deck's volunteer
    activation histories)."""
    t, a = specimen_data.read_pulse(os.path.join(data_dir, "stemper2004_1p8ms_pulse.csv"))
    pulse = os.path.join(workdir, "stemper_pulse.csv")
    with open(pulse, "w") as f:
        f.write("time_s,a_m_s2\n" + "".join("%.9g,%.9g\n" % p for p in zip(t, a)))
    name = "stemper_%s_%s" % (support.lower(), muscles.lower())
    lines = [
        "TITLE     STEMPER 2004 REAR IMPACT 1.8 M/S, T1 POTTED (%s, MUSCLES %s)" % (support, muscles),
        "*         end (s)   step (s)  print (s) method    rtol      atol",
        "CONTROL   0.13      1.0E-4    0.005     ROS34PW2  1.0E-3    1.0E-5",
        "SOLVER    ABA       STRUCT",
        "OUTPUT    1.0E-4",
        "H5FILE    %s.h5" % name,
    ]
    if support == "HOLD":
        lines.append("HOLD      POSTURE")
    elif support != "NONE":
        raise ValueError("support: HOLD or NONE, not %r" % support)
    lines += ["INCLUDE   input/head_neck_54dof.inp",
              "TABLE     STEMPER   %-10d1.0       1.0       CSV" % len(t),
              "          %s" % os.path.basename(pulse),
              "PRESCRIB  T1        TX        ACCEL     STEMPER   0.0       0.0"]
    lines += ["PRESCRIB  T1        %s        CONSTANT" % c for c in ("TY", "TZ", "RX", "RY", "RZ")]
    if muscles == "PASSIVE":
        for act in ("FLEX", "EXT"):
            for k, field in ((2, "U0"), (3, "U1")):
                lines.append("CHANGE    %-10sFIELD%d    ACTIVATE  %-10sSET       0.0" % (act[:4] + field, k, act))
    elif muscles != "REFLEX":
        raise ValueError("muscles: PASSIVE or REFLEX, not %r" % muscles)
    deck = os.path.join(workdir, name + ".inp")
    with open(deck, "w") as f:
        f.write("\n".join(lines) + "\n")
    return deck


def run_stemper(workdir=None, exe=None, support="HOLD", muscles="PASSIVE"):
    """Run the Stemper deck; {channel: (t [ms], model value)} in the data's signs."""
    import h5py
    work = workdir or tempfile.mkdtemp(prefix="hhneck-stemper-")
    os.makedirs(work, exist_ok=True)
    deck = stemper_deck(work, support, muscles)
    exe = exe or segments.default_executable()
    with open(deck) as fin, open(deck[:-4] + ".txt", "w") as fout:
        r = subprocess.run([exe, "-I", segments.ROOT], stdin=fin, stdout=fout, stderr=subprocess.PIPE,
                           text=True, cwd=work)
    if r.returncode != 0:
        raise RuntimeError("%s: hhneck exit %d: %s" % (deck, r.returncode, r.stderr.strip()[-400:]))
    with h5py.File(deck[:-4] + ".h5", "r") as f:
        t = f["time"][:] * 1e3
        c = {n: np.asarray(f["channels"][n][:], dtype=float) for n in
             ["C%d_RY" % k for k in range(2, 7)] + ["HEAD_THETY", "T1_THETY", "HEAD_DX"]}
    out = {"seg_angle_C%d_C%d" % (k, k + 1): (t, -(c["C%d_RY" % k] - c["C%d_RY" % k][0])) for k in range(2, 7)}
    rel = c["HEAD_THETY"] - c["T1_THETY"]
    out["head_T1_angle"] = (t, -(rel - rel[0]))
    out["head_T1_retraction"] = (t, c["HEAD_DX"])
    return out


def rate_stemper(model, data_dir=segments.DATA_DIR):
    """ISO/TS 18571 of every Stemper channel: {channel: dict(scores...,
    grid, reference, lower, upper, model, peak_model, peak_ref)}."""
    path = os.path.join(data_dir, "stemper2004_1p8ms_experiment.csv")
    out = {}
    for ch in STEMPER_CHANNELS:
        g, ref, lo, hi = specimen_data.reference(path, ch)
        t, m = model[ch]
        mi = np.interp(g, t, m)
        s = iso18571.rate(g * 1e-3, ref, mi)
        km, kr = int(np.argmax(np.abs(mi))), int(np.argmax(np.abs(ref)))
        s.update(grid=g, reference=ref, lower=lo, upper=hi, model=mi, peak_model=(mi[km], g[km]),
                 peak_ref=(ref[kr], g[kr]), inside=float(np.mean((mi >= lo) & (mi <= hi))))
        out[ch] = s
    return out
