"""Evaluation: replay, baselines, metrics, plots, tuning, and the dataset converters."""
