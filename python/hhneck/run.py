"""Run a deck through the hhneck executable, with changes, from Python.

    run = run_deck(project_path("input", "nbdl15g.inp"),      # hhneck.paths
                   changes=[change_card("E12", "FAMILY", "DISCS", "E", "SCALE", 1.2)])
    run.h5          # the result file written
    run.listing     # the listing (standard output) as text
    run.channels()  # the channels as a pandas DataFrame with units (hhneck.results.read_channels)
    run.results()   # channels, bodies and injury criteria (hhneck.results.read_results)

Each change is a CHANGE card (docs/deck-format.md, "CHANGE"): an 80-column
card image, or the fields F1 ... F7 as a tuple that change_card() lays out
in their columns; run_deck() hands them to the executable as `--change`
options, after the deck's own cards. The deck is a file name, or the text
of a deck (standard input of the run; INCLUDE files are then looked for in
the working directory `cwd`). The package's project (hhneck.paths) is the
last directory of the include path: the shipped decks' INCLUDE files are
found from any working directory. The executable is `executable`, else
$HHNECK, else fpm's build of the project in the working directory, or
else of the package's own project (release profile; built when needed),
else `hhneck` on PATH.

Command line:

    hhneck-run-deck DECK [--change CARD ...] [--h5 OUT.h5] [--listing OUT.txt] [--exe PATH]
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass

from .decks import CardError, card, field_text
from .paths import find_project, project_root
from .results import read_channels, read_results


class RunError(RuntimeError):
    """A run that ended with a non-zero exit code (the code and the end of its standard error)."""

    def __init__(self, message, returncode, stderr):
        super().__init__(message)
        self.returncode, self.stderr = returncode, stderr


@dataclass
class Run:
    """One finished run: the command, its exit code, the result file (None
    with h5=False), the listing and standard error as text."""
    command: list
    returncode: int
    h5: str
    listing: str
    stderr: str

    def channels(self, names=None):
        """The run's channels (hhneck.results.read_channels): a DataFrame
        indexed by time [s], units in df.attrs["units"]."""
        if self.h5 is None:
            raise ValueError("the run wrote no result file (h5=False)")
        return read_channels(self.h5, names)

    def results(self, names=None):
        """The run's result file read whole (hhneck.results.read_results)."""
        if self.h5 is None:
            raise ValueError("the run wrote no result file (h5=False)")
        return read_results(self.h5, names)


def change_card(name, kind, target, item="", op="SET", value="", f7=""):
    """The CHANGE card image with fields F1 name, F2 kind (FAMILY, BODY,
    FIELDn), F3 target, F4 item, F5 op (SCALE or SET), F6 value, F7 (FIELDn
    only: field F2 of the target card); a field that does not fit its 10
    columns raises CardError."""
    fields = [name, kind, target, item, op, value, f7]
    return card("CHANGE", *[field_text(v, "field F%d of the CHANGE card" % n) for n, v in enumerate(fields, start=1)])


def package_project():
    """The project of the package (hhneck.paths.project_root); None when
    the package is installed outside one and HHNECK_ROOT is not set."""
    try:
        return project_root()
    except FileNotFoundError:
        return None


def find_executable(executable=None, cwd=None, profile="release"):
    """The hhneck executable to run (module docstring); raises
    FileNotFoundError when there is none."""
    exe = executable or os.environ.get("HHNECK")
    if not exe:
        root = find_project(cwd or os.getcwd()) or package_project()
        if root is not None and shutil.which("fpm"):
            out = subprocess.run(["fpm", "run", "hhneck", "--profile", profile, "--runner", "echo"], cwd=root,
                                 capture_output=True, text=True)
            lines = out.stdout.strip().splitlines()
            if out.returncode == 0 and lines:
                exe = os.path.join(root, lines[-1])
    exe = exe or shutil.which("hhneck")
    if not exe or not os.access(exe, os.X_OK):
        raise FileNotFoundError("no hhneck executable (give one, set HHNECK, run in the project with fpm, "
                                "or install it with fpm install): %r" % exe)
    return os.path.abspath(exe)


def run_deck(deck, changes=(), executable=None, h5=None, cwd=None, include=(), options=(), check=True,
             profile="release"):
    """Run `deck` (a file name, or deck text when it holds a newline) with
    the CHANGE cards `changes` (card images, or field tuples for
    change_card) and return a Run. h5: the result file to write (default:
    DECK's stem .h5 in a new temporary directory; False: none, --no-h5);
    cwd: working directory of the run; include: directories for INCLUDE
    files (-I), then the package's project (hhneck.paths: the shipped
    decks' INCLUDE files, such as input/head_neck_54dof.inp, found from
    any working directory); options: further command-line options; check: raise
    RunError on a non-zero exit code (exit 3, an incomplete run, included)."""
    exe = find_executable(executable, cwd, profile)
    cards = [c if isinstance(c, str) else change_card(*c) for c in changes]
    text_deck = "\n" in deck
    if h5 is None:
        stem = "deck" if text_deck else os.path.splitext(os.path.basename(deck))[0]
        h5 = os.path.join(tempfile.mkdtemp(prefix="hhneck-run-"), stem + ".h5")
    cmd = [exe, "--no-progress"] + (["--no-h5"] if h5 is False else ["--h5", os.path.abspath(h5)])
    for d in list(include) + [d for d in [package_project()] if d and d not in include]:
        cmd += ["-I", d]
    for c in cards:
        cmd += ["--change", c]
    cmd += list(options)
    if not text_deck:
        cmd.append(deck)
    r = subprocess.run(cmd, input=deck if text_deck else None, cwd=cwd, capture_output=True, text=True)
    run = Run(cmd, r.returncode, None if h5 is False else os.path.abspath(h5), r.stdout, r.stderr)
    if check and r.returncode != 0:
        raise RunError("hhneck ended with exit code %d: %s" % (r.returncode, r.stderr.strip()[-2000:]),
                       r.returncode, r.stderr)
    return run


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-run-deck", description="Run a deck with changes through the hhneck "
                                "executable; the listing on standard output (or to --listing), a summary of "
                                "the result file on standard error.")
    p.add_argument("deck", help="the deck file")
    p.add_argument("--change", action="append", default=[], metavar="CARD",
                   help="a CHANGE card image (repeatable; docs/deck-format.md)")
    p.add_argument("--h5", help="result file to write (default: DECK's stem .h5 in a temporary directory)")
    p.add_argument("--listing", help="write the listing to this file instead of standard output")
    p.add_argument("--exe", help="the hhneck executable (default: $HHNECK, the project's release build, PATH)")
    args = p.parse_args(argv)
    try:
        run = run_deck(args.deck, args.change, args.exe, args.h5)
    except (RunError, FileNotFoundError, CardError) as e:
        print("hhneck-run-deck: %s" % e, file=sys.stderr)
        return getattr(e, "returncode", 2) or 2
    if args.listing:
        with open(args.listing, "w") as f:
            f.write(run.listing)
    else:
        sys.stdout.write(run.listing)
    ch = run.channels()
    print("hhneck-run-deck: wrote %s (%d channels, %d samples to %g s)"
          % (run.h5, ch.shape[1], ch.shape[0], ch.index[-1]), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
