"""Fixed-format deck cards for the tools that write decks or edit copies of
them (docs/deck-format.md: 80-column card images; columns 1-10 the card
name, field Fn columns 10n+1 .. 10n+10; a comment card starts with `*`).

    from hhneck.decks import card, Right
    card("TABLE", "IMPACT", "35", "0.001", 1.0)    # 'TABLE     IMPACT    35        0.001     1.0'
    card("", Right("1.0"), Right("-0.5000"))       # a continuation card of right-aligned numbers

card() is the one writer of a data card: every module that writes decks
lays its cards out through it. Every deck a tool writes goes through
check_cards() (write_decks() does it for decks written to files): a card
beyond column 80 is refused, since the program refuses it too. Comments
that hold text of any length (a path, a name) are made with
comment_cards(), which wraps them over continuation comment cards instead
of losing any of the text. Fields of existing cards: field(), set_field(),
scale_fields(), is_card(); numbers as fields: number_text(),
number_field(), card_number()."""

COLUMNS = 80     # the width of a card image
FIELD = 10       # the width of a field


class CardError(ValueError):
    """A card that does not fit its columns (the deck is not written)."""


class Right(str):
    """A field's text that card() right-aligns in its 10 columns (a deck of
    right-aligned numbers, such as the NBDL T1 tables)."""


def card_number(value):
    """A number as card() writes it: %g with the most significant digits
    (6 down to 1) within 9 columns (a blank column before the next field),
    a decimal point always ("3.0", "0.0"), the exponent as E (1.5E-5);
    text is returned as it is. ValueError when no form fits."""
    if isinstance(value, str):
        return value
    if value == 0:
        return "0.0"
    for p in range(6, 0, -1):
        s = "%.*g" % (p, value)
        if "e" in s:
            m, e = s.split("e")
            s = m + "E" + str(int(e))
        elif "." not in s:
            s = s + ".0"
        if len(s) <= 9:
            return s
    raise ValueError(value)


def card(name, *fields, strip=True):
    """The card image of card `name` with the fields F1, F2, ... `fields`:
    the name in columns 1-10, field Fn from column 10n+1, left-aligned in
    its 10 columns (a Right text right-aligned). A field None is blank; a
    number is written by card_number(); text as it is. A text wider than
    its 10 columns runs on over the next fields (a title, a file name):
    they must be None, else CardError (they would shift). strip: trailing
    blanks dropped; strip=False keeps every field padded to its 10
    columns, the last one too."""
    if len(name) > FIELD:
        raise CardError("card name %r is wider than %d columns" % (name, FIELD))
    line = name
    for n, value in enumerate(fields, start=1):
        start = FIELD * n
        if value is None:
            if len(line) <= start:
                line = line.ljust(start + FIELD)
            continue
        if len(line) > start and line[start:].strip():
            raise CardError("%s card: field F%d (%r) would start after column %d, where the text before it "
                            "ends" % (name or "continuation", n, value, len(line)))
        text = card_number(value)
        line = line[:start].ljust(start) + (text.rjust(FIELD) if isinstance(text, Right) else text.ljust(FIELD))
    if not fields:
        line = line.ljust(FIELD)
    return line.rstrip() if strip else line


def comment_cards(text):
    """Comment cards '* ' + text, within 80 columns: one card when the text
    fits, else as many as needed, each card after the first continuing the
    text of the one above. A card ends before a blank or after a '/' (a path
    is broken between its directories), failing that at column 80 exactly; no
    character is dropped, so ''.join(card[2:] for card in cards) == text."""
    width = COLUMNS - 2
    cards = []
    while len(text) > width:
        k = _break(text, width)
        cards.append("* " + text[:k])
        text = text[k:]
    return cards + ["* " + text]


def _break(text, width):
    """Where comment_cards() ends a card on `text` (longer than `width`):
    the most characters, at most width, that end before a blank (the first of
    a run of blanks) or after a '/' and hold more than blanks; width when no
    such place exists."""
    for k in range(width, 0, -1):
        at_blank = text[k] == " " and text[k - 1] != " "
        if (at_blank or text[k - 1] == "/") and text[:k].strip():
            return k
    return width


def check_cards(lines, deck="the deck"):
    """`lines` (card images, one per item) unchanged when each is within 80
    columns; else CardError naming the deck, the first longer line (numbered
    from 1), its card and its length. A data card cannot be wrapped: the
    writer must give it shorter contents (a shorter path or name)."""
    for n, line in enumerate(lines, 1):
        if len(line) > COLUMNS:
            kind = "comment card" if line.startswith("*") else "%s card" % (field(line, 0) or "continuation")
            raise CardError("%s, line %d: the %s has %d columns, a card at most %d (docs/deck-format.md): %s"
                            % (deck, n, kind, len(line), COLUMNS, line))
    return lines


def write_decks(decks):
    """Write each deck of `decks` ({path: card images, a list of lines or one
    text}) to its path, one card a line, after check_cards() on all of them:
    when a card of any of them passes column 80, none is written
    (CardError)."""
    texts = {}
    for path, lines in decks.items():
        if isinstance(lines, str):
            lines = lines.splitlines()
        texts[path] = "\n".join(check_cards(lines, path)) + "\n"
    for path, text in texts.items():
        with open(path, "w") as f:
            f.write(text)


def write_deck(path, lines):
    """Write one deck (write_decks())."""
    write_decks({path: lines})


def field(line, n):
    """Field n of a card image, stripped ('' past the end)."""
    return line[10 * n:10 * n + 10].strip()


def field_text(value, where="a field"):
    """`value` (text, or a number as %s prints it) as a field: left-aligned
    in its 10 columns; CardError naming `where` when it is wider (it would
    shift the fields after it)."""
    value = str(value)
    if len(value) > FIELD:
        raise CardError("%r is wider than the %d columns of %s" % (value, FIELD, where))
    return "%-10s" % value


def number_text(value, digits=6):
    """A number as a deck field's text: %g with `digits` significant digits,
    a decimal point always, the exponent as E (1.5E-5)."""
    s = "%.*g" % (digits, value)
    if "e" in s:
        m, e = s.split("e")
        s = m + "E" + str(int(e))
    elif "." not in s:
        s += "."
    return s


def number_field(value, where="a field"):
    """A number in a field: number_text with the most significant digits
    (6 down to 1) that fit 9 of its 10 columns, left-aligned: its last
    column stays blank, so the number never touches the next field's (the
    program refuses a number across a field boundary, docs/deck-format.md);
    CardError naming `where` when none does."""
    for digits in range(6, 0, -1):
        s = number_text(value, digits)
        if len(s) < FIELD:
            return field_text(s, where)
    raise CardError("%r does not fit 9 columns of %s" % (value, where))


def set_field(line, n, value):
    """The card image with field n replaced by `value` (text, field_text()):
    left-aligned, unless the field before ends in its last column (a deck of
    right-aligned numbers), then right-aligned, or with a blank on both
    sides when both neighbours touch it: a number written never runs into
    the next or the previous field's text (the program refuses a number
    across a field boundary, docs/deck-format.md)."""
    where = "field F%d of %s" % (n, line.rstrip())
    text = field_text(value, where)
    v = str(value).strip()
    line = line.ljust(80)
    free_before = line[10 * n - 1] == " "
    free_after = 10 * n + 10 >= COLUMNS or line[10 * n + 10] == " "
    if free_before and (len(v) < FIELD or free_after):
        pass
    elif free_after and len(v) < FIELD:
        text = v.rjust(FIELD)
    elif len(v) < FIELD - 1:
        text = (" " + v).ljust(FIELD)
    return (line[:10 * n] + text + line[10 * n + 10:]).rstrip()


def scale_fields(line, ks, factor):
    """The card image with each of its fields ks (0-based) times factor (at
    most 9 columns of digits: a blank column before the next field)."""
    for k in ks:
        v = float(field(line, k)) * factor
        line = set_field(line, k, next(t for t in (number_text(v, d) for d in range(6, 0, -1)) if len(t) <= 9))
    return line


def is_card(line, card, item=None):
    """True on a `card` image whose F1 is `item` (any F1 when item is None)."""
    return field(line, 0) == card and (item is None or field(line, 1) == item)


def held(body, coord):
    """A PRESCRIB card that holds a body's coordinate at its initial value."""
    return card("PRESCRIB", body, coord, "CONSTANT")


def hold(lines, body, coords):
    """The card images with the PRESCRIB cards of body's `coords` replaced by held ones."""
    return [held(body, field(l, 2)) if is_card(l, "PRESCRIB", body) and field(l, 2) in coords else l
            for l in lines]
