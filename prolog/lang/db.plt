:- begin_tests(kb_db).

:- use_module(db).
:- use_module(query).
:- use_module('../neem_store').

fixture(Name, File) :-
    module_property(kb_db, file(Here)), file_directory_name(Here, Dir),
    atomic_list_concat([Dir, '/../fixtures/knowrob_2x/', Name, '.ttl'], File).

d(L, I) :- atom_concat('http://knowrob.org/kb/datatype_test#', L, I).
f(L, I) :- atom_concat('http://knowrob.org/kb/swrl_test#', L, I).

test(typed_literals, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    fixture(lecturers, F), load_owl(F),
    d('Lecturer1', L), d(studentId, Id), d(height, H), d(last_name, N),
    kb_call(triple(L, Id, X)), X == 1001,
    kb_call(triple(L, H, Y)), float(Y), Y =:= 1.65,
    kb_call(triple(L, N, Z)), Z == 'Byron'.

test(annotations_apart_from_triples, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    fixture(family, F), load_owl(F, [graph(test)]),
    f('Adult', A),
    has_label(A, Label), Label == adult,
    \+ kb_call(triple(A, rdfs:label, _)),
    findall(C, has_comment('http://knowrob.org/kb/swrl_test', C), [_]).

test(file_url, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    fixture(events, F), atom_concat('file://', F, URL),
    load_owl(URL),
    kb_call(triple('http://knowrob.org/kb/test_events.owl#Long', dul:hasTimeInterval, _)).

test(missing_file_changes_nothing, [setup(store_reset), cleanup(store_reset),
                                    error(existence_error(owl_file, 'no/such.owl'))]) :-
    load_owl('no/such.owl').

test(package_url_without_ros, [setup(store_reset), cleanup(store_reset),
                               error(domain_error(ros_package_url, _))]) :-
    load_owl('package://knowrob/owl/test/swrl.owl').

test(package_url_through_the_hook, [nondet, setup(store_reset),
                                    cleanup((store_reset, retractall(kb_db:package_path(mine, _))))]) :-
    fixture(family, F), file_directory_name(F, Dir),
    assertz(kb_db:package_path(mine, Dir)),
    load_owl('package://mine/family.ttl'),
    f('Rex', R), f('Man', M),
    kb_call(triple(R, rdf:type, M)).

:- end_tests(kb_db).
