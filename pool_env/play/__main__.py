"""`python -m pool_env.play`: play a game with the mouse (see `pool_env.play.cli`)."""

import sys

from .cli import main

sys.exit(main())
