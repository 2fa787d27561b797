#!/usr/bin/env python3
"""Narrows the module imports of the suites funitproc generates (called by
tools/pfunit.sh generate), so that the test programs build in about two
thirds of the time and mean the same.

gfortran reads a module file whole at every USE of it, and funit's is
6.6 MB: each generated suite read it three times (the test module, the
wrapper module and the suite function), and a fourth and fifth time through
the test module, which re-exported every name of funit. Here

- every `use funit` of a program unit becomes `use funit, only:` the names
  of funit that the unit's text has: it could reference no other;
- the test module becomes private but for the names the generated wrapper
  and suite function take from it (its tests, test case and parameter types
  and their constructors), followed by a #line directive, so that the
  compiler's messages keep the .pf line numbers.

    tools/pfunit_narrow.py FUNIT_MOD SUITE.F90..."""
import gzip
import re
import sys

WORD = re.compile(r"\b[A-Za-z]\w*\b")


def funit_names(mod):
    """The public names of the module file `mod` (gzipped, gfortran's
    format): its generic interfaces and its symbol tree, lower case."""
    with gzip.open(mod, "rt") as f:
        sections = f.read().split("\n\n")
    generics = set(re.findall(r"\(\s*'(\w+)'\s+'\w+'", sections[2]))
    symbols = set(re.findall(r"'(\w+)'\s+\d+\s+\d+", sections[-1]))
    return {n.lower() for n in generics | symbols if not n.startswith("_")} - {"funit"}


def code(line):
    """A line without its comment (no '!' inside strings in generated code
    that matters here: a name in a string only adds an unused import)."""
    return line.split("!")[0]


def units(lines):
    """(start, end) line ranges of the top-level program units: a module,
    program, function or subroutine to its END MODULE, END PROGRAM, ...
    (the procedures a module contains are inside its range)."""
    out, start, kind = [], None, None
    for i, l in enumerate(lines):
        c = code(l).strip().lower()
        m = re.match(r"(?:\w+(?:\([^)]*\))?\s+)*(module|program|function|subroutine)\s+\w+", c)
        if start is None and m and not c.startswith(("module procedure", "end")):
            start, kind = i, m.group(1)
        elif start is not None and re.match(r"end\s+%s\b" % kind, c):
            out.append((start, i))
            start = None
    return out


def narrow(path, funit):
    """Rewrite the generated suite file `path` in place (module docstring);
    funit: funit's public names."""
    lines = open(path).read().split("\n")
    name = re.sub(r"_suite\.F90$", "", path.rsplit("/", 1)[-1]).lower()
    spans = units(lines)
    words = [set(w.lower() for w in WORD.findall("\n".join(code(l) for l in lines[a:b + 1]))) for a, b in spans]
    inserts = {}     # line number -> the lines that replace it
    test = next((k for k, (a, _) in enumerate(spans) if re.match(r"\s*module\s+%s\s*$" % name, lines[a], re.I)), None)
    if test is not None:
        inserts.update(_private(lines, spans[test], set().union(*(w for k, w in enumerate(words) if k != test))))
    for k, (a, b) in enumerate(spans):
        for i in range(a, b + 1):
            m = re.match(r"(\s*)use\s+funit\s*$", lines[i], re.I)
            if m:
                inserts[i] = _statement(m.group(1) + "use funit, only:", sorted(words[k] & funit),
                                        m.group(1) + "    ") + _directive(lines, i + 1)
    for i in sorted(inserts, reverse=True):
        lines[i:i + 1] = inserts[i]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def _private(lines, span, others):
    """{line of the test module's IMPLICIT NONE: it, PRIVATE and PUBLIC for
    the names the other units (`others`, their words) take from it}; {} when
    the module is private already."""
    a, b = span
    text = "\n".join(code(l) for l in lines[a:b + 1])
    if re.search(r"^\s*private\s*$", text, re.M | re.I):
        return {}
    declared = set()
    for pat in (r"\b(?:subroutine|function)\s+(\w+)", r"^\s*type\s*(?:,[^:]*)?::\s*(\w+)",
                r"^\s*type\s+(\w+)\s*$", r"^\s*interface\s+(\w+)"):
        declared.update(n.lower() for n in re.findall(pat, text, re.M | re.I))
    public = sorted(declared & others)
    imp = next(i for i in range(a, b) if re.match(r"\s*implicit\s+none\s*$", lines[i], re.I))
    return {imp: [lines[imp], "    private"] + (_statement("    public ::", public, "       ") if public else []) +
            _directive(lines, imp + 1)}


def _statement(head, names, indent):
    """`head` followed by the comma-separated names, continued with & on
    lines starting with `indent` so that none passes 100 columns."""
    out, row = [], head
    for k, n in enumerate(names):
        piece = " " + n + ("," if k < len(names) - 1 else "")
        if len(row) + len(piece) > 100:
            out.append(row + " &")
            row = indent
        row += piece
    return out + [row]


def _directive(lines, i):
    """[the #line directive of line i] (_pf_line), or [] when there is none."""
    d = _pf_line(lines, i)
    return [d] if d else []


def _pf_line(lines, i):
    """The #line directive that puts line i (0-based) of the generated file
    back at its line of the .pf file, from the last directive before it
    (None when there is none before it and none after to name the file)."""
    for j in range(i - 1, -1, -1):
        d = re.match(r'#line\s+(\d+)\s+"([^"]*)"', lines[j])
        if d:
            return '#line %d "%s"' % (int(d.group(1)) + i - j - 1, d.group(2))
    d = next((re.match(r'#line\s+\d+\s+"([^"]*)"', l) for l in lines if l.startswith("#line")), None)
    return '#line %d "%s"' % (i + 1, d.group(1)) if d else None


if __name__ == "__main__":
    names = funit_names(sys.argv[1])
    for p in sys.argv[2:]:
        narrow(p, names)
