"""hhneck-compare-listing against listings made by hand: a noise channel
whose peak moves passes, a real peak that moves by 3 ms fails, a unit with
a space is a row of the peaks table, and the one reference failure seen on
another machine (the OC_MX noise peak of nbdl15g) passes; a value that
differs by the listing's resolution (printed as 0 on one machine) passes,
one of three resolutions fails."""
import os

import hhneck.tools.compare_listing as cl

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

PEAKS = """ SUMMARY OF PEAKS (ALL SAMPLES)

   CHANNEL                  UNITS          MAXIMUM   AT (MS)      MINIMUM   AT (MS)
   HEAD_AX                  g                 0.491    238.00      -27.626     98.70
   HEAD_AY                  g             8.643E-13    166.30   -1.239E-12    165.20
   OC_FX                    N               937.892     98.10      -37.914    250.00
   OC_MX                    N m           6.943E-13    245.90   -1.888E-13    166.40
   OC_MY                    N m              28.341    136.80      -21.600     96.50
   C5C4_VX                  N               674.283    149.90   -3.592E-14      0.00
""".splitlines()

TABLE = """ TIME HISTORY: HEAD

    TIME      HEAD_AX     HEAD_AY       OC_MY
    (MS)            g           g         N m
     0.00  -3.500E-03       0.000   1.000E-03
     5.00      -0.016   1.234E-13       0.500
    10.00     -27.626  -2.100E-13      28.341
""".splitlines()


def edited(lines, old, new):
    """The lines with the one line containing `old` replaced by `new`."""
    hits = [k for k, l in enumerate(lines) if old in l]
    assert len(hits) == 1
    out = list(lines)
    out[hits[0]] = new
    return out


def test_identical_listings_pass():
    ok, _ = cl.compare(PEAKS + TABLE, PEAKS + TABLE)
    assert ok


def test_unit_with_a_space_is_a_peaks_row():
    layout = cl.Layout(PEAKS)
    names = sorted(layout.peaks.values())
    assert names == ["C5C4_VX", "HEAD_AX", "HEAD_AY", "OC_FX", "OC_MX", "OC_MY"]
    assert layout.unit["OC_MX"] == "N m"
    assert layout.group_scale("OC_MX") == 28.341


def test_noise_channel_whose_peak_moves_passes():
    new = edited(PEAKS, "OC_MX", "   OC_MX                    N m           3.956E-13    164.00   -4.100E-13     12.30")
    ok, text = cl.compare(new, PEAKS)
    assert ok, text


def test_noise_minimum_of_a_real_channel_moves_passes():
    new = edited(PEAKS, "C5C4_VX", "   C5C4_VX                  N               674.283    149.90    2.100E-13     37.10")
    ok, text = cl.compare(new, PEAKS)
    assert ok, text


def test_real_peak_moved_by_3_ms_fails():
    # value within its tolerance (0.5 % of 28.3 N m), time 3 ms late
    new = edited(PEAKS, "OC_MY", "   OC_MY                    N m              28.250    139.80      -21.600     96.50")
    ok, text = cl.compare(new, PEAKS)
    assert not ok
    assert "139.80 against 136.80" in text


def test_real_peak_moved_by_1_ms_passes():
    new = edited(PEAKS, "OC_MY", "   OC_MY                    N m              28.250    137.80      -21.600     96.50")
    ok, text = cl.compare(new, PEAKS)
    assert ok, text


def test_real_peak_value_off_by_1_percent_fails():
    new = edited(PEAKS, "HEAD_AX", "   HEAD_AX                  g                 0.491    238.00      -27.350     98.70")
    ok, text = cl.compare(new, PEAKS)
    assert not ok
    assert "-27.350 against -27.626" in text


def test_noise_column_of_a_time_table_passes():
    new = edited(TABLE, "    10.00", "    10.00     -27.626   3.300E-13      28.341")
    ok, text = cl.compare(PEAKS + new, PEAKS + TABLE)
    assert ok, text


def test_real_column_of_a_time_table_off_by_1_percent_fails():
    new = edited(TABLE, "    10.00", "    10.00     -27.350  -2.100E-13      28.341")
    ok, text = cl.compare(PEAKS + new, PEAKS + TABLE)
    assert not ok
    assert "-27.350 against -27.626" in text


def test_text_change_fails():
    new = edited(PEAKS, "OC_FX", "   OC_FZ                    N               937.892     98.10      -37.914    250.00")
    ok, text = cl.compare(new, PEAKS)
    assert not ok
    assert "differs in its text" in text


def test_the_other_machines_nbdl15g_listing_passes():
    """The failure reported from a clean clone on another machine: OC_MX's
    noise peak at 164.00 ms against 245.90 ms in the reference."""
    ref = open(os.path.join(ROOT, "reference", "outputs", "nbdl15g.txt")).read().splitlines()
    new = edited(ref, "   OC_MX                    N m", "   OC_MX                    N m           3.956E-13    164.00   -1.888E-13    166.40")
    ok, text = cl.compare(new, ref)
    assert ok, text


RESOLVED = """ SUMMARY OF PEAKS (ALL SAMPLES)

   CHANNEL                  UNITS          MAXIMUM   AT (MS)      MINIMUM   AT (MS)
   T1_DX                    mm             3000.000    250.00        0.000      0.00
   HEAD_DY                  mm                0.000    100.00        0.000     53.10
""".splitlines()


def test_a_value_at_the_resolution_printed_as_itself_passes():
    # HEAD_DY's maximum 2.9E-03 mm is just below the resolution (1e-6 of 3000 mm) on the machine that wrote
    # the reference, 0 there, and just above it on another: it differs by the resolution alone
    new = edited(RESOLVED, "HEAD_DY", "   HEAD_DY                  mm            3.100E-03    100.00        0.000     53.10")
    ok, text = cl.compare(new, RESOLVED)
    assert ok, text
    assert abs(cl.Layout(RESOLVED).tolerance("HEAD_DY", cl.RTOL) - (cl.RTOL * 0.3 + 3.0e-3)) < 1e-9


def test_a_value_of_three_resolutions_fails():
    new = edited(RESOLVED, "HEAD_DY", "   HEAD_DY                  mm            9.000E-03    100.00        0.000     53.10")
    ok, text = cl.compare(new, RESOLVED)
    assert not ok and "9.000E-03 against 0.000" in text, text
