"""hhneck.export (hhneck-export): the hand-made ISO-MME example folder
(test/python/data/mme_example, ISO-MME 1.6, two channels) read as written,
written and read back equal, SAE J211 signs on known vectors, the ISO-MME
folder and the CSV file of the short deck's result file."""
import csv
import os

import h5py
import numpy as np
import pytest

import hhneck.export as hx
from conftest import DATA

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
    assert t.name == "SHORT" and t.get("Version") == "1.6"
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
    assert hx.main(["mme", result_file, "-o", str(tmp_path / "X"), "--channels", "OC_FZ,E_KINETIC"]) == 1
    assert "no ISO-MME code for E_KINETIC" in capsys.readouterr().err
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
