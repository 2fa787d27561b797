"""hhneck-animate's choice of views (docs/animation.md, "Views"): auto picks
the front view for a lateral run and the side view for case 6-2, from the
head's motion relative to T1; --view takes names and comma lists; the
strip and the animation draw the views asked for.

Independent truth: the motion components are checked against the result
file's own datasets (the head's and T1's positions, the rotation of the
head relative to T1 from /bodies/rotation by a second formula: the angle
of the relative rotation from its trace)."""
import h5py
import numpy as np
import pytest

from conftest import hhneck_module
from hhneck.tools import animate


def components(path):
    res = animate.Result(path)
    return res, animate.motion_components(res)


def test_auto_picks_front_view_for_lateral_run(lateral_file):
    res, m = components(lateral_file)
    motion = animate.view_motion(res)
    assert animate.auto_views(res) == ["front"], motion
    # the lateral push moves the head sideways (y) and bends it about x:
    # front sees both, side neither
    assert np.max(np.abs(m[:, 1])) > 20 * np.max(np.abs(m[:, 0]))
    assert np.max(np.abs(m[:, 3])) > 20 * np.max(np.abs(m[:, 4]))
    assert motion["front"] > 10 * motion["side"]


def test_auto_picks_side_view_for_case_6_2(result_file):
    res, m = components(result_file)
    motion = animate.view_motion(res)
    assert animate.auto_views(res) == ["side"], motion
    # a sagittal run: nothing sideways, no rotation about x or z
    assert np.max(np.abs(m[:, [1, 3, 5]])) < 1e-9 * np.max(np.abs(m[:, [0, 2, 4]]))
    assert motion["side"] > motion["top"] > motion["front"]


def test_motion_components_against_the_file(lateral_file):
    res, m = components(lateral_file)
    with h5py.File(lateral_file, "r") as f:
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["model"].attrs["bodies"]]
        h, r = names.index("HEAD"), names.index("T1")
        pos = f["bodies/position"][:]
        rot = f["bodies/rotation"][:]                        # [t, k, j, i] = S_ij
    d = (pos[:, h] - pos[:, r]) - (pos[0, h] - pos[0, r])
    assert np.max(np.abs(m[:, :3] - d)) < 1e-15
    # |phi| is the angle of S_T1(0) S_T1(t)^T S_h(t) S_h(0)^T, from its trace
    s = np.swapaxes(rot, -1, -2)
    q = [s[0, r] @ s[i, r].T @ s[i, h] @ s[0, h].T for i in range(len(s))]
    angle = np.array([np.arccos(np.clip((np.trace(a) - 1) / 2, -1, 1)) for a in q])
    size = np.max(animate.ellipsoid_axes(res.mass[h], res.inertia[h])[0])
    assert angle[-1] > 0.01                                   # the head has turned by more than half a degree
    # (the angle from the trace is good to about sqrt(eps) = 1.5e-8 rad near zero)
    assert np.max(np.abs(np.linalg.norm(m[:, 3:], axis=1) / size - angle)) < 1e-7


def test_parse_views():
    assert animate.parse_views(None) == ["auto"]
    assert animate.parse_views(["front,side", "iso", "front"]) == ["front", "side", "iso"]
    assert animate.parse_views(["side", "auto"]) == ["auto"]
    with pytest.raises(ValueError, match="unknown view back"):
        animate.parse_views(["side,back"])


def test_strip_of_two_views_and_auto_animation(lateral_file, tmp_path):
    """--view front,side: two blocks of key-frame rows; the default (auto)
    animation of the lateral run: front and 3-D views."""
    from PIL import Image
    strip, gif = str(tmp_path / "strip.png"), str(tmp_path / "a.gif")
    r = hhneck_module("tools.animate", lateral_file, gif, "--strip", strip, "--view", "front,side", "--every", "0.01",
                      "--slow", "1", "--fps", "100", "--dpi", "20", "--quiet")
    assert r.returncode == 0, r.stderr
    assert "(3 key frames), views: front, side" in r.stdout            # 0, 10, 20 ms
    # the strip: 3 columns, 1 row a view, 2 views: (2.2 * 3 + 1) x (2.7 * 2 + 0.6) inches at dpi 20 + 20
    assert Image.open(strip).size == (round(7.6 * 40), round(6.0 * 40))
    assert "(3 frames), views: front, side" in r.stdout
    r = hhneck_module("tools.animate", lateral_file, gif, "--slow", "1", "--fps", "100", "--dpi", "20", "--quiet")
    assert r.returncode == 0, r.stderr
    assert "(3 frames), views: front, iso" in r.stdout
    im = Image.open(gif)
    assert im.n_frames == 3 and im.size == (240, 140)                 # 12 x 7 inches at dpi 20


def test_unknown_view_refused(result_file, tmp_path):
    r = hhneck_module("tools.animate", result_file, "--strip", tmp_path / "s.png", "--view", "back")
    assert r.returncode == 2 and "unknown view back" in r.stderr
    assert not (tmp_path / "s.png").exists()
