"""Benchmark campaigns: every problem x solver x tolerance as a separate,
time-limited process, judged by an independently recomputed FCLIB error, and
reported as performance profiles, speed-against-accuracy charts and failure
maps (`fcsolve bench`, `fcsolve report`; issue 7).

Pure Python (numpy, scipy, h5py; matplotlib for reports; Dask optional): it
drives the fcsolve binary and peer runners and needs nothing from the
compiled extension.

    from fcsolve.campaign import run_campaign, build_report
    run_campaign(["examples/data"], solvers="all", tols=[1e-4, 1e-8], out_dir="campaign")
    build_report("campaign")
"""
from .analysis import performance_ratios, profile
from .results import COLUMNS, FAILURE_CLASSES, load_results


def run_campaign(*args, **kwargs):
    """See runner.run_campaign."""
    from .runner import run_campaign as run

    return run(*args, **kwargs)


def build_report(*args, **kwargs):
    """See report.build_report (imports matplotlib)."""
    from .report import build_report as build

    return build(*args, **kwargs)


__all__ = ["COLUMNS", "FAILURE_CLASSES", "build_report", "load_results", "performance_ratios",
           "profile", "run_campaign"]
