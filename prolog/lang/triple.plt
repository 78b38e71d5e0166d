:- begin_tests(kb_triple).

:- use_module(triple).
:- use_module(query).
:- use_module('../neem_store').
:- use_module('../fixtures/test_episode').

n(L, I) :- atom_concat('http://example.org/neem#', L, I).

test(value_operators, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    findall(I, triple(I, soma:hasIntervalBegin, >=(200)), Is), length(Is, 3),
    findall(V, triple(_, soma:hasIntervalBegin, <(101)->V), Vs), msort(Vs, [100, 100]),
    n(a1_ti, I1), n(a3_ti, I3),
    findall(I, triple(I, soma:hasIntervalBegin, in([101, 201])), Both), msort(Both, [I1, I3]),
    findall(S, triple(S, rdf:type, regex('neem#(apple|thermos)')), Objs), length(Objs, 0),
    findall(S, triple(S, soma:hasIntervalBegin, regex('^10')), _).

test(kb_iri) :-
    kb_iri(dul:'Action', I), I == 'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#Action',
    kb_iri(plain, P), P == plain.

test(store_comparison_compiles_to_pattern) :-
    triple_steps(s, p, >=(5), any, Steps, []),
    Steps = [pattern(t(s, p, cmp(>=, 5, _)), any)].

e(L, I) :- atom_concat('http://e.org/fam#', L, I).

family :-
    store_reset,
    maplist(e, [ann, bob, cid, dan, eve, parentOf], [Ann, Bob, Cid, Dan, Eve, P]),
    store_assert(triple(Ann, P, Bob)), store_assert(triple(Ann, P, Cid)),
    store_assert(triple(Bob, P, Dan)), store_assert(triple(Dan, P, Eve)),
    store_assert(triple(Eve, 'http://e.org/fam#age', 7)),
    store_assert(triple(Dan, 'http://e.org/fam#age', 35)),
    store_assert(triple(Dan, 'http://e.org/fam#age', 35), 0.0, 10.0).

test(equals_operator, [nondet, setup(family), cleanup(store_reset)]) :-
    e(eve, Eve), e(age, Age),
    triple(Eve, Age, =(7)), triple(Eve, Age, =(7.0)), \+ triple(Eve, Age, =(8)),
    triple(Eve, Age, =(X)), X == 7.

test(subject_in, [nondet, setup(family), cleanup(store_reset)]) :-
    maplist(e, [bob, dan, eve, parentOf], [Bob, Dan, Eve, P]),
    findall(S-O, triple(in([Bob, Eve]) -> S, P, O), Rows), Rows == [Bob-Dan],
    findall(O, triple(in([Bob, Dan]), P, O), Os), Os == [Dan, Eve].

test(ground_goal_once, [setup(family), cleanup(store_reset)]) :-
    maplist(e, [dan, age], [Dan, Age]),
    findall(x, kb_call(triple(Dan, Age, 35), any), L), L == [x],
    findall(x, kb_call(triple(Dan, Age, _), any), L2), length(L2, 2).

test(transitive_forward, [nondet, setup(family), cleanup(store_reset)]) :-
    maplist(e, [ann, bob, cid, dan, eve, parentOf], [Ann, Bob, Cid, Dan, Eve, P]),
    findall(X, triple(Ann, transitive(P), X), Xs), Xs == [Bob, Cid, Dan, Eve],
    triple(Ann, transitive(P), Eve),
    \+ triple(Bob, transitive(P), Cid).

test(transitive_backward, [setup(family), cleanup(store_reset)]) :-
    maplist(e, [ann, bob, dan, eve, parentOf], [Ann, Bob, Dan, Eve, P]),
    findall(X, triple(X, transitive(P), Eve), Xs), Xs == [Dan, Bob, Ann].

test(reflexive_transitive, [setup(family), cleanup(store_reset)]) :-
    maplist(e, [bob, dan, eve, parentOf], [Bob, Dan, Eve, P]),
    findall(X, triple(Bob, transitive(reflexive(P)), X), Xs), Xs == [Bob, Dan, Eve],
    findall(X, triple(Bob, reflexive(P), X), Ys), Ys == [Bob, Dan].

test(include_parents, [nondet, setup(load_test_episode), cleanup(store_reset)]) :-
    n(pick1, T),
    findall(C, triple(T, include_parents(rdf:type), C), Cs),
    kb_iri(odb:pick, Pick), kb_iri(soma:'PickingUp', PU), kb_iri(dul:'Task', Task),
    subset([Pick, PU, Task], Cs),
    findall(C, triple(T, rdf:type, C), Direct), \+ memberchk(Task, Direct).

test(include_parents_of_a_property, [nondet, cleanup(store_reset)]) :-
    store_reset,
    kb_project(( subproperty_of(hasBrother, hasSibling), subproperty_of(hasSibling, hasRelative),
                 subclass_of(hasSibling, notAProperty) )),
    findall(Q, triple(hasBrother, include_parents(rdfs:subPropertyOf), Q), Qs),
    msort(Qs, [hasRelative, hasSibling]).

:- end_tests(kb_triple).
