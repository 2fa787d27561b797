"""The tools of the hhneck head/neck model (docs/architecture.md, "Python package").

The API, this top level (examples: docs/api.md):

- paths: project_root(), project_path(*parts), the project's files
  whatever the working directory ($HHNECK_ROOT for a copy installed
  elsewhere);
- run: run_deck(deck, changes=(), ...) -> Run, change_card(...),
  RunError: run a deck through the executable with CHANGE cards;
- results: read_channels, read_bodies, read_injury, read_results,
  read_sweep, read_sensitivity: a result file into pandas with units;
- export: write_csv, mme_from_result, write_mme, read_mme (CSV, ISO-MME);
- ratings: rate, rate_many (ISO/TS 18571), cora, compare, peak,
  model_channels (the NBDL cases' CORA-style rating and peaks);
- decks: card(name, *fields), the one writer of a data card, and field,
  set_field, number_field, is_card, comment_cards, check_cards,
  write_deck, CardError;
- signals: cfc, the SAE J211/1 filter;
- volunteers: runs, volunteer_channels, data_dir (the NBDL volunteer runs).

Subpackages: hhneck.tools (the user tools: animate, xdmf, the plots and
comparisons) and hhneck.validation (the validation and calibration
pipeline, its steps run as python3 -m hhneck.validation.MODULE); each
__init__ lists its modules. The user commands (python/pyproject.toml,
[project.scripts]) are hhneck-run-deck, hhneck-results, hhneck-export,
hhneck-iso18571, hhneck-animate, hhneck-xdmf, hhneck-compare-nbdl,
hhneck-compare-listing, hhneck-compare-sweeps, hhneck-plot-sensitivity,
hhneck-plot-corridor, hhneck-plot-work-precision and hhneck-catalogue; each
module with a command line has main(argv=None)."""
__version__ = "0.3.0"
