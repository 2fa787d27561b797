"""The user tools of hhneck: animations and viewers, plots and comparisons
(docs/architecture.md, "Python package"). Each has main(argv=None),
installed as a console command hhneck-NAME and runnable as
python3 -m hhneck.tools.MODULE.

Modules: animate (GIF, MP4 and key-frame strips of a result file), xdmf
(the XDMF file for ParaView), plot_corridor (the prediction corridor
against the volunteers'), plot_sensitivity (a sweep's sensitivity plot and
table), plot_work_precision (the integrators' work-precision diagram),
compare_listing (a listing against its reference within physical
tolerances), compare_sweeps (two sweep result files member by member),
compare_nbdl (the NBDL runs against the volunteers: the table and figures
of docs/validation.md)."""
