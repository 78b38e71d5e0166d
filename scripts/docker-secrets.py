"""Make the compose stack's secrets files when they are missing: random passwords, never printed.

    python scripts/docker-secrets.py [DIR]      (default: docker/secrets)

DIR becomes 0700 (only you can open it); each file holds one password on one line and is 0644
inside it, because compose bind-mounts a secrets file unchanged and the containers' unprivileged
users (mongodb, oracle) must read it. An existing file is kept as it is (so is a password you wrote
yourself). A symlink in place of DIR or a file is refused. Prints one line per file it made.
"""

from __future__ import annotations

import os
import secrets
import stat
import sys
from collections.abc import Sequence
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_DIR = ROOT / "docker" / "secrets"
NAMES = ("mongo_root_password", "neem_app_password")


def make_secrets(folder: Path) -> list[Path]:
    """Create ``folder`` (0700) and each missing secret file; return the files made."""
    if folder.is_symlink():
        raise OSError(f"{folder} is a symlink; refusing to write secrets through it")
    folder.mkdir(mode=0o700, parents=True, exist_ok=True)
    if not folder.is_dir():
        raise OSError(f"{folder} is not a folder")
    os.chmod(folder, 0o700)
    made = []
    for name in NAMES:
        path = folder / name
        if path.is_symlink():
            raise OSError(f"{path} is a symlink; refusing to follow it")
        if path.exists():
            if not stat.S_ISREG(path.stat().st_mode) or path.stat().st_size == 0:
                raise OSError(f"{path} must be a file holding one password")
            continue
        descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
        with os.fdopen(descriptor, "w") as handle:
            handle.write(secrets.token_urlsafe(24) + "\n")
        os.chmod(path, 0o644)  # readable by the containers' users; the 0700 folder keeps others out
        made.append(path)
    return made


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if len(args) > 1 or args[:1] in (["-h"], ["--help"]):
        print("usage: docker-secrets.py [DIR]", file=sys.stderr)
        return 2
    folder = Path(args[0]) if args else DEFAULT_DIR
    try:
        made = make_secrets(folder)
    except OSError as error:
        print(f"docker-secrets: {error}", file=sys.stderr)
        return 1
    for path in made:
        print(f"docker-secrets: made {os.path.relpath(path)} (a random password)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
