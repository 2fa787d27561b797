"""hhneck.export (hhneck-export): the hand-made ISO-MME example folder
(test/python/data/mme_example, ISO-MME 1.6, two channels) read as written,
written and read back equal, SAE J211 signs on known vectors, the ISO-MME
folder and the CSV file of the short deck's result file."""
import csv
import os
import re

import h5py
import numpy as np
import pytest

import hhneck.export as hx
import hhneck.results as hr
from conftest import DATA, run_short, short_deck

EXAMPLE = os.path.join(DATA, "mme_example")


def test_read_the_hand_made_example_as_written():
    t = hx.read_mme(EXAMPLE)
    assert t.name == "HN001"
    assert t.get("Data format") == "ISO-MME" and t.get("Version") == "1.6"
    assert [v for k, v in t.info if k == "Comments"] == [
        "written by hand for test/python/test_export.py",
        "upper-neck force Z and head acceleration X, 5 samples each"]
    assert dict(t.chn_info) == {"Instrumentation standard": "SAE J211", "Number of channels": "2"}
    assert [c.code for c in t.channels] == ["11NECKUP00VHFOZB", "11HEAD0000VHACXA"]
    fz, ax = t.channels
    assert fz.name == "Upper neck force Z" and fz.unit == "N"
    assert ax.name == "Head acceleration X" and ax.unit == "g"
    assert np.array_equal(fz.values, [-12.5, 0.0, 250.0, 1000.0, -325.0])
    assert np.array_equal(ax.values, [0.5, 1.5, -2.0, 12.25, 7.0])
    assert np.allclose(fz.time, [-0.0002, -0.0001, 0.0, 0.0001, 0.0002], rtol=0, atol=1e-15)
    assert fz.get("Channel frequency class") == "600" and hx.FILTER_CFC[fz.code[15]] == 600
    assert hx.FILTER_CFC[ax.code[15]] == 1000


def test_write_then_read_back_equal(tmp_path):
    t = hx.read_mme(EXAMPLE)
    out = tmp_path / "copy"
    hx.write_mme(str(out), t)
    assert sorted(os.listdir(out / "Channel")) == ["HN001.001", "HN001.002", "HN001.chn"]
    u = hx.read_mme(str(out))
    assert u.name == t.name and u.info == t.info and u.chn_info == t.chn_info
    assert len(u.channels) == 2
    for a, b in zip(t.channels, u.channels):
        assert a.header == b.header
        assert np.array_equal(a.values, b.values)
    # the header lines as ISO-MME writes them: key padded to 28 characters, then ':'
    lines = (out / "Channel" / "HN001.001").read_text().splitlines()
    assert lines[0] == "Name of the channel         :Upper neck force Z"
    assert "Number of samples           :5" in lines


def test_a_sample_count_that_disagrees_is_refused(tmp_path):
    t = hx.read_mme(EXAMPLE)
    hx.write_mme(str(tmp_path / "bad"), t)
    p = tmp_path / "bad" / "Channel" / "HN001.002"
    p.write_text(p.read_text().replace("7.0\n", ""))
    with pytest.raises(ValueError, match="Number of samples"):
        hx.read_mme(str(tmp_path / "bad"))


def test_j211_signs_of_known_vectors():
    # project axes x forward, y left, z up; J211 x forward, y right, z down
    assert np.array_equal(hx.kinematic_to_j211([1.0, 2.0, 3.0]), [1.0, -2.0, -3.0])
    # a head pulled up off the neck (tension): the head's force on the neck is up
    # (+z in project axes); J211 reports upper-neck tension as +Fz
    assert hx.neck_load_to_j211([0.0, 0.0, 500.0])[2] == 500.0
    # flexion: MY > 0 in the project and My > 0 in J211
    assert hx.neck_load_to_j211([0.0, 20.0, 0.0])[1] == 20.0
    # the head pulling the neck forward: the neck pulls the head rearward, J211 Fx < 0
    assert np.array_equal(hx.neck_load_to_j211([10.0, 20.0, 30.0]), [-10.0, 20.0, 30.0])
    # the channel table agrees with the vector rules, component by component
    for names, rule in ((("HEAD_AXL", "HEAD_AYL", "HEAD_AZL"), hx.kinematic_to_j211),
                        (("HEAD_OMEGX", "HEAD_OMEGY", "HEAD_OMEGZ"), hx.kinematic_to_j211),
                        (("HEAD_ALPHX", "HEAD_ALPHY", "HEAD_ALPHZ"), hx.kinematic_to_j211),
                        (("OC_FX", "OC_FY", "OC_FZ"), hx.neck_load_to_j211),
                        (("OC_MX", "OC_MY", "OC_MZ"), hx.neck_load_to_j211)):
        v = np.array([1.0, 2.0, 3.0])
        assert [float(hx.to_j211(n, v[k])) for k, n in enumerate(names)] == list(rule(v)), names
    # a flexion rotation about the project's y (left) is a negative one about J211's y (right)
    assert hx.to_j211("HEAD_THETY", 30.0) == -30.0


def test_channel_codes_and_filter_classes():
    assert hx.channel_code("OC_FZ") == "11NECKUP00VHFOZ0"
    assert hx.channel_code("OC_FZ_CFC600") == "11NECKUP00VHFOZB"
    assert hx.channel_code("HEAD_AR_CFC1000", fine3="H3") == "11HEAD0000H3ACRA"
    assert hx.channel_code("HEAD_AXL", position="13") == "13HEAD0000VHACX0"
    with pytest.raises(ValueError):
        hx.channel_code("OC_FZ", position="1")


def test_mme_from_the_result_file(result_file, tmp_path):
    out = tmp_path / "SHORT"
    assert hx.main(["mme", result_file, "-o", str(out), "--channels", "OC_FX,OC_FZ,HEAD_AYL,OC_MY_CFC600"]) == 0
    t = hx.read_mme(str(out))
    assert t.name == "SHORT" and t.get("Data format edition number") == "1.6"
    with h5py.File(result_file, "r") as f:
        time = f["time"][:]
        fx, fz, ayl = f["channels/OC_FX"][:], f["channels/OC_FZ"][:], f["channels/HEAD_AYL"][:]
        my = f["injury/history/oc_my_cfc600"][:]
    c = {ch.code: ch for ch in t.channels}
    assert sorted(c) == sorted(["11NECKUP00VHFOX0", "11NECKUP00VHFOZ0", "11HEAD0000VHACY0", "11NECKUP00VHMOYB"])
    assert np.array_equal(c["11NECKUP00VHFOX0"].values, -fx)
    assert np.array_equal(c["11NECKUP00VHFOZ0"].values, fz)
    assert np.array_equal(c["11HEAD0000VHACY0"].values, -ayl)
    assert np.array_equal(c["11NECKUP00VHMOYB"].values, my)
    assert c["11NECKUP00VHMOYB"].unit == "Nm" and c["11NECKUP00VHMOYB"].get("Channel frequency class") == "600"
    assert np.allclose(c["11NECKUP00VHFOZ0"].time, time, rtol=0, atol=1e-12)


def test_mme_refuses_a_channel_without_a_code(result_file, tmp_path, capsys):
    assert hx.main(["mme", result_file, "-o", str(tmp_path / "X"), "--channels", "OC_FZ,HT1_RX"]) == 1
    assert "no ISO-MME code for HT1_RX" in capsys.readouterr().err
    assert not (tmp_path / "X").exists()


def test_csv_has_units_in_the_header_and_the_values(result_file, tmp_path):
    out = str(tmp_path / "out.csv")
    assert hx.main(["csv", result_file, "--channels", "HEAD_AX,OC_FZ", "-o", out]) == 0
    with open(out) as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["time [s]", "HEAD_AX [g]", "OC_FZ [N]"]
    data = np.array(rows[1:], dtype=float)
    with h5py.File(result_file, "r") as f:
        assert np.allclose(data[:, 0], f["time"][:], rtol=1e-11, atol=0)
        assert np.allclose(data[:, 2], f["channels/OC_FZ"][:], rtol=1e-11, atol=1e-300)


# ISO/TS 13499 channel-code elements (code list RED B 1.6.2) of the channels
# hhneck exports, written out here from the code list, not from the module
CODE = re.compile(r"(?P<pos>[0-9A-Z]{2})(?P<loc>HEAD|NECK|THSP|EKIN)(?P<fl1>00|UP|LO|01)(?P<fl2>00)"
                  r"(?P<fl3>VH)(?P<dim>AC|AV|AA|AN|DS|FO|MO|EN)(?P<dir>[XYZR0])(?P<filter>[0AB])")
# header fields of ISO-MME 1.6 test (.mme) and channel files
TEST_FIELDS = ["Data format edition number", "Laboratory name", "Laboratory test ref. number", "Customer name",
               "Title", "Timestamp", "Type of the test", "Regulation", "Date of the test", "Number of test objects",
               "Name of test object 1", "Mass test object 1", "Type of test object 1", "Code of test object 1",
               "Comments"]
CHANNEL_FIELDS = ["Name of the channel", "Laboratory channel code", "Customer channel code", "Channel code",
                  "Test object number", "Data source", "Location", "Direction", "Reference system",
                  "Transducer type", "Pre-filter type", "Cut off frequency", "Channel frequency class",
                  "Channel amplitude class", "Unit", "Dimension", "Sampling interval", "Bit resolution",
                  "Time of first sample", "Number of samples", "First global maximum value", "Time of maximum value",
                  "First global minimum value", "Time of minimum value", "Data status", "Comments"]


@pytest.fixture(scope="module")
def loadcell_file(tmp_path_factory):
    """The short deck with a LOADCELL at the T1 section (body C7, the root's
    child) and one mid-neck (C4)."""
    deck = short_deck().splitlines()
    k = next(n for n, line in enumerate(deck) if line.startswith("TITLE"))
    deck[k + 1:k + 1] = ["LOADCELL  LNECK     C7", "LOADCELL  MIDC4     C4"]
    return run_short(tmp_path_factory, "cells", "\n".join(deck) + "\n")


def test_full_export_codes_headers_and_values(loadcell_file, tmp_path, capsys):
    out = tmp_path / "FULL"
    assert hx.main(["mme", loadcell_file, "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    t = hx.read_mme(str(out))
    keys = [k for k, _ in t.info]
    assert all(k in keys for k in TEST_FIELDS), [k for k in TEST_FIELDS if k not in keys]
    assert t.get("Data format edition number") == "1.6" and t.get("Number of test objects") == "1"
    with h5py.File(loadcell_file, "r") as f:
        mass = float(np.sum(f["model/mass"][:]))
        time = f["time"][:]
        chan = {n: f["channels"][n][:] for n in f["channels"]}
    assert float(t.get("Mass test object 1")) == pytest.approx(mass, rel=1e-5)
    codes = [c.code for c in t.channels]
    assert len(codes) == len(set(codes)), "every code once"
    byname = {}
    for c in t.channels:
        keys = [k for k, _ in c.header]
        assert all(k in keys for k in CHANNEL_FIELDS), (c.code, [k for k in CHANNEL_FIELDS if k not in keys])
        m = CODE.fullmatch(c.code)
        assert m, c.code
        assert hx.parse_code(c.code)["main location"] == m["loc"]
        assert c.get("Dimension") == m["dim"] and len(c.values) == len(time)
        assert float(c.get("First global maximum value")) == c.values.max()
        assert float(c.get("First global minimum value")) == c.values.min()
        byname[c.get("Laboratory channel code")] = c
    # what the file has: head, upper neck, T1, the lower neck from LNECK, the kinetic energy
    for name, code, sign in (("HEAD_AXL", "11HEAD0000VHACX0", 1), ("OC_MY", "11NECKUP00VHMOY0", 1),
                             ("OC_FX", "11NECKUP00VHFOX0", -1), ("T1_AX", "11THSP0100VHACX0", 1),
                             ("T1_AY", "11THSP0100VHACY0", -1), ("T1_THETY", "11THSP0100VHANY0", -1),
                             ("T1_DZ", "11THSP0100VHDSZ0", -1), ("LNECK_JFZ", "11NECKLO00VHFOZ0", 1),
                             ("LNECK_JMY", "11NECKLO00VHMOY0", 1), ("E_KINETIC", "11EKIN0000VHEN00", 1)):
        assert byname[name].code == code
        assert np.array_equal(byname[name].values, sign * chan[name]), name
    assert len([c for c in codes if c[2:10] == "NECKLO00"]) == 6
    assert byname["LNECK_JFZ"].unit == "N" and byname["LNECK_JMY"].unit == "Nm"
    assert byname["T1_DZ"].unit == "mm" and byname["T1_THETY"].get("Reference system") == "global"
    # every channel of the file is exported or listed as left out, with why
    coded, left = hx.iso_channels(loadcell_file)
    assert set(coded) | set(left) >= set(hr.read_channels(loadcell_file).columns)
    assert set(byname) == set(coded) and not set(coded) & set(left)
    assert "MIDC4_JFZ" in left and "no neck section" in left["MIDC4_JFZ"]
    assert "LNECK_FZ" in left and "HT1_RX" in left and "HEAD_AX" in left
    assert printed.count("left out") == 1 and "MIDC4_JFZ" in printed


def test_parse_code_refuses_what_the_code_list_lacks():
    assert hx.parse_code("11NECKLO00VHFOZB")["fine location 1"] == "LO"
    for bad in ("11NECKLO00VHFOZ", "11NECKMI00VHFOZ0", "11NECKLO00VHFQZ0", "11NECKLO00VHFOZK", "1xNECKLO00VHFOZ0"):
        with pytest.raises(ValueError):
            hx.parse_code(bad)
