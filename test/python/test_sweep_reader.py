"""hhneck.results.read_sweep / read_sensitivity and hhneck-plot-sensitivity
on two real small sweeps run by the program (docs/sweeps.md): the NBDL
15 g frontal deck and the 7 g lateral deck, each a 2 x 2 factorial of the
run's end time (a FIELD parameter, CONTROL F1) and the head's mass (a BODY
scale factor): 4 members of 120 or 150 ms.

Independent truth: the design (the four corners of the factorial), the
sweep file as h5py reads it, the units the sweep deck implies (a scale
factor is 1, a CONTROL F1 value is in that field's units), the listing's
own member table (printed to 4 significant digits), and the physics of the
two sleds (a frontal sled turns the head about y, a lateral one about x,
so the sensitivity plot picks the sagittal or the lateral set of outputs)."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import hhneck.tools.plot_sensitivity as ps
import hhneck.results as hr
from conftest import ROOT, hhneck_executable


def sweep_deck(base):
    return ("TITLE     TEST SWEEP OF %s\n" % base.upper() +
            "BASE      input/%s.inp\n" % base +
            "DESIGN    FACTORIAL 2\n"
            "PARAM     TEND      FIELD1    CONTROL             0.12      0.15\n"
            "PARAM     HEAD_M    BODY      HEAD      MASS      0.9       1.1\n")


@pytest.fixture(scope="module")
def sweeps(tmp_path_factory):
    """{base: (sweep file, listing text)} for nbdl15g and lateral7g."""
    d = tmp_path_factory.mktemp("sweep")
    out = {}
    for base in ("nbdl15g", "lateral7g"):
        h5 = str(d / (base + ".h5"))
        r = subprocess.run([hhneck_executable(), "--sweep", "--h5", h5], input=sweep_deck(base), cwd=ROOT,
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr[-2000:]
        out[base] = (h5, r.stdout)
    return out


def listing_rows(text, title):
    """{run: [values]} of the listing's member table under `title`."""
    lines = text.splitlines()
    k = next(n for n, line in enumerate(lines) if line.startswith(title))
    rows = {}
    for line in lines[k + 4:]:
        w = line.split()
        if len(w) < 3 or not w[0].isdigit():
            break
        rows[int(w[0])] = [float(x) for x in w[2:]]
    return rows


def test_read_sweep_members_and_units(sweeps):
    h5, listing = sweeps["nbdl15g"]
    df = hr.read_sweep(h5)
    assert list(df.index) == [1, 2, 3, 4] and df.index.name == "run"
    assert df.attrs["parameters"] == ["TEND", "HEAD_M"] and len(df.attrs["outputs"]) == 31
    assert df.attrs["design"] == "FACTORIAL" and df.attrs["what"]["HEAD_M"] == "BODY HEAD MASS"
    # the four corners of the 2 x 2 factorial
    assert sorted(zip(df["TEND"], df["HEAD_M"])) == [(0.12, 0.9), (0.12, 1.1), (0.15, 0.9), (0.15, 1.1)]
    u = df.attrs["units"]
    assert (u["TEND"], u["HEAD_M"]) == ("units of CONTROL F1", "1")
    assert (u["THETA_PEAK"], u["OC_FLEX"], u["NIC"], u["HIC15"], u["NIJ"]) == ("deg", "N m", "m^2/s^2", "1", "1")
    assert (u["wall"], u["t_reached"], u["status"]) == ("s", "s", "1")
    assert list(df["status"]) == [0, 0, 0, 0] and np.allclose(df["t_reached"], df["TEND"], rtol=1e-9)
    # a member cannot peak after its end: THETA_TIME [ms] within TEND [s]
    assert np.all(df["THETA_TIME"] <= 1000 * df["TEND"] + 1e-9)
    with h5py.File(h5, "r") as f:
        assert np.array_equal(df[df.attrs["outputs"]].to_numpy(), f["runs/outputs"][()])
        assert np.array_equal(df[["TEND", "HEAD_M"]].to_numpy(), f["runs/inputs"][()])
        # the units as the program wrote them
        assert list(f["runs/outputs"].attrs["column_units"]) == [u[o] for o in df.attrs["outputs"]]
        assert f["runs/outputs"].attrs["units"] == "per column in column_units"
        assert list(f["params/low"].attrs["column_units"]) == ["units of CONTROL F1", "1"]
        assert f["runs/wall"].attrs["units"] == "s" and f["sensitivity/coefficient"].attrs["units"] == "1"
    # the listing's member table, 4 significant digits
    rows = listing_rows(listing, " MEMBER RUNS: SAGITTAL OUTPUTS")
    shown = ["THETA_PEAK", "THETA_TIME", "ALPHA_PEAK", "OC_TENSION", "OC_SHEAR", "OC_FLEX", "OC_EXT", "NIJ"]
    for run, vals in rows.items():
        assert np.allclose(vals, df.loc[run, shown].to_numpy(dtype=float), rtol=6e-4, atol=0), run
    assert len(rows) == 4


def test_read_sensitivity_against_the_file(sweeps):
    h5 = sweeps["nbdl15g"][0]
    s = hr.read_sensitivity(h5)
    with h5py.File(h5, "r") as f:
        coef, valid = f["sensitivity/coefficient"][()], f["sensitivity/valid"][()] == 1
    assert list(s.index) == ["TEND", "HEAD_M"] and s.shape == (2, 31)
    assert np.array_equal(np.isnan(s.to_numpy()), ~valid.T)
    assert np.array_equal(s.to_numpy()[valid.T], coef.T[valid.T])
    assert "regression" in s.attrs["method"] and set(s.attrs["r2"]) == set(s.columns)


def test_each_reader_refuses_the_other_kind_of_file(sweeps, result_file):
    h5 = sweeps["nbdl15g"][0]
    for reader in (hr.read_channels, hr.read_bodies, hr.read_injury, hr.read_results):
        with pytest.raises(hr.FileKindError, match="sweep result file.*read_sweep"):
            reader(h5)
    for reader in (hr.read_sweep, hr.read_sensitivity):
        with pytest.raises(hr.FileKindError, match="not a sweep's.*read_channels"):
            reader(result_file)


def test_results_command_summarises_a_sweep(sweeps, capsys):
    assert hr.main([sweeps["lateral7g"][0]]) == 0
    out = capsys.readouterr().out
    assert "(sweep, FACTORIAL design" in out and "4 members (0 failed), parameters: TEND, HEAD_M" in out


@pytest.mark.parametrize("base, direction, must", [
    ("nbdl15g", "sagittal", ["THETA_PEAK", "OC_FLEX", "NIJ", "NIC"]),
    ("lateral7g", "lateral", ["HEAD_RX_PEAK", "OC_MX_PEAK", "NIC"])])
def test_sensitivity_plot_shows_nic_and_the_direction_criteria(sweeps, tmp_path, capsys, base, direction, must):
    h5 = sweeps[base][0]
    sw = hr.read_sweep(h5)
    # the head turns about y in the frontal sled, about x in the lateral one
    rx, ry = np.median(np.abs(sw["HEAD_RX_PEAK"])), np.median(np.abs(sw["HEAD_RY_PEAK"]))
    assert (rx > 2 * ry) if direction == "lateral" else (ry > 2 * rx)
    png = str(tmp_path / "s.png")
    assert ps.main([h5, png, "--markdown", str(tmp_path / "s.md")]) == 0
    line = capsys.readouterr().out.splitlines()[0]
    assert line.startswith("wrote %s (%s: " % (png, direction))
    shown = line.split(": ", 1)[1].rstrip(")").split(", ")
    assert all(o in shown for o in must), shown
    assert set(shown) <= set(ps.SHOWN[direction]) and os.path.getsize(png) > 10000
    # the table has NIC's column, one row per parameter and the regression's R^2
    md = open(tmp_path / "s.md").read().splitlines()
    assert "| NIC |" in md[0] and len(md) == 2 + 2 + 1 and md[-1].startswith("| R^2 |")


def test_outputs_without_a_sensitivity_are_left_out():
    outs = ["THETA_PEAK", "NIC", "HIC15", "NIJ"]
    valid = np.array([[True, False], [False, False], [True, True], [False, True]])
    assert ps.shown_outputs(outs, valid, "sagittal") == (["THETA_PEAK", "NIJ", "HIC15"], ["NIC"])
    # forced direction: the lateral set, of which the file has HIC15 and NIC
    assert ps.shown_outputs(outs, valid, "lateral") == (["HIC15"], ["NIC"])
