"""hhneck.run.run_deck against a direct run of the executable with the same
deck and the same --change options: the same listing (but for the lines
that name the machine's time: page headers with the date, the wall time)
and bitwise the same channels; change_card's columns; a failing run raises
RunError with the exit code; hhneck-run-deck on the command line."""
import os
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import ROOT, hhneck_executable, hhneck_module, package_env
from hhneck import run

END = "CHANGE    TEND      FIELD1    CONTROL             SET       0.01"     # 10 ms
MASS = "CHANGE    HEADMASS  BODY      HEAD      MASS      SCALE     1.1"


def machine_free(listing):
    """The listing without the lines that depend on when and how fast it ran."""
    return [l for l in listing.splitlines() if not l.startswith("1HHNECK") and "HHNECK " not in l
            and "WALL TIME" not in l and "wall time" not in l]


@pytest.fixture(scope="module")
def direct(tmp_path_factory):
    """case 6-2 with both changes, run directly: (listing, result file)."""
    h5 = str(tmp_path_factory.mktemp("direct") / "direct.h5")
    r = subprocess.run([hhneck_executable(), "--no-progress", "--h5", h5, "--change", END, "--change", MASS,
                        "input/case6-2.inp"], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout, h5


def test_change_card_columns():
    card = run.change_card("HEADMASS", "BODY", "HEAD", "MASS", "SCALE", 1.1)
    assert card == MASS
    assert run.change_card("TEND", "FIELD1", "CONTROL", "", "SET", 0.01) == END
    assert card.index("SCALE") == 50 and card.index("1.1") == 60          # F5 columns 51-60, F6 61-70
    with pytest.raises(run.CardError, match="wider than the 10 columns"):
        run.change_card("A_VERY_LONG_NAME", "BODY", "HEAD", "MASS", "SCALE", 1.1)


def test_run_deck_equals_direct_run(direct, tmp_path):
    listing, h5 = direct
    r = run.run_deck("input/case6-2.inp", changes=[("TEND", "FIELD1", "CONTROL", "", "SET", 0.01), MASS],
                     executable=hhneck_executable(), h5=str(tmp_path / "api.h5"), cwd=ROOT)
    assert r.returncode == 0 and r.h5 == str(tmp_path / "api.h5")
    assert r.command[-5:] == ["--change", END, "--change", MASS, "input/case6-2.inp"]
    a, b = machine_free(r.listing), machine_free(listing)
    assert len(a) > 100 and a == b
    assert any("HEADMASS" in l for l in a)                                  # the change is noted in the listing
    ch = r.channels()
    whole = r.results()
    assert whole.channels.equals(ch) and whole.title == ch.attrs["title"] and whole.schema_version == 2
    assert whole.bodies.loc["HEAD", "number"] == 9 and "HIC15" in whole.injury.index
    assert ch.index[-1] == pytest.approx(0.01, abs=1e-12) and ch.attrs["units"]["HEAD_AX"] == "g"
    with h5py.File(h5, "r") as f:
        assert list(ch.columns) == [n.decode() if isinstance(n, bytes) else n for n in f["channels"].attrs["names"]]
        for name in ("HEAD_AX", "HEAD_THETY", "OC_FX", "OC_MY"):
            assert np.array_equal(ch[name].to_numpy(), f["channels"][name][:]), name
        mass = f["model/mass"][:]
        head = list(f["model"].attrs["bodies"]).index("HEAD")
    with h5py.File(r.h5, "r") as g:
        assert np.array_equal(g["model/mass"][:], mass)
    # without the mass change: the head's mass is the run's divided by 1.1, the other bodies' the same
    plain = run.run_deck("input/case6-2.inp", changes=[END], executable=hhneck_executable(),
                         h5=str(tmp_path / "plain.h5"), cwd=ROOT)
    assert "HEADMASS" not in plain.listing
    with h5py.File(plain.h5, "r") as g:
        m0 = g["model/mass"][:]
    assert mass[head] == pytest.approx(1.1 * m0[head], rel=1e-15)
    assert np.array_equal(np.delete(mass, head), np.delete(m0, head))
    nothing = run.run_deck("input/case6-2.inp", changes=[END], executable=hhneck_executable(), h5=False, cwd=ROOT)
    assert nothing.h5 is None and "--no-h5" in nothing.command


def test_run_deck_text_and_temporary_file():
    with open(os.path.join(ROOT, "input", "case6-2.inp")) as f:
        text = f.read()
    r = run.run_deck(text, changes=[END], executable=hhneck_executable(), cwd=ROOT)
    assert os.path.basename(r.h5) == "deck.h5" and os.path.isfile(r.h5)
    assert r.channels(["HEAD_THETY"]).shape == (101, 1)                     # 0 to 10 ms every 0.1 ms


def test_run_deck_failure_raises():
    bad = "CHANGE    NOSUCH    BODY      NECK      MASS      SCALE     1.1"
    with pytest.raises(run.RunError) as e:
        run.run_deck("input/case6-2.inp", changes=[END, bad], executable=hhneck_executable(), cwd=ROOT)
    assert e.value.returncode == 2 and "--change 2" in e.value.stderr
    r = run.run_deck("input/case6-2.inp", changes=[END, bad], executable=hhneck_executable(), cwd=ROOT,
                     check=False)
    assert r.returncode == 2


def test_executable_from_environment(monkeypatch):
    monkeypatch.setenv("HHNECK", hhneck_executable())
    assert run.find_executable() == hhneck_executable()
    monkeypatch.setenv("HHNECK", os.path.join(ROOT, "no-such-hhneck"))
    with pytest.raises(FileNotFoundError, match="no hhneck executable"):
        run.find_executable()


def test_command_line(direct, tmp_path):
    listing, _ = direct
    out = tmp_path / "cli.h5"
    env = package_env()
    env["HHNECK"] = hhneck_executable()
    r = subprocess.run([sys.executable, "-m", "hhneck.run", "input/case6-2.inp", "--change", END,
                        "--change", MASS, "--h5", str(out)], cwd=ROOT, capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    assert machine_free(r.stdout) == machine_free(listing)
    assert "wrote %s (" % out in r.stderr and "101 samples to 0.01 s" in r.stderr
    assert hhneck_module("run", "--help").stdout.startswith("usage: hhneck-run-deck")
