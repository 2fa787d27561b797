"""The volunteer state's controller (input/volunteer_controller.inp) with
parts of it switched off, and the rest deck pushed other ways: the deck
edits that test/scripts/controller.sh and studies/controller_variants.py
run (docs/validation.md, "The controller's parts").

    edited(lines, feedback=True, spindle=True, bracing=True) -> lines
        the controller deck's lines with its head loops' gains (FEEDBACK:
        kp, kd in fields 5 and 6, ki on the continuation), its stretch
        loops' gains (SPINDLE: kp, kd in fields 3 and 4, ki in field 8) or
        its bracing (ACTIVATE: the base levels, fields 3 and 4) zero where
        False
    pushed_rest(rest) -> {name: deck text}
        the rest deck (input/volunteer_rest.inp) started with the other
        pushes of PUSHES instead of its own C3 RX, C4 RY rates of 5, 5 deg/s
    without_controller(deck) -> deck text
        a deck without its INCLUDE of the controller deck (the model deck's
        held reflex alone)
"""

#: the rest deck's other pushes: name, C3 RX and C4 RY initial rates (deg/s)
PUSHES = (("back", -5.0, -5.0), ("side", 10.0, 0.0), ("both", 10.0, 10.0))
#: the rest deck's own INITIAL cards of the two pushed coordinates
REST_C3 = "INITIAL   C3        RX        0.0       5.0"
REST_C4 = "INITIAL   C4        RY        -3.24     5.0"
INCLUDE = "INCLUDE   input/volunteer_controller.inp\n"


def edited(lines, feedback=True, spindle=True, bracing=True):
    """The controller deck's `lines` with the head loops' (FEEDBACK), the
    stretch loops' (SPINDLE) gains or the bracing (ACTIVATE base levels)
    zero where False (module docstring)."""
    out, key = [], ""
    for line in lines:
        if line[:10].strip() and not line.startswith("*"):
            key = line[:8].strip()
        if line.startswith("FEEDBACK") and not feedback:
            line = line[:40] + "%-10s%-10s" % ("0.0", "0.0") + line[60:]
        elif key == "FEEDBACK" and not feedback and not line[:10].strip() and line.strip():
            line = " " * 10 + "0.0"
        elif line.startswith("SPINDLE") and not spindle:
            line = line[:20] + "%-10s%-10s" % ("0.0", "0.0") + line[40:70] + ("0.0" if line[70:].strip() else "")
        elif line.startswith("ACTIVATE") and not bracing:
            line = line[:20] + "%-10s%-10s" % ("0.0", "0.0") + line[40:]
        out.append(line)
    return out


def pushed_rest(rest):
    """The rest deck's text `rest` with each of PUSHES: {name: text}.
    Raises ValueError when the rest deck's INITIAL cards are not the ones
    this edits (REST_C3, REST_C4)."""
    if REST_C3 not in rest or REST_C4 not in rest:
        raise ValueError("the rest deck's INITIAL cards of C3 RX and C4 RY are not %r and %r" % (REST_C3, REST_C4))
    return {name: rest.replace(REST_C3, REST_C3[:40] + "%-10.4g" % rx).replace(REST_C4, REST_C4[:40] + "%-10.4g" % ry)
            for name, rx, ry in PUSHES}


def without_controller(deck):
    """The deck's text without its INCLUDE of the controller deck."""
    return deck.replace(INCLUDE, "")
