"""pytest set-up of the Python tests (tools/test.sh runs them): the tools
folder on the import path, and the closing line "N passed, N failed" that
every test program of the project prints."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))


def pytest_terminal_summary(terminalreporter):
    """The project's closing line after pytest's own summary."""
    stats = terminalreporter.stats
    passed = len(stats.get("passed", []))
    failed = len(stats.get("failed", [])) + len(stats.get("error", []))
    terminalreporter.write_line("%d passed, %d failed" % (passed, failed))
