#!/usr/bin/env python3
"""The model deck's generator under the name the deck's header gives: it is
python3 -m hhneck.validation.model_deck (python/hhneck/validation/model_deck.py), which reads
reference/model_parameters.csv."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.validation.model_deck import main  # noqa: E402

sys.exit(main())
