"""The options of ``judder`` that carry the studies' and the library's
arguments.

A study or a library module names an argument of its own in backticks
(`` `scatter` `` of :func:`stability.fit.fit_boundary`, `` `freq_hz` ``
of every study); :func:`in_flags` puts the option that carries it in its
place, so the command line's messages and text speak of the options a
user typed (:func:`infra.errors.in_options`). Where one command's option
carries an argument another's does not, the command module says so in
its own ``FLAGS`` (``names`` is ``--fit`` in ``fit``, ``--params`` in
``advise``), which :func:`in_flags` takes over these.
"""

from infra.errors import in_options

#: Argument of a library function or class -> the option carrying it.
FLAGS = {
    # stability.fit.fit_boundary
    "names": "--fit", "bounds": "--bounds", "scatter": "--scatter",
    # studies.report.report
    "fit_names": "--fit", "sensitivity_names": "--sensitivity",
    # the studies' inputs: files, presets, the bench, outputs
    "boundary": "--boundary", "chart": "--chart", "ranges": "--ranges",
    "group": "--group", "param_file": "--param-file", "preset": "--preset",
    "model": "--model", "changes": "--set", "bench": "--bench",
    "class_name": "--modelica", "pdf": "--pdf", "duration": "--duration",
    "starts": "--starts", "samples": "--samples", "refine": "--refine",
    "engine_rpm": "--rpm", "temperatures": "--temperatures",
    "margin_hz": "--margin-hz", "p_f_bar": "--pf",
    "friction": "--friction", "oil_temperature_c": "--oil-temp",
    "engagement": "--engagement",
    "min_growth": "--min-growth", "factors": "--factors",
    # sources: Parameters.with_overrides, FmuParameters, ModelicaParameters
    "assignments": "--set", "path": "--fmu", "library": "--library",
    "amplitude": "--dither-amplitude", "frequency": "--dither-frequency",
    # pysim.bench: the chart's sources, channels and groups
    "paths": "SOURCE", "index": "--index", "channels": "--channel",
    "group_by": "--group-by", "decimal": "--decimal",
    # studies._common.at_dither_frequency
    "freq_hz": "--freq", "freq_range": "--freq-range",
    "p_max_bar": "--pf-max",
    # stability.threshold.friction_threshold
    "bracket": "--mu-g",
    # infra: the cluster and the overwrite rule
    "workers": "--workers", "scheduler": "--scheduler", "force": "--force",
    "overwrite": "--force",
}


def in_flags(message, own=None):
    """``message`` in the options of the command line; ``own``, the
    ``FLAGS`` of the command that runs, over :data:`FLAGS`."""
    return in_options(message, {**FLAGS, **(own or {})})
