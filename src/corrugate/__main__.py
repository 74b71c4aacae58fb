"""``python -m corrugate``: the command line."""

from corrugate.cli import main

main()
