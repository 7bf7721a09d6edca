"""The pieces of analysis/analyze.py: reading `warplab export`'s CSVs (inputs), the tests
(stats), the figures (figures) and report.md (report). analyze.py ties them together."""
