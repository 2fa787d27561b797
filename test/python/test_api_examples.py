"""docs/api.md, the package's public surface: its ```python examples run in
order, as one script, in an empty temporary folder with HHNECK set (each
example asserts what it shows: a run cut to 20 ms ends at 20 ms, a head
mass scaled by 1.1 is 1.1 times the plain run's, a constant passes the
filter unchanged, the 12 g volunteer runs are 10, ...), and every name its
table lists exists in the module it names."""
import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT, hhneck_executable, package_env

PAGE = os.path.join(ROOT, "docs", "api.md")


def page():
    with open(PAGE) as f:
        return f.read()


def examples():
    """The ```python blocks of the page, in order."""
    return re.findall(r"^```python\n(.*?)^```$", page(), re.S | re.M)


def table_names():
    """(module, name) for each `name` of the table's `hhneck.MODULE`: `a`, `b(...)` rows."""
    out = []
    for row in re.findall(r"^\| [^|]+ \| (.+) \|$", page(), re.M):
        for part in row.split(";"):
            m = re.match(r"\s*`(hhneck\.\w+)`:(.*)", part)
            if m:
                out += [(m.group(1), n) for n in re.findall(r"`(\w+)", m.group(2))]
    return out


def test_the_page_has_examples_and_names():
    assert len(examples()) >= 7
    assert len(table_names()) >= 25


@pytest.mark.parametrize("module,name", table_names())
def test_listed_name_exists(module, name):
    import importlib
    assert hasattr(importlib.import_module(module), name), "%s.%s (docs/api.md) does not exist" % (module, name)


def test_examples_run(tmp_path):
    script = "\n".join(examples())
    env = package_env()
    env["HHNECK"] = hhneck_executable()
    r = subprocess.run([sys.executable, "-c", script], cwd=str(tmp_path), capture_output=True, text=True, env=env)
    assert r.returncode == 0, "docs/api.md's examples failed:\n%s" % r.stderr[-3000:]
    assert (tmp_path / "heavy.csv").is_file() and (tmp_path / "short.inp").is_file()
