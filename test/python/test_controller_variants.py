"""The controller deck edits of hhneck.validation.controller_variants (the
controller's parts switched off; the rest deck's pushes) and
hhneck.results.rotation_from_start, against the shipped decks and a closed
form."""
import h5py
import numpy as np
import pytest

from hhneck.decks import field
from hhneck.paths import project_path
from hhneck.results import rotation_from_start
from hhneck.validation.controller_variants import PUSHES, edited, pushed_rest, without_controller


def controller():
    with open(project_path("input", "volunteer_controller.inp")) as f:
        return f.read().splitlines()


def cards(lines, name):
    return [l for l in lines if l.startswith(name)]


def test_each_part_zeroed_alone():
    src = controller()
    for part, name, gains in (("feedback", "FEEDBACK", (4, 5)), ("spindle", "SPINDLE", (2, 3, 7)),
                              ("bracing", "ACTIVATE", (2, 3))):
        out = edited(src, **{part: False})
        assert len(out) == len(src)
        changed = [(a, b) for a, b in zip(src, out) if a != b]
        assert changed and all(a.startswith(name) for a, _ in changed), part
        for line in cards(out, name):
            assert all(float(field(line, n)) == 0.0 for n in gains if field(line, n)), line
            # the fields beside the gains are the deck's own
            old = src[out.index(line)]
            assert all(field(line, n) == field(old, n) for n in range(8) if n not in gains), (old, line)
    assert edited(src) == src


def test_pushed_rest_changes_the_two_rates_only():
    with open(project_path("input", "volunteer_rest.inp")) as f:
        rest = f.read()
    decks = pushed_rest(rest)
    assert sorted(decks) == sorted(p for p, _, _ in PUSHES)
    for name, rx, ry in PUSHES:
        diff = [(a, b) for a, b in zip(rest.splitlines(), decks[name].splitlines()) if a != b]
        got = {(field(b, 1), field(b, 2)): float(field(b, 4)) for _, b in diff}
        assert got == {("C3", "RX"): rx, ("C4", "RY"): ry}, diff
    with pytest.raises(ValueError):
        pushed_rest(rest.replace("INITIAL   C3        RX        0.0       5.0", "INITIAL   C3        RX        0.0       6.0"))


def test_without_controller():
    with open(project_path("input", "rear5g_return.inp")) as f:
        deck = f.read()
    include = "INCLUDE   input/volunteer_controller.inp\n"
    out = without_controller(deck)
    assert include in deck and include not in out and out == deck.replace(include, "")


def test_rotation_from_start_is_the_angle_about_an_axis(tmp_path):
    """A body turned about a fixed oblique axis by angle(t): the angle back."""
    t = np.linspace(0.0, 1.0, 11)
    angle = np.radians(170.0) * t ** 2
    k = np.array([1.0, 2.0, 2.0]) / 3.0
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    start = np.array([[0.0, 0, 1], [1, 0, 0], [0, 1, 0]])        # some start orientation
    rot = np.array([(np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * K @ K) @ start for a in angle])
    path = str(tmp_path / "turn.h5")
    with h5py.File(path, "w") as f:
        f["time"] = t
        f.create_group("channels")
        f.create_dataset("bodies/rotation", data=np.stack([np.broadcast_to(np.eye(3), rot.shape), rot], axis=1))
        f.create_group("model").attrs["bodies"] = np.array([b"T1", b"HEAD"])
    got_t, got = rotation_from_start(path)
    assert np.array_equal(got_t, t)
    assert np.allclose(got, np.degrees(angle), atol=1e-6)
    assert np.allclose(rotation_from_start(path, "T1")[1], 0.0)
    with pytest.raises(KeyError):
        rotation_from_start(path, "C1")
