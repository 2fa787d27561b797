#!/usr/bin/env python3
"""Compare a listing with its reference (reference/outputs/CASE.txt).

    python3 tools/compare_listing.py LISTING REFERENCE [--rtol 5e-3]

Line by line: the text with every number taken out must be the same, and
every number must agree with the reference within rtol of the largest
magnitude on its line plus one unit of its last printed digit; the time of
an extreme (a number followed by MS, or the times of the peaks table) within
2 ms, because a flat extreme may move by a few samples with the roundoff,
and not at all when the extreme's value agrees within a tenth of the
tolerance (two near-equal extremes, far apart in time, are the same
extreme to within roundoff; either time is right). Lines that
depend on the build or the machine are skipped: the page headers (version,
date), the end-of-run statistics (steps, evaluations, wall time) and the
energy-balance residual (a roundoff-level channel). Prints one PASS or FAIL line; exit 1 on a difference.
"""
import re
import sys

NUM = re.compile(r"(?<![\w.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[EeDd][-+]?\d+)?(?![\w.])")
SKIP = ("HHNECK ", "END OF RUN", "ENERGY BALANCE", "WALL TIME", "E_BALANCE")


def ulp(tok):
    mant = re.split(r"[EeDd]", tok)[0]
    exp = int(re.split(r"[EeDd]", tok)[1]) if re.search(r"[EeDd]", tok) else 0
    dec = len(mant.split(".")[1]) if "." in mant else 0
    return 10.0 ** (exp - dec)


def main():
    args = sys.argv[1:]
    rtol = 5e-3
    if "--rtol" in args:
        k = args.index("--rtol")
        rtol = float(args[k + 1])
        del args[k:k + 2]
    new, ref = (open(p).read().splitlines() for p in args[:2])
    if len(new) != len(ref):
        print("FAIL  %s: %d lines, reference %d" % (args[0], len(new), len(ref)))
        return 1
    worst, where = 0.0, ""
    for i, (a, b) in enumerate(zip(new, ref), 1):
        if any(s in b for s in SKIP):
            continue
        if " ".join(NUM.sub("#", a).split()) != " ".join(NUM.sub("#", b).split()):
            print("FAIL  line %d differs in its text:\n  %s\n  %s" % (i, a.strip(), b.strip()))
            return 1
        ta, tb = NUM.findall(a), NUM.findall(b)
        scale = max([abs(float(t.replace("D", "E").replace("d", "e"))) for t in tb] + [0.0])
        times = {k for k, m in enumerate(NUM.finditer(b)) if b[m.end():m.end() + 3] == " MS"}
        words = [w for w in b.split() if not NUM.fullmatch(w)]
        if len(tb) == 4 and len(words) == 2:          # a row of the peaks table: max, time, min, time
            times |= {1, 3}
        vals = [(float(x.replace("D", "E")), float(y.replace("D", "E"))) for x, y in zip(ta, tb)]
        for k, (x, y) in enumerate(zip(ta, tb)):
            fx, fy = vals[k]
            tol = rtol * scale + ulp(y)
            if k in times:
                tol = max(tol, 2.0)
                if k > 0 and abs(vals[k - 1][0] - vals[k - 1][1]) <= 0.1 * (rtol * scale + ulp(tb[k - 1])):
                    # the extreme's value agrees within a tenth of the
                    # tolerance: two near-equal extremes (a plateau, or two
                    # peaks of the same height) cannot be told apart, and the
                    # time of either one is the time of the extreme
                    continue
            dev = abs(fx - fy) / tol if tol > 0 else 0.0
            if dev > worst:
                worst, where = dev, "line %d: %s against %s" % (i, x, y)
    if worst > 1.0:
        print("FAIL  %s: %s (%.1f times the tolerance)" % (args[0], where, worst))
        return 1
    print("PASS  %s matches %s (largest deviation %.2f of the tolerance%s)" % (
        args[0], args[1], worst, ", " + where if where else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
