"""The tools of the hhneck head/neck model (docs/architecture.md, "Python package").

The public surface, with examples: docs/api.md. The project's files are
found from the package's own place, whatever the working directory
(paths.project_root(); $HHNECK_ROOT for a copy installed elsewhere).

Modules: paths (the project's files), run (run a deck with changes),
results (read a result file into pandas with units), export (CSV,
ISO-MME), nbdl (the NBDL volunteer runs, the CFC filter, the ratings of
hhneck-compare-nbdl), compare_nbdl, iso18571,
compare_listing, compare_sweeps, animate, xdmf, plot_sensitivity,
plot_corridor, plot_work_precision, nbdl_tables, case_decks, deck_fields,
segments, specimens, specimen_data, catalogue (the validation catalogue),
calibration (calibration over the specimen cases), model_deck (the model
deck from its parameter table, reference/model_parameters.csv).
Each module with a command line has main(argv=None), installed as the
console command hhneck-NAME and runnable as python3 -m hhneck.MODULE."""
__version__ = "0.3.0"
