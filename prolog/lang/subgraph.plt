:- begin_tests(kb_subgraph).

:- use_module(subgraph).
:- use_module(query).
:- use_module(db).
:- use_module('../neem_store').
:- use_module(triple, [kb_iri/2]).
:- use_module('../model/rdfs').

reset :- store_reset, subgraph_reset.

%   A: a NEEM's narrative in user, SOMA importing DUL, an unrelated graph odb.
soma_world :-
    reset,
    kb_project(triple(act, rdf:type, dul:'Action')),
    kb_project(triple(soma:'Pouring', rdfs:subClassOf, dul:'Action'), dict{}, [graph('SOMA')]),
    kb_project(triple('http://www.ease-crc.org/ont/SOMA.owl', owl:imports,
                      'http://www.ontologydesignpatterns.org/ont/dul/DUL.owl'), dict{}, [graph('SOMA')]),
    kb_project(triple(dul:'Action', rdfs:subClassOf, dul:'Event'), dict{}, [graph('DUL')]),
    kb_project(triple(odb:pour, rdfs:subClassOf, soma:'Pouring'), dict{}, [graph(odb)]),
    kb_project(triple(top, p, v), dict{}, [graph(common)]).

subjects(G, Ss) :-
    findall(S, kb_call(triple(S, _, _), dict{}, _, [graph(G)]), Ss0),
    msort(Ss0, Ss).

test(supgraphs_follow_imports_and_common, [nondet, setup(soma_world), cleanup(reset)]) :-
    get_supgraphs('SOMA', Gs), Gs == ['SOMA', common, 'DUL'],
    get_supgraphs(odb, [odb, common]),
    get_supgraphs(nothing_here, [nothing_here]).

test(graph_reads_itself_and_above, [nondet, setup(soma_world), cleanup(reset)]) :-
    kb_iri(soma:'Pouring', P), kb_iri(dul:'Action', A),
    kb_iri(odb:pour, O),
    S = 'http://www.ease-crc.org/ont/SOMA.owl',
    subjects('SOMA', L1), msort([P, S, A, top], L1),
    subjects('DUL', L2), msort([A, top], L2),
    subjects(odb, L3), msort([O, top], L3),
    subjects(=('SOMA'), L4), msort([P, S], L4).

test(user_and_test_read_everything, [nondet, setup(soma_world), cleanup(reset)]) :-
    subjects(user, L), length(L, 6),
    subjects(test, L), subjects('*', L).

test(unknown_graph_is_empty_not_an_error, [nondet, setup(soma_world), cleanup(reset)]) :-
    subjects(nothing_here, []),
    \+ kb_call(has_type(_, _), dict{}, _, [graph(nothing_here)]).

test(model_predicates_in_a_graph, [nondet, setup(soma_world), cleanup(reset)]) :-
    % the NEEM's action is in user only
    \+ kb_call(has_type(act, dul:'Action'), dict{}, _, [graph('SOMA')]),
    kb_call(has_type(act, dul:'Action'), dict{}, _, [graph(user)]),
    % a document read in a graph brings its o* closure (computed over the whole store, as
    % KnowRob's); SOMA's own axiom is not among odb's documents
    kb_iri(odb:pour, O), kb_iri(soma:'Pouring', P), kb_iri(dul:'Event', E),
    kb_call(subclass_of(O, E), dict{}, _, [graph(odb)]),
    \+ kb_call(subclass_of(P, E), dict{}, _, [graph(odb)]),
    kb_call(subclass_of(P, E), dict{}, _, [graph('SOMA')]).

test(add_subgraph_links_graphs, [nondet, setup(soma_world), cleanup(reset)]) :-
    add_subgraph(odb, 'SOMA'),
    get_supgraphs(odb, Gs), msort(Gs, ['DUL', 'SOMA', common, odb]),
    kb_iri(soma:'Pouring', P), kb_iri(dul:'Event', E),
    kb_call(subclass_of(P, E), dict{}, _, [graph(odb)]).

test(load_owl_parent_graph, [nondet, setup(reset), cleanup(reset)]) :-
    tmp_file_stream(text, File0, Out),
    format(Out, "<http://e.org/a> <http://e.org/p> <http://e.org/b> .~n", []),
    close(Out),
    atom_concat(File0, '.ttl', File), rename_file(File0, File),
    kb_project(triple(x, p, y), dict{}, [graph(parent)]),
    load_owl(File, [graph(child), parent_graph(parent)]),
    get_supgraphs(child, Gs), memberchk(parent, Gs),
    findall(S, kb_call(triple(S, _, _), dict{}, _, [graph(child)]), Ss), msort(Ss, ['http://e.org/a', x]),
    delete_file(File).

test(bad_graph_list, [error(domain_error(non_empty_graph_list, []))]) :-
    store_in_graphs([], true).

test(subgraphs, [cleanup(subgraph_reset)]) :-
    subgraph_reset,
    add_subgraph(g1, common), add_subgraph(g2, g1),
    get_subgraphs(g1, Gs), msort(Gs, [string(g1), string(g2)]),
    get_subgraphs(common, Cs), memberchk(string(user), Cs), memberchk(string(g2), Cs),
    load_graph_structure.

:- end_tests(kb_subgraph).
