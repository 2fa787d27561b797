"""hhneck.results and the schema-2 result file (docs/output-format.md),
on the result file of a short deck written by the debug build: lists as
UTF-8 string arrays that h5py reads as str, an integer schema_version, and
the reader's DataFrames against the deck and the file as h5py reads it."""
import os

import h5py
import numpy as np
import pytest

import hhneck.results as hr
from conftest import ROOT, SHORT_END


def deck_bodies():
    """(name, parent, mass, Ixx, Iyy, Izz) of the BODY cards of the shipped model deck, in order."""
    out = []
    with open(os.path.join(ROOT, "input", "head_neck_54dof.inp")) as f:
        for line in f:
            if line.startswith("BODY "):
                fields = [line[k:k + 10].strip() for k in range(10, 70, 10)]
                out.append((fields[0], fields[1]) + tuple(float(x) for x in fields[2:6]))
    return out


def utf8_str_list(obj, name):
    t = obj.attrs.get_id(name).get_type()
    assert isinstance(t, h5py.h5t.TypeStringID) and t.get_cset() == h5py.h5t.CSET_UTF8, name + " is UTF-8 text"
    a = obj.attrs[name]
    assert isinstance(a, np.ndarray) and a.ndim == 1, name + " is an array"
    assert all(type(x) is str for x in a), name + " reads as str"
    return list(a)


def test_schema_version_is_the_integer_2(result_file):
    with h5py.File(result_file, "r") as f:
        v = f.attrs["schema_version"]
        assert isinstance(v, np.integer) and v.shape == () and v == 2


def test_list_attributes_are_utf8_string_arrays(result_file):
    with h5py.File(result_file, "r") as f:
        assert utf8_str_list(f["model"], "bodies") == [b[0] for b in deck_bodies()]
        coords = utf8_str_list(f["model"], "coordinates")
        assert len(coords) == f["coordinates/x"].shape[1] and coords[:3] == ["T1.tx", "T1.ty", "T1.tz"]
        assert utf8_str_list(f["coordinates/x"], "columns") == coords
        assert set(utf8_str_list(f["coordinates/x"], "column_units")) == {"m", "rad"}
        assert utf8_str_list(f["injury/nij"], "modes") == ["NTE", "NTF", "NCE", "NCF"]
        names = utf8_str_list(f["channels"], "names")
        assert sorted(names) == sorted(f["channels"].keys())
        assert utf8_str_list(f["channels"], "units") == [f["channels"][n].attrs["units"] for n in names]


def test_element_names_are_utf8_strings_without_padding(result_file):
    with h5py.File(result_file, "r") as f:
        ds = f["model/elements/discs/name"]
        assert h5py.check_string_dtype(ds.dtype).encoding == "utf-8"
        assert list(ds.asstr()[:]) == ["T1C7", "C7C6", "C6C5", "C5C4", "C4C3", "C3C2", "C2C1", "C1HD"]


def test_read_channels_time_index_units_and_values(result_file):
    df = hr.read_channels(result_file, ["OC_FZ", "HEAD_AX"])
    assert list(df.columns) == ["OC_FZ", "HEAD_AX"]
    assert df.index.name == "time"
    # the deck samples every 1E-4 s (OUTPUT card) from 0 to the end time
    assert len(df) == round(SHORT_END / 1e-4) + 1
    assert df.index[0] == 0.0 and abs(df.index[-1] - SHORT_END) < 1e-12
    assert np.allclose(np.diff(df.index), 1e-4, rtol=1e-9, atol=0)
    assert df.attrs["units"] == {"OC_FZ": "N", "HEAD_AX": "g"}
    assert df.attrs["schema_version"] == 2
    with h5py.File(result_file, "r") as f:
        assert np.array_equal(df["OC_FZ"].to_numpy(), f["channels/OC_FZ"][:])
    # at rest at the start the head's weight compresses the neck: OC_FZ = -m g (HEAD 3.847 kg)
    assert abs(df["OC_FZ"].iloc[0] + 3.847 * 9.80665) < 0.02 * 3.847 * 9.80665


def test_read_channels_all_in_the_files_order(result_file):
    df = hr.read_channels(result_file)
    with h5py.File(result_file, "r") as f:
        assert list(df.columns) == list(f["channels"].attrs["names"])
    assert df.columns[0] == "HEAD_AX"         # the listing's first channel
    assert df.shape[1] == len(df.attrs["units"])


def test_unknown_channel_is_named():
    with pytest.raises(KeyError, match="NO_SUCH"):
        hr.read_channels(os.path.join(ROOT, "reference", "outputs", "case6-1.h5"), ["OC_FZ", "NO_SUCH"])


def test_reads_a_reference_file_of_schema_1(tmp_path):
    # the reference files before schema 2: /channels one (nt, nch) dataset, names
    # and units one space-separated text each (units with '_' for blanks), no
    # schema_version; written here in that layout from two channels of the
    # NBDL 15 g reference (the references are now of schema 2)
    new = hr.read_channels(os.path.join(ROOT, "reference", "outputs", "nbdl15g.h5"), ["OC_MY", "HEAD_AX"])
    path = tmp_path / "schema1.h5"
    with h5py.File(path, "w") as f:
        f.attrs["code"] = "HHNECK 0.3.0"
        f["time"] = new.index.to_numpy()
        f["channels"] = new[["OC_MY", "HEAD_AX"]].to_numpy()
        f["channels"].attrs["names"] = np.bytes_("OC_MY HEAD_AX")
        f["channels"].attrs["units"] = np.bytes_("N_m g")
    df = hr.read_channels(str(path), ["HEAD_AX", "OC_MY"])
    assert df.attrs["schema_version"] == 1
    assert df.attrs["units"] == {"OC_MY": "N m", "HEAD_AX": "g"}
    assert new.attrs["schema_version"] == 2 and new.attrs["units"] == df.attrs["units"]
    assert np.array_equal(df["OC_MY"].to_numpy(), new["OC_MY"].to_numpy())
    assert np.array_equal(df["HEAD_AX"].to_numpy(), new["HEAD_AX"].to_numpy())
    assert np.array_equal(df.index.to_numpy(), new.index.to_numpy())


def test_read_bodies_as_the_deck_says(result_file):
    df = hr.read_bodies(result_file)
    want = deck_bodies()
    assert list(df.index) == [b[0] for b in want]
    assert list(df["parent"]) == [b[1] for b in want]
    assert list(df["number"]) == list(range(1, len(want) + 1))
    assert list(df["parent_number"]) == list(range(0, len(want)))      # a chain T1 <- C7 <- ... <- HEAD
    assert np.allclose(df["mass"], [b[2] for b in want], rtol=1e-12)
    assert np.allclose(df[["Ixx", "Iyy", "Izz"]].to_numpy(), [b[3:6] for b in want], rtol=1e-12)


def test_read_injury_rows_match_the_file(result_file):
    df = hr.read_injury(result_file)
    assert list(df.index) == ["HIC15", "HIC36", "NIJ_NTE", "NIJ_NTF", "NIJ_NCE", "NIJ_NCF", "NIC", "TENSION",
                              "COMPRESSION", "SHEAR", "FLEXION_MOMENT", "EXTENSION_MOMENT"]
    with h5py.File(result_file, "r") as f:
        assert df.loc["HIC15", "value"] == f["injury/hic15/value"][()]
        assert df.loc["HIC15", "t_end"] - df.loc["HIC15", "t_start"] <= 0.015 + 1e-12
        assert df.loc["NIJ_NCE", "value"] == f["injury/nij/value"][2]
        assert df.loc["COMPRESSION", "value"] == f["injury/compression/value"][()]
        # the compression peak is the lowest filtered OC_FZ, at its time
        fz = f["injury/history/oc_fz_cfc600"][:]
        t = f["time"][:]
        assert df.loc["COMPRESSION", "value"] == pytest.approx(fz.min())
        assert df.loc["COMPRESSION", "time"] == pytest.approx(t[np.argmin(fz)])
    assert df.loc["TENSION", "units"] == "N" and df.loc["EXTENSION_MOMENT", "units"] == "N m"
    assert np.isnan(df.loc["TENSION", "t_start"])


def test_main_prints_a_summary(result_file, capsys):
    assert hr.main([result_file]) == 0
    out = capsys.readouterr().out
    assert "schema version 2" in out and "HEAD" in out and "HIC15" in out
