"""The package works from any working directory (hhneck.paths): from an
empty temporary folder, every module of python/hhneck imports, every
console command of python/pyproject.toml answers --help, and real commands
find the project's decks and volunteer runs (a short deck run with its
INCLUDE of the shipped model deck, the NBDL 12 g T1 tables written again
from the shipped runs, equal to the shipped ones); a copy of the package
outside the project finds it through HHNECK_ROOT, and says so when
HHNECK_ROOT is not set; python3 -m hhneck.validation.case_decks writes the decks into the
project it is given."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import pytest

from conftest import PACKAGE, ROOT, SHORT_END, hhneck_executable, package_env, short_deck
from test_commands import COMMANDS


def package_modules():
    """Every module of python/hhneck and of its subpackages, named from
    hhneck ("paths", "tools", "tools.animate", "validation.catalogue", ...),
    found in the folders (not from the probe)."""
    out = []
    top = os.path.join(PACKAGE, "hhneck")
    for folder, dirs, files in os.walk(top):
        dirs[:] = sorted(d for d in dirs if os.path.isfile(os.path.join(folder, d, "__init__.py")))
        prefix = os.path.relpath(folder, top).replace(os.sep, ".")
        prefix = "" if prefix == "." else prefix + "."
        if prefix:
            out.append(prefix[:-1])
        out += [prefix + f[:-3] for f in files if f.endswith(".py") and f != "__init__.py"]
    return sorted(out)


MODULES = package_modules()


def python(code, cwd, env=None):
    """Run python3 -c CODE in cwd with this project's package first on the path; the CompletedProcess."""
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True,
                          env=env or package_env())


def module(name, *args, cwd, env=None):
    """Run python3 -m hhneck.NAME ARGS in cwd (this project's package); the CompletedProcess."""
    return subprocess.run([sys.executable, "-m", "hhneck." + name] + [str(a) for a in args], cwd=cwd,
                          capture_output=True, text=True, env=env or package_env())


# every module imported, and every command's main(["--help"]) called, in one
# process started in the folder: {module: error or ""}, {command: [exit code, usage printed]}
PROBE = r"""
import contextlib, importlib, io, json, sys
modules, commands = json.loads(sys.argv[1]), json.loads(sys.argv[2])
imported, helped = {}, {}
for m in modules:
    try:
        importlib.import_module("hhneck." + m)
        imported[m] = ""
    except Exception as e:
        imported[m] = "%s: %s" % (type(e).__name__, e)
for cmd, m in commands.items():
    out = io.StringIO()
    code = None
    try:
        with contextlib.redirect_stdout(out):
            importlib.import_module(m).main(["--help"])
    except SystemExit as e:
        code = e.code
    except Exception as e:
        code = "%s: %s" % (type(e).__name__, e)
    helped[cmd] = [code, out.getvalue().startswith("usage: " + cmd)]
print(json.dumps([imported, helped]))
"""


def probe(cwd, env=None):
    """PROBE run in cwd: ({module: error}, {command: [exit code, usage]})."""
    r = subprocess.run([sys.executable, "-c", PROBE, json.dumps(MODULES),
                        json.dumps({c: m for c, (m, _) in COMMANDS.items()})],
                       cwd=cwd, capture_output=True, text=True, env=env or package_env())
    assert r.returncode == 0, r.stderr[-2000:]
    return json.loads(r.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def elsewhere(tmp_path_factory):
    """An empty folder outside the project, and the probe run there."""
    d = str(tmp_path_factory.mktemp("elsewhere"))
    return d, probe(d)


def test_the_module_list():
    """The package's modules, counted from the folder (not from the probe)."""
    assert len(MODULES) >= 28 and "paths" in MODULES and "volunteers" in MODULES
    assert "tools.animate" in MODULES and "validation.catalogue" in MODULES and "validation" in MODULES


@pytest.mark.parametrize("name", MODULES)
def test_import(elsewhere, name):
    imported = elsewhere[1][0]
    assert imported[name] == "", "hhneck.%s does not import outside the project: %s" % (name, imported[name])


@pytest.mark.parametrize("cmd", sorted(COMMANDS))
def test_help(elsewhere, cmd):
    code, usage = elsewhere[1][1][cmd]
    assert code == 0 and usage, "%s --help outside the project: exit %r, usage printed: %s" % (cmd, code, usage)


def test_project_root(elsewhere):
    """hhneck.paths.project_root() is this tree (conftest's ROOT, found from the tests' place), seen from elsewhere."""
    r = python("from hhneck.paths import project_root, project_path; print(project_root()); "
               "print(project_path('input', 'case6-2.inp'))", elsewhere[0])
    assert r.returncode == 0, r.stderr
    root, deck = r.stdout.split()
    assert os.path.samefile(root, ROOT) and os.path.isfile(deck)


def test_run_a_shipped_deck_elsewhere(elsewhere, tmp_path):
    """hhneck-run-deck on case 6-2 cut to 20 ms, written in the folder: its
    INCLUDE input/head_neck_54dof.inp is the project's (the last directory
    of the include path), and the result file ends at 20 ms."""
    d = elsewhere[0]
    with open(os.path.join(d, "short.inp"), "w") as f:
        f.write(short_deck())
    env = package_env()
    env["HHNECK"] = hhneck_executable()
    r = module("run", "short.inp", "--h5", str(tmp_path / "short.h5"), "--listing", str(tmp_path / "short.txt"),
               cwd=d, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    with h5py.File(str(tmp_path / "short.h5"), "r") as f:
        t = f["time"][:]
    assert t[0] == 0.0 and abs(t[-1] - SHORT_END) < 1e-12
    assert os.path.getsize(str(tmp_path / "short.txt")) > 1000


def test_nbdl_runs_elsewhere(elsewhere):
    """hhneck.volunteers reads the project's 12 g runs (runs 1607-1617, n = 10,
    every 0.5 ms; reference/cases.md) from elsewhere."""
    r = python("from hhneck import volunteers; t, runs, cols = volunteers.runs('T1_XAccel', '12g'); "
               "print(runs.shape[0], t[1] - t[0], cols[0])", elsewhere[0])
    assert r.returncode == 0, r.stderr[-2000:]
    n, step, first = r.stdout.split()
    assert int(n) == 10 and float(step) == 0.5 and first.startswith("run_")


def test_nbdl_tables_elsewhere():
    """python3 -m hhneck.validation.nbdl_tables --data (the shipped 12 g runs) from elsewhere: it
    reads the project's input/nbdl12g.inp, and its T1 tables are those of
    the shipped input/nbdl12g_t1.inp, line for line."""
    d = tempfile.mkdtemp(prefix="hh")   # short: the INCLUDE card names it within 80 columns
    try:
        r = module("validation.nbdl_tables", "--data", os.path.join(ROOT, "reference", "nbdl_12g"), "--name", "again12",
                   "--into", d, cwd=d)
        assert r.returncode == 0, r.stderr[-2000:]

        def tables(path):
            with open(path) as f:
                return [l for l in f.read().splitlines() if not l.startswith("*")]
        again = tables(os.path.join(d, "again12_t1.inp"))
        assert again == tables(os.path.join(ROOT, "input", "nbdl12g_t1.inp")) and len(again) > 300
        with open(os.path.join(d, "again12.inp")) as f:
            assert "INCLUDE   %s" % os.path.join(d, "again12_t1.inp") in f.read()
    finally:
        shutil.rmtree(d)


@pytest.fixture(scope="module")
def copied(tmp_path_factory):
    """A copy of the package in a folder outside any project."""
    d = tmp_path_factory.mktemp("installed")
    shutil.copytree(os.path.join(PACKAGE, "hhneck"), str(d / "hhneck"),
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ)
    env.pop("HHNECK_ROOT", None)
    env["PYTHONPATH"] = str(d)
    return str(d), env


def test_copy_without_hhneck_root(copied):
    """Outside the project and without HHNECK_ROOT, project_root() says what to set."""
    d, env = copied
    r = python("import hhneck.paths as p; print(p.__file__); p.project_root()", d, env)
    assert r.stdout.startswith(d) and r.returncode != 0
    assert "FileNotFoundError" in r.stderr and "HHNECK_ROOT" in r.stderr


def test_copy_with_hhneck_root(copied):
    """With HHNECK_ROOT the copy finds the project: its modules import, and volunteers reads the 15 g runs (n = 7)."""
    d, env = copied
    env = dict(env, HHNECK_ROOT=ROOT)
    imported = probe(d, env)[0]
    assert imported == {m: "" for m in MODULES}
    r = python("from hhneck import paths, volunteers; print(paths.__file__); print(volunteers.runs('T1_XAccel', '15g')[1].shape[0])",
               d, env)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split() == [os.path.join(d, "hhneck", "paths.py"), "7"]


def test_copy_with_a_wrong_hhneck_root(copied, tmp_path):
    d, env = copied
    r = python("import hhneck.paths as p; p.project_root()", d, dict(env, HHNECK_ROOT=str(tmp_path)))
    assert r.returncode != 0 and "HHNECK_ROOT=%s: no hhneck fpm.toml there" % tmp_path in r.stderr


def test_case_decks_elsewhere(tmp_path):
    """python3 -m hhneck.validation.case_decks from elsewhere writes the decks of a project (HHNECK_ROOT: one made here, so that
    the tree's own decks are not rewritten) equal to the shipped ones."""
    proj = tmp_path / "proj"
    (proj / "input").mkdir(parents=True)
    os.symlink(os.path.join(ROOT, "fpm.toml"), str(proj / "fpm.toml"))
    os.symlink(os.path.join(ROOT, "reference"), str(proj / "reference"))
    (tmp_path / "elsewhere").mkdir()
    r = module("validation.case_decks", cwd=str(tmp_path / "elsewhere"), env=dict(package_env(), HHNECK_ROOT=str(proj)))
    assert r.returncode == 0, r.stderr[-2000:]
    for name in ("case6-1", "case6-2", "case6-5", "hybrid3_flexion"):
        with open(str(proj / "input" / (name + ".inp"))) as a, open(os.path.join(ROOT, "input", name + ".inp")) as b:
            assert a.read() == b.read(), name
