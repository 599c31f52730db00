"""``python -m fricgen``: the command line."""

import sys

from .app.cli.commands import main

sys.exit(main())
