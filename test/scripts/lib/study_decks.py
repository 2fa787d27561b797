"""What deck_writers.sh checks of every deck a study writes: each card
within 80 columns, and `hhneck --check` passes on it in the study's work
folder (where its relative INCLUDEs are found), the model decks found
through -I ROOT."""
import subprocess

from hhneck.validation import segments


def deck_problems(hhneck, text, work, label):
    """The problems of one deck's text, [] when it is a deck the program takes."""
    bad = ["%s: a card beyond column 80: %r" % (label, l) for l in text.splitlines() if len(l) > 80]
    p = subprocess.run([hhneck, "-I", segments.ROOT, "--check"], input=text, capture_output=True, text=True,
                       timeout=120, cwd=work)
    if p.returncode:
        bad.append("%s: %s" % (label, p.stderr.strip()))
    return bad
