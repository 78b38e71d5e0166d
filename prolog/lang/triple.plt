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

:- end_tests(kb_triple).
