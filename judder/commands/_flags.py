"""The options of ``judder`` that carry the library's arguments.

A library module names an argument of its own in backticks (`` `scatter` ``
of :func:`stability.fit.fit_boundary`); :func:`in_flags` puts the option
that carries it in its place, so the command line's messages speak of
the options a user typed (:func:`infra.errors.in_options`).
"""

from infra.errors import in_options

#: Argument of a library function or class -> the option carrying it.
FLAGS = {
    # stability.fit.fit_boundary
    "names": "--fit", "bounds": "--bounds", "scatter": "--scatter",
    # judder.commands.report.report
    "fit_names": "--fit",
    # sources: Parameters.with_overrides, FmuParameters, ModelicaParameters
    "assignments": "--set", "path": "--fmu", "library": "--library",
    "amplitude": "--dither-amplitude", "frequency": "--dither-frequency",
    # pysim.bench_data: the chart's sources, channels and groups
    "paths": "SOURCE", "index": "--index", "channels": "--channel",
    "group_by": "--group-by", "decimal": "--decimal",
    # judder.commands._common.at_dither_frequency
    "freq_hz": "--freq", "freq_range": "--freq-range",
    "p_max_bar": "--pf-max",
    # stability.threshold.friction_threshold
    "bracket": "--mu-g",
    # infra: the cluster and the overwrite rule
    "workers": "--workers", "scheduler": "--scheduler", "force": "--force",
    "overwrite": "--force",
}


def in_flags(message):
    """``message`` in the options of the command line."""
    return in_options(message, FLAGS)
