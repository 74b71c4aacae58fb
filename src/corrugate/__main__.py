"""``python -m corrugate``: the command line."""

from .cli import main

main()
