"""Find the MongoDB for ``make test-mongo``, check it answers, then run a command against it.

    python scripts/check-mongo.py [--env-file docker/.env] [--timeout 3] [-- COMMAND ...]

The URI is ``NEEM_MONGO_URI`` from the environment or, when that is unset, the local compose stack's
built from the env file (root account with the password of ``docker/secrets/mongo_root_password``,
database ``NEEM_TEST_DB``, 127.0.0.1:``MONGO_PORT``, which ``make up-host`` publishes). If no
server answers a ping within the timeout, one line goes to stderr and the exit code is 1. Otherwise
COMMAND (if given) replaces this process with ``NEEM_MONGO_URI`` set in its environment.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from urllib.parse import quote

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_ENV_FILE = ROOT / "docker" / ".env"


def read_env_file(path: Path) -> dict[str, str]:
    """``KEY=VALUE`` lines of a compose env file (comments, blanks and optional quotes allowed)."""
    values: dict[str, str] = {}
    for line in path.read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#") or "=" not in line:
            continue
        key, value = line.split("=", 1)
        value = value.strip()
        if len(value) >= 2 and value[0] == value[-1] and value[0] in "'\"":
            value = value[1:-1]
        values[key.strip()] = value
    return values


def stack_uri(env: Mapping[str, str], secrets_dir: Path) -> str:
    """URI of the local compose stack's MongoDB for the test suite (root account, test database;
    the root password from the stack's secrets file)."""
    user = quote(env.get("MONGO_ROOT_USER", "root"), safe="")
    secret = secrets_dir / "mongo_root_password"
    try:
        password = secret.read_text().rstrip("\r\n")
    except OSError:
        raise LookupError(f"{os.path.relpath(secret)} is missing (`make up-host` makes it)") from None
    port = env.get("MONGO_PORT", "27017")
    database = env.get("NEEM_TEST_DB", "roslog_test")
    return f"mongodb://{user}:{quote(password, safe='')}@127.0.0.1:{port}/{database}?authSource=admin"


def redact(uri: str) -> str:
    """``uri`` with any password replaced by ``***``, for messages."""
    return re.sub(r"^([a-z+]+://[^:/@?]*):[^?]*@", r"\1:***@", uri)


def resolve_uri(environ: Mapping[str, str], env_file: Path) -> str:
    uri = environ.get("NEEM_MONGO_URI", "").strip()
    if uri:
        return uri
    if env_file.is_file():
        return stack_uri(read_env_file(env_file), env_file.parent / "secrets")
    raise LookupError(
        f"NEEM_MONGO_URI is not set and {os.path.relpath(env_file)} is missing "
        "(start the stack with its loopback port: `make up-host`, or set NEEM_MONGO_URI)"
    )


def ping(uri: str, timeout: float) -> str | None:
    """None if the server at ``uri`` answers a ping within ``timeout`` seconds, else why not."""
    from pymongo import MongoClient
    from pymongo.errors import ConfigurationError, InvalidURI, OperationFailure, PyMongoError

    ms = int(timeout * 1000)
    try:
        client = MongoClient(uri, serverSelectionTimeoutMS=ms, connectTimeoutMS=ms, socketTimeoutMS=ms)
    except (ConfigurationError, InvalidURI, ValueError) as error:
        return f"invalid URI ({error})"
    try:
        client.admin.command("ping")
    except OperationFailure as error:
        return f"server refused: {error.details.get('errmsg', error) if error.details else error}"
    except PyMongoError as error:
        return f"not reachable within {timeout:g} s ({type(error).__name__})"
    finally:
        client.close()
    return None


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="check-mongo.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("--env-file", type=Path, default=DEFAULT_ENV_FILE)
    parser.add_argument("--timeout", type=float, default=3.0, help="seconds to wait for the server")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- COMMAND ... to run when reachable")
    args = parser.parse_args(argv)
    command = args.command[1:] if args.command[:1] == ["--"] else args.command

    try:
        uri = resolve_uri(os.environ, args.env_file)
    except LookupError as error:
        print(f"test-mongo: {error}", file=sys.stderr)
        return 2
    problem = ping(uri, args.timeout)
    if problem is not None:
        print(
            f"test-mongo: no MongoDB at {redact(uri)}: {problem}; start one with `make up-host` or set NEEM_MONGO_URI",
            file=sys.stderr,
        )
        return 1
    print(f"test-mongo: MongoDB at {redact(uri)} answers", flush=True)
    if not command:
        return 0
    os.execvpe(command[0], command, {**os.environ, "NEEM_MONGO_URI": uri})
    return 127  # not reached


if __name__ == "__main__":
    raise SystemExit(main())
