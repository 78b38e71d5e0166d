"""Store URIs in messages: credentials are masked wherever a URI is echoed."""

from __future__ import annotations

import re

#: ``scheme://userinfo@`` up to the last ``@`` before the host; userinfo may itself hold an
#: unescaped ``@``, ``/`` or ``:`` (a password the user forgot to percent-encode).
_USERINFO = re.compile(r"(?P<scheme>\b[a-z][a-z0-9+.\-]*://)(?P<userinfo>[^\s@]*@(?:[^\s@/]*@)*)", re.IGNORECASE)


def mask_uri(uri: str) -> str:
    """``mongodb://alice:pw@host/db`` -> ``mongodb://***@host/db`` (no userinfo: unchanged)."""
    scheme, sep, rest = uri.partition("://")
    if not sep or "@" not in rest:
        return uri
    return f"{scheme}://***@{rest.rsplit('@', 1)[1]}"


def secrets_of(uri: str) -> list[str]:
    """The user name and password pieces a message about ``uri`` must not contain."""
    _, sep, rest = uri.partition("://")
    if not sep or "@" not in rest:
        return []
    userinfo = rest.rsplit("@", 1)[0]
    user, _, password = userinfo.partition(":")
    # A driver that misreads an unescaped '@' or '/' may quote a fragment of the password;
    # fragments shorter than 4 characters would match ordinary words, so they are left.
    pieces = {userinfo, user, password, *(p for p in re.split(r"[:@/]", userinfo) if len(p) >= 4)}
    return sorted((piece for piece in pieces if piece), key=len, reverse=True)


def scrub(message: str, uri: str) -> str:
    """``message`` (e.g. a driver's error about ``uri``) with the URI masked and the user
    name and password replaced by ``***``."""
    text = message.replace(uri, mask_uri(uri))
    for secret in secrets_of(uri):
        text = text.replace(secret, "***")
    return mask_credentials(text)


def mask_credentials(text: str) -> str:
    """Mask the userinfo of every ``scheme://user:password@`` in free text."""
    return _USERINFO.sub(lambda match: f"{match.group('scheme')}***@", text)


#: Environment variable naming a file that holds the password of $NEEM_MONGO_URI's user (a compose
#: secret such as /run/secrets/neem_app_password), so the password never sits in the environment.
PASSWORD_FILE_ENV = "NEEM_MONGO_PASSWORD_FILE"


class PasswordFileError(ValueError):
    """The password file cannot be used with the URI (the message never holds the password)."""


def short_reason(error: BaseException) -> str:
    """pymongo's reason in a few words: its first server's error, without the timeouts and the
    topology description it appends (600 characters for a refused connection)."""
    text = str(error).split(", Timeout:", 1)[0]
    text = re.sub(r"\s*\(configured timeouts:[^)]*\)", "", text)
    text = text.split(", full error:", 1)[0]
    return text if len(text) <= 160 else text[:157] + "..."


def with_password_file(uri: str, path: str) -> str:
    """``uri`` (``mongodb://USER@host/...``, no password) with the password read from ``path``
    put in, percent-encoded (so a password may hold ``@``, ``/`` or ``:``).

    The file holds the password alone; one trailing newline is dropped."""
    from urllib.parse import quote

    scheme, sep, rest = uri.partition("://")
    authority = rest.split("/", 1)[0]
    if not sep or "@" not in authority:
        raise PasswordFileError(f"{PASSWORD_FILE_ENV} is set but the URI {mask_uri(uri)} names no user (mongodb://USER@HOST)")
    userinfo, host = authority.rsplit("@", 1)
    if ":" in userinfo:
        raise PasswordFileError(f"{PASSWORD_FILE_ENV} is set but the URI {mask_uri(uri)} already holds a password")
    from oracle.handed import Handed, open_handed

    try:
        with open_handed(path, Handed("it", PasswordFileError)) as handle:  # a regular file: a FIFO would block
            raw = handle.read(4097)
    except PasswordFileError as error:
        raise PasswordFileError(f"{PASSWORD_FILE_ENV}={error}") from None
    except OSError as error:
        raise PasswordFileError(f"{PASSWORD_FILE_ENV}={path}: cannot read it ({error.strerror or type(error).__name__})") from None
    if len(raw) > 4096:
        raise PasswordFileError(f"{PASSWORD_FILE_ENV}={path}: longer than 4096 bytes; it must hold the password alone")
    try:
        password = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise PasswordFileError(f"{PASSWORD_FILE_ENV}={path}: not UTF-8 text") from None
    password = password[:-1] if password.endswith("\n") else password
    password = password[:-1] if password.endswith("\r") else password
    if not password or "\n" in password:
        raise PasswordFileError(f"{PASSWORD_FILE_ENV}={path}: must hold one password on one line")
    tail = rest[len(authority):]
    return f"{scheme}://{userinfo}:{quote(password, safe='')}@{host}{tail}"
