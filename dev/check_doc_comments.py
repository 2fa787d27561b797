#!/usr/bin/env python3
"""Dummy arguments of public procedures without a trailing `!!` comment.

The project's style (minpack's): every dummy argument of a public procedure
is declared on its own line with a short FORD comment after it,

    real(wp), intent(in) :: t            !! time [s]

This lists, for every Fortran file under the given paths (default: src),
each dummy argument of a public procedure whose declaration line has no
trailing `!!` comment, one line each:

    file:line procedure argument

and exits with 1 when there is any (0 when none, 2 on a usage error). A
summary (how many dummies were checked, how many lack a comment) goes to
stderr.

Public procedures are
  - module procedures named in their module's `public` list (or all of a
    module's procedures when it has no bare `private` statement),
  - the specific procedures of a public generic interface,
  - procedures bound to a type (`procedure :: name => impl`), except
    bindings declared `private`; for a deferred binding, the abstract
    interface it names,
  - separate module procedures (`module subroutine`/`module function`
    interfaces, implemented in a submodule) and bodies in a submodule that
    repeat their dummies (`module subroutine name(...)`),
  - interface bodies of external procedures whose name is public (the
    LAPACK interfaces of hn_lapack), and public abstract interfaces.
Internal procedures (after a procedure's `contains`) are not checked.

The passed-object dummies `me` and `this` are exempt. A function's result
is not a dummy. A dummy's declaration is the type declaration statement
that names it (`real(wp), intent(in) :: x`, `procedure(f_t) :: f`, ...),
or for a dummy procedure given by an interface block, the interface body's
first line; without one, an attribute statement (`intent(in) :: x`,
`dimension x(3)`). Its lines are the physical lines of the statement from
its name to the end of its entity (`w(:, &` / `:)  !! ...` counts); the
line reported is the first. When several dummies of the procedure stand
on one line, none of them counts as documented (one comment cannot say
what each is): the line is to be split, and each such dummy is listed with
"(shares its line)"; a dummy that is not declared at all is listed at the
procedure's first line with "(not declared)".

Usage:
    dev/check_doc_comments.py [--skip PATH]... [--all] [PATH...]

    --skip PATH   leave out a file, or every file under a directory (may be
                  given more than once); a PATH that names no checked file
                  is an error, so a stale skip shows
    --all         list every checked dummy, "ok" or "missing" after it
"""

import argparse
import bisect
import os
import re
import sys

EXEMPT = {'me', 'this'}

TYPE_DECL = re.compile(
    r'(integer|real|logical|character|complex|double\s*precision|double\s*complex|'
    r'type\s*\(|class\s*\(|procedure\s*\()', re.I)
ATTR_STMT = re.compile(
    r'(intent\s*\(|optional\b|dimension\b|allocatable\b|pointer\b|target\b|value\b|'
    r'volatile\b|contiguous\b|asynchronous\b|external\b)', re.I)
OTHER_SPEC = re.compile(
    r'(use\b|import\b|implicit\b|parameter\s*\(|save\b|intrinsic\b|data\b|common\b|equivalence\b|'
    r'namelist\b|format\s*\(|entry\b|include\b|public\b|private\b|protected\b|bind\s*\(|enum\b|'
    r'enumerator\b|end\s*enum\b)', re.I)
PREFIX_WORDS = {'pure', 'impure', 'elemental', 'recursive', 'non_recursive', 'module'}
END_UNIT = re.compile(
    r'end(\s*(subroutine|function|procedure|module|submodule|program|type|interface|block\s*data)\b.*)?$', re.I)


class Statement:
    """One Fortran statement, continuation lines joined."""

    def __init__(self, text, starts, first_line):
        self.text = text            # code, continuations joined, comments removed
        self.starts = starts        # [(offset in text, physical line number)]
        self.line = first_line

    def line_at(self, offset):
        """Physical line of the character at offset."""
        k = bisect.bisect_right([s for s, _ in self.starts], offset) - 1
        return self.starts[max(k, 0)][1]

    def lower(self):
        return self.text.lower().strip()


def split_code_comment(line, quote):
    """(code, comment, quote at the end): comment is the text from the first
    '!' outside a character literal; quote carries an open literal into a
    continuation line."""
    i = 0
    while i < len(line):
        c = line[i]
        if quote:
            if c == quote:
                if i + 1 < len(line) and line[i + 1] == quote:
                    i += 1
                else:
                    quote = None
        elif c in ('"', "'"):
            quote = c
        elif c == '!':
            return line[:i], line[i:], None
        i += 1
    return line, '', quote


def top_level_split(text, sep):
    """Pieces of text between separators sep outside parentheses and
    character literals, as (offset, piece)."""
    out, depth, quote, start, i = [], 0, None, 0, 0
    while i < len(text):
        c = text[i]
        if quote:
            if c == quote:
                quote = None
        elif c in ('"', "'"):
            quote = c
        elif c in '([':
            depth += 1
        elif c in ')]':
            depth -= 1
        elif depth == 0 and text.startswith(sep, i):
            out.append((start, text[start:i]))
            i += len(sep)
            start = i
            continue
        i += 1
    out.append((start, text[start:]))
    return out


def read_statements(path):
    """The statements of a file and the comment of each physical line."""
    with open(path, encoding='utf-8', errors='replace') as fh:
        lines = fh.read().split('\n')
    comments = {}
    stmts = []
    text, starts, first, quote = '', [], None, None
    for n, raw in enumerate(lines, start=1):
        if raw.lstrip().startswith('#'):
            continue
        code, comment, quote = split_code_comment(raw, quote)
        comments[n] = comment
        body = code.rstrip()
        if not body.strip():
            continue        # blank or comment only: does not end a continuation
        if first is not None:
            s = body.lstrip()
            body = s[1:] if s.startswith('&') else ' ' + s
        cont = body.endswith('&')
        if cont:
            body = body[:-1]
        if first is None:
            first = n
        starts.append((len(text), n))
        text += body
        if not cont:
            whole = Statement(text, starts, first)
            for off, piece in top_level_split(text, ';'):     # several statements on one line
                if piece.strip():
                    sub = [(0, whole.line_at(off))] + [(s - off, ln) for s, ln in starts
                                                       if off < s < off + len(piece)]
                    stmts.append(Statement(piece, sub, sub[0][1]))
            text, starts, first = '', [], None
    return stmts, comments


def skip_parens(s, i):
    """Index after the balanced parenthesis group that starts at s[i]."""
    depth, quote = 0, None
    while i < len(s):
        c = s[i]
        if quote:
            if c == quote:
                quote = None
        elif c in ('"', "'"):
            quote = c
        elif c == '(':
            depth += 1
        elif c == ')':
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    return i


def type_spec_end(s):
    """Index after the type specification that starts s (a declaration)."""
    m = re.match(r'\s*(double\s*precision|double\s*complex|integer|real|logical|character|complex|'
                 r'type|class|procedure)\s*', s, re.I)
    i = m.end()
    if i < len(s) and s[i] == '(':
        i = skip_parens(s, i)
    elif i < len(s) and s[i] == '*':
        m2 = re.match(r'\*\s*(\(\s*[^)]*\)|\d+)\s*', s[i:])
        if m2:
            i += m2.end()
    return i


def parse_header(text):
    """(kind, name, dummies, prefixes) of a subroutine/function statement,
    or None."""
    s = text.strip()
    prefixes = []
    i = 0
    while True:
        m = re.match(r'\s*(\w+)', s[i:])
        if not m:
            return None
        word = m.group(1).lower()
        j = i + m.end()
        if word in ('subroutine', 'function'):
            m2 = re.match(r'\s+(\w+)\s*', s[j:])
            if not m2:
                return None
            name = m2.group(1)
            k = j + m2.end()
            args = []
            if k < len(s) and s[k] == '(':
                e = skip_parens(s, k)
                args = [a.strip() for a in s[k + 1:e - 1].split(',') if a.strip()]
            return word, name, args, prefixes
        if word in PREFIX_WORDS:
            prefixes.append(word)
            i = j
            continue
        if TYPE_DECL.match(s[i:].lstrip()) and word not in ('procedure',):
            i = i + (len(s[i:]) - len(s[i:].lstrip()))
            i += type_spec_end(s[i:])
            prefixes.append('typed')
            continue
        return None


def entities(stmt, after):
    """[(name, (first line, last line))] of the entity list that starts at
    offset `after` of the statement: the physical lines from the entity's
    name to its last character (an entity may span continuation lines)."""
    out = []
    for off, piece in top_level_split(stmt.text[after:], ','):
        m = re.match(r'\s*(\w+)', piece)
        if m:
            first = stmt.line_at(after + off + m.start(1))
            last = stmt.line_at(after + off + len(piece.rstrip()) - 1)
            out.append((m.group(1).lower(), (first, last)))
    return out


def declaration(stmt):
    """('type' | 'attr', [(name, line)], interface name of a procedure()
    declaration or None) of a specification statement, or None."""
    s = stmt.text
    lead = len(s) - len(s.lstrip())
    body = s.lstrip()
    if TYPE_DECL.match(body) and not re.match(r'type\s*,|type\s*::|type\s+\w+\s*$|type\s+is\b',
                                                body, re.I):
        if re.match(r'(real|integer|logical|complex|character)\s*\(.*\)\s*function\b', body, re.I):
            return None
        iface = None
        m = re.match(r'procedure\s*\(\s*(\w*)\s*\)', body, re.I)
        if m:
            iface = m.group(1).lower() or None
        parts = top_level_split(s, '::')
        if len(parts) >= 2:
            return 'type', entities(stmt, parts[1][0]), iface
        return 'type', entities(stmt, lead + type_spec_end(body)), iface
    if ATTR_STMT.match(body):
        parts = top_level_split(s, '::')
        if len(parts) >= 2:
            return 'attr', entities(stmt, parts[1][0]), None
        m = re.match(r'(\w+)(\s*\([^)]*\))?\s*', body)
        return 'attr', entities(stmt, lead + m.end()), None
    return None


ASSIGNMENT = re.compile(r'\w+\s*(\([^=]*\))?\s*(%\s*\w+\s*(\([^=]*\))?\s*)*=(?!=)')


def is_spec(stmt):
    """Whether a statement may stand in a specification part."""
    body = stmt.text.lstrip()
    if ASSIGNMENT.match(body) and len(top_level_split(body, '::')) == 1:
        return False        # an assignment to a variable named like a keyword (value = 0)
    return bool(TYPE_DECL.match(body) or ATTR_STMT.match(body) or OTHER_SPEC.match(body)
                or re.match(r'(abstract\s+)?interface\b|type\b', body, re.I))


class Procedure:
    def __init__(self, name, dummies, line, prefixes):
        self.name = name
        self.dummies = [d.lower() for d in dummies if d != '*']
        self.line = line
        self.prefixes = prefixes
        self.decl = {}      # dummy -> (first, last) line of it in its type declaration
        self.attr = {}      # dummy -> the same in an attribute statement naming it
        self.ifaces = {}    # dummy -> interface name of a procedure(...) dummy


class Unit:
    """What one module or submodule says about its procedures."""

    def __init__(self, name, is_submodule):
        self.name = name
        self.is_submodule = is_submodule
        self.default_private = False
        self.public = set()
        self.private = set()
        self.bound = set()          # implementations of public bindings
        self.deferred = set()       # interfaces of deferred bindings
        self.generics = {}          # generic name -> specific names
        self.procs = []             # (Procedure, origin): 'contains', 'module', 'external', 'abstract', 'generic:name'


class Parser:
    def __init__(self, stmts):
        self.stmts = stmts
        self.i = 0

    def peek(self):
        return self.stmts[self.i] if self.i < len(self.stmts) else None

    def next(self):
        st = self.stmts[self.i]
        self.i += 1
        return st

    def units(self):
        out = []
        while self.peek() is not None:
            st = self.next()
            low = st.lower()
            m = re.match(r'module\s+(\w+)$', low)
            if m and m.group(1) not in ('procedure', 'subroutine', 'function'):
                out.append(self.unit(m.group(1), False))
                continue
            m = re.match(r'submodule\s*\(([^)]*)\)\s*(\w+)$', low)
            if m:
                out.append(self.unit(m.group(2), True))
        return out

    def unit(self, name, is_submodule):
        u = Unit(name, is_submodule)
        in_contains = False
        while self.peek() is not None:
            st = self.next()
            low = st.lower()
            if low == 'end' or re.match(r'end\s*(module|submodule)\b', low):
                break
            if low == 'contains':
                in_contains = True
                continue
            if not in_contains:
                self.module_spec(u, st, low)
                continue
            m = re.match(r'module\s+procedure\s+(\w+)$', low)
            if m:
                self.skip_body(r'procedure')
                continue
            h = parse_header(st.text)
            if h:
                p = self.procedure(h, st)
                u.procs.append((p, 'module' if 'module' in h[3] else 'contains'))
        return u

    def module_spec(self, u, st, low):
        m = re.match(r'(public|private)\s*(::)?\s*(.*)$', low)
        if m:
            names = [n.strip() for n in m.group(3).split(',') if n.strip()]
            if not names:
                u.default_private = m.group(1) == 'private'
            else:
                (u.public if m.group(1) == 'public' else u.private).update(
                    re.sub(r'\s+', '', n) for n in names)
            return
        if re.match(r'type\s*(,[^:]*)?::\s*\w+|type\s+\w+\s*$', low) and not low.startswith('type is'):
            self.type_block(u)
            return
        m = re.match(r'(abstract\s+)?interface\s*(.*)$', low)
        if m:
            kind = 'abstract' if m.group(1) else ('generic:' + re.sub(r'\s+', '', m.group(2))
                                                  if m.group(2) else 'external')
            self.interface_block(u, kind)

    def type_block(self, u):
        in_contains, default_private = False, False
        while self.peek() is not None:
            st = self.next()
            low = st.lower()
            if re.match(r'end\s*type\b', low):
                return
            if low == 'contains':
                in_contains = True
                continue
            if not in_contains:
                continue
            if low == 'private':
                default_private = True
                continue
            if low == 'public':
                default_private = False
                continue
            m = re.match(r'procedure\s*(\(\s*(\w+)\s*\))?\s*(,\s*([^:]*))?(::)?\s*(.*)$', low)
            if not m:
                continue        # generic, final
            attrs = [a.strip() for a in (m.group(4) or '').split(',')]
            private = 'private' in attrs or (default_private and 'public' not in attrs)
            if m.group(2) and 'deferred' in attrs:
                u.deferred.add(m.group(2))
                continue
            if private:
                continue
            for _, piece in top_level_split(m.group(6), ','):
                parts = piece.split('=>')
                impl = parts[-1].strip()
                if impl:
                    u.bound.add(impl)

    def interface_block(self, u, kind):
        while self.peek() is not None:
            st = self.next()
            low = st.lower()
            if re.match(r'end\s*interface\b', low):
                return
            m = re.match(r'(module\s+)?procedure\s*(::)?\s*(.*)$', low)
            if m and kind.startswith('generic:'):
                specs = [n.strip() for n in m.group(3).split(',') if n.strip()]
                u.generics.setdefault(kind[8:], set()).update(specs)
                continue
            h = parse_header(st.text)
            if h:
                p = self.procedure(h, st, interface_body=True)
                origin = 'module' if 'module' in h[3] else kind
                if kind.startswith('generic:'):
                    u.generics.setdefault(kind[8:], set()).add(p.name.lower())
                u.procs.append((p, origin))

    def skip_body(self, kind):
        """Skip to the end of a `module procedure` body."""
        while self.peek() is not None:
            st = self.next()
            low = st.lower()
            if low == 'contains':
                self.internal_procedures()
                return
            if re.match(r'end\s*(procedure\b.*)?$', low):
                return

    def internal_procedures(self):
        """Internal procedures up to the host's end statement (consumed)."""
        while self.peek() is not None:
            st = self.next()
            low = st.lower()
            h = parse_header(st.text)
            if h:
                self.procedure(h, st)
                continue
            if END_UNIT.match(low):
                return

    def procedure(self, header, st, interface_body=False):
        kind, name, dummies, prefixes = header
        p = Procedure(name, dummies, st.line, prefixes)
        wanted = set(p.dummies)
        in_spec = True
        while self.peek() is not None:
            st = self.next()
            low = st.lower()
            if low == 'contains':
                self.internal_procedures()
                return p
            if END_UNIT.match(low) and not re.match(r'end\s*(type|interface|module|submodule)\b', low):
                return p
            if not in_spec:
                continue
            if not is_spec(st):
                in_spec = False
                continue
            if re.match(r'(abstract\s+)?interface\b', low):
                # interface bodies here declare dummy procedures
                while self.peek() is not None:
                    s2 = self.next()
                    l2 = s2.lower()
                    if re.match(r'end\s*interface\b', l2):
                        break
                    h = parse_header(s2.text)
                    if h:
                        inner = self.procedure(h, s2, interface_body=True)
                        n = inner.name.lower()
                        if n in wanted and n not in p.decl:
                            p.decl[n] = (s2.line, s2.line)
                continue
            if re.match(r'type\s*(,[^:]*)?::\s*\w+|type\s+\w+\s*$', low) and not low.startswith('type is'):
                while self.peek() is not None and not re.match(r'end\s*type\b', self.next().lower()):
                    pass
                continue
            d = declaration(st)
            if not d:
                continue
            what, ents, iface = d
            for n, span in ents:
                if n not in wanted:
                    continue
                if what == 'type':
                    p.decl.setdefault(n, span)
                    if iface:
                        p.ifaces[n] = iface
                else:
                    p.attr.setdefault(n, span)
        return p


def is_public(u, p, origin, deferred, dummy_ifaces):
    """Whether procedure p, found in unit u as `origin`, is checked.
    deferred: interfaces of deferred bindings (all files); dummy_ifaces:
    interfaces of procedure(...) dummies of checked procedures."""
    n = p.name.lower()
    if origin == 'module':
        return True
    if origin == 'abstract':
        return n in u.public or n in deferred or n in dummy_ifaces
    generic = any(n in specs and (g in u.public or not u.default_private) and g not in u.private
                  for g, specs in u.generics.items())
    if origin.startswith('generic:'):
        return generic
    if origin == 'contains' and u.is_submodule:
        return False        # private to the submodule
    if origin == 'contains' and (n in u.bound or generic):
        return True
    return n in u.public or (not u.default_private and n not in u.private)


def doc_comment(comment):
    """A trailing FORD comment with some text."""
    return comment.startswith('!!') and comment[2:].strip() != ''


def dummy_rows(path, p, comments):
    """[(path, line, procedure, dummy, status)] of procedure p. A dummy is
    documented when a line of its declaration (from its name to the end of
    its entity) has a trailing `!!` comment and no other dummy of p stands
    on those lines."""
    dummies = [d for d in p.dummies if d not in EXEMPT]
    span = {d: p.decl.get(d, p.attr.get(d)) for d in dummies}
    rows = []
    for d in dummies:
        if span[d] is None:
            rows.append((path, p.line, p.name, d, 'missing (not declared)'))
            continue
        first, last = span[d]
        shared = any(e != d and span[e] is not None and span[e][0] <= last and first <= span[e][1]
                     for e in dummies)
        if shared:
            status = 'missing (shares its line)'
        elif any(doc_comment(comments.get(n, '')) for n in range(first, last + 1)):
            status = 'ok'
        else:
            status = 'missing'
        rows.append((path, first, p.name, d, status))
    return rows


def source_files(paths):
    """The Fortran files under paths, sorted; None when a path is missing."""
    files = []
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, names in os.walk(p):
                dirs.sort()
                files += [os.path.join(root, f) for f in sorted(names)
                          if f.lower().endswith(('.f90', '.f95', '.f03', '.f08'))]
        elif os.path.isfile(p):
            files.append(p)
        else:
            print(f'check_doc_comments: no such file or directory: {p}', file=sys.stderr)
            return None
    return files


def main(argv):
    ap = argparse.ArgumentParser(description='Dummy arguments of public procedures without a '
                                 'trailing !! comment (see the module docstring).')
    ap.add_argument('paths', nargs='*', default=['src'], help='files or directories (default: src)')
    ap.add_argument('--skip', action='append', default=[], metavar='PATH',
                    help='leave out a file or every file under a directory (repeatable)')
    ap.add_argument('--all', action='store_true', help='list every checked dummy with ok/missing')
    args = ap.parse_args(argv)

    files = source_files(args.paths)
    if files is None:
        return 2
    skips = {s: os.path.abspath(s) for s in args.skip}
    used, kept = set(), []
    for f in files:
        nf = os.path.abspath(f)
        hit = [s for s, a in skips.items() if nf == a or nf.startswith(a.rstrip(os.sep) + os.sep)]
        used.update(hit)
        if not hit:
            kept.append(f)
    stale = [s for s in skips if s not in used]
    for s in stale:
        print(f'check_doc_comments: --skip {s} names no file that would be checked', file=sys.stderr)
    if stale:
        return 2

    parsed = []
    for f in kept:
        stmts, comments = read_statements(f)
        parsed.append((f, Parser(stmts).units(), comments))
    # abstract interfaces count when a deferred binding or a checked
    # procedure's dummy names them, in whichever file
    deferred = set().union(*[u.deferred for _, units, _ in parsed for u in units])
    dummy_ifaces = set()
    for _, units, _ in parsed:
        for u in units:
            for p, origin in u.procs:
                if origin != 'abstract' and is_public(u, p, origin, deferred, set()):
                    dummy_ifaces.update(p.ifaces.values())
    rows, nproc = [], 0
    for path, units, comments in parsed:
        for u in units:
            for p, origin in u.procs:
                if is_public(u, p, origin, deferred, dummy_ifaces):
                    nproc += 1
                    rows += dummy_rows(path, p, comments)
    rows.sort(key=lambda r: (r[0], r[1]))
    missing = [r for r in rows if r[4] != 'ok']
    for path, line, name, d, status in (rows if args.all else missing):
        note = ' ' + status if args.all else status[len('missing'):]
        print(f'{path}:{line} {name} {d}{note}')
    print(f'{len(rows)} dummy arguments of {nproc} public procedures in {len(kept)} files checked; '
          f'{len(missing)} without a trailing !! comment of their own', file=sys.stderr)
    return 1 if missing else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
