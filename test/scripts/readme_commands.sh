#!/bin/sh
# Every command of the README runs (docs/testing.md): each line of its
# ```sh blocks and each ```python block (run by the python3 on PATH then),
# in the README's order, in one shell, in a scratch copy of the project
# (the files of this tree that git tracks or would track; its build/ this
# tree's own, so that fpm compiles nothing: the release build is made
# before the scripts run), with HOME a scratch folder (fpm install writes
# there); each exits 0, and the first command prints a listing (its title,
# the injury criteria, the END OF RUN line). Skipped, with the reason
# printed: the test command (./tools/setup.sh && ./tools/test.sh), which
# would run the whole suite again, this script among it. Also: the README
# starts with the two commands, .ci/run runs exactly the README's test
# command, and the deck table names every deck of input/.
# builds: release
. test/scripts/lib/checks.sh
root=$(pwd -P)
test_command='./tools/setup.sh && ./tools/test.sh'

# the README's first block: the two commands, the run and the test command
first=$(awk '/^```/ {n++; next} n == 1' README.md)
check "the README starts with the two commands (set-up and case 6-2, set-up and the test suite)" \
    [ "$first" = "$(printf '%s\n%s' './tools/setup.sh && fpm run --profile release < input/case6-2.inp' "$test_command")" ]
check ".ci/run runs exactly the README's test command" grep -q -x -F "$test_command" .ci/run
for deck in input/*.inp; do
    check "the README's deck table names $deck" grep -q "^| .*\`$deck\`" README.md
done

# the scratch copy: what git tracks or would track, as it is in this tree
scratch=$tmp/project
mkdir -p "$scratch" "$tmp/home"
git ls-files --cached --others --exclude-standard | while IFS= read -r f; do [ -e "$f" ] && printf '%s\n' "$f"; done |
    tar -cf - -T - | tar -C "$scratch" -xf -
ln -s "$root/build" "$scratch/build"

# the script of the README's commands: each followed by its exit code in
# $tmp/rc/N, its output in $tmp/rc/N.out and N.err, its text in N.cmd
mkdir -p "$tmp/rc"
awk -v dir="$tmp/rc" -v skip="$test_command" '
    function quote(s) { return "\047" s "\047" }
    function emit(text, runner) {
        n++
        print text > (dir "/" n ".cmd"); close(dir "/" n ".cmd")
        print "{ " runner
        print "} > " quote(dir "/" n ".out") " 2> " quote(dir "/" n ".err")
        print "echo $? > " quote(dir "/" n)
    }
    /^```sh$/ { block = "sh"; next }
    /^```python$/ { block = "python"; py = ""; next }
    /^```/ {
        if (block == "python") emit(py, "python3 - <<\047HHNECK_README_PYTHON\047\n" py "HHNECK_README_PYTHON")
        block = ""; next
    }
    block == "python" { py = py $0 "\n"; next }
    block == "sh" && $0 !~ /^[ \t]*(#|$)/ {
        if ($0 == skip) { print "SKIP  " $0 " (the test command: it would run this script again; .ci/run runs it)" > "/dev/stderr"; next }
        emit($0, $0)
    }
' README.md > "$tmp/readme.sh" 2> "$tmp/skipped"
cat "$tmp/skipped"
check "the test command is the one command skipped" [ "$(grep -c '^SKIP' "$tmp/skipped")" -eq 1 ]

# run them: this checkout's environment and PYTHONPATH out of the way (the
# scratch copy's set-up makes the copy's own); pyenv's shims keep finding
# pyenv with HOME elsewhere
PYENV_ROOT=${PYENV_ROOT:-$(pyenv root 2>/dev/null || true)}
[ -n "$PYENV_ROOT" ] && export PYENV_ROOT
PATH=$(printf '%s\n' "$PATH" | tr ':' '\n' | grep -v -x "$root/.venv/bin" | paste -s -d: -)
(cd "$scratch" && unset PYTHONPATH VIRTUAL_ENV && HOME=$tmp/home MPLBACKEND=Agg PATH=$PATH sh "$tmp/readme.sh")

n=1
while [ -f "$tmp/rc/$n.cmd" ]; do
    what=$(head -n 1 "$tmp/rc/$n.cmd")
    [ "$(wc -l < "$tmp/rc/$n.cmd")" -gt 1 ] && what="the python block: $what ..."
    rc=$(cat "$tmp/rc/$n" 2>/dev/null || echo "none")
    if [ "$rc" = 0 ]; then
        pass "README: $what"
    else
        fail "README: $what (exit code $rc)"
        tail -n 5 "$tmp/rc/$n.err"
    fi
    n=$((n + 1))
done
check "the README has commands to run (sh and python blocks)" [ "$n" -gt 10 ]
check "the first command prints the listing of case 6-2 (its title)" grep -q "CASE 6-2 FOREHEAD PENDULUM IMPACT" "$tmp/rc/1.out"
check "the first command's listing has the injury criteria" grep -q "INJURY CRITERIA" "$tmp/rc/1.out"
check "the first command's listing ends with END OF RUN" sh -c 'tail -n 6 "$0" | grep -q "END OF RUN AT T ="' "$tmp/rc/1.out"
check "the first command's standard output is the listing alone (it starts with the page rule)" \
    sh -c 'head -n 1 "$0" | grep -q "^====="' "$tmp/rc/1.out"
finish
