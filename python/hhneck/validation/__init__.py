"""The validation and calibration pipeline of hhneck: the decks it writes,
the catalogue of cases it runs and rates, the fits that write the model's
parameter table (docs/architecture.md, "Python package"; docs/validation.md).
Its steps run as python3 -m hhneck.validation.MODULE; only the catalogue
is also a console command, hhneck-catalogue (a user's check of a changed
model against every case).

Modules: catalogue (the validation catalogue), calibration (calibration
over the catalogue's cases), segments (the quasi-static segment tests),
specimens and specimen_data (the specimen sled tests and their data),
newton_balance (Newton's law between a sled test's head and its load cell),
fit_column (the passive column fitted to the segment tests), fit_joints
(the neutral-zone springs), upper_cervical (the upper-cervical factors),
model_deck (the model deck input/head_neck_54dof.inp from
reference/model_parameters.csv), hyoid_muscles (the cervical muscles'
rows of that table, mapped from the HYOID neck model), case_decks (the pulse-driven case decks
of input/), nbdl_tables (the T1 drive tables of the NBDL decks, and new
cases from other runs), controller_variants (the volunteer controller's
parts switched off, and the rest deck's other pushes)."""
