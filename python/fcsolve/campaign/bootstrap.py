"""Imports the campaign without fcsolve/__init__.py (standard library only).

The campaign is pure Python and needs nothing from the compiled extension
that `import fcsolve` loads. When it is started by path (the `fcsolve bench`
and `fcsolve report` commands do that) or runs on a Dask worker that has no
fcsolve installed, `fcsolve` is registered as a bare package over the folder
that holds this file's parent, so `fcsolve.campaign` imports alone.

This module is shipped to Dask workers by value (cloudpickle), so it must not
import anything from the campaign at module level.
"""
import importlib
import os
import sys
import types


def import_campaign(campaign_dir):
    """Returns the module fcsolve.campaign found in `campaign_dir`.

    If `fcsolve` is already imported (a full package, perhaps without the
    campaign), the folder is added to its search path instead.
    """
    parent = os.path.dirname(os.path.abspath(campaign_dir))
    package = sys.modules.get("fcsolve")
    if package is None:
        package = types.ModuleType("fcsolve")
        package.__path__ = [parent]
        package.__package__ = "fcsolve"
        sys.modules["fcsolve"] = package
    elif parent not in list(getattr(package, "__path__", [])):
        package.__path__.append(parent)
    return importlib.import_module("fcsolve.campaign")


def run_task_dict(campaign_dir, task):
    """Runs one task given as a dict (Dask workers: no campaign class in the pickle)."""
    import_campaign(campaign_dir)
    from fcsolve.campaign.tasks import Task, run_task

    return run_task(Task(**task))
