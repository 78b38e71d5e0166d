:- begin_tests(neem_interface_compat).

:- use_module(neem_interface).
:- use_module('../neem_store').
:- use_module('../lang/query').
:- use_module('../model/situation').
:- use_module('../model/object').

test(library_client_is_found, [nondet]) :-
    absolute_file_name(library('db/mongo/client'), F, [file_type(prolog), access(read)]),
    sub_atom(F, _, _, _, 'compat/library/db/mongo/client').

test(new_iri_in_a_projection_list, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project([new_iri(E, soma:'Episode'), is_episode(E)]),
    atom(E), sub_atom(E, 0, _, _, 'http://www.ease-crc.org/ont/SOMA.owl#Episode_'),
    is_episode(E).

test(an_unbound_typed_individual_is_named, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project([has_type(R, soma:'Patient'), has_role(cup, R)]),
    atom(R), has_role(cup, R1), R1 == R.

:- end_tests(neem_interface_compat).
