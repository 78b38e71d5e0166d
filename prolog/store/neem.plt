:- begin_tests(store_neem).

:- use_module(neem).

% A memory fact of this test, named to store_reset/0 as the store's modules name theirs.
:- dynamic user:neem_scratch/1.
:- multifile store_neem:memory_facts/1.
store_neem:memory_facts(user:neem_scratch(_)).

% A stand-in for the bridge's py_match/2, made at run time: a clause asserting it written
% in this file would declare it at load time, and store_use_python/1 would find it.
stub_match :-
    Head =.. [py_match, _, "r(d,[])"],
    assertz(store_python:Head).

unstub_match :-
    abolish(store_python:py_match/2),
    store_use_memory.

test(memory_is_the_default) :-
    store_backend(B), B == memory,
    store_current_neem(N), N == memory.

test(python_needs_the_foreign_predicates,
     [error(existence_error(foreign_predicate, store_python:py_match/2))]) :-
    store_use_python(n1).

test(without_them_the_backend_stays) :-
    catch(store_use_python(n1), error(existence_error(_, _), _), true),
    store_backend(memory).

test(python_backend_names_its_neem, [cleanup(unstub_match)]) :-
    stub_match,
    store_use_python(n1),
    store_backend(B), B == python(n1),
    store_current_neem(N), N == n1,
    store_use_memory,
    store_current_neem(M), M == memory.

test(neem_id_is_an_atom, [error(type_error(atom, "n1"))]) :-
    store_use_python("n1").

test(reset_wipes_the_memory_facts_and_goes_back_to_memory,
     [cleanup(unstub_match)]) :-
    assertz(user:neem_scratch(1)),
    stub_match,
    store_use_python(n1),
    store_reset,
    \+ user:neem_scratch(_),
    store_backend(memory).

:- end_tests(store_neem).
