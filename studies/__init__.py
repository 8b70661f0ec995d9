"""Research on the tool, apart from it and not installed with it: the paper's figures and
claims, benchmarks, the fine reference, and the studies docs/ explains. Each module runs
as ``python -m studies.NAME`` from the repository and writes into results/: a study that
measures something writes, beside its CSV, a markdown report of its tables and findings
(studies/report.py formats them), which docs/ links instead of typing its numbers;
it uses the tool's public API only (the ``orchestrate`` package and its layers'
packages, never a module inside them: tests/test_layers.py)."""
