#!/bin/sh
# The two-stage fit of docs/validation.md ("Passive to the catalogue, then
# the muscles to the volunteers"): hhneck-calibrate-catalogue --two-stage on
# the shipped model deck, or with SEGMENTAL=1 in the environment on the deck
# generator's variant with the segmental muscles (python3 -m hhneck.model_deck
# --segmental yes: every other value the table's, the shipped deck's).
# Writes WORK/ and WORK.md.
# Usage: dev/catalogue_two_stage.sh [WORK]   (default two_stage; about 15 minutes)
set -e
cd "$(dirname "$0")/.."
work=${1:-two_stage}
# this tree's Python package, whichever one the machine's Python has
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"
exe=$(fpm run --profile release --runner echo 2>/dev/null | tail -1)
case $exe in /*) ;; *) exe=$PWD/$exe ;; esac
model=input/head_neck_54dof.inp
if [ "${SEGMENTAL:-0}" = 1 ]; then
    PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}" python3 -m hhneck.model_deck --segmental yes \
        --output "$work.inp"
    model=$work.inp
fi
HHNECK=$exe python3 -m hhneck.calibration "$work" --two-stage --evals 150 --starts 16 --model "$model" \
    --table "$work.md"
