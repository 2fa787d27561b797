#!/bin/sh
# The shipped model deck from its fits, in order (docs/validation.md,
# "Calibration"). The fits write their values into the parameter table
# reference/model_parameters.csv (status fitted, the stage named) or their own
# deck, and the model deck is regenerated from the table
# (python3 -m hhneck.validation.model_deck; reference/parameters.md):
#   0. the cervical muscles' rows mapped from the published neck-muscle model
#      (python3 -m hhneck.validation.hyoid_muscles --update; seconds);
#   1. the passive column from the segment tests alone (Panjabi 2001,
#      Nightingale 2007): python3 -m hhneck.validation.fit_column fits the discs' bending
#      and torsion fractions and the range-of-motion factors, the neutral-zone
#      springs refitted by python3 -m hhneck.validation.fit_joints at every candidate
#      -> reference/column_fit.csv and reference/nz_springs.csv, written into
#      the table's rows (stages segments and nz_springs). Deterministic; about
#      20 minutes on two shared cores (60 evaluations of 48 segment runs as
#      statics, 15-25 s each; 1030 s measured);
#   2. if dev/fit_controller.sh exists: the volunteer state's controller
#      (input/volunteer_controller.inp, included after the model deck) fitted
#      to the NBDL 12 g volunteers on the column of step 1; it moves no row of
#      the table (constraint 1); its time is its own header's;
#   3. the model deck from the table (seconds).
# The specimen state is the model deck itself (its muscles passive); the
# volunteer state adds the controller of step 2.
# Usage: dev/fit_model.sh   (MAX_EVAL=N: the column's evaluations, default 60;
# FIT_COLUMN=COMMAND stands in for step 1's fit, as the tests do).
# It rewrites reference/column_fit.csv, reference/nz_springs.csv,
# reference/model_parameters.csv and input/head_neck_54dof.inp in place: run
# an experiment in a scratch copy (git worktree add), not in a tree you commit
# from while it runs.
set -e
cd "$(dirname "$0")/.."
# this tree's Python package, whichever tree the installed one points to
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"
exe=$(fpm run --profile release --runner echo 2>/dev/null | tail -1)
case $exe in /*) ;; *) exe=$PWD/$exe ;; esac
export HHNECK=$exe
python3 -m hhneck.validation.hyoid_muscles --update
${FIT_COLUMN:-python3 -m hhneck.validation.fit_column} --max-eval "${MAX_EVAL:-60}"
python3 -m hhneck.validation.model_deck --record segments reference/column_fit.csv
python3 -m hhneck.validation.model_deck --record nz_springs reference/nz_springs.csv --output input/head_neck_54dof.inp
if [ -f dev/fit_controller.sh ]; then
    sh dev/fit_controller.sh
fi
python3 -m hhneck.validation.model_deck --output input/head_neck_54dof.inp
echo "fit_model.sh: reference/model_parameters.csv written from reference/column_fit.csv and" \
     "reference/nz_springs.csv, input/head_neck_54dof.inp from it" >&2
