"""Store URIs in messages: credentials are masked wherever a URI is echoed (issue 16)."""

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
