"""The cervical muscles of the HYOID OpenSim neck model (reference/parameters.md
S22; shared/data/neck_muscles) that span the column below the skull, mapped
onto the model's bodies: the scalenes (anterior, middle, posterior), levator
scapulae and the cervical parts of splenius, semispinalis, longissimus and
iliocostalis, each from T1 (the data's ribcage, spine and scapula, welded to
T1) to one vertebra, C2 to C5.

    python3 -m hhneck.validation.hyoid_muscles --update     # their rows of the table
    python3 -m hhneck.validation.hyoid_muscles              # the rows, printed

For each muscle the table (reference/model_parameters.csv) gets, status
sourced, source S22: the origin (the last path point on T1) and the
insertion (the first on the vertebra) from the body's mass centre; the
physiological cross-section F0 / sigma_max (the model's F0 = PCSA x
sigma_max gives back the data's F0); the optimal fibre length lopt; the
fibre length over lopt in the data's neutral posture at activation 0.01
(the FIBRE card). A point moves from the data's spine frame (x anterior,
y superior, z right, every neck frame parallel at neutral) to the model's
(x forward, y left, z up) by keeping its offset from the joint centre below
its vertebra (T1: the T1-C7 joint), scaled by the ratio of the two models'
T1-C7 to C1-skull heights. The path points between the origin and the
insertion all lie on T1 in the data, so the straight line from the last of
them has the data's length changes and moment arms. model_deck writes their
HILL and FIBRE cards (CERVICAL_MUSCLES); the controller groups them with the
flexors (scalenes) or the extensors (the others) of their side."""
import argparse
import csv
import os
import sys

from hhneck.validation import model_deck as md
from hhneck.paths import project_root

# the model's name of each (KEY: its table rows; + L or R: its HILL cards),
# the data's muscle (its right side), the data's body of the insertion
MUSCLES = (("SCALA", "scalenus_ant", "C4"), ("SCALM", "scalenus_med", "C3"), ("SCALP", "scalenus_post", "C5"),
           ("LEVS", "levator_scap", "C2"), ("SPLCV", "splen_cerv_c3thx", "C3"), ("SSCV", "semi_cerv_c3thx", "C3"),
           ("LNGCV", "longissi_cerv_c4thx", "C4"), ("ILCV", "iliocost_cerv_c5rib", "C5"))
# the data's joint centres (x, y) in its spine frame at neutral, by the model's
# body above the joint (the data's README, bodies.csv)
JOINTS = {"C7": (-0.0475, 0.3613), "C6": (-0.0411, 0.3793), "C5": (-0.0407, 0.3932), "C4": (-0.0379, 0.4088),
          "C3": (-0.0356, 0.4269), "C2": (-0.0351, 0.4409), "C1": (-0.0336, 0.4734), "HEAD": (-0.0327, 0.4848)}


def data_dir():
    """shared/data/neck_muscles beside the project."""
    return os.path.join(os.path.dirname(project_root()), "shared", "data", "neck_muscles")


def _csv(name):
    with open(os.path.join(data_dir(), name), newline="") as f:
        return list(csv.DictReader(f))


def _model_point(geo, scale, r):
    """(body, position in the model's neutral frame R) of a data path point r."""
    body = r["hhneck_body_inferred"]
    x, y, z = (float(r["%s_spine_neutral_derived_m" % a]) for a in "xyz")
    ref = "C7" if body == "T1" else body
    jx, jy = JOINTS[ref]
    j = geo.joint[ref]
    return body, (j[0] + scale * (x - jx), -scale * z, j[2] + scale * (y - jy))


def mapped(p):
    """{KEY: {origin, insertion (offsets from the mass centre, left side),
    pcsa (cm^2), lopt (m), ln, F0 (N), data muscle}} of MUSCLES on the
    model of parameter values p (md.table_values)."""
    geo = md._Geometry(p)
    scale = (geo.joint["HEAD"][2] - geo.joint["C7"][2]) / (JOINTS["HEAD"][1] - JOINTS["C7"][1])
    arch = {r["muscle"]: r for r in _csv("muscles.csv")}
    neutral = {r["muscle"]: r for r in _csv("derived_opensim_neutral_operating_point.csv")
               if float(r["activation"]) == 0.01}
    points = {}
    for r in _csv("path_points.csv"):
        points.setdefault(r["muscle"], []).append(r)
    out = {}
    for key, name, insertion in MUSCLES:
        path = sorted(points[name], key=lambda r: int(r["order"]))
        on_t1 = [r for r in path if r["hhneck_body_inferred"] == "T1"]
        last = [r for r in path if r["hhneck_body_inferred"] == insertion]
        if not on_t1 or not last or len(on_t1) + len(last) != len(path):
            raise md.DeckError("%s: its path runs from T1 to %s with no body between (data: %s)"
                               % (name, insertion, " ".join(r["hhneck_body_inferred"] for r in path)))
        ends = []
        for r in (on_t1[-1], last[0]):
            body, pos = _model_point(geo, scale, r)
            rel = geo.rel(pos, body)
            ends.append((rel[0], -rel[1], rel[2]))          # the left side: y mirrored
        f0 = float(arch[name]["F0_N"])
        out[key] = {"origin": ends[0], "insertion": ends[1], "F0": f0,
                    "pcsa": f0 / p["muscle.sigma_max"] * 1e4, "lopt": float(arch[name]["lopt_m"]),
                    "ln": float(neutral[name]["norm_fiber_length"]), "data": name, "body": insertion}
    return out


def rows(p):
    """The table rows (md.read_table's dicts) of MUSCLES on parameter values p."""
    out = []
    for key, m in mapped(p).items():
        what = "the HYOID model's %s (S22), mapped by hhneck.validation.hyoid_muscles" % m["data"]
        for end, body in (("origin", "T1"), ("insertion", m["body"])):
            for a, v in zip("xyz", m[end]):
                side = " (left side; the right mirrored)" if a == "y" else ""
                out.append(_row("muscle.%s.%s_%s" % (key, end, a), "%.6f" % v, "m",
                                "%s %s, %s from %s's mass centre%s: %s" % (key, end, a, body, side, what)))
        out.append(_row("muscle.%s.pcsa" % key, "%.5g" % m["pcsa"], "cm^2",
                        "%s physiological cross-section per side, F0 %.5g N / sigma_max: %s" % (key, m["F0"], what)))
        out.append(_row("muscle.%s.lopt" % key, "%.5g" % m["lopt"], "m", "%s optimal fibre length: %s" % (key, what)))
        out.append(_row("muscle.%s.ln" % key, "%.4g" % m["ln"], "1",
                        "%s normalised fibre length lf/lopt in the neutral posture (FIBRE card), at activation "
                        "0.01: %s" % (key, what)))
    return out


def _row(name, value, unit, description):
    return {"name": name, "value": value, "unit": unit, "status": "sourced", "source": "S22", "stage": "",
            "description": description}


def update(table=md.TABLE):
    """Write the rows of MUSCLES into the table: replaced where the table has
    them, else after the last muscle.KEY row before muscle.sigma_max. The
    number of rows written."""
    table_rows = md.read_table(table)
    new = rows(md.table_values(table_rows))
    names = {r["name"] for r in new}
    kept = [r for r in table_rows if r["name"] not in names]
    at = next(i for i, r in enumerate(kept) if r["name"] == "muscle.sigma_max")
    md.write_table(table, kept[:at] + new + kept[at:])
    return len(new)


def main(argv=None):
    """Print the rows, or with --update write them into the table; 0, else 1."""
    ap = argparse.ArgumentParser(prog="python3 -m hhneck.validation.hyoid_muscles", description=__doc__.split("\n\n")[0])
    ap.add_argument("--update", action="store_true", help="write the rows into the table")
    ap.add_argument("--table", default=md.TABLE, help="the parameter table (default reference/model_parameters.csv)")
    a = ap.parse_args(argv)
    try:
        if a.update:
            print("hyoid_muscles: %d rows written to %s" % (update(a.table), a.table), file=sys.stderr)
        else:
            w = csv.DictWriter(sys.stdout, fieldnames=list(_row("", "", "", "")))
            w.writeheader()
            w.writerows(rows(md.table_values(md.read_table(a.table))))
    except (OSError, md.DeckError) as e:
        print("hyoid_muscles: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
