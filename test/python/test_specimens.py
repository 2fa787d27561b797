"""The Stemper 2004 specimen set-up of the catalogue (python/hhneck/specimens.py):
its deck takes the source's pulse and passive muscles, the T1 drive gives
the pulse's velocity change, and the rated channels agree with a second
computation from the result file's body positions and the joints' angles."""
import os

import h5py
import numpy as np
import pytest

from conftest import hhneck_executable
from hhneck import segments, specimen_data, specimens


@pytest.fixture(scope="module")
def stemper(tmp_path_factory):
    work = tmp_path_factory.mktemp("stemper")
    model = specimens.run_stemper(str(work), hhneck_executable())
    return work, model


def test_deck_cards(tmp_path):
    deck = specimens.stemper_deck(str(tmp_path))
    text = open(deck).read()
    assert "HOLD      POSTURE" in text and "PRESCRIB  T1        TX        ACCEL     STEMPER" in text
    for card in ("CHANGE    FLEXU0    FIELD2    ACTIVATE  FLEX      SET       0.0",
                 "CHANGE    EXTU1     FIELD3    ACTIVATE  EXT       SET       0.0"):
        assert card in text
    rows = open(tmp_path / "stemper_pulse.csv").read().splitlines()
    assert len(rows) == 1 + 113 and "TABLE     STEMPER   113" in text
    assert "HOLD" not in open(specimens.stemper_deck(str(tmp_path), support="NONE")).read()
    with pytest.raises(ValueError):
        specimens.stemper_deck(str(tmp_path), support="CABLES")


def test_t1_moves_by_the_pulse(stemper):
    """T1's forward speed at 120 ms is the pulse's velocity change (1.831 m/s
    by the trapezoid of the source's points)."""
    work, _ = stemper
    with h5py.File(work / "stemper_hold_passive.h5", "r") as f:
        t = f["time"][:]
        x = f["bodies/position"][:, 0, 0]
    v = np.gradient(x, t)
    tp, a = specimen_data.read_pulse(os.path.join(segments.DATA_DIR, "stemper2004_1p8ms_pulse.csv"))
    assert np.interp(0.12, t, v) == pytest.approx(specimen_data.delta_v(tp, a, 0.12), rel=2e-3)


def test_channels_against_body_positions_and_joint_angles(stemper):
    work, model = stemper
    with h5py.File(work / "stemper_hold_passive.h5", "r") as f:
        t = f["time"][:] * 1e3
        pos = f["bodies/position"][:]
        ry = {b: f["channels"]["%s_RY" % b][:] for b in ("C7", "C6", "C5", "C4", "C3", "C2", "C1", "HEAD")}
        ry_any = {b: (f["channels"]["%s_RX" % b][:], f["channels"]["%s_RZ" % b][:]) for b in ry}
    # retraction: head mass centre x minus T1's, from the start, in mm
    hand = 1e3 * ((pos[:, 8, 0] - pos[:, 0, 0]) - (pos[0, 8, 0] - pos[0, 0, 0]))
    tm, retr = model["head_T1_retraction"]
    assert np.allclose(retr, hand, atol=0.01)
    # the motion stays in the sagittal plane (x and z rotations zero), so the
    # head's angle relative to T1 is the sum of the joints' y rotations
    assert max(np.max(np.abs(v)) for pair in ry_any.values() for v in pair) < 1e-6
    total = sum(v - v[0] for v in ry.values())
    tm, ang = model["head_T1_angle"]
    assert np.allclose(ang, -total, atol=1e-6)
    tm, c45 = model["seg_angle_C4_C5"]
    assert np.allclose(c45, -(ry["C4"] - ry["C4"][0]))
    assert np.max(ang) > 20.0                        # the head extends: a rear impact


def test_rating_uses_the_corridor_midline(stemper):
    _, model = stemper
    rated = specimens.rate_stemper(model)
    assert sorted(rated) == sorted(specimens.STEMPER_CHANNELS)
    for ch, s in rated.items():
        assert 0.0 <= s["overall"] <= 1.0
        assert np.allclose(s["reference"], 0.5 * (s["lower"] + s["upper"]))


def test_head_bryant_x_of_known_matrices():
    """The first Bryant angle of Rx(a) Ry(b) Rz(c), stored as the result
    file stores S (h5py [t, j, i] = S_ij)."""
    def rx(a):
        return np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])

    def ry(b):
        return np.array([[np.cos(b), 0, np.sin(b)], [0, 1, 0], [-np.sin(b), 0, np.cos(b)]])

    def rz(c):
        return np.array([[np.cos(c), -np.sin(c), 0], [np.sin(c), np.cos(c), 0], [0, 0, 1]])
    angles = [(-0.9, 0.3, 0.5), (0.2, -1.2, -2.0), (1.4, 0.0, 0.1)]
    stored = np.array([(rx(a) @ ry(b) @ rz(c)).T for a, b, c in angles])
    assert np.allclose(specimens.head_bryant_x(stored), np.degrees([a for a, _, _ in angles]), atol=1e-12)


@pytest.mark.parametrize("direction", ["front", "side"])
def test_kang_drive_and_signs(tmp_path, direction):
    """Front: T1 driven rearward (-x), side: toward the specimen's right (the
    model's -y), each by the pulse's velocity change; the head's answer has
    the data's signs (front: rearward x-acceleration, flexion negative in
    J211; side: +y acceleration, left bending negative)."""
    model = specimens.run_kang(direction, str(tmp_path), hhneck_executable())
    with h5py.File(tmp_path / ("kang_%s_hold.h5" % direction), "r") as f:
        t = f["time"][:]
        p = f["bodies/position"][:, 0, :]
        ay = f["channels"]["HEAD_AY"][:]
    k = 0 if direction == "front" else 1
    v = np.gradient(p[:, k], t)
    tp, a = specimen_data.read_pulse(os.path.join(segments.DATA_DIR, "kang2018_sled_pulse.csv"))
    assert np.interp(0.0666, t, v) == pytest.approx(-specimen_data.delta_v(tp, a, 0.0666), rel=3e-3)
    assert np.max(np.abs(p[:, 1 - k])) < 1e-9                     # the other direction held
    if direction == "front":
        tm, ax = model["head_acc_x"]
        assert ax[np.argmax(np.abs(ax))] < 0
        tm, ry = model["head_rot_y"]
        assert ry.min() < -30.0
    else:
        tm, aj = model["head_acc_y"]
        assert np.allclose(aj, -ay) and aj[np.argmax(np.abs(aj))] > 0
        tm, rx = model["head_rot_x"]
        assert rx.min() < -30.0 and rx[0] == 0.0
    rated = specimens.rate_kang(direction, model)
    assert sorted(rated) == sorted(specimens.KANG_CHANNELS[direction])
    for sc in rated.values():
        assert sc["grid"][0] >= 0.0 and 0.0 <= sc["overall"] <= 1.0
