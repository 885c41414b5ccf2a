"""Tests of the benchmark scripts and recipes in ``benchmarks/``."""
