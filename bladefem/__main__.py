"""python -m bladefem: the command line."""

from .cli import entry

entry()
