"""``judder threshold``: friction-gradient threshold without dither (Fig. 19).
"""

from studies._preflight import check_threshold
from studies.threshold import threshold

from ._arguments import force_option, model_options
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._values import Grid

#: The command's --help text.
DESCRIPTION = (
    "Largest real part of the eigenvalues without dither against mu_g "
    "(Fig. 19a), and the threshold mu_g* against the external damping "
    "c_i (Fig. 19b; every c_i set to the value). Uses the mean pressure "
    "in the damping (mean_pressure_damping = 1) unless --set gives it.")


OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))
#: This command's options for the study's arguments
#: (:func:`judder.commands._flags.in_flags`).
FLAGS = {"mu_g": "--mu-g", "c_ext": "--c-ext"}


def add_arguments(p):
    """The options of ``judder threshold``."""
    p.add_argument("--mu-g", type=Grid("--mu-g", "s/rad", allow_negative=True),
                   default="-0.001:0.001:81",
                   metavar="START:STOP:N",
                   help="friction gradients for Fig. 19a, s/rad")
    p.add_argument("--c-ext", type=Grid("--c-ext", "N m s/rad"),
                   default="0:2:41", metavar="START:STOP:N",
                   help="external damping values for Fig. 19b, N m s/rad")
    p.add_argument("--out", metavar="FILE.csv",
                   help="threshold against c_i as CSV")
    p.add_argument("--plot", metavar="FILE.png", help="Fig. 19a and 19b")
    model_options(p, modelica=False)
    force_option(p)


def run(args):
    """Friction-gradient threshold without dither (Fig. 19)."""
    mu_g = args.mu_g
    damping = args.c_ext
    params, changes = parameters_of(args)
    check_threshold(len(mu_g), len(damping))
    make_parents(args.out, args.plot)
    with Progress(len(damping), "threshold") as progress:
        result = threshold(mu_g, damping, params, changes,
                           progress=progress)
    files = write_outputs(args, result,
                           figure={"title": model_title(args, params)})
    study = result.study
    text = (f"threshold mu_g* = {study.threshold:.6g} s/rad for this set "
            f"(unstable without dither below it)")
    if result.slope is not None:
        text += (f"\nthreshold against c_i: slope {result.slope:.4g} s/rad "
                 f"per N m s/rad over c_i = {damping[0]:g}..{damping[-1]:g}")
    emit(args, {**result.as_dict(), **files},
         text + written(args.out, args.plot))
