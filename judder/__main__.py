"""``python -m judder`` runs the ``judder`` command line."""

import sys

from .cli import main

sys.exit(main())
