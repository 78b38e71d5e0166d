"""Entry point for ``python -m oracle``."""

from oracle.cli import main

raise SystemExit(main())
