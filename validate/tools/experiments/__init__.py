"""`isorock experiments` (issue 21): the rigid rocking model and the contact engines scored
against measured shake-table tests of two granite rocks (the Virtual Shake Robot data,
GPL-3.0, read at run time from a folder outside the repository, never copied into it).

Data flow: tests (data) → processed table acceleration (processing) → the specimen's
equivalent block or its hull (specimen) → engine → overturned or not, θmax/α → scores
held out by cross-validation (scores) → tables and figures (study).
"""
