"""``python -m judder`` runs the ``judder`` command line."""

import sys

if __name__ == "__main__":   # Dask's worker processes import this module
    try:
        from .cli import main   # light: the handlers come before numpy
    except KeyboardInterrupt:   # in the first milliseconds
        print("judder: interrupted; no partial output was written",
              file=sys.stderr)
        sys.exit(130)
    sys.exit(main())
