:- module(kb_subgraph,
    [ add_subgraph/2,           % +Sub, +Sup
      get_supgraphs/2,          % +Graph, -Graphs
      graph_filter/2,           % +GraphOption, -Filter
      subgraph_reset/0,
      get_subgraphs/2,          % +Graph, -Graphs
      load_graph_structure/0
    ]).
/** <module> The sub-graph hierarchy of named graphs (KnowRob 2.x src/lang/subgraph.pl)

Every document of the store names its graph: `user` for kb_project, an ontology's own graph
for load_owl and `--soma` imports (`DUL`, `SOMA`, `SOMA-HOME`, `odb`). A query with the
option `graph(G)` reads G and the graphs above it, as KnowRob filters its `graph` field with
`$in` G's super-graphs:

    ?- kb_call(subclass_of(C, dul:'Object'), dict{}, _, [graph('SOMA')]).

The hierarchy is KnowRob's: `user` is below `common` and below every graph the store holds,
every stored graph other than `user` is below `common`, a graph is below the graphs its
ontology imports (`owl:imports` statements in it, the imported file's base name) and below
the `parent_graph` load_owl gave it (default `common`); `test` is below `user`. So
`graph(user)` (the default) sees every graph, `graph('SOMA')` sees SOMA, DUL and `common`
but no NEEM narrative, and a graph nothing is stored in sees nothing (an empty answer, no
error, as KnowRob). The store's part of the hierarchy is read when a query asks for it; the
edges load_owl adds live in this process, as KnowRob's.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module('../neem_store', [store_in_graphs/2, store_match/3]).
:- use_module('../store/graph', [store_graph_version/2]).

:- dynamic subgraph_of_/2.      % Sub, Sup: asserted edges (load_owl's parent_graph, ...)

%!  add_subgraph(+Sub, +Sup) is det.
%   Record that named graph Sub is below Sup: a query in Sub also reads Sup.
add_subgraph(Sub, Sup) :-
    must_be(atom, Sub), must_be(atom, Sup),
    (   subgraph_of_(Sub, Sup) -> true ; assertz(subgraph_of_(Sub, Sup)) ).

%!  subgraph_reset is det.
%   Forget the edges add_subgraph/2 recorded (back to KnowRob's initial `user` below
%   `common`, `test` below `user`).
subgraph_reset :-
    retractall(subgraph_of_(_, _)),
    assertz(subgraph_of_(user, common)),
    assertz(subgraph_of_(test, user)).

:- initialization(subgraph_reset).

%!  get_supgraphs(+Graph, -Graphs) is det.
%   Graphs is Graph followed by every graph above it (transitively).
get_supgraphs(G, Graphs) :-
    must_be(atom, G),
    closure([G], [G], Rev),
    reverse(Rev, Graphs).

closure([], Seen, Seen).
closure([G|Gs], Seen0, Seen) :-
    findall(Sup, ( sup_edge(G, Sup), \+ memberchk(Sup, Seen0) ), Sups0),
    list_to_set(Sups0, Sups),
    reverse(Sups, RevSups),
    append(RevSups, Seen0, Seen1),
    append(Gs, Sups, Queue),
    closure(Queue, Seen1, Seen).

%   The graphs directly above G.
sup_edge(G, Sup) :- subgraph_of_(G, Sup).
sup_edge(G, common) :-
    G \== user, G \== common,
    stored_graph(G).
sup_edge(G, Sup) :-
    G \== user,
    findall(I, store_in_graphs([G], store_match([t(_, 'http://www.w3.org/2002/07/owl#imports', I)], any, [])), Is),
    member(I, Is), atom(I),
    ontology_graph(I, Sup).

%   G holds documents (a version marker or a triple).
stored_graph(G) :- store_graph_version(G, _), !.
stored_graph(G) :- store_in_graphs([G], once(store_match([t(_, _, _)], any, [limit(1)]))).

%   KnowRob's graph of an ontology IRI: its base name without the extension.
ontology_graph(IRI, Graph) :-
    file_base_name(IRI, Base),
    file_name_extension(Graph, _, Base),
    Graph \== ''.

%!  graph_filter(+GraphOption, -Filter) is det.
%   The documents a query with option `graph(GraphOption)` reads: `all` for `'*'` and for
%   `user` (it is below every graph), `[G]` for `=(G)` (that graph alone), else the list of
%   G and its super-graphs (`all` when `user` is among them, as for `test`).
graph_filter(G, _) :-
    var(G), !,
    instantiation_error(G).
graph_filter('*', all) :- !.
graph_filter(user, all) :- !.
graph_filter(=(G), [G]) :- !,
    must_be(atom, G).
graph_filter(G, Filter) :-
    must_be(atom, G),
    get_supgraphs(G, Graphs),
    (   memberchk(user, Graphs) -> Filter = all ; Filter = Graphs ).

%!  get_subgraphs(+Graph, -Graphs) is det.
%   Graph and the graphs below it, each as `string(G)` (KnowRob's form), among the graphs the
%   hierarchy names (load_owl/2's graphs, add_subgraph/2's edges, `user`, `test`, `common`).
get_subgraphs(G, Graphs) :-
    must_be(atom, G),
    findall(X, ( subgraph_of_(X, _) ; subgraph_of_(_, X) ), Xs0),
    sort([G|Xs0], Xs),
    findall(string(X), ( member(X, Xs), atom(X), ( X == G -> true ; get_supgraphs(X, Sups), memberchk(G, Sups) ) ), Graphs).

%!  load_graph_structure is det.
%   KnowRob reads the stored graphs into its hierarchy at start-up; here the store's part of
%   the hierarchy is read whenever a query asks for a graph, so there is nothing to load.
load_graph_structure.
