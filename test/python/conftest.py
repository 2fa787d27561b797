"""Shared by the Python tests of the tools (test/python): the project's
package hhneck (python/hhneck: the one of the checkout's environment .venv
that tools/setup.sh makes and tools/test.sh uses, else python/ put first on
the import path), result files made by the program
from short decks (case 6-2 cut to 20 ms, and a lateral variant of
it), and the closing line "N passed, N failed" that tools/test.sh and CI
count. The executable is $HHNECK (tools/test.sh: the release build), else
fpm's debug build (built if needed)."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PACKAGE = os.path.join(ROOT, "python")


def use_project_package():
    """Import hhneck from this project: the installed package when it is
    python/hhneck of this tree (the checkout's .venv, tools/setup.sh), else
    python/ first on sys.path (not installed, or installed from another
    copy)."""
    try:
        import hhneck
        if os.path.dirname(os.path.dirname(os.path.abspath(hhneck.__file__))) == PACKAGE:
            return
    except ImportError:
        pass
    for name in [m for m in sys.modules if m == "hhneck" or m.startswith("hhneck.")]:
        del sys.modules[name]
    sys.path.insert(0, PACKAGE)


use_project_package()


def package_env():
    """The environment for a subprocess that runs `python3 -m hhneck.NAME`:
    this project's python/ first on PYTHONPATH."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([PACKAGE] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    return env


def hhneck_module(name, *args, cwd=ROOT, env=None):
    """Run `python3 -m hhneck.NAME ARGS` (this project's package) in cwd, with the variables of `env`
    added to the package's environment; the CompletedProcess."""
    return subprocess.run([sys.executable, "-m", "hhneck." + name] + [str(a) for a in args], cwd=cwd,
                          capture_output=True, text=True, env=dict(package_env(), **(env or {})))
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
SHORT_END = 0.02          # [s] end time of the short deck


def hhneck_executable():
    """The executable the tests run: $HHNECK, else fpm's debug build (absolute paths)."""
    exe = os.environ.get("HHNECK")
    if not exe:
        out = subprocess.run(["fpm", "run", "hhneck", "--runner", "echo"], cwd=ROOT, capture_output=True, text=True)
        lines = out.stdout.strip().splitlines()
        exe = lines[-1] if out.returncode == 0 and lines else ""
    if exe and not os.path.isabs(exe):
        exe = os.path.join(ROOT, exe)
    if not exe or not os.access(exe, os.X_OK):
        pytest.fail("no hhneck executable (set HHNECK or build with fpm): %r" % exe)
    return exe


def short_deck(lateral=False):
    """input/case6-2.inp with the CONTROL card's end time (F1, columns 11-20)
    20 ms. lateral: the impact turned sideways, a push on the left side of
    the head toward the subject's right: the FORCE card's direction (F4-F6)
    -y in R, its point (continuation card two lines below) 83 mm to the
    left of the head's mass centre (the ellipsoid's lateral semi-axis) and
    30 mm up as before, so the force bends the neck sideways and twists it
    not at all (r x F along x)."""
    with open(os.path.join(ROOT, "input", "case6-2.inp")) as f:
        lines = f.read().splitlines()
    out = []
    force = None
    for n, line in enumerate(lines):
        if line.startswith("CONTROL "):
            line = line[:10] + ("%-10s" % SHORT_END) + line[20:]
        if lateral and line.startswith("FORCE "):
            line, force = line[:40] + "%-10s%-10s%s" % ("0.0", "-1.0", "0.0"), n
        elif lateral and force is not None and n == force + 2:
            line = " " * 10 + "%-10s%-10s%s" % ("0.0", "0.083", "0.030")
        out.append(line)
    if lateral and force is None:
        pytest.fail("input/case6-2.inp has no FORCE card to turn sideways")
    return "\n".join(out) + "\n"


def run_short(tmp_path_factory, name, deck):
    """Run a deck text with the executable to NAME.h5 in a temporary directory; its path."""
    d = tmp_path_factory.mktemp("run")
    h5 = str(d / (name + ".h5"))
    r = subprocess.run([hhneck_executable(), "--h5", h5, "--no-progress"], input=deck, cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, "hhneck failed (exit %d): %s" % (r.returncode, r.stderr[-2000:])
    return h5


@pytest.fixture(scope="session")
def result_file(tmp_path_factory):
    """The result file of the short deck, written by the executable."""
    return run_short(tmp_path_factory, "short", short_deck())


@pytest.fixture(scope="session")
def lateral_file(tmp_path_factory):
    """The result file of the short deck turned lateral (short_deck(lateral=True))."""
    return run_short(tmp_path_factory, "lateral", short_deck(lateral=True))


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    s = terminalreporter.stats
    passed = len(s.get("passed", []))
    failed = len(s.get("failed", [])) + len(s.get("error", []))
    terminalreporter.write_line("%d passed, %d failed" % (passed, failed))
