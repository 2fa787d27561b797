#!/bin/sh
# The card registries (src/deck/hn_cards.f90 and, for the element families'
# cards, the families' registry entries in src/elements/) and the deck format
# (docs/deck-format.md) list the same cards: every registry card has a
# `### NAME` section (a section may name several, "### FORCE, COUPLE"),
# and every section names registry cards (INCLUDE, read by hn_deck_reader
# before any card is grouped, is the one exception). Also shown to fail: a
# copy of the format with one section taken out and one card added.
# This check runs no executable: HHNECK is not needed.
HHNECK=${HHNECK:-none}
. test/scripts/lib/checks.sh

compare() {   # compare REGISTRY DOC: one line per card missing on either side, exit 1 on any
    python3 - "$1" "$2" src/elements <<'PY'
import glob, os, re, sys
reg = set(re.findall(r"card_info_t\('([A-Z0-9]+)'", open(sys.argv[1], encoding='utf-8').read()))
families = set()
for path in sorted(glob.glob(os.path.join(sys.argv[3], '*.f90'))):
    families |= set(re.findall(r"family_card_t\('([A-Z0-9]+)'", open(path, encoding='utf-8').read()))
if not families:
    print('no family_card_t lines in ' + sys.argv[3]); sys.exit(1)
reg |= families
doc = set()
for line in open(sys.argv[2], encoding='utf-8'):
    m = re.match(r'###\s+([A-Z0-9, ]+?)\s+—', line)
    if m:
        doc.update(n.strip() for n in m.group(1).split(','))
doc.discard('INCLUDE')
bad = 0
if not reg:
    print('no card_info_t lines in ' + sys.argv[1]); sys.exit(1)
for name in sorted(reg - doc):
    print(f'card {name} of the registry has no ### section in {sys.argv[2]}'); bad += 1
for name in sorted(doc - reg):
    print(f'section ### {name} of {sys.argv[2]} is no card of the registry'); bad += 1
sys.exit(1 if bad else 0)
PY
}

if compare src/deck/hn_cards.f90 docs/deck-format.md > "$tmp/report" 2>&1; then
    pass "every card of the registry has a section of docs/deck-format.md, and every section a card"
else
    cat "$tmp/report"
    fail "the registry's cards and docs/deck-format.md's sections differ"
fi

# a format without the ROM section, with a section of a card the registry lacks
sed -e 's/^### ROM —/#### ROM —/' -e 's/^### TITLE —/### TITLE, NOSUCH —/' docs/deck-format.md > "$tmp/format.md"
if compare src/deck/hn_cards.f90 "$tmp/format.md" > "$tmp/report2" 2>&1; then
    fail "the check accepts a format without ROM and with NOSUCH"
elif grep -q 'card ROM of the registry' "$tmp/report2" && grep -q 'section ### NOSUCH' "$tmp/report2"; then
    pass "the check names a missing section (ROM) and a section of no card (NOSUCH)"
else
    cat "$tmp/report2"
    fail "the check fails on the altered format, but does not name ROM and NOSUCH"
fi

finish
