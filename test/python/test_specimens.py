"""The Stemper 2004 and Kang 2018 specimen set-ups of the catalogue
(python/hhneck/validation/specimens.py): the decks take the source's pulses and passive
muscles, the T1 drive gives the pulse's velocity change, the rated channels
(the Fortran run's own) agree with a second computation from the result
file's body positions, rotation matrices and joint angles, and the Kang
load cell sits where the set-up put it and reads the specimen's weight at
the start."""
import os

import h5py
import numpy as np
import pytest

from conftest import hhneck_executable
from hhneck.validation import segments, specimen_data, specimens
from hhneck.signals import cfc


@pytest.fixture(scope="module")
def stemper(tmp_path_factory):
    work = tmp_path_factory.mktemp("stemper")
    model = specimens.run_stemper(str(work), hhneck_executable())
    return work, model


def test_deck_cards(tmp_path):
    deck = specimens.stemper_deck(str(tmp_path))
    text = open(deck).read()
    # the potted T1 tilted to the source's slope, 25 deg, less the model deck's 23.8 on C7
    assert specimens.model_t1_slope() == 23.8
    assert "PRESCRIB  T1        RY        CONSTANT  1.2000" in text.splitlines()
    assert "CONSTANT  -2.0000" in open(specimens.stemper_deck(str(tmp_path), t1_slope=21.8)).read()
    assert "HOLD      POSTURE" in text.splitlines() and "PRESCRIB  T1        TX        ACCEL     STEMPER" in text
    for card in ("CHANGE    FLEXU0    FIELD2    ACTIVATE  FLEX      SET       0.0",
                 "CHANGE    EXTU1     FIELD3    ACTIVATE  EXT       SET       0.0"):
        assert card in text
    rows = open(tmp_path / "stemper_pulse.csv").read().splitlines()
    assert len(rows) == 1 + 113 and "TABLE     STEMPER   113" in text
    assert "HOLD" not in open(specimens.stemper_deck(str(tmp_path), support="NONE")).read()
    assert "HOLD      POSTURE   0.0" in open(specimens.stemper_deck(str(tmp_path), support="RELEASE")).read().splitlines()
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
        s1 = np.transpose(f["bodies/rotation"][:, 0], (0, 2, 1))          # T1's S_ij at every sample
        ry = {b: f["channels"]["%s_RY" % b][:] for b in ("C7", "C6", "C5", "C4", "C3", "C2", "C1", "HEAD")}
        ry_any = {b: (f["channels"]["%s_RX" % b][:], f["channels"]["%s_RZ" % b][:]) for b in ry}
    # retraction: head mass centre x minus T1's in T1's axes, from the start, in mm
    rel = np.einsum("tji,tj->ti", s1, pos[:, 8, :] - pos[:, 0, :])
    hand = 1e3 * (rel[:, 0] - rel[0, 0])
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


@pytest.mark.parametrize("direction", ["front", "side"])
def test_kang_drive_and_signs(tmp_path, direction):
    """Front: T1 driven rearward (-x), side: toward the specimen's right (the
    model's -y), each by the pulse's velocity change; the head's answer has
    the data's signs (front: rearward x-acceleration, flexion negative in
    J211, the cell's Fx negative and My positive; side: +y acceleration,
    left bending negative); the head's angles are those of its matrices; the
    load cell's point and its start value by hand; the rated curves tared and
    filtered by the source notebook's CFC classes."""
    model = specimens.run_kang(direction, str(tmp_path), hhneck_executable())
    with h5py.File(tmp_path / ("kang_%s_hold_passive.h5" % direction), "r") as f:
        t = f["time"][:]
        p = f["bodies/position"][:, 0, :]
        ays = f["channels"]["HEAD_AYS"][:]
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
        # the sled pushes the specimen rearward, the cell resists the flexion (the data's signs)
        tm, fx = model["loadcell_force_x"]
        tm, my = model["loadcell_moment_y"]
        assert fx[np.argmax(np.abs(fx))] < 0 and my[np.argmax(np.abs(my))] > 0
    else:
        # rated as the source's notebook filters the SAFER HBM's: head y CFC 180
        tm, aj = model["head_acc_y"]
        assert np.allclose(aj, cfc(-(ays - ays[0]), 180, 1e-4), atol=1e-12) and aj[np.argmax(np.abs(aj))] > 0
        assert abs(aj[0]) < 1e-3
        tm, rx = model["head_rot_x"]
        assert rx.min() < -30.0 and abs(rx[0]) < 1e-3
    rated = specimens.rate_kang(direction, model)
    assert sorted(rated) == sorted(specimens.KANG_CHANNELS[direction])
    assert any(ch.startswith("loadcell_") for ch in rated)
    for sc in rated.values():
        assert sc["grid"][0] >= 0.0 and 0.0 <= sc["overall"] <= 1.0
    with h5py.File(tmp_path / ("kang_%s_hold_passive.h5" % direction), "r") as f:
        names = [str(n) for n in f["model"].attrs["bodies"]]
        rot = f["bodies/rotation"][:, names.index("HEAD")]       # [t, j, i] = S_ij
        st1 = f["bodies/rotation"][0, names.index("T1")].T       # T1's S_ij at the start
        pos = f["bodies/position"][0]
        mass = f["model/mass"][:]
        ch = {n: f["channels"][n][:] for n in ("HEADL_RX", "HEADL_RY", "T1CELL_JFZ", "T1CELL_JFX", "T1CELL_JMY",
                                               "HEAD_AX", "HEAD_AY", "HEAD_AZ", "HEAD_AXS", "HEAD_AYS", "HEAD_AZS")}
    # the head's Bryant angles in R against its stored matrices: x = atan2(-S23, S33), y = asin(S13)
    s = np.transpose(rot, (0, 2, 1))
    assert np.allclose(ch["HEADL_RX"], np.degrees(np.arctan2(-s[:, 1, 2], s[:, 2, 2])), atol=1e-9)
    assert np.allclose(ch["HEADL_RY"], np.degrees(np.arcsin(s[:, 0, 2])), atol=1e-9)
    # the head's accelerometer: the lab-frame acceleration less gravity (-1 g along z), turned
    # into head axes by the stored matrices; upright at rest it reads +1 g along the head's z
    lab = np.stack([ch["HEAD_AX"], ch["HEAD_AY"], ch["HEAD_AZ"] + 1.0], axis=1)
    own = np.einsum("tji,tj->ti", s, lab)
    assert np.allclose(np.stack([ch["HEAD_AXS"], ch["HEAD_AYS"], ch["HEAD_AZS"]], axis=1), own, atol=1e-9)
    assert ch["HEAD_AZS"][0] == pytest.approx(1.0, abs=0.01)
    # the rated readings: tared, in J211 signs (front: x as is, z down), filtered by the
    # notebook's classes (README "What the notebook computes": head x CFC 60, y and z 180)
    if direction == "front":
        assert np.allclose(model["head_acc_x"][1], cfc(ch["HEAD_AXS"] - ch["HEAD_AXS"][0], 60, 1e-4), atol=1e-12)
    assert np.allclose(model["head_acc_z"][1], cfc(-(ch["HEAD_AZS"] - ch["HEAD_AZS"][0]), 180, 1e-4), atol=1e-12)
    # the cell 81 mm behind and 229 mm below the head's mass centre at the start, in T1's axes
    # (T1 tilted by the potting's slope less the model's: 0.2 deg about y)
    tilt = np.radians(specimens.T1_SLOPE["kang"] - specimens.model_t1_slope())
    assert np.allclose(st1, [[np.cos(tilt), 0, np.sin(tilt)], [0, 1, 0], [-np.sin(tilt), 0, np.cos(tilt)]],
                       atol=1e-12)
    head = st1.T @ (pos[names.index("HEAD")] - pos[names.index("T1")])
    assert np.allclose(1e3 * (head - np.array(specimens.KANG_CELL_POINT)), [81.0, 0.0, 229.0], atol=0.5)
    # held at rest at the start: the cell carries the weight of C7 ... head, in T1's J211 axes
    # (x forward, z down: the weight's components along T1's tilted axes)
    w = 9.80665 * mass[names.index("C7"):].sum()
    assert ch["T1CELL_JFZ"][0] == pytest.approx(-w * np.cos(tilt), rel=1e-6)
    assert ch["T1CELL_JFX"][0] == pytest.approx(-w * np.sin(tilt), rel=1e-6)
    # rated from the start value (the data are tared), filtered as the notebook's forces (CFC 60)
    tm, fz = model["loadcell_force_z"]
    assert abs(fz[0]) < 1.0 and np.allclose(fz, cfc(ch["T1CELL_JFZ"] - ch["T1CELL_JFZ"][0], 60, 1e-4), atol=1e-9)
    # the filter smooths the digitised pulse's corners without moving the curve: within 5 % of the raw peak
    raw = ch["T1CELL_JFZ"] - ch["T1CELL_JFZ"][0]
    assert np.max(np.abs(fz - raw)) < 0.05 * np.max(np.abs(raw))


def test_settled_start_carries_the_weight(tmp_path):
    """The PRESTRAIN support (HOLD PRESTRAIN): the deck has the card and no
    holding forces; at rest at the start the Kang cell reads the weight of
    C7 ... head as the held start does (the pre-strain equals HOLD at t = 0),
    no E_HOLD energy is stored, and the listing states the settled start."""
    deck = specimens.kang_deck(str(tmp_path), "front", support="PRESTRAIN")
    lines = open(deck).read().splitlines()
    assert "HOLD      PRESTRAIN" in lines and "HOLD      POSTURE" not in lines
    specimens.run_kang("front", str(tmp_path), hhneck_executable(), support="PRESTRAIN")
    name = specimens.run_name("kang_front", "PRESTRAIN")
    with h5py.File(tmp_path / (name + ".h5"), "r") as f:
        names = [str(n) for n in f["model"].attrs["bodies"]]
        mass = f["model/mass"][:]
        st1 = f["bodies/rotation"][0, names.index("T1")].T
        fz = f["channels"]["T1CELL_JFZ"][:]
        ehold = f["channels"]["E_HOLD"][:]
    tilt = np.arccos(st1[0, 0])
    w = 9.80665 * mass[names.index("C7"):].sum()
    assert fz[0] == pytest.approx(-w * np.cos(tilt), rel=1e-6)
    assert np.all(ehold == 0.0)
    listing = open(tmp_path / (name + ".txt")).read()
    assert "PRE-STRAINED (HOLD PRESTRAIN)" in listing and "NEWTON ITERATIONS" in listing


def test_kang_shifted_reference_rates_its_own_shifted_curve():
    """rate_kang's shifts move a reference's times: the front z-acceleration
    corridor's midline, moved 25 ms earlier as the model curve, rates 1 against
    the reference moved the same, and far lower against the one as given."""
    path = os.path.join(segments.DATA_DIR, "kang2018_front_experiment.csv")
    model = {}
    for ch in specimens.KANG_CHANNELS["front"]:
        g, ref, _, _ = specimen_data.reference(path, ch)
        model[ch] = (g - 25.0 if ch == "head_acc_z" else g, ref)
    moved = specimens.rate_kang("front", model, shifts={"head_acc_z": -25.0})
    given = specimens.rate_kang("front", model)
    assert moved["head_acc_z"]["overall"] > 0.999
    assert moved["head_acc_z"]["peak_ref"][1] == pytest.approx(given["head_acc_z"]["peak_ref"][1] - 25.0, abs=1e-9)
    assert given["head_acc_z"]["overall"] < 0.6
    for ch in specimens.KANG_CHANNELS["front"]:             # the others are their own references
        if ch != "head_acc_z":
            assert moved[ch]["overall"] > 0.999 and given[ch]["overall"] > 0.999


def test_rating_stops_at_the_runs_end():
    """A reference that runs past the model's run is rated over the times
    both cover: the model equal to the reference up to its end at 60 ms
    rates 1 (held at its last value to 100 ms it rated lower), the rated
    window and the reference's own end are reported; a run that does not
    reach the reference is refused."""
    g = np.arange(0.0, 100.05, 0.1)
    ref = np.sin(np.pi * g / 100.0)
    t = np.arange(0.0, 60.05, 0.1)
    sc = specimens.rate_channel(g, ref, ref - 0.1, ref + 0.1, t, np.sin(np.pi * t / 100.0))
    assert sc["overall"] > 0.999 and sc["inside"] == 1.0
    assert sc["window"] == pytest.approx((0.0, 60.0)) and sc["reference_end"] == pytest.approx(100.0)
    assert sc["grid"][-1] == pytest.approx(60.0) and sc["model"].size == sc["reference"].size == 601
    with pytest.raises(ValueError, match="does not cover"):
        specimens.rate_channel(g, ref, ref, ref, t + 200.0, t)


def test_kang_window_searches_the_sources_times():
    """The Kang window ends at 1.2 x the time of the reference's largest
    magnitude between 0 and 99.9 ms: a larger value at 150 ms is not
    searched. The front head rotation's corridor is still rising at
    99.9 ms: its window ends near 119.9 ms (searched over the whole
    reference, at 1.2 x 101.4 ms = 121.7)."""
    g = 0.1 * np.arange(-100, 2001)
    ref = np.exp(-((g - 60.0) / 10.0) ** 2) + 2.0 * np.exp(-((g - 150.0) / 10.0) ** 2)
    wg, wr, wl, wh = specimens.kang_window(g, ref, ref - 1, ref + 1)
    assert wg[0] == pytest.approx(0.0, abs=1e-9) and wg[-1] == pytest.approx(72.0, abs=0.051)
    assert np.allclose(wl, wr - 1) and wr.size == wg.size
    wg = specimens.kang_reference("front", "head_rot_y")[0]
    assert 119.5 < wg[-1] <= 119.9                              # its grid's last point before 1.2 x 99.9


def _rot(axis, angle):
    c, s = np.cos(angle), np.sin(angle)
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    r = np.eye(3)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return r


def test_planar_angle_of_a_hand_built_rotation():
    """The head turned relative to a tilted T1 by theta about T1's y, then
    by phi about its own x (a sagittal angle with a lateral bend): its
    planar angle in T1's sagittal plane is theta exactly, where the Bryant
    angle asin(R13) reads asin(sin theta cos phi); likewise about x and
    about z; a turn past 180 deg goes on."""
    theta = np.radians(np.linspace(0.0, 60.0, 7))
    phi = np.radians(40.0)
    parent = np.array([_rot("y", np.radians(24.0)) @ _rot("z", 0.1)] * theta.size)
    body = np.array([p @ _rot("y", a) @ _rot("x", phi) for p, a in zip(parent, theta)])
    assert np.allclose(specimens.planar_angle(parent, body, "y"), np.degrees(theta), atol=1e-9)
    bryant = np.degrees(np.arcsin(np.sin(theta) * np.cos(phi)))
    assert abs(bryant[-1] - 60.0) > 10.0                       # the Bryant angle is another angle
    body = np.array([p @ _rot("x", a) @ _rot("y", phi) for p, a in zip(parent, theta)])
    assert np.allclose(specimens.planar_angle(parent, body, "x"), np.degrees(theta), atol=1e-9)
    body = np.array([p @ _rot("z", a) @ _rot("x", phi) for p, a in zip(parent, theta)])
    assert np.allclose(specimens.planar_angle(parent, body, "z"), np.degrees(theta), atol=1e-9)
    turn = np.radians(np.linspace(0.0, 200.0, 41))
    body = np.array([parent[0] @ _rot("y", a) for a in turn])
    assert np.allclose(specimens.planar_angle(parent[:1].repeat(41, 0), body, "y"), np.degrees(turn), atol=1e-9)


def test_integrated_rotation_of_a_hand_built_rotation():
    """A head turned about a fixed axis n by theta(t) = 50 deg sin^2(pi t /
    0.2 s) has the angular velocity theta'(t) n: its integral is theta(t)
    n, the rotation vector of the turn (Rodrigues' formula gives the
    matrices), to the trapezoid's error on a 0.1 ms step."""
    n = np.array([1.0, -2.0, 2.0]) / 3.0
    t = np.arange(0.0, 0.2 + 1e-12, 1e-4)
    amp = np.radians(50.0)
    theta = amp * np.sin(np.pi * t / 0.2) ** 2
    dtheta = amp * np.pi / 0.2 * np.sin(2 * np.pi * t / 0.2)
    k = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    s = np.array([np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k for a in theta])
    # the rotation vector of each matrix (axis x angle) against the integral
    angle = np.arccos(np.clip((np.trace(s, axis1=1, axis2=2) - 1) / 2, -1, 1))
    for c in range(3):
        got = specimens.integrated_rotation(t, dtheta * n[c])
        assert np.allclose(got, np.degrees(angle * n[c]), atol=2e-4)
    assert specimens.integrated_rotation(t, dtheta)[0] == 0.0


def _fake_result(path, case, t, channels, rotations=None):
    """A result file with the datasets model_channels reads: every run
    channel of `case` (zeros unless given), the time and, when given,
    /bodies/rotation ({body: (nt, 3, 3) S_ij}) with the bodies' names."""
    with h5py.File(path, "w") as f:
        f["time"] = t
        for _, run, *_ in specimens.CHANNELS[case]:
            f["channels/" + run] = channels.get(run, np.zeros_like(t))
        for name, v in channels.items():
            if "channels/" + name not in f:
                f["channels/" + name] = v
        if rotations:
            names = list(rotations)
            f["model"] = h5py.Empty("f")
            f["model"].attrs["bodies"] = names
            f["bodies/rotation"] = np.stack([np.swapaxes(rotations[b], 1, 2) for b in names], axis=1)


def test_model_channels_rate_each_sources_angle(tmp_path):
    """model_channels reads each rotation as ANGLES defines it, not the
    result file's Bryant channel beside it in CHANNELS: Kang's head
    rotation the integral of its angular velocity (side: about x, J211
    sign as is; front: about y, sign changed), Stemper's head-T1 angle
    the planar angle from the rotation matrices (extension positive)."""
    t = np.arange(0.0, 0.1 + 1e-12, 1e-4)
    w = 10.0 * np.sin(np.pi * t / 0.1)                         # rad/s
    turned = np.degrees(10.0 * 0.1 / np.pi * (1 - np.cos(np.pi * t / 0.1)))
    _fake_result(tmp_path / "side.h5", "kang_side", t, {"HEAD_OMEGX": w, "HEADL_RX": -7.0 * np.ones_like(t)})
    got = specimens.model_channels("kang_side", str(tmp_path / "side.h5"))["head_rot_x"][1]
    assert np.allclose(got, cfc(turned, 180, 1e-4), atol=1e-3) and got.max() > 30.0
    _fake_result(tmp_path / "front.h5", "kang_front", t, {"HEAD_OMEGY": w, "HEADL_RY": 3.0 * t})
    got = specimens.model_channels("kang_front", str(tmp_path / "front.h5"))["head_rot_y"][1]
    assert np.allclose(got, cfc(-turned, 180, 1e-4), atol=1e-3)
    theta = -np.radians(turned)                                # extension: a negative turn about y
    t1 = np.array([_rot("y", np.radians(1.2))] * t.size)
    head = np.array([a @ _rot("y", b) @ _rot("x", 0.3) for a, b in zip(t1, theta)])
    _fake_result(tmp_path / "stemper.h5", "stemper", t, {"HT1_RY": np.zeros_like(t)}, {"T1": t1, "HEAD": head})
    got = specimens.model_channels("stemper", str(tmp_path / "stemper.h5"))["head_T1_angle"][1]
    assert np.allclose(got, turned, atol=1e-9)
