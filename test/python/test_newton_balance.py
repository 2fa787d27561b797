"""hhneck.validation.newton_balance: the lag fit against a force built with a known
lag and masses (closed form), and the head's lab acceleration from an
accelerometer's reading against the reading derived by hand from the SAE
J211 right-hand rule, in both planes."""
import numpy as np
import pytest

from hhneck.validation import newton_balance as nb


def _bump(t, t0, w):
    return np.exp(-((t - t0) / w) ** 2)


def test_fit_lag_recovers_the_lag_and_masses_of_a_force_built_with_them():
    t = np.arange(-50.0, 250.0, 0.1)
    a = 80.0 * _bump(t, 60.0, 12.0) - 30.0 * _bump(t, 95.0, 10.0)    # head [m/s^2]
    p = 110.0 * _bump(t, 28.0, 9.0)                                # T1 [m/s^2]
    f = 4.0 * np.interp(t + 12.0, t, a) + 1.5 * p                  # the cell: the head 12 ms late
    r2, lag, mh, mn = nb.fit_lag((t, f), (t, a), (t, p), (0.0, 120.0))
    assert lag == 12.0
    assert mh == pytest.approx(4.0, rel=1e-6) and mn == pytest.approx(1.5, rel=1e-6) and r2 > 0.999999
    # without the pulse term, the head's alone: the same lag, Mn 0
    r2, lag, mh, mn = nb.fit_lag((t, 4.0 * np.interp(t - 7.5, t, a)), (t, a), None, (20.0, 150.0))
    assert (lag, mn) == (-7.5, 0.0) and mh == pytest.approx(4.0, rel=1e-6)


@pytest.mark.parametrize("sense", [1.0, -1.0])
def test_lab_acceleration_inverts_the_accelerometer_reading(sense):
    # J211 (x forward, y right, z down), right-hand rule: a rotation phi
    # about y turns the head's x axis toward -z (nose up); about x it turns
    # its y axis toward +z. Head axes in the lab's (in-plane, z):
    #   about y (the front plane, sense +1): e1 = (cos, -sin), e3 = (sin, cos)
    #   about x (the side plane, sense -1):  e1 = (cos, sin),  e3 = (-sin, cos)
    t = np.linspace(0.0, 0.15, 301)
    phi = np.radians(-63.0) * np.sin(np.pi * t / 0.3) ** 2
    a1, a3 = -90.0 * np.sin(20 * t), 60.0 * np.sin(35 * t) ** 2     # the lab acceleration [m/s^2]
    f1, f3 = a1, a3 - nb.G                                           # specific force a - g (g along +z)
    c, s = np.cos(phi), np.sin(phi)
    e1 = (c, -s) if sense > 0 else (c, s)
    e3 = (s, c) if sense > 0 else (-s, c)
    read1 = (f1 * e1[0] + f3 * e1[1]) / nb.G
    read3 = (f1 * e3[0] + f3 * e3[1]) / nb.G + 1.0                   # tared upright: z read -1 g
    lab1, lab3 = nb.lab_acceleration(read1, read3, np.degrees(phi), sense)
    assert np.max(np.abs(lab1 - a1)) < 1e-9 and np.max(np.abs(lab3 - a3)) < 1e-9
    # the other sense is a different frame: it misses by tens of m/s^2
    w1, w3 = nb.lab_acceleration(read1, read3, np.degrees(phi), -sense)
    assert np.max(np.hypot(w1 - a1, w3 - a3)) > 20.0
