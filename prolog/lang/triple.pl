:- module(kb_triple,
    [ triple/3,                 % ?Subject, ?Property, ?Object
      kb_iri/2,                 % +Term, -IRI
      iri_term/1,               % @Term
      triple_steps/6,           % +S, +P, +O, +Scope, -Steps, ?Tail
      value_test/3              % +Operator, +Argument, +Value
    ]).
/** <module> triple/3: KnowRob 2.x's triple goal (src/lang/terms/triple.pl)

`triple(S, P, O)` asks the store for a triple with KnowRob's `p*`/`o*` semantics (see
neem_store). This module owns what a triple goal may say and how it becomes a store
pattern: IRIs written `prefix:'Local'` for the registered prefixes (rdf, rdfs, owl, xsd,
dul, soma, knowrob, odb), and the value operators of the object `<(V)`, `=<(V)`, `>(V)`,
`>=(V)`, `in(List)`, `nin(List)`, `regex(Pattern)` and `Op->Var` (the actual value back).
A comparison with a number known when the goal is compiled is evaluated by the store;
the other operators filter the solutions afterwards.

The compiler (kb_query) calls triple_steps/6 for every triple and holds goal; triple/3
called from Prolog is `kb_call(triple(S,P,O))`.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pcre), []).
:- use_module(library(semweb/rdf_prefixes)).

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
triple_steps(Su, P, O, Scope, [pattern(t(Su, P, X), Scope)|S0], S) :-
    value_filter(O, X, S0, S).

value_filter(O, cmp(Op, Arg, V), S, S) :-
    nonvar(O), O = (C -> V), var(V), store_comparison(C, Op, Arg), !.
value_filter(O, X, S0, S) :-
    nonvar(O), O = (Op -> V), !,
    value_filter(Op, X, S0, [call(V = X)|S]).
value_filter(O, cmp(Op, Arg, _), S, S) :-
    store_comparison(O, Op, Arg), !.
value_filter(O, X, [call(kb_triple:value_test(Op, Arg, X))|S], S) :-
    nonvar(O), O =.. [Op, Arg],
    memberchk(Op, [<, =<, >, >=, in, nin, regex]), !.
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
value_test(in, L, X) :- must_be(list, L), maplist(kb_iri, L, L1), memberchk(X, L1).
value_test(nin, L, X) :- must_be(list, L), maplist(kb_iri, L, L1), \+ memberchk(X, L1).
value_test(regex, Pattern, X) :-
    atomic(X), atom_string(X, Text), text_to_string(Pattern, Re),
    pcre:re_match(Re, Text).
