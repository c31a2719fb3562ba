"""Stability fuzz of the whole CLI: seeded random invocations run in subprocesses and checked.

``python -m tests.fuzz --n 5000 [--seed S] [--seconds T]`` runs a long campaign and prints a
summary (record it in benchmarks/results.md); tests/fuzz/test_fuzz.py runs a short one in CI.
"""
