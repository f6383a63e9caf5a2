"""The ``judder`` command line, made from the command registry.

Units on the command line are those engineers read: dither frequency in
Hz, dither amplitude in bar (a number may carry its unit instead:
``--freq 1.2kHz``, ``--pf 300mbar``). Parameters (``--set``) and files
are SI. Every command can print JSON (``--json``) for scripts. The exit
codes are those of :mod:`infra.errors` and :mod:`infra.contract`: errors
in the input give ``judder: error: ...`` and exit status 2; an internal
failure says so and exits with 1; Ctrl-C exits with 130, SIGTERM with
143, and neither leaves a partial output file nor prints a traceback, at
any moment: this module imports nothing heavy, so the handlers of
:func:`infra.contract.run_guarded` are in place before numpy, scipy and
Dask are loaded (inside the guarded command).

The subcommands and ``judder --help`` come from
:data:`judder.commands.COMMANDS`; only the module of the command given is
imported (``judder --help`` imports none).
"""

import argparse
import re
import sys

from .commands import COMMANDS, command_module

__all__ = ["main", "build_parser"]

EPILOG = ("Long work (map, floquet, tongues, sensitivity, crosscheck, "
          "campaign, envelope) is estimated before it starts: above 10 s "
          "the estimate is printed on a terminal, above 24 h the request is "
          "refused; the environment variable JUDDER_MAX_HOURS=HOURS sets "
          "another limit.")


class _VersionAction(argparse.Action):
    """``--version``: the package metadata is read only when asked."""

    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        from infra.provenance import tool_version
        print(f"judder {tool_version()}")
        parser.exit()


class _Parser(argparse.ArgumentParser):
    """argparse, with the project's one-line errors for option values.

    A value refused by its ``type=`` parser (:mod:`judder.commands._values`)
    names the option, the value and what is allowed; it is reported as
    every input error is (``judder: error: ...``, exit status 2), without
    argparse's usage lines.
    """

    def error(self, message):
        value_error = re.match(r"argument [^:]+: (--\S+ .*)$", message, re.S)
        if value_error:
            from infra.errors import JudderError
            raise JudderError(value_error.group(1))
        super().error(message)


def build_parser(commands=None):
    """The argparse parser of ``judder``.

    Parameters
    ----------
    commands : iterable of str, optional
        The commands whose options are declared (their modules are
        imported); the others are listed with their summary only. Default:
        every command.
    """
    parser = _Parser(
        prog="judder",
        description="Clutch judder from parametric excitation by hydraulic "
                    "dither: Floquet stability of the 3-DOF and 4-DOF "
                    "driveline. Frequencies in Hz, dither amplitude in bar, "
                    "parameters in SI units.",
        epilog=EPILOG)
    parser.add_argument("--version", action=_VersionAction,
                        help="print the version and exit")
    sub = parser.add_subparsers(dest="command", required=True,
                                metavar="COMMAND")
    wanted = set(COMMANDS) if commands is None else set(commands)
    for name, command in COMMANDS.items():
        if name not in wanted:
            sub.add_parser(name, help=command.summary)
            continue
        module = command_module(name)
        p = sub.add_parser(name, help=command.summary,
                           description=module.DESCRIPTION)
        module.add_arguments(p)
        p.set_defaults(handler=module.run, outputs=module.OUTPUTS,
                       flags=getattr(module, "FLAGS", None),
                       output_check=getattr(module, "check_outputs", None),
                       read_too=getattr(module, "read_too", None),
                       amplitude=getattr(module, "AMPLITUDE", None))
    return parser


def _command_given(argv):
    """The command named in ``argv`` (its first word that is not an
    option), or None."""
    for word in argv:
        if not word.startswith("-"):
            return word if word in COMMANDS else None
    return None


def main(argv=None):
    """Run ``judder``; returns the exit status.

    Parameters
    ----------
    argv : list of str, optional
        The arguments; ``None``: this process's command line (then the
        signal handlers stay until the process exits).
    """
    # the standard library only
    from infra.contract import run_guarded, signals_held
    words = sys.argv[1:] if argv is None else list(argv)

    def command():
        name = _command_given(words)
        with signals_held():     # acted on once the imports are complete
            from infra.contract import join_negative_values
            parser = build_parser(() if name is None else (name,))
        args = parser.parse_args(join_negative_values(words))
        with signals_held():
            from threadpoolctl import threadpool_limits
            from infra.parallel import cluster
            from infra.errors import JudderError
            from .commands._flags import in_flags
            from .commands._model import check_plausible
            from infra.provenance import recorded
            from .commands._output import check_outputs, provenance_of
        try:
            check_outputs(args)
            check_plausible(args)
            # the kernels work on many tiny matrices: BLAS threads only
            # contend
            with threadpool_limits(limits=1), cluster(
                    getattr(args, "workers", None),
                    getattr(args, "scheduler", None)), recorded(
                        provenance_of(args)):
                args.handler(args)
        except JudderError as exc:
            # the library's messages name its arguments: say the options
            raise JudderError(in_flags(str(exc), getattr(args, "flags", None))) from None
    return run_guarded("judder", command, whole_process=argv is None,
                       words=_in_flags)


def _in_flags(message):
    """A library's message in the options of the command line."""
    from .commands._flags import in_flags
    return in_flags(message)
