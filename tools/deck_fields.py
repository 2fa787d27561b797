"""Fixed-format deck fields for the tools that edit copies of the decks
(docs/deck-format.md: columns 1-10 the card name, field Fn columns
10n+1 .. 10n+10)."""


def field(line, n):
    """Field n of a card image, stripped ('' past the end)."""
    return line[10 * n:10 * n + 10].strip()


def set_field(line, n, value):
    """The card image with field n replaced by `value` (text, left-aligned)."""
    line = line.ljust(80)
    return (line[:10 * n] + "%-10s" % value + line[10 * n + 10:]).rstrip()


def is_card(line, card, item=None):
    """True on a `card` image whose F1 is `item` (any F1 when item is None)."""
    return field(line, 0) == card and (item is None or field(line, 1) == item)


def held(body, coord):
    """A PRESCRIB card that holds a body's coordinate at its initial value."""
    return "%-10s%-10s%-10sCONSTANT" % ("PRESCRIB", body, coord)


def hold(lines, body, coords):
    """The card images with the PRESCRIB cards of body's `coords` replaced by held ones."""
    return [held(body, field(l, 2)) if is_card(l, "PRESCRIB", body) and field(l, 2) in coords else l
            for l in lines]
