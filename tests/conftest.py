"""Test-suite configuration.

Hypothesis: under CI (``CI`` set in the environment) the property tests run derandomised, with a
fixed example sequence and no example database, so that a submission's CI verdict is
reproducible; locally they explore new random examples on every run (and keep failures in
``.hypothesis/``), which is where new edge cases get found and then pinned with ``@example``.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
settings.register_profile("dev", print_blob=True)
settings.load_profile("ci" if os.environ.get("CI") else "dev")
