"""Compare two sweep result files member by member.

    hhneck-compare-sweeps A.h5 B.h5 [--expect-failed N]

Passes when the designs, the status and message of every member, its
evaluation count and every summary output are exactly equal (bit for bit:
the same build must give the same numbers however the members were spread
over ranks), and, with --expect-failed, when exactly N members failed and
every failed member has a message. Prints one PASS or FAIL line per check
and exits non-zero on any failure.
"""
import argparse
import sys

import h5py
import numpy as np


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-compare-sweeps", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("a", help="first sweep result file")
    p.add_argument("b", help="second sweep result file (its ranks are checked)")
    p.add_argument("--expect-failed", type=int, metavar="N", help="exactly N members failed")
    args = p.parse_args(argv)
    expect_failed = args.expect_failed
    a, b = h5py.File(args.a, "r"), h5py.File(args.b, "r")
    passes = failures = 0

    def check(ok, what, detail=""):
        nonlocal passes, failures
        print(("PASS  " if ok else "FAIL  ") + what + (f"  [{detail}]" if detail else ""))
        passes += 1 if ok else 0
        failures += 0 if ok else 1

    for path in ["runs/inputs", "runs/outputs", "runs/status", "runs/evaluations", "runs/t_reached",
                 "runs/message", "sensitivity/coefficient", "sensitivity/valid"]:
        x, y = a[path][()], b[path][()]
        check(x.shape == y.shape and np.array_equal(x, y), f"{path} identical", f"shape {x.shape}")
    ranks = sorted(set(b["runs/rank"][()].tolist()))
    nranks = int(np.ravel(b.attrs["ranks"])[0])    # a scalar integer; an array of one real before schema 2
    nrun = b["runs/status"].shape[0]
    check(ranks == list(range(min(nranks, nrun))) if nrun >= nranks else set(ranks) <= set(range(nranks)),
          f"the work was spread over the {nranks} rank(s) of the second file",
          "ranks used: " + " ".join(map(str, ranks)))
    if expect_failed is not None:
        status = b["runs/status"][()]
        msgs = b["runs/message"][()]
        failed = np.flatnonzero(status != 0)
        check(len(failed) == expect_failed, f"{expect_failed} failed member(s) recorded with their exit code",
              "; ".join(f"run {i + 1}: exit {status[i]}" for i in failed))
        check(all(len(msgs[i].strip()) > 0 for i in failed), "every failed member has a message")
        check(bool(np.all(b["runs/outputs"][()][failed] == 0.0)), "outputs of the failed members are zero")
        check(bool(np.all(np.isfinite(b["runs/outputs"][()]))), "every output finite (no NaN)")
    print(f"{passes} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
