:- module(store_graph,
    [ store_graph_version/2,    % +Graph, -Version
      store_set_graph_version/3, % +Ontology, +Version, +Graph
      store_drop_graph/1        % +Graph
    ]).
/** <module> Named graphs: their version markers, and dropping one

A stored fact belongs to one named graph (KnowRob's `graph` of a document): `user` for what
kb_project/1 asserts, the ontology's name for what load_owl/1 loads. A graph loaded from a
file carries a version marker, so that load_owl/1 loads a file once per version.
*/

:- use_module(library(error)).
:- use_module(neem, [store_backend/1]).
:- use_module(python, [store_python_call/3]).
:- use_module(memory, [store_memory_drop_graph/1]).

:- dynamic mem_version/3.       % Graph, Ontology, Version

:- multifile store_neem:memory_facts/1.
store_neem:memory_facts(store_graph:mem_version(_, _, _)).

%!  store_graph_version(+Graph, -Version) is semidet.
%   Version is the `tripledbVersionString` marker of named graph Graph (KnowRob's
%   get_ontology_version/2): what load_owl compares with the file's version.
store_graph_version(Graph, Version) :-
    must_be(atom, Graph),
    (   store_backend(python(Neem))
    ->  store_python_call(graph, [Neem, get, Graph, '', ''], [[_, Version]|_])
    ;   once(mem_version(Graph, _, Version))
    ).

%!  store_set_graph_version(+Ontology, +Version, +Graph) is det.
%   Record that Graph holds version Version of ontology Ontology (KnowRob's
%   set_ontology_version/3: a document without scope or closures).
store_set_graph_version(Ontology, Version, Graph) :-
    must_be(atom, Ontology), must_be(atomic, Version), must_be(atom, Graph),
    (   store_backend(python(Neem))
    ->  store_python_call(graph, [Neem, set, Graph, Ontology, Version], _)
    ;   assertz(mem_version(Graph, Ontology, Version))
    ).

%!  store_drop_graph(+Graph) is det.
%   Delete every triple of named graph Graph, its version marker with them (KnowRob's
%   drop_graph/1).
store_drop_graph(Graph) :-
    must_be(atom, Graph),
    (   store_backend(python(Neem))
    ->  store_python_call(graph, [Neem, drop, Graph, '', ''], _)
    ;   retractall(mem_version(Graph, _, _)),
        store_memory_drop_graph(Graph)
    ).
