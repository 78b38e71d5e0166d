"""Sub-commands of ``python -m oracle``; each module exposes ``register(subparsers)``."""
