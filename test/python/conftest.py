"""Shared by the Python tests of the tools (test/python): the tools/ folder
on the import path, a result file made by the debug build from a short deck
(case 6-2 cut to 20 ms), and the closing line "N passed, N failed" that
tools/test.sh and CI count. The executable is $HHNECK, else fpm's debug
build (built if needed)."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
SHORT_END = 0.02          # [s] end time of the short deck


def hhneck_executable():
    exe = os.environ.get("HHNECK")
    if not exe:
        out = subprocess.run(["fpm", "run", "--runner", "echo"], cwd=ROOT, capture_output=True, text=True)
        lines = out.stdout.strip().splitlines()
        exe = lines[-1] if out.returncode == 0 and lines else ""
    if exe and not os.path.isabs(exe):
        exe = os.path.join(ROOT, exe)
    if not exe or not os.access(exe, os.X_OK):
        pytest.fail("no hhneck executable (set HHNECK or build with fpm): %r" % exe)
    return exe


def short_deck():
    """input/case6-2.inp with the CONTROL card's end time (F1, columns 11-20) 20 ms."""
    with open(os.path.join(ROOT, "input", "case6-2.inp")) as f:
        lines = f.read().splitlines()
    out = []
    for line in lines:
        if line.startswith("CONTROL "):
            line = line[:10] + ("%-10s" % SHORT_END) + line[20:]
        out.append(line)
    return "\n".join(out) + "\n"


@pytest.fixture(scope="session")
def result_file(tmp_path_factory):
    """The result file of the short deck, written by the debug build."""
    d = tmp_path_factory.mktemp("run")
    h5 = str(d / "short.h5")
    r = subprocess.run([hhneck_executable(), "--h5", h5, "--no-progress"], input=short_deck(), cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, "hhneck failed (exit %d): %s" % (r.returncode, r.stderr[-2000:])
    return h5


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    s = terminalreporter.stats
    passed = len(s.get("passed", []))
    failed = len(s.get("failed", [])) + len(s.get("error", []))
    terminalreporter.write_line("%d passed, %d failed" % (passed, failed))
