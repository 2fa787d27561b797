"""The catalogue command (python/hhneck/validation/catalogue.py) as a user runs it:
its report goes outside the project's docs unless asked, its folders are
made and checked before any run, its report is rewritten as each case ends
so that a failed case or an interruption keeps what was done, a progress
line per case goes to stderr, and the runs' warnings reach the report.
The run here is the quick form (test_segments runs it complete) through a
wrapper of the executable that fails chosen cases and adds a warning."""
import hashlib
import os
import re
import stat
import sys

import numpy as np
import pytest

from conftest import hhneck_executable
from hhneck.validation import catalogue, segments, specimens

DOCS = os.path.join(segments.ROOT, "docs")
WARNING = "hhneck: WARNING: 1 joint rotation(s) past the physiological range plus margin; largest: simulated"


def _docs_state():
    """{file: (mtime, sha1)} of everything under the project's docs."""
    out = {}
    for d, _, files in os.walk(DOCS):
        for name in files:
            path = os.path.join(d, name)
            with open(path, "rb") as f:
                out[path] = (os.stat(path).st_mtime_ns, hashlib.sha1(f.read()).hexdigest())
    return out


def _wrapper(path, real):
    """An executable that runs the real hhneck, but fails the Kang side and
    NBDL decks (exit 4, a line on stderr) and adds a warning line to the
    Stemper run's stderr."""
    path.write_text("""#!%s
import subprocess, sys
args = sys.argv[1:]
decks = [a for a in args if a.endswith(".inp")]
deck = open(decks[-1]).read() if decks else sys.stdin.read()
if "KANG 2018 SIDE" in deck or any("nbdl" in d for d in decks):
    sys.stderr.write("hhneck: simulated failure of this case\\n")
    sys.exit(4)
r = subprocess.run([%r] + args, input=None if decks else deck, capture_output=True, text=True)
sys.stdout.write(r.stdout)
sys.stderr.write(r.stderr)
if "STEMPER 2004" in deck:
    sys.stderr.write(%r + "\\n")
sys.exit(r.returncode)
""" % (sys.executable, real, WARNING))
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return str(path)


def test_report_path_stays_out_of_the_docs_unless_asked(tmp_path):
    assert catalogue.report_path(cwd=str(tmp_path)) == str(tmp_path / "catalogue" / "catalogue.md")
    assert catalogue.report_path(update_docs=True) == os.path.join(DOCS, "catalogue.md")
    assert catalogue.report_path(os.path.join(DOCS, "catalogue.md"), update_docs=True) == \
        os.path.join(DOCS, "catalogue.md")
    assert catalogue.report_path("x/r.md") == os.path.abspath("x/r.md")
    with pytest.raises(ValueError, match="inside the project's docs"):
        catalogue.report_path(cwd=DOCS)
    with pytest.raises(ValueError, match="another file"):
        catalogue.report_path(str(tmp_path / "r.md"), update_docs=True)


def test_a_report_folder_that_cannot_be_made_stops_before_any_run(tmp_path, capsys):
    """A report under a plain file: exit 2 at once with the folder named,
    the executable never called, nothing written."""
    (tmp_path / "plain").write_text("a file, not a folder\n")
    called = tmp_path / "called"
    exe = tmp_path / "exe"
    exe.write_text("#!/bin/sh\ntouch %s\n" % called)
    exe.chmod(0o755)
    assert catalogue.main(["--quick", "--exe", str(exe), "--report", str(tmp_path / "plain" / "sub" / "r.md"),
                           "--out", str(tmp_path / "work")]) == 2
    err = capsys.readouterr().err
    assert "cannot write the report folder" in err and str(tmp_path / "plain" / "sub") in err
    assert not called.exists() and not (tmp_path / "work").exists()


def test_failed_cases_keep_the_others_warnings_and_the_docs(tmp_path, monkeypatch, capsys):
    """The quick catalogue from a scratch folder with no report option: the
    report is catalogue/catalogue.md there (the folder made), nothing under
    the project's docs changes; the Kang side and NBDL runs fail, the other
    cases are in the report with a line naming what failed (exit 1); the
    warning the Stemper run printed on its stderr is in the report; one
    progress line per case on stderr."""
    before = _docs_state()
    exe = _wrapper(tmp_path / "hhneck-wrapper", hhneck_executable())
    monkeypatch.chdir(tmp_path)
    assert catalogue.main(["--quick", "--exe", exe, "--out", str(tmp_path / "work"), "--jobs", "2"]) == 1
    assert _docs_state() == before
    report = tmp_path / "catalogue" / "catalogue.md"
    text = report.read_text()
    status = next(l for l in text.splitlines() if l.startswith("**Incomplete**"))
    assert "Kang 2018 side 14 km/h failed" in status and "simulated failure" in status
    assert "NBDL 15 g failed" in status and "NBDL 12 g failed" in status
    assert len([l for l in text.splitlines() if l.startswith("| C4–C5 |")]) == 4
    assert "### Stemper 2004 rear 1.8 m/s" in text and "### Kang 2018 front 14 km/h" in text
    assert "### Kang 2018 side 14 km/h" not in text
    assert (report.parent / "catalogue_stemper_rear.png").exists()
    assert "| Stemper 2004 rear 1.8 m/s | %s |" % WARNING in text
    assert WARNING in (tmp_path / "work" / "stemper_hold_passive.err").read_text()
    err = capsys.readouterr().err
    lines = re.findall(r"^hhneck-catalogue: \[(\d+)/(\d+)\] (.*)$", err, flags=re.M)
    assert [int(k) for k, _, _ in lines] == list(range(1, 10)) and {n for _, n, _ in lines} == {"9"}
    assert sum("FAILED" in l for _, _, l in lines) == 3


def test_an_interrupted_run_keeps_the_cases_done(tmp_path, monkeypatch, capsys):
    """Ctrl-C during the second step: exit 130, the report has the first
    step's case and says where it stopped and what did not run."""
    g = np.arange(0.0, 100.05, 0.1)
    title = "Stemper 2004 rear 1.8 m/s"

    def first(pr):
        pr.cases[title] = ({ch: specimens.rate_channel(g, np.sin(g / 30), np.sin(g / 30) - 1, np.sin(g / 30) + 1,
                                                       g, 0.9 * np.sin(g / 30)) for ch in specimens.STEMPER_CHANNELS},
                           [])
        pr.line("first")

    def second(pr):
        raise KeyboardInterrupt

    monkeypatch.setattr(catalogue, "catalogue_steps", lambda a, work: [("one", first), ("two", second),
                                                                         ("three", first)])
    report = tmp_path / "r" / "catalogue.md"
    assert catalogue.main(["--quick", "--exe", sys.executable, "--report", str(report),
                           "--out", str(tmp_path / "work")]) == 130
    text = report.read_text()
    assert "**Incomplete**: interrupted during two; not run: three." in text
    assert "### %s" % title in text and "| head_T1_angle |" in text
    assert "interrupted during two" in capsys.readouterr().err


def test_required_scores_and_their_margins():
    """The summary's required column: the given specimen cases' required
    scores come from their case files, the segment sources' from the
    catalogue; a score just below its requirement is "no" with its margin
    to three significant digits, even where the printed mean would round
    onto the requirement (0.68055 prints as 0.681)."""
    from hhneck.validation import catalogue as cat
    assert cat.REQUIRED["Stemper 2004 rear 1.8 m/s"] == 0.681
    assert cat.REQUIRED["Kang 2018 side 14 km/h"] == 0.644
    assert cat.REQUIRED["Nightingale 2007"] == 0.586
    assert cat.met_cell(0.68055, 0.681) == "no (-0.00045)"
    assert cat.met_cell(0.812, 0.80) == "yes (+0.012)"
    assert cat.required_cells("Stemper 2004 rear 1.8 m/s", 0.687) == "≥ 0.681 (SAFER HBM v11) | yes (+0.006)"
    assert cat.required_cells("a case with none", 0.5) == "none given | —"


def test_segment_goal_cell_says_yes_only_at_every_level():
    """The summary's goal cell of a source with ±1 SD ranges: yes at every
    level inside, no with the count otherwise (it once said no at 30 of 30)."""
    from hhneck.validation import catalogue as cat
    assert cat.segment_goal_cell(30, 30) == "yes: 30 of 30 levels inside ±1 SD"
    assert cat.segment_goal_cell(26, 30) == "no: 26 of 30 levels inside ±1 SD"
