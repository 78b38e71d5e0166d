"""The SQLite backend's query compiler: triple patterns -> one SQL join with KnowRob's p*/o*
semantics (the SQL counterpart of ``mongo.compile_pipeline``), and the whole statement of a
match (join order, kept columns, sort keys)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

from oracle.errors import StoreError
from oracle.store.model import TAXONOMIC, Cmp, Scope, Term, TriplePattern, Var
from oracle.store.sqlite.sides import Side
from oracle.store.sqlite.tables import TAXONOMIC_SQL, non_taxonomic
from oracle.store.sqlite.terms import K_DATE, K_DECIMAL, K_DOUBLE, K_INT, K_LONG, K_OTHER, K_STR, sql_value

_NUMERIC_KINDS = (K_DOUBLE, K_DECIMAL, K_INT, K_LONG)
#: Kinds a comparison (``Cmp``) sees as numbers: Prolog receives Dates as unix seconds too.
_COMPARABLE_SQL = f"({K_DOUBLE}, {K_DECIMAL}, {K_INT}, {K_LONG}, {K_DATE})"
_SQL_OPS = {"<": "<", "=<": "<=", ">": ">", ">=": ">="}


class TermIds(Protocol):
    """What the compiler needs from the store: interned term ids and closure membership."""

    def known_term_id(self, value: str) -> int:
        """The id of a stored term, or an id no row holds."""

    def closures_containing(self, term_id: int) -> list[int]:
        """Ids of the closures holding a term."""


def join_order(patterns: Sequence[TriplePattern], first: str) -> tuple[list[int], set[int]]:
    """A join order for "the first rows by ``first``", and the patterns in it joined to one
    before. It starts at the pattern binding ``first`` (its index scan yields rows in that
    order, so LIMIT stops early instead of joining everything and sorting), then takes each
    pattern sharing a variable with those before (a pattern sharing none comes last)."""
    names = [set(pattern.variables()) for pattern in patterns]
    start = next(i for i, vs in enumerate(names) if first in vs)
    chosen, bound, joined = [start], set(names[start]), set()
    while len(chosen) < len(patterns):
        rest = [i for i in range(len(patterns)) if i not in chosen]
        nxt = next((i for i in rest if names[i] & bound), None)
        if nxt is None:
            nxt = rest[0]
        else:
            joined.add(nxt)
        chosen.append(nxt)
        bound |= names[nxt]
    return chosen, joined


def joined_in_order(patterns: Sequence[TriplePattern]) -> set[int]:
    """The patterns sharing a variable with one before them (joined to it, in written order)."""
    seen: set[str] = set()
    joined = set()
    for i, pattern in enumerate(patterns):
        names = set(pattern.variables())
        if names & seen:
            joined.add(i)
        seen |= names
    return joined


class SqlCompiler:
    """Turns triple patterns into one SQL join with KnowRob's p*/o* semantics."""

    def __init__(self, store: TermIds, table: str, scope: Scope | None, side: Side | None = None) -> None:
        self.store = store
        self.table = table
        self.scope = scope
        self.side = side
        #: The table each pattern reads (``table``, the side table, or both).
        self.sources: list[str] = []
        self.aliases: list[str] = []
        self.inline_closures = False
        #: The pattern being added is reached from an earlier one in a forced join order:
        #: its closure tests must not drive an index (``+column``), so SQLite looks it up by
        #: the joined subject or object instead of scanning the closure's whole range (an
        #: ordered "latest decision" query fell from ~90 ms to ~0.1 ms on 10,000 actions).
        self.joined = False
        #: Likewise for a pattern with a known subject: the (s, p) index finds its few rows,
        #: where SQLite (no statistics) would scan the (p, ostar) range of every type triple.
        self.constant_subject = False
        self.conds: list[str] = []
        self.params: list[Any] = []
        #: variable -> (SQL expression of its value, SQL expression of its kind; None for a term id)
        self.bound: dict[str, tuple[str, str | None]] = {}
        #: With ``semi_joins``, a pattern after the first that binds no new variable is a test
        #: (``EXISTS``), not a join: goal by goal it is a ground goal, which succeeds once
        #: however many documents match it (two type triples of one subject, one of them
        #: through the class closure), so the compiled query gives the same solutions.
        self.semi_joins = False
        self.semi: set[int] = set()
        #: KnowRob's extent rule (``kb_scope``): a document is seen only where its scope has an
        #: extent (since < until), and a solution only where the scopes of the documents joined
        #: share one (mongolog's ``v_scope``); set for ``match``, the queries Prolog asks.
        #: ``find`` (the store's own reads: dumps, the writer) sees every document.
        self.knowrob_extent = False

    def from_clause(self) -> str:
        return ", ".join(f"{self.sources[i]} AS {self.aliases[i]}" for i in self.joined_patterns())

    def ordered_from_clause(self, plan: Sequence[int]) -> str:
        """The patterns joined in ``plan`` order (``join_order``); CROSS JOIN makes SQLite
        keep it."""
        return " CROSS JOIN ".join(f"{self.sources[i]} AS {self.aliases[i]}" for i in plan if i not in self.semi)

    def joined_patterns(self) -> list[int]:
        """The patterns in the FROM clause (those that are no ``EXISTS`` test)."""
        return [i for i in range(len(self.aliases)) if i not in self.semi]

    def where(self) -> str:
        conds = self.conds
        joined = self.joined_patterns()
        if self.knowrob_extent and len(joined) > 1:
            since = ", ".join(f"coalesce({self.aliases[i]}.since, 0)" for i in joined)
            until = ", ".join(f"coalesce({self.aliases[i]}.until, 9e999)" for i in joined)
            conds = [*conds, f"max({since}) < min({until})"]
        return " AND ".join(conds) if conds else "1"

    def _iri(self, value: Any) -> int:
        return self.store.known_term_id(value) if isinstance(value, str) else -1

    def _constant(self, column: str, kind_column: str | None, value: Any) -> None:
        if kind_column is None:  # s or p: always a term
            self.conds.append(f"{column}=?")
            self.params.append(self._iri(value))
            return
        if isinstance(value, str):
            self.conds.append(f"{column}=? AND {kind_column}={K_STR}")
            self.params.append(self._iri(value))
            return
        sql, kind = sql_value(value)
        if kind == K_OTHER:
            raise StoreError(f"cannot query for a {type(value).__name__} value: {value!r}")
        self.conds.append(f"{column}=?")
        self.params.append(sql)
        if kind in _NUMERIC_KINDS:
            self.conds.append(f"{kind_column} IN (1, 2, 3, 4)")
        else:
            self.conds.append(f"{kind_column}={kind}")

    def _closure_test(self, column: str, var: str | None, value: Any = None) -> None:
        """``column`` names a closure containing the term (a bound variable or a constant)."""
        if self.joined or self.constant_subject:
            column = "+" + column
        if var is None and self.inline_closures:
            # The closure ids as literals: an ordered query can then scan the (pstar, o)
            # index by o, where a subquery makes SQLite fall back to the (o, p) index.
            cids = self.store.closures_containing(self._iri(value))
            if column.endswith("ostar"):
                self._inline_ostar(column, cids)
                return
            if len(cids) == 1:
                self.conds.append(f"{column}=? AND {column} > 0")
            else:
                self.conds.append(f"{column} IN ({', '.join('?' * len(cids))}) AND {column} > 0")
            self.params.extend(cids)
            return
        if var is None:
            self.conds.append(f"{column} IN (SELECT cid FROM closure_member WHERE value=?) AND {column} > 0")
            self.params.append(self._iri(value))
            return
        expr, kind = self.bound[var]
        self.conds.append(f"{column} IN (SELECT cid FROM closure_member WHERE value={expr}) AND {column} > 0")
        if kind is not None:
            self.conds.append(f"{kind}={K_STR}")

    def _inline_ostar(self, column: str, cids: list[int]) -> None:
        """An ``o*`` test with literal closure ids. ``column > 0`` lets SQLite use the partial
        (p, ostar) index, but SQLite then seeks by that range (every type triple) rather than
        by the ids, even by one id; a range from the least id to the greatest is the seek it
        takes instead (why-not on 10,000 actions: the first pick-task row ~14 ms -> ~1 ms, the
        candidate calls of a task ~8 ms -> ~0.4 ms)."""
        low, high = min(cids, default=0), max(cids, default=0)
        test = f"{column}=?" if len(cids) == 1 else f"{column} IN ({', '.join('?' * len(cids))})"
        self.conds.append(f"{test} AND {column} >= ? AND {column} <= ? AND {column} > 0")
        self.params.extend([*cids, low, high])

    def add(self, pattern: TriplePattern, exact: bool = False) -> None:
        index, first_cond = len(self.aliases), len(self.conds)
        semi = self.semi_joins and not exact and index > 0 and set(pattern.variables()) <= set(self.bound)
        joined = self.joined
        # A test is always reached from the patterns binding its variables (their index, not
        # a scan of its closure's range, finds its rows).
        self.joined = joined or semi
        self._add(pattern, exact)
        self.joined = joined
        if semi:
            a = self.aliases[index]
            test = " AND ".join(self.conds[first_cond:]) or "1"
            del self.conds[first_cond:]  # its parameters keep their place: the test stands where they did
            self.conds.append(f"EXISTS (SELECT 1 FROM {self.sources[index]} AS {a} WHERE {test})")
            self.semi.add(index)

    def _add(self, pattern: TriplePattern, exact: bool) -> None:
        a = f"t{len(self.aliases)}"
        self.aliases.append(a)
        self.sources.append(self.table if self.side is None else self.side.sources(self.table, pattern, exact, self._iri))
        p = pattern.p
        if exact:
            self._term(pattern.s, f"{a}.s", None)
            self._term(p, f"{a}.p", None)
            self._object(pattern.o, a)
            self._filters(a, pattern)
            return
        taxonomic = isinstance(p, str) and p in TAXONOMIC
        self.constant_subject = pattern.s is not None and not isinstance(pattern.s, Var)
        # Only a variable bound by an earlier pattern is "bound" for o* (mongolog binds per goal).
        earlier = set(self.bound)
        self._term(pattern.s, f"{a}.s", None)
        if isinstance(p, Var):
            self._term(p, f"{a}.p", None)
        elif p is not None:
            if not isinstance(p, str):
                raise StoreError(f"a property must be an IRI, got {p!r}")
            if taxonomic:
                self.conds.append(f"{a}.p=?")
                self.params.append(self._iri(p))
            else:
                self._closure_test(f"{a}.pstar", None, p)
                self.conds.append(f"{a}.p NOT IN {TAXONOMIC_SQL} AND {non_taxonomic(a + '.p')}")
        o = pattern.o
        if taxonomic and isinstance(o, Var) and o.name in earlier:
            self._closure_test(f"{a}.ostar", o.name)
        elif taxonomic and o is not None and not isinstance(o, Var):
            self._closure_test(f"{a}.ostar", None, o)
        else:
            self._object(o, a)
        self._filters(a, pattern)

    def _object(self, o: Any, a: str) -> None:
        if not isinstance(o, Cmp):
            self._term(o, f"{a}.o", f"{a}.ok")
            return
        self._term(o.var, f"{a}.o", f"{a}.ok")
        # NaN is stored as NULL, so it never compares, as in Prolog. Two bounds side by side
        # are one range of the (pstar, o) index: a slice's begins, not every begin past one.
        tests = " AND ".join(f"{a}.o {_SQL_OPS[op]} ?" for op, _ in o.conditions())
        self.conds.append(f"{a}.ok IN {_COMPARABLE_SQL} AND {tests}")
        self.params.extend(float(value) for _, value in o.conditions())

    def _filters(self, a: str, pattern: TriplePattern) -> None:
        if isinstance(pattern.graph, str):
            self.conds.append(f"{a}.graph=?")
            self.params.append(pattern.graph)
        elif pattern.graph is not None:
            self.conds.append(f"{a}.graph IN ({','.join('?' * len(pattern.graph))})")
            self.params.extend(pattern.graph)
        if self.scope is not None:
            self.conds.append(f"({a}.since IS NULL OR {a}.since<=?) AND ({a}.until IS NULL OR {a}.until>=?)")
            self.params.extend([self.scope.until, self.scope.since])
        if self.knowrob_extent:
            self.conds.append(f"({a}.since IS NULL OR {a}.until IS NULL OR {a}.since < {a}.until)")

    def _term(self, term: Term, column: str, kind_column: str | None) -> None:
        if term is None:
            return
        if not isinstance(term, Var):
            self._constant(column, kind_column, term)
            return
        if term.name not in self.bound:
            self.bound[term.name] = (column, kind_column)
            return
        expr, kind = self.bound[term.name]
        self.conds.append(f"{column}={expr}")
        # Term ids and literal numbers share the column types: compare like with like.
        if kind_column is None and kind is not None:
            self.conds.append(f"{kind}={K_STR}")
        elif kind_column is not None and kind is None:
            self.conds.append(f"{kind_column}={K_STR}")
        elif kind_column is not None and kind is not None:
            self.conds.append(f"({kind_column}={K_STR})=({kind}={K_STR})")


def match_sql(
    query: SqlCompiler,
    patterns: Sequence[TriplePattern],
    limit: int | None,
    order: Sequence[tuple[str, bool]],
    select: Sequence[str] | None,
    group: str | None,
    written_order: bool,
) -> tuple[list[str], list[str], str, list[Any]]:
    """The SQL of one join (``Store.match``): the kept variables (``group`` last), the column
    expressions (a value and a kind per variable), the text after the select list and the
    parameters."""
    query.semi_joins = True
    query.knowrob_extent = True
    if written_order:  # with an order too: joined as written, then sorted (a top-N sort)
        plan, joined = list(range(len(patterns))), joined_in_order(patterns)
    elif order:
        plan, joined = join_order(patterns, order[0][0])
    else:
        plan, joined = [], set()
    first = plan[0] if plan else -1
    for i, pattern in enumerate(patterns):
        query.inline_closures = i == first
        query.joined = i in joined
        query.add(pattern)
    names = [name for name in query.bound if (select is None or name in select) and name != group]
    if group is not None:
        names.append(group)
    columns = [expr for n in names for expr in (query.bound[n][0], str(query.bound[n][1] or K_STR))]
    keys = [f"{query.bound[name][0]} {'DESC' if descending else 'ASC'}" for name, descending in order]
    # In the written order the rows are sorted after the join ("+": SQLite would otherwise
    # scan the first table in id order to skip the sort, instead of using its index).
    mark = "+" if written_order else ""
    # Rows equal in every key come in insertion order, but not in a top-N scan by the key
    # (an order and a limit, joined by the store's plan): SQLite 3.40 then sorts the ties
    # of every key value before it stops, which walks the whole index (0.4 s at 50,000
    # actions for the latest of two decisions). Groups come in no fixed order (Store.match),
    # and so do the rows of a limit without an order: the scan stops at the Nth row it finds
    # instead of sorting every row by id first (a "fewer than 64 decisions?" test read all
    # 50,000 imaginings and sorted them: 40 ms against 0.3 ms).
    if group is None and (limit is None or (order and written_order)):
        keys += [f"{mark}{query.aliases[i]}.id" for i in query.joined_patterns()]
    source = query.ordered_from_clause(plan) if plan else query.from_clause()
    rest = f"FROM {source} WHERE {query.where()}"
    if keys:
        rest += f" ORDER BY {', '.join(keys)}"
    if limit is not None:
        rest += f" LIMIT {int(limit)}"
    return names, columns, rest, query.params
