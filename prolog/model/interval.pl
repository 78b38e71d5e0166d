:- module(allen_interval,
    [ interval/2,               % +IntervalOrEvent, -[Begin, End]
      interval_before/2,        % +I1, +I2
      interval_after/2,
      interval_meets/2,
      interval_met_by/2,
      interval_overlaps/2,
      interval_overlapped_by/2,
      interval_starts/2,
      interval_started_by/2,
      interval_during/2,
      interval_contains/2,
      interval_finishes/2,
      interval_finished_by/2,
      interval_equals/2,
      interval_constraint/2,    % ?Interval, ?Constraint
      interval_constraint/3,    % ?Interval, ?Constraint, ?Other
      interval_query/1,         % +Constraint
      interval_order/2          % +Intervals, -Ordered
    ]).
/** <module> Allen's interval relations (KnowRob 2.x src/model/... interval predicates)

Each argument is `[Begin, End]` (unix seconds), an event with a time interval (its
event_interval/3) or a time interval individual (soma:hasIntervalBegin/End). As in KnowRob,
interval_during/2 includes a shared begin or end (`B2 =< B1, E1 =< E2`); the others are exclusive for
proper intervals.

Without times, the relations SOMA states between events (`soma:before`, `soma:meets`,
`soma:during`, ... KnowRob's interval_constraint/3) decide: their endpoints form a graph
(KnowRob's event endpoint graph: each constraint orders or equates begins and ends) and a
relation holds when the graph orders the endpoints as it requires.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(library(yall)).
:- use_module('../lang/query', [kb_call/2]).
:- use_module('../lang/triple', [kb_iri/2]).
:- use_module(event, []).

%!  interval(+IntervalOrEvent, -Interval) is semidet.
%   `[Begin, End]` of an interval term or an event.
interval(I, [B, E]) :-
    nonvar(I), I = [B, E], !,
    must_be(number, B), must_be(number, E).
interval(Ev0, [B, E]) :-
    must_be(nonvar, Ev0),
    kb_iri(Ev0, Ev),
    once((   kb_call(event_interval(Ev, B, E), any)
         ;   kb_call(( has_interval_begin(Ev, B), has_interval_end(Ev, E) ), any)
         )).

%   relation(+Name, +I1, +I2, +Test, +Endpoints): Test on the two [B, E] intervals, or, when
%   one has no times, the endpoint order the stated constraints imply.
relation(I1, I2, Test, Orders) :-
    (   interval(I1, T1), interval(I2, T2)
    ->  call(Test, T1, T2)
    ;   atom_or_iri(I1), atom_or_iri(I2)
    ->  kb_iri(I1, A), kb_iri(I2, B),
        endpoint_graph(A, G),
        forall(member(O, Orders), graph_holds(G, A, B, O))
    ).

atom_or_iri(X) :- atom(X), !.
atom_or_iri(P:L) :- atom(P), atom(L).

%!  interval_before(+I1, +I2) is semidet.
%   I1 ends before I2 begins.
interval_before(I1, I2) :- relation(I1, I2, [[_, E1], [B2, _]]>>(E1 < B2), [end(1) < begin(2)]).
%!  interval_after(+I1, +I2) is semidet.
interval_after(I1, I2) :- interval_before(I2, I1).
%!  interval_meets(+I1, +I2) is semidet.
%   I1 ends when I2 begins.
interval_meets(I1, I2) :- relation(I1, I2, [[_, E1], [B2, _]]>>(E1 =:= B2), [end(1) = begin(2)]).
%!  interval_met_by(+I1, +I2) is semidet.
interval_met_by(I1, I2) :- interval_meets(I2, I1).
%!  interval_overlaps(+I1, +I2) is semidet.
%   I1 begins first and ends inside I2.
interval_overlaps(I1, I2) :-
    relation(I1, I2, [[B1, E1], [B2, E2]]>>(B1 < B2, E1 > B2, E1 < E2),
             [begin(1) < begin(2), begin(2) < end(1), end(1) < end(2)]).
%!  interval_overlapped_by(+I1, +I2) is semidet.
interval_overlapped_by(I1, I2) :- interval_overlaps(I2, I1).
%!  interval_starts(+I1, +I2) is semidet.
%   Both begin together and I1 ends first.
interval_starts(I1, I2) :-
    relation(I1, I2, [[B1, E1], [B2, E2]]>>(B1 =:= B2, E1 < E2), [begin(1) = begin(2), end(1) < end(2)]).
%!  interval_started_by(+I1, +I2) is semidet.
interval_started_by(I1, I2) :- interval_starts(I2, I1).
%!  interval_during(+I1, +I2) is semidet.
%   I1 lies inside I2, a shared begin or end included (KnowRob's test).
interval_during(I1, I2) :-
    relation(I1, I2, [[B1, E1], [B2, E2]]>>(B2 =< B1, E1 =< E2), [begin(2) < begin(1), end(1) < end(2)]).
%!  interval_contains(+I1, +I2) is semidet.
interval_contains(I1, I2) :- interval_during(I2, I1).
%!  interval_finishes(+I1, +I2) is semidet.
%   Both end together and I1 begins later.
interval_finishes(I1, I2) :-
    relation(I1, I2, [[B1, E1], [B2, E2]]>>(E1 =:= E2, B1 > B2), [end(1) = end(2), begin(2) < begin(1)]).
%!  interval_finished_by(+I1, +I2) is semidet.
interval_finished_by(I1, I2) :- interval_finishes(I2, I1).
%!  interval_equals(+I1, +I2) is semidet.
interval_equals(I1, I2) :-
    relation(I1, I2, [[B1, E1], [B2, E2]]>>(B1 =:= B2, E1 =:= E2), [begin(1) = begin(2), end(1) = end(2)]).

                 /*******************************
                 *     STATED CONSTRAINTS       *
                 *******************************/

%   The SOMA property stating each constraint, and its endpoint orders.
allen(=, soma:simultaneous, [begin(1) = begin(2), end(1) = end(2)]).
allen(<, soma:before, [end(1) < begin(2)]).
allen(>, soma:after, [end(2) < begin(1)]).
allen(m, soma:meets, [end(1) = begin(2)]).
allen(mi, soma:metBy, [end(2) = begin(1)]).
allen(o, soma:overlappedOn, [begin(1) < begin(2), begin(2) < end(1), end(1) < end(2)]).
allen(oi, soma:overlappedBy, [begin(2) < begin(1), begin(1) < end(2), end(2) < end(1)]).
allen(s, soma:starts, [begin(1) = begin(2), end(1) < end(2)]).
allen(si, soma:startedBy, [begin(1) = begin(2), end(2) < end(1)]).
allen(f, soma:finishes, [end(1) = end(2), begin(2) < begin(1)]).
allen(fi, soma:finishedBy, [end(1) = end(2), begin(1) < begin(2)]).
allen(d, soma:during, [begin(2) < begin(1), end(1) < end(2)]).

%!  interval_constraint(?Interval, ?Constraint) is nondet.
%!  interval_constraint(?Interval, ?Constraint, ?Other) is nondet.
%   A relation SOMA states from Interval to Other (an event or interval), as KnowRob's
%   constraint term: `<(I, O)` (soma:before), `m(I, O)` (meets), `d(I, O)` (during), ...
interval_constraint(I, C) :- interval_constraint(I, C, _).
interval_constraint(I0, C, O0) :-
    kb_iri(I0, I), kb_iri(O0, O),
    allen(Sym, P0, _), kb_iri(P0, P),
    kb_call(triple(I, P, O), any),
    C =.. [Sym, I, O].

%!  interval_query(+Constraint) is semidet.
%   The relation of Constraint (`<(A, B)`, `d(A, B)`, ...) holds between A and B.
interval_query(C) :-
    must_be(compound, C), C =.. [Sym, A, B],
    (   query_relation(Sym, Rel, Swap) -> true ; domain_error(allen_constraint, C) ),
    (   Swap == true -> call(Rel, B, A) ; call(Rel, A, B) ).

query_relation(=, interval_equals, false).
query_relation(<, interval_before, false).
query_relation(>, interval_before, true).
query_relation(m, interval_meets, false).
query_relation(mi, interval_meets, true).
query_relation(o, interval_overlaps, false).
query_relation(oi, interval_overlaps, true).
query_relation(s, interval_starts, false).
query_relation(si, interval_starts, true).
query_relation(f, interval_finishes, false).
query_relation(fi, interval_finishes, true).
query_relation(d, interval_during, false).

%   endpoint_graph(+Interval, -Graph): the constraints stated among the intervals connected
%   to Interval by stated relations, as `Graph = g(Equal, Less)`: Equal a list of sets of
%   equal endpoints, Less the ordered pairs between endpoints (-(I) begin, +(I) end).
endpoint_graph(I, g(Classes, Less)) :-
    connected([I], [I], Nodes),
    findall(C, ( member(X, Nodes), interval_constraint(X, C, Y), memberchk(Y, Nodes) ), Cs),
    findall(E, ( member(C, Cs), C =.. [Sym, A, B], allen(Sym, _, Os), member(O, Os), endpoint_fact(O, A, B, E) ), Es0),
    findall(-(X) < +(X), member(X, Nodes), Own),
    append(Es0, Own, Es),
    findall(X-Y, member(X = Y, Es), Eqs),
    equal_classes(Nodes, Eqs, Classes),
    findall(X-Y, member(X < Y, Es), Less).

connected([], Seen, Seen).
connected([X|Xs], Seen, Nodes) :-
    findall(Y, ( interval_constraint(X, _, Y) ; interval_constraint(Y, _, X) ), Ys0),
    sort(Ys0, Ys),
    exclude(in_list(Seen), Ys, New),
    append(Seen, New, Seen1),
    append(Xs, New, Queue),
    connected(Queue, Seen1, Nodes).

endpoint_fact(P < Q, A, B, X < Y) :- endpoint(P, A, B, X), endpoint(Q, A, B, Y).
endpoint_fact(P = Q, A, B, X = Y) :- endpoint(P, A, B, X), endpoint(Q, A, B, Y).
endpoint(begin(1), A, _, -(A)).
endpoint(end(1), A, _, +(A)).
endpoint(begin(2), _, B, -(B)).
endpoint(end(2), _, B, +(B)).

equal_classes(Nodes, Eqs, Classes) :-
    findall([E], ( member(N, Nodes), member(E, [-(N), +(N)]) ), Singletons),
    foldl(merge_equal, Eqs, Singletons, Classes).

merge_equal(X-Y, Cs0, [Merged|Rest]) :-
    partition(holds_either(X, Y), Cs0, Hit, Rest),
    append(Hit, Merged).

class_of(g(Classes, _), E, C) :- member(C, Classes), memberchk(E, C), !.

%   graph_holds(+Graph, +A, +B, +Order): the endpoint order Order over A (1) and B (2).
graph_holds(G, A, B, P = Q) :-
    endpoint(P, A, B, X), endpoint(Q, A, B, Y),
    class_of(G, X, C), memberchk(Y, C).
graph_holds(G, A, B, P < Q) :-
    endpoint(P, A, B, X), endpoint(Q, A, B, Y),
    class_of(G, X, CX), class_of(G, Y, CY),
    before(G, [CX], [CX], CY), !.

before(G, [C|Queue], Seen, Target) :-
    G = g(_, Less),
    findall(D, ( member(U, C), member(U-V, Less), class_of(G, V, D) ), Ds0),
    sort(Ds0, Ds),
    (   memberchk(Target, Ds) -> true
    ;   exclude(in_list(Seen), Ds, New),
        append(Seen, New, Seen1), append(Queue, New, Queue1),
        before(G, Queue1, Seen1, Target)
    ).

%!  interval_order(+Intervals, -Ordered) is det.
%   Intervals in an order of their begins the stated constraints among them allow (times
%   first when they have them; ties by name).
interval_order(Is, Ordered) :-
    (   maplist([I, B-I]>>interval(I, [B, _]), Is, Keyed)
    ->  keysort(Keyed, Sorted), pairs_values(Sorted, Ordered)
    ;   Is = [] -> Ordered = []
    ;   Is = [I0|_], endpoint_graph(I0, G),
        topological(Is, G, Ordered)
    ).

topological([], _, []) :- !.
topological(Is, G, [First|Rest]) :-
    msort(Is, Sorted),
    (   member(First, Sorted),
        \+ ( member(Other, Is), Other \== First, graph_holds(G, Other, First, begin(1) < begin(2)) )
    ->  true
    ;   Sorted = [First|_]
    ),
    exclude(==(First), Is, Is1),
    topological(Is1, G, Rest).

in_list(List, X) :- memberchk(X, List).
holds_either(X, Y, C) :- ( memberchk(X, C) -> true ; memberchk(Y, C) ).
