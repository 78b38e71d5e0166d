:- module(store_read,
    [ store_match/2,            % +Patterns, +Scope
      store_match/3,            % +Patterns, +Scope, +Options
      store_match_scoped/3      % +Patterns, +Scope, -FactScope
    ]).
/** <module> Triple matches: a conjunction of patterns answered in ONE store query

Every triple lookup of the Prolog side goes through store_match/2,3, which evaluates a list
of triple patterns `t(S,P,O)` (store_pattern) as ONE conjunction with KnowRob 2.x's
`p*`/`o*` semantics (knowrob-2x-facts §5):

  - a taxonomic property (rdf:type, rdfs:subClassOf, rdfs:subPropertyOf) matches the
    asserted property exactly and a bound object against the class closure `o*`;
  - any other property matches the property closure `p*`, the object exactly.

On the `python` backend the conjunction crosses into Python once (store_python) and becomes
one SQL join (SQLite) or one aggregation pipeline (MongoDB); results come back in chunks.
On the `memory` backend store_memory evaluates it. Both see facts as store_scope says.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(neem, [store_backend/1]).
:- use_module(python, [store_python_call/3, store_python_rows/2]).
:- use_module(memory, [store_memory_match/3]).
:- use_module(pattern, [store_check_pattern/1, store_compare/3]).
:- use_module(scope, [store_check_scope/1, store_in_scope/3, store_scope_intersection/4,
                      store_query_graphs/1]).

%!  store_match(+Patterns, +Scope) is nondet.
%!  store_match(+Patterns, +Scope, +Options) is nondet.
%   Solve the conjunction of `t(S,P,O)` patterns in ONE store query, binding their
%   variables. Options: `limit(N)`, `order(Keys)` (with a limit, solutions equal in every
%   key come in no fixed order: the store's top-N scan stops at its Nth row) and
%   `select(Term)`: only the variables of
%   Term are bound by a solution (the store does not send the others back; the memory
%   backend binds them all), for callers that collect a few variables of many rows;
%   `group(Var, Values)` (with select(Term), no limit or order): one solution per distinct
%   binding of Term's other variables, Var left free and Values the list of its values in
%   those rows (duplicates kept, in no fixed order), grouped by the store; `plan(written)`:
%   the store joins the patterns in the order written (SQLite has no statistics to plan a
%   long join by; MongoDB's pipeline is always in that order), with `order(Keys)` too (the
%   rows are then sorted after the join, not scanned in the key's order). Terms must be variables or
%   atomic values.
store_match(Patterns, Scope) :-
    store_match(Patterns, Scope, []).

store_match(Patterns0, Scope, Options) :-
    checked_query(Patterns0, Scope, Patterns, Backend),
    match(Backend, Patterns, Scope, Options).

%   A store query checked (non-empty list of patterns, a scope) with its comparisons bound,
%   and the backend that answers it.
checked_query(Patterns0, Scope, Patterns, Backend) :-
    must_be(list, Patterns0),
    Patterns0 \== [],
    maplist(store_check_pattern, Patterns0),
    store_check_scope(Scope),
    maplist(bound_comparison, Patterns0, Patterns),
    store_backend(Backend).

%!  store_match_scoped(+Patterns, +Scope, -FactScope) is nondet.
%   store_match/2 that also says when the matched facts hold together: FactScope is
%   `scope(Since, Until)`, the intersection of the scopes of the documents matched (one
%   solution per combination of documents, as mongolog's `v_scope`; empty intersections
%   are dropped). What `G during [S,U]` with S and U free and kb_call/3 report.
store_match_scoped(Patterns0, Scope, FactScope) :-
    checked_query(Patterns0, Scope, Patterns, Backend),
    Inf is inf,
    (   Backend == memory
    ->  store_memory_match(Patterns, Scope, FactScope)
    ;   match(Backend, Patterns, Scope, []),
        Backend = python(Neem),
        foldl(doc_scope(Neem, Scope), Patterns, scope(0.0, Inf), FactScope)
    ).

%   The scope of one matched (now ground) pattern's document, intersected with Acc.
doc_scope(Neem, Scope, t(S, P, O0), Acc, FS) :-
    compared_value(O0, O),
    (   store_query_graphs(Graphs) -> Request = [Neem, S, P, O, Graphs] ; Request = [Neem, S, P, O] ),
    store_python_call(scopes, Request, Rows),
    member([Since, Until], Rows),
    store_in_scope(Scope, Since, Until),
    store_scope_intersection(Acc, Since, Until, FS).

%   The value an object stands for: a comparison's variable, or the object itself.
compared_value(C, X) :- nonvar(C), C = cmp(_, _, X), !.
compared_value(C, X) :- nonvar(C), C = cmp(_, _, _, _, X), !.
compared_value(O, O).

%   A comparison whose value is already bound is that value, if it passes.
bound_comparison(t(S, P, C), t(S, P, O)) :-
    nonvar(C), C = cmp(Op, A, X), nonvar(X), !,
    number(X), store_compare(Op, X, A),
    O = X.
bound_comparison(t(S, P, C), t(S, P, O)) :-
    nonvar(C), C = cmp(Op1, A1, Op2, A2, X), nonvar(X), !,
    number(X), store_compare(Op1, X, A1), store_compare(Op2, X, A2),
    O = X.
bound_comparison(T, T).

%   fused_ranges(+Patterns, -Fused): two comparisons of one value, `t(S, P, cmp(Op1, A1, X))`
%   and a later `t(S, P, cmp(Op2, A2, X))` (S, P and X the same terms), as one pattern
%   `t(S, P, cmp(Op1, A1, Op2, A2, X))` where the first stood: KnowRob's way to ask for a
%   range, `triple(I, P, >(A)->B), triple(I, P, =<(U)->B)`, then costs the store one index
%   range (the begins of a slice of a NEEM), not a scan from one bound to the end with the
%   other tested on each row. The same solutions: the second pattern binds nothing new and
%   is a test (a ground goal, one answer), and a document passing both comparisons passes it.
fused_ranges([], []).
fused_ranges([T|Ts], [F|Fs]) :-
    (   T = t(S, P, C), nonvar(C), C = cmp(Op1, A1, X), var(X),
        same_comparison(Ts, S, P, X, Op2, A2, Rest)
    ->  F = t(S, P, cmp(Op1, A1, Op2, A2, X)),
        fused_ranges(Rest, Fs)
    ;   F = T,
        fused_ranges(Ts, Fs)
    ).

%   The first of Patterns comparing X of S and P, and Patterns without it.
same_comparison([T|Ts], S, P, X, Op, A, Rest) :-
    (   T = t(S1, P1, C), S1 == S, P1 == P, nonvar(C), C = cmp(Op, A, X1), X1 == X
    ->  Rest = Ts
    ;   Rest = [T|Rest1],
        same_comparison(Ts, S, P, X, Op, A, Rest1)
    ).

mem_conj(Patterns, Scope) :-
    store_memory_match(Patterns, Scope, _).

match(Backend, Patterns, Scope, Options) :-
    memberchk(group(Var, Values), Options), !,
    group_option(Options, Patterns, Var, Keep, Keys),
    (   Backend = python(_)
    ->  maplist(replace_var(Var, Values), Patterns, Patterns1),
        (   memberchk(plan(written), Options) -> Plan = [plan(written)] ; Plan = [] ),
        match(Backend, Patterns1, Scope, [select(Keep-Values), group_last|Plan])
    ;   findall(Keys-Var, mem_conj(Patterns, Scope), Pairs),
        msort(Pairs, Sorted),
        group_pairs_by_key(Sorted, Groups),
        member(Keys-Values, Groups)
    ).
match(memory, Patterns, Scope, Options) :-
    option_order(Options, Keys),
    Keys \== [], !,
    term_variables(Patterns, Vars),
    findall(Row, ( mem_conj(Patterns, Scope), order_row(Keys, Vars, Row) ), Rows0),
    length(Keys, NKeys),
    sort_rows(NKeys, Keys, Rows0, Rows1),
    VarsArg is NKeys+1,
    (   option_limit(Options, N)
    ->  limit(N, ( member(Row, Rows1), arg(VarsArg, Row, Vars) ))
    ;   member(Row, Rows1), arg(VarsArg, Row, Vars)
    ).
match(memory, Patterns, Scope, Options) :-
    (   option_limit(Options, N)
    ->  limit(N, mem_conj(Patterns, Scope))
    ;   mem_conj(Patterns, Scope)
    ).
match(python(Neem), Patterns0, Scope, Options) :-
    fused_ranges(Patterns0, Patterns),
    term_variables(Patterns, All),
    selected_first(Options, All, Vars, Order0),
    maplist(encode_pattern(Order0), Patterns, Encoded0),
    (   store_query_graphs(Graphs)
    ->  maplist(graph_cells(Graphs), Encoded0, Encoded)
    ;   Encoded = Encoded0
    ),
    encode_scope(Scope, S0, S1),
    (   option_limit(Options, N) -> true ; N = -1 ),
    option_order(Options, Keys),
    maplist(encode_key(Order0), Keys, Order),
    length(Vars, NVars),
    (   memberchk(group_last, Options) -> Group is NVars-1 ; Group = -1 ),
    (   memberchk(plan(written), Options) -> Plan = written ; Plan = store ),
    Request = [Neem, S0, S1, N, NVars, Order, Group, Plan|Encoded],
    store_python_rows(Request, Vars).

%   replace_var(+Var, +New, +Term, -Term1): Term with the variable Var replaced by New (the
%   grouped variable of the python backend, selected last, comes back bound to its list of
%   values; Var itself stays free, as on the memory backend).
replace_var(Var, New, T, New) :-
    T == Var, !.
replace_var(Var, New, T, T1) :-
    compound(T), !,
    T =.. [F|As],
    maplist(replace_var(Var, New), As, As1),
    T1 =.. [F|As1].
replace_var(_, _, T, T).

%   group(Var, Values) checked: Var a variable of the patterns, kept by select(Term), and
%   neither limit nor order given; Keep is Term without Var, Keys its variables.
group_option(Options, Patterns, Var, Keep, Keys) :-
    (   var(Var), term_variables(Patterns, All), occurs_in(All, Var)
    ->  true
    ;   domain_error(pattern_variable, Var)
    ),
    (   memberchk(select(Term), Options)
    ->  term_variables(Term, TermVars),
        (   occurs_in(TermVars, Var) -> true ; domain_error(selected_variable, Var) )
    ;   TermVars = All
    ),
    (   ( memberchk(limit(_), Options) ; memberchk(order(_), Options) )
    ->  domain_error(group_without_limit_or_order, Options)
    ;   true
    ),
    exclude(==(Var), TermVars, KeyVars0),
    include(occurs_in(All), KeyVars0, KeyVars),
    Keep = KeyVars,
    Keys = KeyVars.

%   select(Keep): only the variables of Keep come back (the bridge returns the first NVars
%   variables of the numbering, so these are numbered first); the others are existential.
selected_first(Options, All, Vars, Numbering) :-
    (   memberchk(select(Keep), Options)
    ->  term_variables(Keep, KeepVars),
        include(occurs_in(All), KeepVars, Vars),
        exclude(occurs_in(Vars), All, Rest),
        append(Vars, Rest, Numbering)
    ;   Vars = All,
        Numbering = All
    ).

occurs_in(Vars, V) :- member(X, Vars), X == V, !.

option_limit(Options, N) :-
    memberchk(limit(N), Options),
    must_be(positive_integer, N).

%   order(Keys): Keys is a list of asc(Var) and desc(Var) over numeric variables of the
%   patterns, applied before limit(N) (by the database on the python backend).
option_order(Options, Keys) :-
    (   memberchk(order(Keys), Options)
    ->  must_be(list, Keys),
        maplist(check_key, Keys)
    ;   Keys = []
    ).

check_key(asc(V)) :- var(V), !.
check_key(desc(V)) :- var(V), !.
check_key(K) :- type_error(order_key, K).

encode_key(Vars, Key, [I, Dir]) :-
    Key =.. [Dir, V],
    nth0_var(Vars, V, 0, I).

order_row(Keys, Vars, Row) :-
    maplist(key_value, Keys, Vs),
    append(Vs, [Vars], Args),
    Row =.. [row|Args].

key_value(K, V) :- arg(1, K, V).

%   Stable sorts from the last key to the first give the lexicographic order.
sort_rows(0, _, Rows, Rows) :- !.
sort_rows(I, Keys, Rows0, Rows) :-
    nth1(I, Keys, Key),
    (   Key = asc(_) -> Ord = @=< ; Ord = @>= ),
    sort(I, Ord, Rows0, Rows1),
    I1 is I-1,
    sort_rows(I1, Keys, Rows1, Rows).

%   Scope ends as numbers; -1, -1 for no time filter. The bridge turns them into the
%   store's Scope (see python/oracle/bridge/foreign.py).
encode_scope(any, -1, -1).
encode_scope(scope(S, U), S, U).

%   The graph filter as two more cells of an encoded pattern: `g` and the list of graphs.
graph_cells(Graphs, Cells0, Cells) :- append(Cells0, [g, Graphs], Cells).

%   A pattern slot as two list cells: kind (v, c) and value (variable index or constant).
encode_pattern(Vars, t(S,P,O), [SK,SV,PK,PV,OK,OV]) :-
    encode_term(Vars, S, SK, SV),
    encode_term(Vars, P, PK, PV),
    encode_term(Vars, O, OK, OV).

encode_term(Vars, X, v, I) :-
    var(X), !,
    nth0_var(Vars, X, 0, I).
encode_term(Vars, cmp(Op, A, X), cmp, [Op, A, I]) :- !,
    nth0_var(Vars, X, 0, I).
encode_term(Vars, cmp(Op1, A1, Op2, A2, X), cmp2, [Op1, A1, Op2, A2, I]) :- !,
    nth0_var(Vars, X, 0, I).
encode_term(_, X, c, X).

nth0_var([V|Vs], X, I0, I) :-
    (   V == X -> I = I0 ; I1 is I0+1, nth0_var(Vs, X, I1, I) ).
