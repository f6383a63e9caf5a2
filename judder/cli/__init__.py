"""The ``judder`` command line: a thin layer over :mod:`judder.api`.

Units on the command line are those engineers read: dither frequency in
Hz, dither amplitude in bar. Parameters (``--set``) and files are SI.
Every command can print JSON (``--json``) for scripts. The exit codes are
those of :mod:`infra.errors`: errors in the input give ``judder: error:
...`` and exit status 2; Ctrl-C exits with 130 and leaves no partial
output file.

:mod:`judder.cli.parser` declares the options, :mod:`judder.cli.commands`
turns them into API calls and formats the results,
:mod:`judder.cli.options` parses and checks option values.
"""

import sys

from infra.errors import EXIT_ERROR, EXIT_INTERRUPTED, EXIT_OK, JudderError

from .options import check_plot_format
from .parser import build_parser

__all__ = ["main", "build_parser"]


def main(argv=None):
    """Run ``judder``; returns the exit status."""
    from threadpoolctl import threadpool_limits
    from infra.parallel import cluster
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if getattr(args, "plot", None):
            check_plot_format(args.plot)
        # the kernels work on many tiny matrices: BLAS threads only contend
        with threadpool_limits(limits=1), cluster(
                getattr(args, "workers", None),
                getattr(args, "scheduler", None)):
            args.handler(args)
    except JudderError as exc:
        print(f"judder: error: {exc}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt:
        print("judder: interrupted; no partial output was written",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    return EXIT_OK
