"""The ``judder`` command line: a thin layer over :mod:`judder.api`.

Units on the command line are those engineers read: dither frequency in
Hz, dither amplitude in bar. Parameters (``--set``) and files are SI.
Every command can print JSON (``--json``) for scripts. The exit codes are
those of :mod:`infra.errors` and :mod:`infra.contract`: errors in the
input give ``judder: error: ...`` and exit status 2; an internal failure
says so and exits with 1; Ctrl-C exits with 130, SIGTERM with 143, and
neither leaves a partial output file nor prints a traceback, at any
moment: this module imports nothing heavy, so the handlers of
:func:`infra.contract.run_guarded` are in place before numpy, scipy and
Dask are loaded (inside the guarded command).

:mod:`judder.cli.parser` declares the options, :mod:`judder.cli.commands`
turns them into API calls and formats the results,
:mod:`judder.cli.options` parses and checks option values.
"""

__all__ = ["main", "build_parser"]


def build_parser():
    """The argparse parser of every command (:mod:`judder.cli.parser`)."""
    from .parser import build_parser as build
    return build()


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

    def command():
        import sys
        with signals_held():     # acted on once the imports are complete
            from threadpoolctl import threadpool_limits
            from infra.contract import join_negative_values
            from infra.parallel import cluster
            from .options import check_outputs
            from .values import check_plausible, normalise_options
            parser = build_parser()
        args = parser.parse_args(join_negative_values(
            sys.argv[1:] if argv is None else list(argv)))
        normalise_options(args)
        check_outputs(args)
        check_plausible(args)
        # the kernels work on many tiny matrices: BLAS threads only contend
        with threadpool_limits(limits=1), cluster(
                getattr(args, "workers", None),
                getattr(args, "scheduler", None)):
            args.handler(args)
    return run_guarded("judder", command, whole_process=argv is None)
