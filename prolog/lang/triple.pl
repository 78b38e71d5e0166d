:- module(kb_triple,
    [ triple/3,                 % ?Subject, ?Property, ?Object
      kb_iri/2,                 % +Term, -IRI
      iri_term/1,               % @Term
      triple_steps/6,           % +S, +P, +O, +Scope, -Steps, ?Tail
      value_test/3,             % +Operator, +Argument, +Value
      modified_triple/4,        % ?S, +ModifiedProperty, ?O, +Scope
      unit_factor/2             % ?Unit, ?Factor
    ]).
/** <module> triple/3: KnowRob 2.x's triple goal (src/lang/terms/triple.pl)

`triple(S, P, O)` asks the store for a triple with KnowRob's `p*`/`o*` semantics (see
neem_store). This module owns what a triple goal may say and how it becomes a store
pattern: IRIs written `prefix:'Local'` for the registered prefixes (rdf, rdfs, owl, xsd,
dul, soma, knowrob, odb), and the value operators of the object `<(V)`, `=<(V)`, `>(V)`,
`>=(V)`, `in(List)`, `nin(List)`, `regex(Pattern)` and `Op->Var` (the actual value back).
A comparison with a number known when the goal is compiled is evaluated by the store;
the other operators filter the solutions afterwards.

The subject takes the same operators as the object (`in(List)`, `Op->Var`, ...): a subject
`in(List)` is tried with each member. `=(V)` is value equality (numbers by value). A ground
triple goal succeeds at most once, however many documents (scopes) state it.

The property may carry KnowRob's modifiers: `transitive(P)` (S reaches O over a chain of P
triples, nearest first), `reflexive(P)` (also O = S) and `include_parents(P)` (for the
taxonomic properties: a free object is bound to every ancestor of the asserted class, not
only the asserted class). Modified triples are evaluated by modified_triple/4, one store
query per step of the chain.

The compiler (kb_query) calls triple_steps/6 for every triple and holds goal; triple/3
called from Prolog is `kb_call(triple(S,P,O))`.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- autoload(library(pcre), [re_match/2]).   % loaded on the first regex test
:- use_module(library(semweb/rdf_prefixes)).
:- use_module('../neem_store', [store_match/2, store_taxonomic/1]).

:- rdf_register_prefix(dul, 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#', [keep(true)]).
:- rdf_register_prefix(soma, 'http://www.ease-crc.org/ont/SOMA.owl#', [keep(true)]).
:- rdf_register_prefix(knowrob, 'http://knowrob.org/kb/knowrob.owl#', [keep(true)]).
:- rdf_register_prefix(odb, 'https://ontology.dlr.de/soma/odb#', [keep(true)]).

%!  triple(?Subject, ?Property, ?Object) is nondet.
%   A triple true in the question scope "now" (kb_call/1 of the goal).
triple(S, P, O) :- kb_query:kb_call(triple(S, P, O)).

%!  kb_iri(+Term, -IRI) is det.
%   `prefix:'Local'` as the full IRI atom; anything else unchanged.
kb_iri(T, T) :- var(T), !.
kb_iri(Prefix:Local, IRI) :-
    atom(Prefix), atom(Local), !,
    rdf_global_id(Prefix:Local, IRI).
kb_iri(T, T).

%!  iri_term(@Term) is semidet.
%   Term names a resource: an atomic value or `prefix:'Local'`.
iri_term(T) :- atomic(T), !.
iri_term(P:L) :- atom(P), atom(L).

%!  triple_steps(+S, +P, +O, +Scope, -Steps, ?Tail) is det.
%   The compiler steps of a triple goal: a `pattern(t(S,P,X), Scope)` and the
%   `call(value_test(...))` filters its value operator needs, as a difference list.
triple_steps(Su, P, O, Scope, S0, S) :-
    subject_steps(Su, X0, S0, S1),
    (   modified_property(P)
    ->  S1 = [call(kb_triple:modified_triple(X0, P, X, Scope))|S2]
    ;   ground(t(Su, P, O)), \+ operator_value(O)
    ->  S1 = [once_pattern(t(X0, P, X), Scope)|S2]
    ;   S1 = [pattern(t(X0, P, X), Scope)|S2]
    ),
    value_filter(O, X, S2, S3),
    subject_filter(Su, X0, S3, S).

%   A subject operator: in(List) enumerates the members (each then a bound subject); the
%   others filter the subject afterwards; `Op->V` binds V to the subject.
subject_steps(Su, X, [call(kb_triple:member_iri(X, L))|S], S) :-
    nonvar(Su), subject_in(Su, L), !.
subject_steps(Su, _Fresh, S, S) :-
    nonvar(Su), operator_value(Su), !.
subject_steps(Su, Su, S, S).

subject_in(in(L), L).
subject_in((in(L) -> _), L).

subject_filter(Su, X, S0, S) :-
    nonvar(Su), subject_in(Su, _), !,
    (   Su = (_ -> V) -> S0 = [call(V = X)|S] ; S0 = S ).
subject_filter(Su, X, S0, S) :-
    nonvar(Su), operator_value(Su), !,
    value_filter(Su, X, S0, S).
subject_filter(_, _, S, S).

%!  member_iri(-X, +List) is nondet.
member_iri(X, L0) :-
    untyped(L0, L),
    must_be(list, L),
    member(X0, L),
    untyped(X0, X1),
    kb_iri(X1, X).

%   KnowRob's typed values (`array(List)`, `string(X)`, `double(X)`, ...) as plain values.
untyped(V, V) :- var(V), !.
untyped(T, V) :-
    compound(T), T =.. [F, V0], memberchk(F, [array, string, atom, double, float, int, integer, number]), !,
    untyped(V0, V).
untyped(V, V).

operator_value(V) :- compound(V), V = (_ -> _), !.
operator_value(V) :-
    compound(V), V =.. [Op, _],
    memberchk(Op, [<, =<, >, >=, in, nin, regex, =]).

modified_property(P) :-
    compound(P), P =.. [M, _],
    memberchk(M, [transitive, reflexive, include_parents]).

value_filter(O, cmp(Op, Arg, V), S, S) :-
    nonvar(O), O = (C -> V), var(V), store_comparison(C, Op, Arg), !.
value_filter(O, X, S0, S) :-
    nonvar(O), O = (Op -> V), !,
    value_filter(Op, X, S0, [call(V = X)|S]).
value_filter(O, cmp(Op, Arg, _), S, S) :-
    store_comparison(O, Op, Arg), !.
value_filter(O, X, [call(X = V)|S], S) :-
    nonvar(O), O = =(V), var(V), !.
value_filter(O, X, [call(kb_triple:term_value(T, X))|S], S) :-
    nonvar(O), O = term(T), !.
value_filter(O, X, [call(kb_triple:value_test(Op, Arg, X))|S], S) :-
    nonvar(O), O =.. [Op, Arg],
    memberchk(Op, [<, =<, >, >=, in, nin, regex, =]), !.
value_filter(O, O, S, S).

store_comparison(O, Op, Arg) :-
    nonvar(O), O =.. [Op, Arg],
    memberchk(Op, [<, =<, >, >=]), number(Arg).

%!  value_test(+Op, +Arg, +Value) is semidet.
%   Value passes the operator Op with argument Arg (`in`/`nin` take a list of IRIs or
%   values, `regex` a PCRE pattern matched anywhere in the value's text).
value_test(<, A, X) :- number(X), X < A.
value_test(=<, A, X) :- number(X), X =< A.
value_test(>, A, X) :- number(X), X > A.
value_test(>=, A, X) :- number(X), X >= A.
value_test(in, L, X) :- member_iri(Y, L), Y == X, !.
value_test(nin, L, X) :- \+ value_test(in, L, X).
value_test(=, A0, X) :-
    untyped(A0, A1), kb_iri(A1, A),
    (   number(A), number(X) -> X =:= A ; X == A ).
value_test(regex, Pattern, X) :-
    atomic(X), atom_string(X, Text), text_to_string(Pattern, Re),
    re_match(Re, Text).

                 /*******************************
                 *      PROPERTY MODIFIERS      *
                 *******************************/

%!  modified_triple(?S, +Property, ?O, +Scope) is nondet.
%   triple/3 with a modified property (see the module comment). Each object once.
modified_triple(S0, PM, O0, Scope) :-
    modifiers(PM, Mods, P0),
    kb_iri(P0, P), kb_iri(S0, S), kb_iri(O0, O),
    must_be(atom, P),
    (   memberchk(include_parents, Mods)
    ->  parents_triple(S, P, O, Scope)
    ;   memberchk(transitive, Mods)
    ->  (   nonvar(S)
        ->  reach(S, P, forward, Mods, Scope, O)
        ;   nonvar(O)
        ->  reach(O, P, backward, Mods, Scope, S)
        ;   distinct(S, store_match([t(S, P, _)], Scope)),
            reach(S, P, forward, Mods, Scope, O)
        )
    ;   memberchk(reflexive, Mods)
    ->  (   nonvar(S) -> ( O = S ; store_match([t(S, P, O)], Scope), O \== S )
        ;   nonvar(O) -> ( S = O ; store_match([t(S, P, O)], Scope), S \== O )
        ;   distinct(S-O, ( store_match([t(S, P, O1)], Scope), ( O = S ; O = O1 ) ))
        )
    ).

modifiers(PM, [M|Ms], P) :-
    compound(PM), PM =.. [M, Inner],
    memberchk(M, [transitive, reflexive, include_parents]), !,
    modifiers(Inner, Ms, P).
modifiers(P, [], P).

%   Everything Start reaches over P (breadth first, nearest first); Start itself first when
%   reflexive.
reach(Start, P, Dir, Mods, Scope, X) :-
    (   memberchk(reflexive, Mods) -> Seen0 = [Start], First = [Start] ; Seen0 = [Start], First = [] ),
    bfs([Start], P, Dir, Scope, Seen0, Found),
    append(First, Found, All),
    member(X, All).

bfs([], _, _, _, _, []).
bfs([N|Queue], P, Dir, Scope, Seen, Found) :-
    findall(M, step(Dir, N, P, M, Scope), Ms0),
    exclude(seen(Seen), Ms0, Ms1),
    dedup(Ms1, Ms),
    append(Seen, Ms, Seen1),
    append(Queue, Ms, Queue1),
    bfs(Queue1, P, Dir, Scope, Seen1, Found0),
    append(Ms, Found0, Found).

step(forward, N, P, M, Scope) :- store_match([t(N, P, M)], Scope), atom(M).
step(backward, N, P, M, Scope) :- store_match([t(M, P, N)], Scope).

seen(Seen, X) :- memberchk(X, Seen).

dedup([], []).
dedup([X|Xs], [X|Ys]) :- exclude(==(X), Xs, Xs1), dedup(Xs1, Ys).

%   include_parents on a taxonomic property: the asserted object and its ancestors.
parents_triple(S, P, O, Scope) :-
    (   store_taxonomic(P)
    ->  (   kb_iri(rdfs:subPropertyOf, P) -> Sub = P   % a property's super-properties
        ;   kb_iri(rdfs:subClassOf, Sub)                % a class's (or a type's) ancestors
        ),
        (   nonvar(O)
        ->  store_match([t(S, P, O)], Scope)
        ;   distinct(S-O, ( store_match([t(S, P, D)], Scope),
                            reach(D, Sub, forward, [reflexive], any, O) ))
        )
    ;   store_match([t(S, P, O)], Scope)
    ).

%!  term_value(?Term, +Stored) is semidet.
%   A `term(T)` value: the stored text read back as a term (KnowRob stores term_to_atom/2).
term_value(T, X) :-
    atom(X),
    catch(term_to_atom(T1, X), _, fail),
    T = T1.

%!  unit_factor(?Unit, ?Factor) is nondet.
%   Unit terms of holds/3 (`m(6.5)`, `cm(X)`): a value in Unit is Factor times the SI unit
%   the store holds (length m, mass kg, time s, angle rad).
unit_factor(m, 1.0).
unit_factor(km, 1000.0).
unit_factor(dm, 0.1).
unit_factor(cm, 0.01).
unit_factor(mm, 0.001).
unit_factor(kg, 1.0).
unit_factor(g, 0.001).
unit_factor(s, 1.0).
unit_factor(ms, 0.001).
unit_factor(min, 60.0).
unit_factor(h, 3600.0).
unit_factor(rad, 1.0).
unit_factor(deg, F) :- F is pi / 180.
