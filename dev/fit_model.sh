#!/bin/sh
# The shipped model deck from its fits, in order (docs/validation.md). The
# fits write their values into the parameter table
# reference/model_parameters.csv (status fitted, the stage named), and the
# deck is regenerated from the table (python3 -m hhneck.model_deck;
# reference/parameters.md):
#   1. the model deck at the calibration's starting point (the PARAM values of
#      the VALUES cards of input/calibrate_nbdl12g.inp, --fit: the table
#      unchanged), the discs' bending and torsion at the table's
#      disc.rot_fraction, the upper-cervical cards as sourced
#      (--upper-cervical none);
#   2. hhneck-fit-joints on it: the neutral-zone springs fitted to the segment
#      tests (Panjabi 2001, Nightingale 2007) less the other elements' moment,
#      its runs with the NZSPRING cards dropped -> reference/nz_springs.csv,
#      written into the table's rows nz.* (stage nz_springs)
#      (with UPPER_CERVICAL=1 in the environment, first the upper-cervical
#      factors, hhneck.upper_cervical -> reference/upper_cervical.csv, and the
#      springs on the deck with them: an experiment, docs/validation.md "The
#      upper cervical joints"; the shipped model is fitted without; SUBOCCIPITAL=1
#      adds the suboccipital muscles, --suboccipital yes, in every step, the
#      same section's other experiment; SEGMENTAL=1 the segmental muscles with
#      the subaxial discs' bending at 0.2 (SUB_BEND=F another fraction),
#      --segmental yes --sub-bend 0.2, docs/validation.md "Segmental
#      muscles"; SUB_FLEXION=F the flexion-extension bending of the discs
#      C3-C4 ... C7-T1 at F, --sub-flexion F, docs/validation.md "The
#      subaxial discs' flexion-extension");
#   3. hhneck --calibrate < input/calibrate_nbdl12g.inp on the model deck with
#      those springs: muscles, damping and the discs' and stops' factors fitted
#      to the NBDL 12 g volunteers -> the listing FIT, its PARAM values
#      written into the table's rows of those names (stage nbdl12g);
#   4. the model deck from the table.
# Every step is deterministic, so the shipped deck, reference/nz_springs.csv
# and reference/model_parameters.csv come out as they are committed (the
# springs fitted at the starting point, not refitted at the fit:
# docs/validation.md says what that changes).
# Usage: dev/fit_model.sh [FIT]   (default fit12.txt; about 15 minutes). It
# rewrites input/head_neck_54dof.inp, reference/nz_springs.csv and
# reference/model_parameters.csv in place: run an experiment's variant in a
# scratch copy (git worktree add), not in a tree you commit from while it runs.
set -e
cd "$(dirname "$0")/.."
# this tree's Python package, whichever tree the installed one points to, so
# that a scratch copy's fit writes its own springs (hhneck-fit-joints writes
# reference/nz_springs.csv below the package's tree)
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"
fit=${1:-fit12.txt}
exe=$(fpm run --profile release --runner echo 2>/dev/null | tail -1)
case $exe in /*) ;; *) exe=$PWD/$exe ;; esac
start=$(mktemp)
trap 'rm -f "$start"' EXIT
# the VALUES point as the PARAM lines of a calibration listing
awk '/^PARAM /{name[++n] = substr($0, 11, 10); gsub(/ /, "", name[n])}
     /^VALUES/{for (k = 11; k <= length($0); k += 10) {v = substr($0, k, 10); gsub(/ /, "", v);
                                                        if (v != "") val[++m] = v}}
     END {if (m != n) {print "fit_model.sh: " m " VALUES for " n " PARAM cards" > "/dev/stderr"; exit 1}
          for (k = 1; k <= n; k++) print "PARAM " name[k] " = " val[k]}' input/calibrate_nbdl12g.inp > "$start"
if [ "${UPPER_CERVICAL:-0}" = 1 ]; then upper=reference/upper_cervical.csv; flag=--upper-cervical
else upper=none; flag=; fi
if [ "${SUBOCCIPITAL:-0}" = 1 ]; then sub=yes; else sub=no; fi
if [ "${SEGMENTAL:-0}" = 1 ]; then seg="--segmental yes --sub-bend ${SUB_BEND:-0.2}"; else seg=; fi
if [ -n "${SUB_FLEXION:-}" ]; then seg="$seg --sub-flexion $SUB_FLEXION"; fi
deck() { python3 -m hhneck.model_deck --upper-cervical $upper --suboccipital $sub $seg "$@"; }
deck --fit "$start" --upper-cervical none --output input/head_neck_54dof.inp
HHNECK=$exe ${FIT_JOINTS:-python3 -m hhneck.fit_joints} $flag
python3 -m hhneck.model_deck --record nz_springs reference/nz_springs.csv
deck --fit "$start" --output input/head_neck_54dof.inp
"$exe" --calibrate < input/calibrate_nbdl12g.inp > "$fit"
python3 -m hhneck.model_deck --record nbdl12g "$fit"
deck --output input/head_neck_54dof.inp
echo "fit_model.sh: reference/model_parameters.csv written from reference/nz_springs.csv and $fit," \
     "input/head_neck_54dof.inp from it (upper cervical: $upper)" >&2
