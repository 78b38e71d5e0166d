"""Per-user tokens: a token that opens only one user's NEEMs, and read-only tokens.

One service on a care home's hub serves several people; one token would let each of them (or
their relatives' tablets) read everyone's NEEMs. ``serve --tokens FILE`` reads a token file
(0600, like ``--token-file``), one token a line::

    # TOKEN            what it may do
    Zq3...long...x1    user=ada             # ada's NEEMs, read and write
    Hw8...long...p4    user=ada read-only   # ada's NEEMs, read only (a relative's tablet)
    K2m...long...c9    read-only            # every NEEM, read only (a carer's overview)
    Lr5...long...d0                         # every NEEM (as --token-file's token)

Each token follows the rule of ``--token`` (commands/serve.py ``strong_token``); a line that
does not parse is one error naming its line, before the service starts. The guard admits a
request presenting any of these tokens (or ``--token-file``'s); this middleware, inside the
guard, then holds it to its grant:

- a ``user=`` token reaches only the NEEMs whose user is that user: any other NEEM is 404 (as
  a NEEM that does not exist: nothing tells it apart), the NEEM listings show only that user's,
  a NEEM it creates must be that user's, the event stream must name one of its NEEMs
  (``?neem=``), the page opens that user's newest NEEM, and ``/api/prolog`` and the rosbridge
  door are refused (a query may read beyond one NEEM);
- a ``read-only`` token may only GET (and ask ``/api/prolog``'s read-only queries when the
  service does not allow Prolog writes).
"""

from __future__ import annotations

import hmac
import json
import re
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlencode

from oracle.errors import NeemOracleError

#: Paths that name one NEEM: /api/neems/{neem}/... and the explore page's API.
NEEM_PATH = re.compile(r"^(?:/explore)?/api/neems/([^/]+)(?:/.*)?$")
#: Paths that list NEEMs (answered with a JSON list of objects with a ``user``).
LISTINGS = frozenset({"/api/neems", "/explore/api/neems"})
#: What a user's token may not reach at all.
WHOLE_STORE = ("/api/prolog", "/rosbridge")
_USER = re.compile(r"^[^\s=]{1,128}$")


@dataclass(frozen=True)
class Grant:
    """What one token may do: ``user`` None reaches every NEEM."""

    user: str | None = None
    read_only: bool = False

    @property
    def everything(self) -> bool:
        return self.user is None and not self.read_only


@dataclass(frozen=True)
class Access:
    """The tokens of a token file and their grants."""

    grants: tuple[tuple[str, Grant], ...]

    def grant(self, presented: str | None) -> Grant | None:
        """The grant of the presented token (compared in constant time with every token)."""
        if presented is None:
            return None
        found = None
        for token, grant in self.grants:
            if hmac.compare_digest(presented.encode(), token.encode()):
                found = grant
        return found


def admits(ctx: Any, presented: str | None) -> bool:
    """The guard's question: is ``presented`` the service's token or one of its token file's."""
    if presented is None:
        return False
    access: Access | None = getattr(ctx, "access", None)
    token: str | None = ctx.token
    return (token is not None and hmac.compare_digest(presented.encode(), token.encode())) or (
        access is not None and access.grant(presented) is not None)


def read_tokens(path: Path, strong: Any) -> Access:
    """The token file ``path`` (the module's docstring); ``strong(token, where)`` checks each
    token (commands/serve.py ``strong_token``). NeemOracleError naming the line otherwise."""
    from oracle.handed import Handed, read_handed_text

    where = f"--tokens {path}"
    kind = Handed("token file", NeemOracleError)
    text = read_handed_text(path, kind, 1 << 20)
    try:
        if path.stat().st_mode & (stat.S_IRWXG | stat.S_IRWXO):
            raise NeemOracleError(f"{where}: others can read it; chmod 600 it first")
    except OSError as error:
        raise NeemOracleError(f"{where}: cannot read ({error.strerror})") from None
    grants: list[tuple[str, Grant]] = []
    for number, line in enumerate(text.splitlines(), start=1):
        words = line.split("#", 1)[0].split()
        if not words:
            continue
        token = strong(words[0], f"{where}:{number}")
        user, read_only = None, False
        for word in words[1:]:
            if word == "read-only" and not read_only:
                read_only = True
            elif word.startswith("user=") and user is None and _USER.match(word[5:]):
                user = word[5:]
            else:
                raise NeemOracleError(f"{where}:{number}: {word[:40]!r} is neither user=ID nor read-only (once each)")
        if any(hmac.compare_digest(token, seen) for seen, _ in grants):
            raise NeemOracleError(f"{where}:{number}: the same token is on an earlier line")
        grants.append((token, Grant(user, read_only)))
    if not grants:
        raise NeemOracleError(f"{where}: holds no token")
    return Access(tuple(grants))


def presented(headers: dict[str, str], query: bytes) -> str | None:
    """The token a request presents: ``Authorization: Bearer T``, else ``?token=T``."""
    header = headers.get("authorization", "")
    if header.lower().startswith("bearer "):
        return header[7:].strip()
    values = parse_qs(query.decode("latin-1")).get("token")
    return values[0] if values else None


class AccessCheck:
    """The ASGI middleware that holds a request to its token's grant (inside the guard, which
    has admitted the token already)."""

    def __init__(self, app: Any, ctx: Any) -> None:
        self.app = app
        self.ctx = ctx

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        access: Access | None = getattr(self.ctx, "access", None)
        if access is None or scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
        grant = access.grant(presented(headers, scope.get("query_string", b"")))
        if grant is None or grant.everything:  # the service's own token, or an open path
            await self.app(scope, receive, send)
            return
        if scope["type"] == "websocket":
            await send({"type": "websocket.close", "code": 1008})
            return
        method, path = scope["method"], scope["path"]
        writes = method not in ("GET", "HEAD")
        if grant.user is not None and path.startswith(WHOLE_STORE):
            await _refuse(send, 403, f"this token reaches only the NEEMs of user {grant.user}; {path} reads the whole store")
            return
        if grant.read_only and writes and not (path == "/api/prolog" and not self.ctx.prolog_writes):
            await _refuse(send, 403, "this token is read-only")
            return
        if grant.user is None:
            await self.app(scope, receive, send)
            return
        await self._one_user(scope, receive, send, grant.user, writes)

    async def _one_user(self, scope: dict[str, Any], receive: Any, send: Any, user: str, writes: bool) -> None:
        path = scope["path"]
        query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
        named = NEEM_PATH.match(path)
        if named is not None or (path in ("/api/events", "/", "/explore") and "neem" in query):
            neem = named.group(1) if named is not None else query["neem"][0]
            if await self._user_of(neem) != user:
                await _refuse(send, 404, f"no NEEM {neem[:80]!r} in the store")
                return
        elif path == "/api/events":
            await _refuse(send, 403, f"this token reaches only the NEEMs of user {user}: name one (?neem=)")
            return
        elif path in ("/", "/explore"):  # each page opens a NEEM: the user's own newest, never the store's
            newest = await self._newest_of(user)
            if newest is None:
                await _refuse(send, 404, f"user {user} has no NEEM in the store yet")
                return
            query["neem"] = [newest]
            scope = {**scope, "query_string": urlencode(query, doseq=True).encode()}
        if path == "/api/neems" and writes:
            body, receive = await _whole(receive)
            try:
                asked = json.loads(body).get("user")
            except (ValueError, AttributeError):
                asked = None  # the route answers a malformed body as it always does
            if asked is not None and asked != user:
                await _refuse(send, 403, f"this token may only make NEEMs of user {user}")
                return
        if path in LISTINGS and not writes:
            send = _listing_of(user, send)
        await self.app(scope, receive, send)

    async def _user_of(self, neem: str) -> str | None:
        def job() -> str | None:
            try:
                return str(self.ctx.engine.store.neem(self.ctx.engine.resolve(neem)).user)
            except NeemOracleError:
                return None

        result: str | None = await self.ctx.thread.run(job)
        return result

    async def _newest_of(self, user: str) -> str | None:
        def job() -> str | None:
            mine = [info for info in self.ctx.engine.store.neems() if info.user == user]
            return max(mine, key=lambda info: (info.created_at or "", info.id)).id if mine else None

        result: str | None = await self.ctx.thread.run(job)
        return result


async def _whole(receive: Any) -> tuple[bytes, Any]:
    """The request's body (already read and checked by the guard) and a receive that replays it."""
    chunks, more = [], True
    while more:
        message = await receive()
        if message["type"] != "http.request":
            break
        chunks.append(message.get("body", b""))
        more = message.get("more_body", False)
    body = b"".join(chunks)
    sent = False

    async def replay() -> dict[str, Any]:
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        return dict(await receive())

    return body, replay


def _listing_of(user: str, send: Any) -> Any:
    """``send`` for a NEEM listing, keeping only ``user``'s entries (the listing is small: it is
    held whole, filtered, and sent with its new length)."""
    start: dict[str, Any] = {}
    chunks: list[bytes] = []

    async def filtered(message: dict[str, Any]) -> None:
        if message["type"] == "http.response.start":
            start.update(message)
            return
        if message["type"] != "http.response.body":
            await send(message)
            return
        chunks.append(message.get("body", b""))
        if message.get("more_body", False):
            return
        body = b"".join(chunks)
        if start.get("status") == 200:
            try:
                listed = json.loads(body)
                body = json.dumps([entry for entry in listed if isinstance(entry, dict) and entry.get("user") == user]).encode()
            except (ValueError, TypeError):
                body = b"[]"
        headers = [(k, v) for k, v in start.get("headers", []) if k.lower() != b"content-length"]
        await send({**start, "headers": [*headers, (b"content-length", str(len(body)).encode())]})
        await send({"type": "http.response.body", "body": body, "more_body": False})

    return filtered


async def _refuse(send: Any, status: int, message: str) -> None:
    body = json.dumps({"error": message}).encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body, "more_body": False})


__all__ = ["Access", "AccessCheck", "Grant", "admits", "read_tokens"]
