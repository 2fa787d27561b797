"""Signal processing of the channels: the SAE J211/1 filter of channel
frequency class CLS (CFC 60, 180, 600, 1000 ...).

    from hhneck.signals import cfc
    filtered = cfc(x, 60, dt)          # x sampled every dt [s]
"""
import numpy as np


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
