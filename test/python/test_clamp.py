"""The CLAMP support and the RATE drive against closed forms: a body
clamped to R under gravity carries its weight in the clamp (reaction = m g,
deflection = m g / kt, rotation = m g a / kr for a clamp a from the mass
centre) and a load cell on the body reads none of it; a rate table
integrates to the angle of its closed form; the model's head clamped to a
rig turning at constant angular velocity about the vertical: the rig's
angle is omega t and the clamp's couple balances the neck's own moment on
the head (a load cell cutting the head off C1)."""
import os
import subprocess

import h5py
import numpy as np
import pytest

from conftest import hhneck_executable
from hhneck.validation import segments

G, MASS, KT, KR, ARM = 9.80665, 2.0, 1.0e5, 1.0e3, 0.1


def run(tmp_path, name, lines):
    """Run a deck (its lines) in tmp_path: the open result file's channels
    {name: values} and the times, the bodies' rotation matrices and names."""
    deck = tmp_path / (name + ".inp")
    deck.write_text("\n".join(lines + ["H5FILE    %s.h5" % name]) + "\n")
    res = subprocess.run([hhneck_executable(), "-I", segments.ROOT], stdin=open(deck), capture_output=True, text=True,
                         cwd=tmp_path)
    assert res.returncode == 0, res.stderr[-800:]
    with h5py.File(tmp_path / (name + ".h5"), "r") as f:
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["model"].attrs["bodies"]]
        return ({k: f["channels"][k][:] for k in f["channels"]}, f["time"][:],
                np.swapaxes(f["bodies/rotation"][:], 2, 3), names)


BOX = ["TITLE     ONE BODY",
       "CONTROL   %-10s1.0E-4    0.01      ROS34PW2  1.0E-8    1.0E-11",
       "OUTPUT    1.0E-3",
       "BODY      BOX       R         %-10.1f0.01      0.01      0.01" % MASS]


def test_clamp_under_gravity(tmp_path):
    deck = [BOX[0], BOX[1] % "0.5"] + BOX[2:] + [
        "GRAVITY   0.0       0.0       %.5f" % -G,
        "*         name      body      rig       kt        ct        kr        cr",
        "CLAMP     HOLD      BOX       R         %-10.1f900.0     %-10.1f8.0" % (KT, KR),
        "          %-10.2f0.0       0.0" % ARM,
        "LOADCELL  BC        BOX"]
    ch, t, _, _ = run(tmp_path, "clamp_gravity", deck)
    assert ch["HOLD_FZ"][-1] == pytest.approx(MASS * G, rel=1e-6)       # the reaction carries the weight
    assert ch["HOLD_D"][-1] == pytest.approx(1e3 * MASS * G / KT, rel=1e-4)    # [mm]
    assert ch["HOLD_R"][-1] == pytest.approx(np.degrees(MASS * G * ARM / KR), rel=1e-4)
    assert ch["HOLD_MY"][-1] == pytest.approx(MASS * G * ARM, rel=1e-4)
    assert abs(ch["HOLD_FX"][-1]) < 1e-6 * MASS * G and abs(ch["HOLD_A"][-1]) == 0.0
    # the load cell on the clamped body reads no clamp: at rest, nothing else holds it
    for c in ("BC_FX", "BC_FY", "BC_FZ"):
        assert abs(ch[c][-1]) < 1e-4 * MASS * G
    assert abs(ch["BC_MY"][-1]) < 1e-4 * MASS * G * ARM


def rate_angle(t):
    """[deg] The integral of the rate table W: 0 to 30 deg/s over 0.1 s,
    held to 0.3 s, back to 0 at 0.4 s."""
    t = np.asarray(t)
    return np.select([t <= 0.1, t <= 0.3, t <= 0.4],
                     [150 * t ** 2, 1.5 + 30 * (t - 0.1), 7.5 + 30 * (t - 0.3) - 150 * (t - 0.3) ** 2], 9.0)


def test_rate_drive(tmp_path):
    deck = [BOX[0], BOX[1] % "0.5"] + BOX[2:] + [
        "GRAVITY   0.0       0.0       0.0",
        "TABLE     W         4         1.0       1.0",
        "          0.0       0.0       0.1       30.0      0.3       30.0",
        "          0.4       0.0",
        "PRESCRIB  BOX       RZ        RATE      W",
        "PRESCRIB  BOX       RX        CONSTANT",
        "PRESCRIB  BOX       RY        CONSTANT"]
    _, t, s, names = run(tmp_path, "rate_drive", deck)
    box = s[:, names.index("BOX")]
    angle = np.degrees(np.unwrap(np.arctan2(box[:, 1, 0], box[:, 0, 0])))
    assert np.max(np.abs(angle - rate_angle(t))) < 1e-9
    assert angle[-1] == pytest.approx(9.0, abs=1e-9)       # the table's area: 1.5 + 6 + 1.5 deg


OMEGA, DEG = 20.0, 0.01745329    # the table's rate [deg/s] and its value scale (deg to rad, 7 digits)


def test_clamped_head_twist(tmp_path):
    """T1 held, the head clamped at its mass centre to a rig that turns at
    OMEGA about R's z; muscles off, no gravity: the head follows the rig and
    the neck twists."""
    deck = ["TITLE     HEAD CLAMPED TO A TWIST RIG",
            "CONTROL   0.4       1.0E-4    0.01      ROS34PW2  1.0E-5    1.0E-8",
            "SOLVER    ABA       STRUCT",
            "OUTPUT    1.0E-3",
            "GRAVITY   0.0       0.0       0.0",
            "INCLUDE   input/head_neck_54dof.inp",
            "FAMILY    MUSCLES   OFF",
            "TABLE     TWIST     2         1.0       %.8f" % DEG,
            "          0.0       %-10.1f1.0       %-10.1f" % (OMEGA, OMEGA),
            "CLAMP     RIG       HEAD      R         1.0E6     2000.0    1.0E4     20.0",
            "          0.0       0.0       0.0       TWIST     0.0       0.0       1.0",
            "LOADCELL  HC        HEAD      0.0       0.0       0.0       HEAD"]
    deck += ["PRESCRIB  T1        %s        CONSTANT" % c for c in ("TX", "TY", "TZ", "RX", "RY", "RZ")]
    ch, t, s, names = run(tmp_path, "twist", deck)
    rate = np.degrees(OMEGA * DEG)                                    # [deg/s] the table's, as the deck gives it
    assert np.max(np.abs(ch["RIG_A"] - rate * t)) < 1e-9                  # the rig's angle, omega t
    head = s[:, names.index("HEAD")]
    # the head turns with the rig (about R's z, from its start)
    q = np.einsum("tij,kj->tik", head, head[0])                 # S(t) S(0)^T: the turn since the start, in R
    turn = np.degrees(np.unwrap(np.arctan2(q[:, 1, 0], q[:, 0, 0])))
    assert turn[-1] == pytest.approx(rate * t[-1], abs=0.05)
    # the clamp's couple (on the head, in R) balances the neck's moment on the head about its mass centre
    clamp = np.stack([ch["RIG_MX"], ch["RIG_MY"], ch["RIG_MZ"]], axis=1)
    neck = np.einsum("tij,tj->ti", head, np.stack([ch["HC_MX"], ch["HC_MY"], ch["HC_MZ"]], axis=1))
    assert clamp[-1, 2] > 0.02                                 # the neck resists: the rig turns the head against it
    # after the start (the head taking up the rig's rate) the head's inertia is
    # negligible: the balance holds to 0.1 % of the twisting couple at every sample
    late = t >= 0.05
    assert np.all(np.abs(clamp[late, 2] + neck[late, 2]) < 1e-3 * np.abs(clamp[late, 2]))
