:- module(store_scope,
    [ store_scope_now/1,        % -Scope
      store_check_scope/1,      % @Scope
      store_in_scope/3,         % +Scope, +Since, +Until
      store_scope_intersection/4, % +Scope0, +Since, +Until, -Scope
      store_in_graphs/2,        % +Graphs, :Goal
      store_query_graphs/1      % -Graphs
    ]).
/** <module> When and where a stored fact is visible to a store query

A question scope is `scope(Since, Until)`: a fact is visible when its own scope contains
`[Since, Until]` (KnowRob's `since =< Since, until >= Until`), or `any` for no time filter.
Whatever the question scope, a fact is seen only where its scope has an extent
(`since < until`) and a conjunction only where its facts' scopes share one, as mongolog drops
every row whose running scope intersection `v_scope` is empty (KnowRob's triple.pl).

Where: store_in_graphs/2 narrows the store queries of a goal to some named graphs; both
backends read the filter with store_query_graphs/1.
*/

:- use_module(library(error)).

:- meta_predicate store_in_graphs(+, 0).

%!  store_scope_now(-Scope) is det.
%   KnowRob's default question scope: the facts true now.
store_scope_now(scope(Now, Now)) :- get_time(Now).

%!  store_check_scope(@Scope) is det.
%   Scope is `any` or `scope(Since, Until)` over numbers; raises `type_error(scope, Scope)`
%   otherwise.
store_check_scope(any) :- !.
store_check_scope(scope(S, U)) :- number(S), number(U), !.
store_check_scope(X) :- type_error(scope, X).

%!  store_in_scope(+Scope, +Since, +Until) is semidet.
%   A fact stated over [Since, Until] is visible to the question scope Scope. KnowRob's rule
%   (src/lang/terms/triple.pl, scope_intersect/5): a fact is seen only where its scope has
%   an extent, `Since < Until`, whatever the question scope; a question scope
%   `scope(QS, QU)` further asks that it contain [QS, QU].
store_in_scope(any, Since, Until) :- !,
    Since < Until.
store_in_scope(scope(QS, QU), Since, Until) :-
    Since < Until,
    Since =< QS,
    Until >= QU.

%!  store_scope_intersection(+Scope0, +Since, +Until, -Scope) is semidet.
%   Scope is `scope(S, U)`, the intersection of Scope0 with [Since, Until]; fails when it has
%   no extent (mongolog's `v_scope`).
store_scope_intersection(scope(S0, U0), S1, U1, scope(S, U)) :-
    num_max(S0, S1, S),
    num_min(U0, U1, U),
    S < U.

%   min/max by comparison: `is max(inf, inf)` raises float_overflow in SWI-Prolog.
num_min(A, B, M) :- ( A =< B -> M = A ; M = B ).
num_max(A, B, M) :- ( A >= B -> M = A ; M = B ).

%!  store_in_graphs(+Graphs, :Goal) is nondet.
%   Goal with every store query (store_match/2,3, store_match_scoped/3) reading only the
%   documents of the named graphs in the list Graphs (KnowRob's `graph` field filter,
%   `$in` its super-graphs); `all` reads every graph. Queries outside Goal are not
%   filtered: the filter is undone when Goal exits and restored when it is retried.
store_in_graphs(Graphs, Goal) :-
    (   Graphs == all -> true
    ;   must_be(list(atom), Graphs),
        ( Graphs == [] -> domain_error(non_empty_graph_list, Graphs) ; true )
    ),
    (   nb_current(neem_store_graphs, Old) -> true ; Old = all ),
    b_setval(neem_store_graphs, Graphs),
    call(Goal),
    b_setval(neem_store_graphs, Old).

%!  store_query_graphs(-Graphs) is semidet.
%   The graphs the current query reads (store_in_graphs/2); fails when it reads all of
%   them. (A key first created by b_setval/2 reads `[]` once backtracked over: no filter
%   either.)
store_query_graphs(Graphs) :-
    nb_current(neem_store_graphs, Graphs),
    Graphs \== all, Graphs \== [].
