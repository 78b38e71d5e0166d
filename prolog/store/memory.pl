:- module(store_memory,
    [ store_assert/1,           % +Triple
      store_assert/3,           % +Triple, +Since, +Until
      store_memory_insert/3,    % +Merge, +Graph, +Triple
      store_memory_retract/1,   % +Pattern
      store_memory_drop_graph/1, % +Graph
      store_memory_match/3      % +Patterns, +Scope, -FactScope
    ]).
/** <module> The memory backend's triples: asserted in Prolog, matched in Prolog

The triples of the `memory` backend (store_neem) with their scope and named graph, and the
evaluation of a conjunction of `t(S,P,O)` patterns over them with KnowRob 2.x's `p*`/`o*`
semantics (store_pattern) and scopes (store_scope), as the Python stores evaluate it in one
query. store_write, store_read and store_graph call it when the memory backend is in use.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(pattern, [store_taxonomic/1, store_closure_edge/1, store_compare/3]).
:- use_module(scope, [store_in_scope/3, store_scope_intersection/4, store_query_graphs/1]).
:- use_module(neem, []).

:- dynamic mem_triple/6.        % S, P, O, Since, Until, Graph

:- multifile store_neem:memory_facts/1.
store_neem:memory_facts(store_memory:mem_triple(_, _, _, _, _, _)).

%!  store_assert(+Triple) is det.
%!  store_assert(+Triple, +Since, +Until) is det.
%   Add `triple(S,P,O)` to the memory backend, universal scope unless given.
store_assert(Triple) :-
    Inf is inf,
    store_assert(Triple, 0.0, Inf).
store_assert(triple(S, P, O), Since, Until) :-
    !,
    must_be(atom, S), must_be(atom, P), must_be(atomic, O),
    must_be(number, Since), must_be(number, Until),
    assertz(mem_triple(S, P, O, Since, Until, user)).
store_assert(Triple, _, _) :-
    type_error(triple, Triple).

%!  store_memory_insert(+Merge, +Graph, +Triple) is det.
%   Add the checked `triple(S,P,O,Since,Until)` to graph Graph, merged (`union`) with or
%   narrowing (`intersect`) the copies of S, P, O in Graph whose scope overlaps its own
%   (store_insert/3 says how).
store_memory_insert(Merge, G, triple(S, P, O, Since, Until)) :-
    findall(S1-U1, ( mem_triple(S, P, O, S1, U1, G), S1 =< Until, U1 >= Since ), Overlaps),
    (   Overlaps == []
    ->  assertz(mem_triple(S, P, O, Since, Until, G))
    ;   Merge == union
    ->  retractall_overlapping(S, P, O, Since, Until, G),
        pairs_keys_values(Overlaps, Ss, Us),
        foldl(num_min, Ss, Since, Since1), foldl(num_max, Us, Until, Until1),
        assertz(mem_triple(S, P, O, Since1, Until1, G))
    ;   retractall_overlapping(S, P, O, Since, Until, G),
        forall(member(S1-U1, Overlaps),
               ( num_max(S1, Since, Since1), num_min(U1, Until, Until1),
                 assertz(mem_triple(S, P, O, Since1, Until1, G)) ))
    ).

%   min/max by comparison: `is max(inf, inf)` raises float_overflow in SWI-Prolog.
num_min(A, B, M) :- ( A =< B -> M = A ; M = B ).
num_max(A, B, M) :- ( A >= B -> M = A ; M = B ).

retractall_overlapping(S, P, O, Since, Until, G) :-
    forall(( clause(mem_triple(S, P, O, S1, U1, G), true, Ref), S1 =< Until, U1 >= Since ),
           erase(Ref)).

%!  store_memory_retract(+Pattern) is det.
%   Delete every triple matching the checked pattern `t(S,P,O)`, in every graph and scope.
store_memory_retract(t(S, P, O)) :-
    retractall(mem_triple(S, P, O, _, _, _)).

%!  store_memory_drop_graph(+Graph) is det.
%   Delete every triple of named graph Graph.
store_memory_drop_graph(Graph) :-
    retractall(mem_triple(_, _, _, _, _, Graph)).

%!  store_memory_match(+Patterns, +Scope, -FactScope) is nondet.
%   Solve the conjunction of checked `t(S,P,O)` patterns over the triples visible in Scope
%   (and in the graphs of store_in_graphs/2); FactScope is `scope(Since, Until)`, the
%   intersection of the matched triples' scopes (never empty).
store_memory_match(Patterns, Scope, FactScope) :-
    Inf is inf,
    mem_conj_scoped(Patterns, Scope, scope(0.0, Inf), FactScope).

mem_conj_scoped([], _, FS, FS).
mem_conj_scoped([t(S,P,O)|Ps], Scope, FS0, FS) :-
    mem_pattern(S, P, O, Scope, Since, Until),
    store_scope_intersection(FS0, Since, Until, FS1),
    mem_conj_scoped(Ps, Scope, FS1, FS).

%   mem_pattern(?S, ?P, ?O, +Scope, -Since, -Until): a stored triple and its scope.
mem_pattern(S, P, C, Scope, Since, Until) :-
    nonvar(C), C = cmp(Op, A, X), !,
    mem_pattern(S, P, X, Scope, Since, Until),
    number(X),
    store_compare(Op, X, A).
mem_pattern(S, P, C, Scope, Since, Until) :-
    nonvar(C), C = cmp(Op1, A1, Op2, A2, X), !,
    mem_pattern(S, P, X, Scope, Since, Until),
    number(X),
    store_compare(Op1, X, A1),
    store_compare(Op2, X, A2).
mem_pattern(S, P, O, Scope, Since, Until) :-
    atom(P), store_taxonomic(P), !,
    (   var(O)
    ->  mem_visible(S, P, O, Since, Until)
    ;   mem_visible(S, P, O0, Since, Until),
        mem_closure(O0, Closure),
        memberchk(O, Closure)
    ),
    store_in_scope(Scope, Since, Until).
mem_pattern(S, P, O, Scope, Since, Until) :-
    atom(P), !,
    mem_visible(S, P0, O, Since, Until),
    (   P0 == P
    ->  true
    ;   \+ store_taxonomic(P0),
        mem_closure(P0, Closure),
        memberchk(P, Closure)
    ),
    store_in_scope(Scope, Since, Until).
mem_pattern(S, P, O, Scope, Since, Until) :-
    mem_visible(S, P, O, Since, Until),
    store_in_scope(Scope, Since, Until).

%   A stored triple in one of the graphs the query reads (store_in_graphs/2).
mem_visible(S, P, O, Since, Until) :-
    (   store_query_graphs(Graphs)
    ->  mem_triple(S, P, O, Since, Until, G),
        memberchk(G, Graphs)
    ;   mem_triple(S, P, O, Since, Until, _)
    ).

%   The term and its ancestors over asserted subClassOf/subPropertyOf edges (KnowRob's o*).
mem_closure(Term, Closure) :-
    mem_closure_([Term], [Term], Rev),
    reverse(Rev, Closure).

mem_closure_([], Seen, Seen).
mem_closure_([T|Ts], Seen0, Seen) :-
    findall(Parent,
            ( store_closure_edge(E),
              mem_triple(T, E, Parent, _, _, _),
              \+ memberchk(Parent, Seen0) ),
            Parents0),
    list_to_set(Parents0, Parents),
    reverse(Parents, RevParents),
    append(RevParents, Seen0, Seen1),
    append(Ts, Parents, Queue),
    mem_closure_(Queue, Seen1, Seen).
