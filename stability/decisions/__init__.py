"""Decisions on a design read from the Floquet analysis: which
instabilities are judder (:mod:`~stability.decisions.relevance`), how far
a dither setting lies from the nearest judder-relevant tongue
(:mod:`~stability.decisions.margins`), and the safe dither windows and
smallest design change that clears them (:mod:`~stability.decisions.advice`,
section 4.3 and 5 of the paper).

The growth-rate threshold itself is :mod:`infra.criteria`'s, shared with
the time-domain verdict of :mod:`pysim.bench.verdict`.
"""

from .advice import Advice, OperatingRange, advise_design, safe_windows
from .margins import Margin, SettingCheck, check_settings, setting_margin
from .relevance import is_judder_relevant, verdict

__all__ = ["is_judder_relevant", "verdict", "Margin", "SettingCheck",
           "setting_margin", "check_settings", "OperatingRange", "Advice",
           "advise_design", "safe_windows"]
