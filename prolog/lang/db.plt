:- begin_tests(kb_db).

:- use_module(db).
:- use_module(query).
:- use_module('../neem_store').
:- use_module('../store/graph').

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

% A copy of a fixture in a temporary file, so its modification time can be changed.
fixture_copy(Name, Copy) :-
    fixture(Name, F),
    tmp_file(kb_db, Tmp), atom_concat(Tmp, '.ttl', Copy),
    copy_file(F, Copy).

test(version_marker_of_the_file, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    fixture_copy(family, F),
    load_owl(F),
    file_base_name(F, B), file_name_extension(G, _, B),
    store_graph_version(G, V),
    set_time_file(F, [modified(T)], []),
    atom_number(V, T),                           % KnowRob's comparison
    delete_file(F).

test(an_unchanged_file_is_not_loaded_again, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    fixture_copy(family, F),
    load_owl(F),
    f('Rex', R), f('Man', M),
    kb_unproject(triple(R, rdf:type, M)),
    load_owl(F),                                 % same version: nothing is loaded
    \+ kb_call(triple(R, rdf:type, M)),
    set_time_file(F, [], [modified(1000000000)]),
    load_owl(F),                                 % changed: loaded again, new marker
    kb_call(triple(R, rdf:type, M)),
    file_base_name(F, B), file_name_extension(G, _, B),
    store_graph_version(G, V), atom_number(V, 1000000000.0),
    delete_file(F).

test(graph_option_names_the_graph, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    fixture_copy(family, F),
    load_owl(F, [graph(test)]),
    store_graph_version(test, _),
    delete_file(F).

:- end_tests(kb_db).
