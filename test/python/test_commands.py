"""Every console command of the package (python/pyproject.toml,
[project.scripts]): its module has main(argv=None), `--help` works (as
`python3 -m hhneck.MODULE` and, when pip installed this project's package,
as the console command on PATH), and one real invocation of each on small
inputs whose numbers are known: result files of short decks, a small
sweep, and files made here from closed formulas.

hhneck-animate: test_animate_views.py; hhneck-run-deck: test_run_deck.py."""
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import pytest

from conftest import PACKAGE, ROOT, hhneck_executable, hhneck_module, short_deck
import hhneck.ratings as ratings


def scripts():
    """{command: (module, function)} of [project.scripts] in python/pyproject.toml."""
    with open(os.path.join(PACKAGE, "pyproject.toml")) as f:
        text = f.read()
    block = text.split("[project.scripts]", 1)[1].split("\n[", 1)[0]
    return {m.group(1): (m.group(2), m.group(3))
            for m in re.finditer(r'^(\S+)\s*=\s*"([\w.]+):(\w+)"', block, re.M)}


COMMANDS = scripts()


def test_the_command_table():
    """The user commands only (docs/architecture.md, "Python package"): the
    validation pipeline's steps run as python3 -m hhneck.validation.MODULE."""
    assert sorted(COMMANDS) == sorted("hhneck-" + n for n in (
        "animate", "xdmf", "compare-nbdl", "plot-sensitivity", "plot-corridor", "plot-work-precision", "export",
        "results", "iso18571", "compare-listing", "compare-sweeps", "run-deck", "catalogue"))
    for cmd, (module, func) in COMMANDS.items():
        assert module.startswith("hhneck.") and func == "main", cmd
        assert cmd == "hhneck-" + module.split(".")[-1].replace("_", "-") or (cmd, module) in (
            ("hhneck-run-deck", "hhneck.run"), ("hhneck-iso18571", "hhneck.ratings")), cmd
        assert module.count(".") == 1 or module.split(".")[1] in ("tools", "validation"), cmd


@pytest.mark.parametrize("cmd", sorted(COMMANDS))
def test_help(cmd):
    module = COMMANDS[cmd][0]
    r = hhneck_module(module.split(".", 1)[1], "--help")
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("usage: %s" % cmd), r.stdout[:200]


def test_console_commands_on_path():
    """When pip installed this project's package (tools/setup.sh), every
    command is on PATH as pip's launcher of its module's main (whose --help
    test_help runs), and a launcher runs: its interpreter imports this
    project's package."""
    r = subprocess.run([sys.executable, "-c", "import hhneck, os; print(os.path.realpath(hhneck.__file__))"],
                       cwd="/", capture_output=True, text=True)
    if r.returncode != 0 or os.path.dirname(os.path.dirname(r.stdout.strip())) != os.path.realpath(PACKAGE):
        pytest.skip("the package is not installed from this project (tools/setup.sh installs it)")
    for cmd, (module, func) in COMMANDS.items():
        path = shutil.which(cmd)
        assert path, "%s not on PATH" % cmd
        assert os.access(path, os.X_OK), path
        with open(path) as f:
            launcher = f.read()
        assert re.search(r"^from %s import %s$" % (re.escape(module), func), launcher, re.M), (cmd, launcher)
    h = subprocess.run([shutil.which("hhneck-results"), "--help"], capture_output=True, text=True, cwd="/")
    assert h.returncode == 0 and h.stdout.startswith("usage: hhneck-results"), h.stderr


# --- result files ------------------------------------------------------------

def test_results_summary(result_file):
    r = hhneck_module("results", result_file)
    assert r.returncode == 0, r.stderr
    with h5py.File(result_file, "r") as f:
        nch, nt = len(f["channels"].attrs["names"]), len(f["time"])
        assert nt == 201                                   # 0 to 20 ms every 0.1 ms
    assert "%d channels, %d samples from 0 s to 0.02 s" % (nch, nt) in r.stdout
    assert re.search(r"^HEAD\s+9\s+C1\s+8\s", r.stdout, re.M)                 # the bodies table


def test_export_csv_equals_the_datasets(result_file, tmp_path):
    out = tmp_path / "all.csv"
    r = hhneck_module("export", "csv", result_file, "-o", out)
    assert r.returncode == 0, r.stderr
    with open(out) as f:
        rows = list(csv.reader(f))
    with h5py.File(result_file, "r") as f:
        names = [str(n) for n in f["channels"].attrs["names"]]
        units = [str(u) for u in f["channels"].attrs["units"]]
        assert rows[0] == ["time [s]"] + ["%s [%s]" % nu for nu in zip(names, units)]
        data = np.array(rows[1:], dtype=float)
        assert data.shape == (len(f["time"]), len(names) + 1)
        assert np.allclose(data[:, 0], f["time"][:], rtol=1e-11, atol=0)
        for k, n in enumerate(names):
            assert np.allclose(data[:, k + 1], f["channels"][n][:], rtol=1e-11, atol=1e-300), n


def test_xdmf_nodes_are_the_bodies(result_file, tmp_path):
    import xml.etree.ElementTree as ET
    h5 = tmp_path / "r.h5"
    shutil.copy(result_file, h5)
    r = hhneck_module("tools.xdmf", h5, "--every", "0.005")
    assert r.returncode == 0, r.stderr
    assert "(5 time steps, 9 bodies," in r.stdout                          # 0, 5, 10, 15, 20 ms
    root = ET.parse(str(tmp_path / "r.xmf")).getroot()
    steps = root.find("Domain/Grid").findall("Grid")
    assert [float(g.find("Time").get("Value")) for g in steps] == pytest.approx([0, 0.005, 0.01, 0.015, 0.02])
    with h5py.File(h5, "r") as f:
        nb = f["bodies/position"].shape[1]
    for g in steps:
        bodies = [b for b in g.findall("Grid") if b.get("Name") == "bodies"][0]
        item = bodies.find("Geometry/DataItem")
        assert [int(v) for v in item.get("Dimensions").split()][:1] == [nb]


def test_compare_listing_itself_and_a_changed_number(result_file, tmp_path):
    listing = tmp_path / "a.txt"
    r = subprocess.run([hhneck_executable(), "--no-h5", "--no-progress"], input=short_deck(), cwd=ROOT,
                       capture_output=True, text=True)
    listing.write_text(r.stdout)
    ok = hhneck_module("tools.compare_listing", listing, listing)
    assert ok.returncode == 0 and ok.stdout.startswith("PASS") and "largest deviation 0.00 of the tolerance" in ok.stdout
    # the head's peak x-acceleration row of the peaks table, its maximum 10 % larger
    lines = r.stdout.splitlines()
    k = next(i for i, l in enumerate(lines) if re.match(r"^\s+HEAD_AX\s+g\s+\S+\s+\S+\s+\S+\s+\S+\s*$", l))
    f = lines[k].split()
    lines[k] = lines[k].replace(f[2], "%.4E" % (1.1 * float(f[2])), 1)
    bad = tmp_path / "b.txt"
    bad.write_text("\n".join(lines) + "\n")
    r = hhneck_module("tools.compare_listing", bad, listing)
    assert r.returncode == 1 and r.stdout.startswith("FAIL") and "line %d" % (k + 1) in r.stdout


def test_iso18571_identical_and_halved(tmp_path, capsys):
    """Identical curves rate 1 (the command in a process of its own); a
    curve halved rates what rate() gives (main() in this process: the
    package compiles its scoring on first use, some 15 s a process)."""
    from hhneck import ratings as iso18571
    t = np.arange(0, 0.02 + 1e-12, 1e-4)                                  # 201 samples at 10 kHz
    ref = np.sin(2 * np.pi * 50 * t) * np.exp(-50 * t)
    same = tmp_path / "same.csv"
    np.savetxt(same, np.column_stack([t, ref, ref]), delimiter=",")
    r = hhneck_module("ratings", same)
    assert r.returncode == 0, r.stderr
    scores = {k: float(v) for k, v in (l.split() for l in r.stdout.splitlines())}
    assert scores == {k: 1.0 for k in ("corridor", "phase", "magnitude", "slope", "overall")}
    half = tmp_path / "half.csv"
    np.savetxt(half, np.column_stack([t, ref, 0.5 * ref]), delimiter=",")
    want = iso18571.rate(t, ref, 0.5 * ref, window=(0.0, 0.015))
    assert iso18571.main([str(half), "0.0", "0.015"]) == 0
    got = {k: float(v) for k, v in (l.split() for l in capsys.readouterr().out.splitlines())}
    assert got["overall"] < 0.9
    assert got == pytest.approx(want, abs=1e-6)                            # printed with 6 decimals


# --- a small sweep: plot-sensitivity and compare-sweeps ---------------------------

@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    """An OAT sweep of case 6-2 cut to 10 ms, the head's mass +- 20 % (3 members)."""
    d = tmp_path_factory.mktemp("sweep")
    base = d / "base.inp"
    base.write_text(short_deck().replace("CONTROL   0.02      ", "CONTROL   0.01      "))
    deck = d / "sweep.inp"
    deck.write_text("TITLE     TEST SWEEP: HEAD MASS +- 20 %%\nBASE      %s\nDESIGN    OAT       20.0\n"
                    "PARAM     HEAD_M    BODY      HEAD      MASS\n" % base)
    h5 = str(d / "sweep.h5")
    r = subprocess.run([hhneck_executable(), "--sweep", "--h5", h5, "--no-progress", str(deck)], cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    return h5


def test_plot_sensitivity_table_is_the_file(sweep_file, tmp_path):
    png, md = tmp_path / "s.png", tmp_path / "s.md"
    r = hhneck_module("tools.plot_sensitivity", sweep_file, png, "--markdown", md)
    assert r.returncode == 0, r.stderr
    assert png.stat().st_size > 1000
    rows = [l.strip("|").split("|") for l in md.read_text().splitlines()]
    with h5py.File(sweep_file, "r") as f:
        outs = [str(o).strip() for o in f["runs/output_names"][()].astype(str)]
        coef, valid = f["sensitivity/coefficient"][()], f["sensitivity/valid"][()] == 1
        assert f["runs/status"].shape == (3,)
    assert [c.strip() for c in rows[0][1:]] == outs
    cells = [c.strip() for c in rows[2][1:]]
    assert rows[2][0].strip().startswith("HEAD_M")
    assert valid[:, 0].any()
    for k in range(len(outs)):
        assert cells[k] == ("%.3f" % coef[k, 0] if valid[k, 0] else "n/a"), outs[k]


def test_compare_sweeps(sweep_file, tmp_path):
    r = hhneck_module("tools.compare_sweeps", sweep_file, sweep_file, "--expect-failed", 0)
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.splitlines()[-1] == "13 passed, 0 failed"
    other = tmp_path / "other.h5"
    shutil.copy(sweep_file, other)
    with h5py.File(other, "a") as f:
        out = f["runs/outputs"][()]
        out[1, 0] = np.nextafter(out[1, 0], np.inf)                         # one ulp up
        f["runs/outputs"][...] = out
    r = hhneck_module("tools.compare_sweeps", sweep_file, other)
    assert r.returncode == 1 and "FAIL  runs/outputs identical" in r.stdout
    assert r.stdout.splitlines()[-1] == "8 passed, 1 failed"


# --- files made from closed formulas: compare-nbdl, plot-corridor, plot-work-precision

def test_compare_nbdl_model_against_itself(tmp_path):
    """Volunteer runs that are the model's own head x-acceleration times
    0.9, 1.0 and 1.1: their mean is the model, so its rating is 1 and its
    peak is the mean peak, (model - mean)/SD = 0; the peak is the formula's
    -20 g at 125 ms to within the CFC 60 filter's effect."""
    t = np.arange(0, 0.3 + 1e-12, 5e-4)
    ax = np.where((t > 0.05) & (t < 0.2), -20 * np.sin(np.pi * (t - 0.05) / 0.15) ** 2, 0.0)
    h5 = tmp_path / "model.h5"
    with h5py.File(h5, "w") as f:
        f["time"] = t
        for ch in ratings.MODEL.values():
            f["channels/" + ch] = ax if ch == "HEAD_AX" else np.zeros_like(t)
    runs = tmp_path / "runs"
    runs.mkdir()
    with open(runs / "Head_XAccel.csv", "w") as f:
        f.write("time_ms,run_1,run_2,run_3\n")
        for k in range(len(t)):
            f.write("%.1f,%.17g,%.17g,%.17g\n" % (1e3 * t[k], 0.9 * ax[k], ax[k], 1.1 * ax[k]))
    out = tmp_path / "out"
    r = hhneck_module("tools.compare_nbdl", "--data", "syn=%s" % runs, "--case", "syn", "--h5", "syn=%s" % h5,
                      "--out", out)
    assert r.returncode == 0, r.stderr
    row = [l for l in r.stdout.splitlines() if l.startswith("| head x-acceleration (g) |")][0]
    assert [c.strip() for c in row.strip("|").split("|")] == ["head x-acceleration (g)", "1.000", "1.000",
                                                               "**1.000**", "+0.0", "100 %", "1.000"]
    peak = [l for l in r.stdout.splitlines() if l.startswith("| x-acceleration (g) |")][0]
    cells = [c.strip() for c in peak.strip("|").split("|")]
    assert float(cells[1]) == pytest.approx(-20.0, rel=0.01) and cells[2] == "125"
    assert abs(float(cells[5])) < 0.005                                   # (model - mean)/SD printed +-0.00
    assert "(mean of the 1 rated head channels the runs have;" in r.stdout and "**1.000**" in r.stdout
    assert (out / "validation_table.md").read_text() + "\n" == r.stdout
    assert (out / "validation_nbdlsyn.png").stat().st_size > 1000


def test_plot_corridor_share_inside(tmp_path):
    """The volunteers' mean on the model's mean before 140 ms and 2 SD off
    after: inside the band for the samples from 30 to 139 ms of 30-250 ms."""
    t = np.arange(0, 300.0 + 1e-9, 1.0)
    cols = ["time_ms"]
    data = [t]
    for ch, _ in [("HEAD_AX", 0), ("HEAD_AZ", 0), ("HEAD_ALPHY", 0), ("HEAD_OMEGY", 0), ("HEAD_THETY", 0)]:
        mm = np.sin(t / 30.0)
        cols += [ch + "_model_mean", ch + "_model_sd", ch + "_vol_mean", ch + "_vol_sd"]
        data += [mm, np.ones_like(t), mm + np.where(t < 140, 0.0, 2.0), np.ones_like(t)]
    for sev in ("15g", "12g"):
        np.savetxt(tmp_path / ("c_nbdl%s.csv" % sev), np.column_stack(data), delimiter=",",
                   header=",".join(cols), comments="")
    r = hhneck_module("tools.plot_corridor", tmp_path / "c", tmp_path / "c.png")
    assert r.returncode == 0, r.stderr
    share = 100.0 * np.sum((t >= 30) & (t < 140)) / np.sum((t >= 30) & (t <= 250))     # 110 of 221 samples
    lines = r.stdout.splitlines()
    assert len(lines) == 10
    assert all(l.endswith("inside the model band %.1f %% of 30-250 ms" % share) for l in lines), lines[0]
    assert "%.1f" % share == "49.8"


def test_plot_work_precision(tmp_path):
    from PIL import Image
    from hhneck.tools import plot_work_precision as wp
    src = os.path.join(ROOT, "docs", "work_precision.csv")
    png = tmp_path / "wp.png"
    r = hhneck_module("tools.plot_work_precision", src, png)
    assert r.returncode == 0, r.stderr
    rows, cases = wp.read_rows(src)
    assert Image.open(png).size == (5 * len(cases) * 110, 8 * 110)
    lines = wp.curves(rows, cases[0])
    with open(src) as f:
        want = [r for r in csv.DictReader(f) if r["case"] == cases[0] and r["status"] == "ok"
                and float(r["err_theta_deg"]) > 0]
    assert sum(len(v) for v in lines.values()) == len(want) > 0


# --- the deck writers --------------------------------------------------------------

def test_case_decks_are_the_shipped_decks(tmp_path):
    """python3 -m hhneck.validation.case_decks writes into the project it is given (HHNECK_ROOT: one made here, so that the
    tree's own decks are not rewritten) the shipped decks, and nothing else."""
    (tmp_path / "input").mkdir()
    os.symlink(os.path.join(ROOT, "fpm.toml"), str(tmp_path / "fpm.toml"))
    r = hhneck_module("validation.case_decks", cwd=str(tmp_path), env={"HHNECK_ROOT": str(tmp_path)})
    assert r.returncode == 0, r.stderr
    written = sorted(os.listdir(tmp_path / "input"))
    assert written == ["case6-1.inp", "case6-2.inp", "case6-5.inp", "hybrid3_flexion.inp"]
    for name in written:
        with open(os.path.join(ROOT, "input", name)) as f:
            assert (tmp_path / "input" / name).read_text() == f.read(), name


@pytest.fixture
def short_dir():
    """A temporary directory with a short path (the deck's INCLUDE card names it within 80 columns)."""
    d = tempfile.mkdtemp(prefix="hh")
    yield d
    shutil.rmtree(d)


def test_nbdl_tables_of_the_shipped_12g_runs(short_dir):
    """--data with the shipped 12 g runs: the T1 tables of input/nbdl12g_t1.inp."""
    tmp_path = short_dir
    r = hhneck_module("validation.nbdl_tables", "--data", os.path.join("reference", "nbdl_12g"), "--name", "again12",
                      "--into", tmp_path)
    assert r.returncode == 0, r.stderr
    assert "read as rad" in r.stderr

    def tables(path):
        with open(path) as f:
            return [l for l in f.read().splitlines() if not l.startswith("*")]
    again = tables(os.path.join(tmp_path, "again12_t1.inp"))
    assert again == tables(os.path.join(ROOT, "input", "nbdl12g_t1.inp")) and len(again) > 300
