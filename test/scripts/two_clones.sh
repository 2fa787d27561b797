#!/bin/sh
# Two checkouts on one machine each use their own Python package
# (tools/setup.sh, docs/testing.md): the repository cloned twice into
# temporary folders, each set up (`tools/setup.sh --python`: the checkout's
# environment .venv, no build), then in each clone its environment's
# `python -c 'import hhneck'` and a console command (hhneck-results) import
# that clone's package; setting up the second changes nothing in the first
# (its .venv file by file, its tree) nor the machine's Python (which hhneck,
# if any, it imports); a second set-up of a clone installs nothing and says
# nothing. The clones get this tree's set-up files (tools/setup.sh,
# python/pyproject.toml, .gitignore), so that the set-up under test is the
# one in the working tree, committed or not. Run outside this checkout's
# environment: neither its .venv/bin on PATH nor PYTHONPATH.
. test/scripts/lib/checks.sh
root=$(pwd -P)
unset PYTHONPATH VIRTUAL_ENV
PATH=$(printf '%s\n' "$PATH" | tr ':' '\n' | grep -v -x "$root/.venv/bin" | paste -s -d: -)
export PATH
tmp=$(cd "$tmp" && pwd -P)

# where the machine's python3 imports hhneck from (or "none")
machine_hhneck() {
    (cd / && python3 -c 'import hhneck, os; print(os.path.realpath(hhneck.__file__))' 2>/dev/null) || echo none
}
# snapshot CLONE: every file of its .venv with its checksum, and its git status
snapshot() {
    (cd "$1" && find .venv -type f -exec cksum {} + | sort -k 3 && git status --porcelain --untracked-files=all)
}
machine_before=$(machine_hhneck)

for c in one two; do
    git clone -q "$root" "$tmp/$c" || { fail "git clone into $c"; finish; exit 1; }
    for f in tools/setup.sh python/pyproject.toml .gitignore; do cp "$root/$f" "$tmp/$c/$f"; done
done

setup() {   # setup CLONE LOG: its set-up's Python part, stderr to LOG
    (cd "$tmp/$1" && sh tools/setup.sh --python > /dev/null 2> "$2")
}
check "clone one set up (tools/setup.sh --python)" setup one "$tmp/one.setup1"
snapshot "$tmp/one" > "$tmp/one.before"
check "clone two set up (tools/setup.sh --python)" setup two "$tmp/two.setup1"
snapshot "$tmp/one" > "$tmp/one.after"
check "setting up clone two left clone one's .venv and tree as they were" cmp -s "$tmp/one.before" "$tmp/one.after"
check "clone one's .venv holds files (the snapshot is not empty)" grep -q "python" "$tmp/one.before"
machine_after=$(machine_hhneck)
check "the machine's python3 imports the same hhneck as before ($machine_after)" \
    [ "$machine_before" = "$machine_after" ]

for c in one two; do
    dir=$tmp/$c
    got=$(cd / && "$dir/.venv/bin/python" -c 'import hhneck, os; print(os.path.realpath(hhneck.__file__))' 2>&1)
    check "clone $c: its .venv's python imports its own package ($got)" \
        [ "$got" = "$dir/python/hhneck/__init__.py" ]
    # the console command: which hhneck/__init__.py it runs, printed by a
    # line added to this clone's package (editable: the change is live)
    printf '\nimport os as _os\nif _os.environ.get("HHNECK_SHOW_PACKAGE"):\n    print("PACKAGE", _os.path.realpath(__file__))\n' \
        >> "$dir/python/hhneck/__init__.py"
    got=$(cd / && HHNECK_SHOW_PACKAGE=1 "$dir/.venv/bin/hhneck-results" --help 2>&1 | sed -n 's/^PACKAGE //p')
    check "clone $c: its console command hhneck-results imports its own package ($got)" \
        [ "$got" = "$dir/python/hhneck/__init__.py" ]
    check "clone $c: its .venv is ignored by git" \
        [ -z "$(cd "$dir" && git status --porcelain --untracked-files=all -- .venv)" ]
done

# again: nothing to install, nothing said, nothing changed
snapshot "$tmp/one" > "$tmp/one.before"
check "clone one set up again" setup one "$tmp/one.setup2"
check "the second set-up says nothing (installs nothing)" [ ! -s "$tmp/one.setup2" ]
snapshot "$tmp/one" > "$tmp/one.after"
check "the second set-up changed nothing in clone one" cmp -s "$tmp/one.before" "$tmp/one.after"
[ -s "$tmp/one.setup2" ] && cat "$tmp/one.setup2"
finish
