"""``judder eig``: natural frequencies and damping factor."""

from sources.dither_modes import linearised_mode, mode_words
from studies.eig import eig

from ._arguments import driveline_option, model_options
from ._model import parameters_of
from ._output import emit

#: The command's --help text.
DESCRIPTION = (
    "Undamped natural frequencies (Eq. 14-15, Hz), clutch-damper "
    "damping factor (Eq. 16) and the damped modes without dither, "
    "rigid-body angles removed. For --modelica or --fmu: the "
    "frequencies of its Jacobian's stiffness part and its damped modes; "
    "Eq. 15-16 are the paper's chains' formulas (null in --json).")


OUTPUTS = ()


def add_arguments(p):
    """The options of ``judder eig``."""
    model_options(p)
    driveline_option(p)


def run(args):
    """Natural frequencies and the clutch-damper damping factor."""
    result = eig(*parameters_of(args), driveline=args.driveline)
    zeta = result.damping_factor_12
    words = mode_words(linearised_mode(result.params))
    from stability.bench import driveline_words
    lines = [f"model {result.params.model}: "
             f"{driveline_words(result.params, result.driveline)}"
             + (f", {words} (held over a period at the class's own "
                "dither setting)"
                if words else ""),
             f"undamped natural frequencies ({result.frequencies_from}): "
             + ", ".join(f"{f:.3f} Hz" for f in result.natural_frequencies_hz),
             "clutch-damper damping factor (Eq. 16): "
             + ("not defined (a formula of the paper's chains)"
                if zeta is None else f"{100 * zeta:.2f} %"),
             ("damped modes of the bench (its speed control damps body "
              "1) without dither: " if result.driveline == "bench" else
              "damped modes without dither, rigid-body angles removed: ")
             + ", ".join(f"{f:.3f} Hz ({100 * r:.2f} %)" for f, r in
                         zip(result.damped_frequencies_hz,
                             result.damping_ratio))]
    emit(args, result.as_dict(), "\n".join(lines))
