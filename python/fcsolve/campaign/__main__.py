"""`python3 -m fcsolve.campaign bench|report ...`, or this file run by path
(what `fcsolve bench` and `fcsolve report` do: then `fcsolve` is not
imported, so the campaign works without the compiled extension)."""
import os
import sys

if not __package__:  # run by path
    import importlib.util

    _here = os.path.dirname(os.path.abspath(__file__))
    _spec = importlib.util.spec_from_file_location("_fcsolve_campaign_bootstrap",
                                                   os.path.join(_here, "bootstrap.py"))
    _bootstrap = importlib.util.module_from_spec(_spec)
    _spec.loader.exec_module(_bootstrap)
    sys.path[0:1] = []  # the script's folder holds modules that must not shadow others
    _bootstrap.import_campaign(_here)
    from fcsolve.campaign.cli import main
else:
    from .cli import main

sys.exit(main())
