#!/bin/sh
# The card registries and their documents list the same cards:
#   * the case deck: src/deck/hn_cards.f90 and, for the element families'
#     cards, the families' registry entries in src/elements/, against
#     docs/deck-format.md;
#   * the sweep deck: the table of `sweep_format` (src/sweeps/hn_sweep.f90),
#     against the section "## The sweep deck" of docs/sweeps.md;
#   * the calibration deck: the table of `calibration_format`
#     (src/sweeps/hn_calibrate_deck.f90), against the section
#     "## Calibration" of docs/sweeps.md.
# Every registry card has a `### NAME —` section (a section may name
# several, "### FORCE, COUPLE"), and every section names registry cards
# (INCLUDE and END, the reader's and the card engine's, not cards, are the
# exceptions). Also shown to fail, for each deck: a copy of its document with
# one section taken out and one card added.
# This check runs no executable: HHNECK is not needed.
HHNECK=${HHNECK:-none}
. test/scripts/lib/checks.sh

# compare REGISTRY DOC [SECTION]: one line per card missing on either side,
# exit 1 on any. REGISTRY src/deck/hn_cards.f90: its card_info_t lines and
# the family_card_t lines of src/elements/, against the whole of DOC; any
# other: its deck_card_t lines, against the `##` section SECTION of DOC.
compare() {
    python3 - "$1" "$2" "${3:-}" src/elements <<'PY'
import glob, os, re, sys
registry, docfile, section, elements = sys.argv[1:5]
text = open(registry, encoding='utf-8').read()
if os.path.basename(registry) == 'hn_cards.f90':
    reg = set(re.findall(r"card_info_t\('([A-Z0-9]+)'", text))
    families = set()
    for path in sorted(glob.glob(os.path.join(elements, '*.f90'))):
        families |= set(re.findall(r"family_card_t\('([A-Z0-9]+)'", open(path, encoding='utf-8').read()))
    if not families:
        print('no family_card_t lines in ' + elements); sys.exit(1)
    reg |= families
    what = 'card_info_t'
else:
    reg = set(re.findall(r"deck_card_t\('([A-Z0-9]+)'", text))
    what = 'deck_card_t'
if not reg:
    print(f'no {what} lines in {registry}'); sys.exit(1)
doc, inside, found = set(), not section, not section
for line in open(docfile, encoding='utf-8'):
    if section and line.startswith('## '):
        inside = line.strip() == '## ' + section
        found = found or inside
        continue
    m = re.match(r'###\s+([A-Z0-9, ]+?)\s+—', line)
    if m and inside:
        doc.update(n.strip() for n in m.group(1).split(','))
if not found:
    print(f'no section "## {section}" in {docfile}'); sys.exit(1)
doc -= {'INCLUDE', 'END'}
where = docfile + (f' ("## {section}")' if section else '')
bad = 0
for name in sorted(reg - doc):
    print(f'card {name} of the registry {registry} has no ### section in {where}'); bad += 1
for name in sorted(doc - reg):
    print(f'section ### {name} of {where} is no card of the registry {registry}'); bad += 1
sys.exit(1 if bad else 0)
PY
}

# check_deck WHAT REGISTRY DOC SECTION DROPPED RENAMED: the registry against
# its document, then against a copy without the section of card DROPPED and
# with the section of card RENAMED naming NOSUCH too (both must be named)
check_deck() {
    what=$1; registry=$2; doc=$3; section=$4; dropped=$5; renamed=$6
    if compare "$registry" "$doc" "$section" > "$tmp/report" 2>&1; then
        pass "$what: every card of the registry has a section of $doc, and every section a card"
    else
        cat "$tmp/report"
        fail "$what: the registry's cards and $doc's sections differ"
    fi
    # the first section of each card in the deck's part of the document
    python3 - "$doc" "$section" "$dropped" "$renamed" > "$tmp/altered.md" <<'PY'
import re, sys
doc, section, dropped, renamed = sys.argv[1:5]
inside, done = not section, set()
for line in open(doc, encoding='utf-8'):
    if section and line.startswith('## '):
        inside = line.strip() == '## ' + section
    for name, new in ((dropped, '#### ' + dropped + ' —'), (renamed, '### ' + renamed + ', NOSUCH —')):
        if inside and name not in done and line.startswith('### ' + name + ' —'):
            line = line.replace('### ' + name + ' —', new, 1)
            done.add(name)
    sys.stdout.write(line)
PY
    if compare "$registry" "$tmp/altered.md" "$section" > "$tmp/report2" 2>&1; then
        fail "$what: the check accepts a document without $dropped and with NOSUCH"
    elif grep -q "card $dropped of the registry" "$tmp/report2" && grep -q 'section ### NOSUCH' "$tmp/report2"; then
        pass "$what: the check names a missing section ($dropped) and a section of no card (NOSUCH)"
    else
        cat "$tmp/report2"
        fail "$what: the check fails on the altered document, but does not name $dropped and NOSUCH"
    fi
}

check_deck 'case deck' src/deck/hn_cards.f90 docs/deck-format.md '' ROM TITLE
check_deck 'sweep deck' src/sweeps/hn_sweep.f90 docs/sweeps.md 'The sweep deck' BASE TITLE
check_deck 'calibration deck' src/sweeps/hn_calibrate_deck.f90 docs/sweeps.md 'Calibration' RATING CURVES

finish
