"""The ``judder`` command line: a thin layer over :mod:`judder.api`.

Units on the command line are those engineers read: dither frequency in
Hz, dither amplitude in bar. Parameters (``--set``) and files are SI.
Every command can print JSON (``--json``) for scripts. The exit codes are
those of :mod:`infra.errors` and :mod:`infra.contract`: errors in the
input give ``judder: error: ...`` and exit status 2; an internal failure
says so and exits with 1; Ctrl-C exits with 130, SIGTERM with 143, and
neither leaves a partial output file.

:mod:`judder.cli.parser` declares the options, :mod:`judder.cli.commands`
turns them into API calls and formats the results,
:mod:`judder.cli.options` parses and checks option values.
"""

from infra.contract import join_negative_values, run_guarded
from .options import check_outputs
from .parser import build_parser
from .values import check_plausible, normalise_options

__all__ = ["main", "build_parser"]


def main(argv=None):
    """Run ``judder``; returns the exit status."""
    import sys
    from threadpoolctl import threadpool_limits
    from infra.parallel import cluster
    parser = build_parser()
    args = parser.parse_args(join_negative_values(
        sys.argv[1:] if argv is None else list(argv)))

    def command():
        normalise_options(args)
        check_outputs(args)
        check_plausible(args)
        # the kernels work on many tiny matrices: BLAS threads only contend
        with threadpool_limits(limits=1), cluster(
                getattr(args, "workers", None),
                getattr(args, "scheduler", None)):
            args.handler(args)
    return run_guarded("judder", command)
