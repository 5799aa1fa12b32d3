"""Benchmarks: `situated bench kb|dialogue|http|all` prints measured figures beside baselines."""
