"""A small JSON client for the service (standard library only; one kept-alive connection),
used by the simulated robot and the load test."""

from __future__ import annotations

import http.client
import json
import time
from typing import Any
from urllib.parse import urlsplit

from oracle.errors import NeemOracleError


class ServiceError(NeemOracleError):
    """The service answered with an error, or could not be reached."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(f"{status}: {message}" if status else message)
        self.status = status


class Client:
    def __init__(self, url: str, token: str | None = None, timeout: float = 30.0) -> None:
        parts = urlsplit(url)
        if parts.scheme != "http" or not parts.hostname:
            raise NeemOracleError(f"--serve {url!r}: expected http://HOST:PORT")
        self.host, self.port, self.timeout = parts.hostname, parts.port or 80, timeout
        self.headers = {"Content-Type": "application/json", "Accept": "application/json"}
        if token:
            self.headers["Authorization"] = f"Bearer {token}"
        self._conn: http.client.HTTPConnection | None = None
        #: The last answer's Server-Timing metrics (name -> ms), where the service sent them.
        self.server_timing: dict[str, float] = {}

    def request(self, method: str, path: str, body: dict[str, Any] | None = None) -> tuple[Any, float]:
        """The answer's JSON and the round trip in milliseconds; ServiceError on a 4xx/5xx."""
        payload = None if body is None else json.dumps(body).encode()
        for attempt in (1, 2):  # a kept-alive connection the server closed is reopened once
            if self._conn is None:
                self._conn = http.client.HTTPConnection(self.host, self.port, timeout=self.timeout)
            started = time.perf_counter()
            try:
                self._conn.request(method, path, payload, self.headers)
                response = self._conn.getresponse()
                data = response.read()
            except (ConnectionError, http.client.HTTPException, OSError) as error:
                self.close()
                if attempt == 2:
                    raise ServiceError(0, f"http://{self.host}:{self.port}{path}: {error}") from None
                continue
            ms = (time.perf_counter() - started) * 1000
            self.server_timing = _server_timing(response.getheader("Server-Timing"))
            answer = json.loads(data) if data else None
            if response.status >= 400:
                message = answer.get("error") if isinstance(answer, dict) else str(answer)
                raise ServiceError(response.status, str(message))
            return answer, ms
        raise AssertionError("unreachable")

    def post(self, path: str, body: dict[str, Any]) -> Any:
        return self.request("POST", path, body)[0]

    def get(self, path: str) -> Any:
        return self.request("GET", path)[0]

    def close(self) -> None:
        if self._conn is not None:
            self._conn.close()
            self._conn = None


def _server_timing(header: str | None) -> dict[str, float]:
    """``queue;dur=0.2, engine;dur=2.5`` as {"queue": 0.2, "engine": 2.5}."""
    metrics: dict[str, float] = {}
    for part in (header or "").split(","):
        name, _, rest = part.strip().partition(";")
        if rest.startswith("dur="):
            try:
                metrics[name] = float(rest[4:])
            except ValueError:
                pass
    return metrics
