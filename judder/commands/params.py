"""``judder params``: show, or save as TOML, a parameter set."""

from studies.params import params

from ._arguments import model_options
from ._model import parameters_of
from ._output import emit, make_parents

#: The command's --help text.
DESCRIPTION = (
    "Show a parameter set with units, or save it (--save FILE.toml) to "
    "edit and load with --param-file.")


OUTPUTS = (("save", "--save", ("toml",)),)


def add_arguments(p):
    """The options of ``judder params``."""
    model_options(p)
    p.add_argument("--save", metavar="FILE.toml",
                   help="write the set as TOML (never overwrites unless "
                        "--force)")
    p.add_argument("--force", action="store_true",
                   help="allow --save to replace an existing file")


def run(args):
    """Show (and optionally save) the parameter set."""
    result = params(*parameters_of(args, dithered=False))
    if args.save:
        make_parents(args.save)
        result.save(args.save, overwrite=args.force)
    specs = result.params.specs
    rows = [f"{'name':22s} {'value':14s} {'unit':10s} {'allowed':24s} "
            "meaning"]
    rows += [f"{name:22s} {result.params[name]:<14.6g} {spec.unit:10s} "
            f"{spec.allowed():24s} {spec.description}"
            for name, spec in specs.items()]
    emit(args, {**result.as_dict(), "saved": args.save},
         f"model {result.params.model}\n"
         + ("" if result.as_dict()["friction"] is None else
            f"friction: {result.as_dict()['friction']}; mu0 and mu_g are "
            "its value and slope at the bench's slip\n")
         + "\n".join(rows)
         + (f"\nsaved to {args.save}" if args.save else ""))
