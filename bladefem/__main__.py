"""python -m bladefem: the command line."""

from .cli import main

raise SystemExit(main())
