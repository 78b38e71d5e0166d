:- module(kb_db,
    [ load_owl/1,               % +URL
      load_owl/2,               % +URL, +Options
      load_owl/3,               % +URL, +Scope, +ParentGraph
      annotation/3,             % ?Subject, ?Property, ?Value
      has_label/2,              % ?Resource, ?Label
      has_comment/2,            % ?Resource, ?Comment
      drop_graph/1,             % +Graph
      memorize/1,               % +Directory
      remember/1                % +Directory
    ]).
/** <module> Ontology files into the store, and annotations (KnowRob 2.x src/lang/db.pl)

load_owl/1,2 reads an OWL file (RDF/XML, Turtle or N-Triples, by the file's extension)
and writes its statements into the current store as KnowRob's load_owl does: triples with
universal scope (their `p*`/`o*` closures are made by the store), literals by their XSD
type (integers as integers, decimals and doubles as floats, booleans as `true`/`false`,
other values as atoms), and annotation values (rdfs:label, rdfs:comment, rdfs:seeAlso,
owl:versionInfo and any owl:AnnotationProperty) into the annotations collection instead
of the triples, English or untagged ones only. annotation/3, has_label/2 and
has_comment/2 read them back.

    ?- load_owl('ontology/soma-extract.owl').
    ?- load_owl('file:///data/test.ttl', [graph(test)]).

As KnowRob, each file goes into its own named graph (the file's base name without extension,
or `graph(G)`) with a `tripledbVersionString` marker holding the file's version (its
modification time, KnowRob's file_version/2). A file whose version the graph already records
is not loaded again; a changed one replaces its graph (KnowRob's drop_graph/1, then the load).
The NEEMs logged with `--soma DIR` carry the same markers, so loading the same file here, or
in KnowRob, finds it loaded.

A `package://Pkg/Path` URL (a ROS package) is resolved without ROS: through the multifile
hook kb_db:package_path/2, else along the search path `$KNOWROB_PACKAGE_PATH` (folders
separated by `:`; package Pkg is the folder `Dir/Pkg`, or `Dir` itself when it is named
Pkg), as ROS's `$ROS_PACKAGE_PATH`; a package found nowhere is an error naming the URL.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(option)).
% The RDF parsers (~60 ms to load) are needed only when an OWL file is loaded: on first use.
:- autoload(library(semweb/rdf_db), [rdf_load/2, rdf/4, rdf_unload_graph/1]).
:- use_module('../neem_store', [store_insert/3, store_backend/1]).
:- use_module('../store/graph', [store_graph_version/2, store_set_graph_version/3, store_drop_graph/1]).
:- use_module('../store/annotations', [store_insert_annotations/1, store_annotation/3]).
:- use_module('../store/python', [store_python_call/3]).
:- use_module(triple, [kb_iri/2]).
:- use_module(subgraph, [add_subgraph/2]).
:- use_module(owl_guard, [owl_file_safe/1]).

%!  drop_graph(+Graph) is det.
%   KnowRob's drop_graph/1: delete every fact of named graph Graph (`user`: everything
%   asserted at run time) from the current NEEM.
drop_graph(Graph) :-
    must_be(atom, Graph),
    store_drop_graph(Graph).

%!  memorize(+Directory) is det.
%   KnowRob's memorize/1: the current NEEM as a mongodump folder in Directory (triples/,
%   annotations/, tf/, inferred/, plus the registry entry), which remember/1, `oracle load`
%   and KnowRob's remember/1 read. Only a NEEM of a store can be memorized.
memorize(Dir) :-
    dump_request(memorize, Dir).

%!  remember(+Directory) is det.
%   KnowRob's remember/1: add the documents of the NEEM dump in Directory to the current NEEM
%   (as mongorestore adds them to the current collections: what is stored stays, a document
%   stored already is not added twice).
remember(Dir) :-
    dump_request(remember, Dir).

dump_request(Action, Dir0) :-
    must_be(atomic, Dir0),
    atom_string(Dir, Dir0),
    (   store_backend(python(Neem))
    ->  store_python_call(dump, [Action, Neem, Dir], _)
    ;   throw(error(existence_error(neem, Action), context(Action/1, 'the memory backend holds no NEEM to dump')))
    ).

%!  package_path(+Package, -Directory) is semidet.
%   Where a ROS package's files are (multifile and dynamic: a ROS set-up adds its packages).
:- multifile package_path/2.
:- dynamic package_path/2.

%!  load_owl(+URL) is det.
%!  load_owl(+URL, +Options) is det.
%   Put the statements of the OWL file at URL (a path, `file://...` or `package://...`) into
%   the store, in the named graph of the file unless that graph records the file's version
%   already. Options: `graph(G)` names the graph (as KnowRob's load_owl/3 with a ground graph);
%   `parent_graph(P)` puts the graph below P in the graph hierarchy (default `common`, as
%   KnowRob: a query in the graph also reads P; kb_subgraph), loaded or not.
load_owl(URL) :-
    load_owl(URL, []).
load_owl(URL, Options) :-
    must_be(list, Options),
    owl_file(URL, File),
    owl_file_safe(File),        % a regular file, its XML entities bounded (rdf_load bounds none)
    file_base_name(File, Base),
    file_name_extension(Name, _, Base),
    option(graph(OntoGraph), Options, Name),
    must_be(atom, OntoGraph),
    option(parent_graph(Parent), Options, common),
    must_be(atom, Parent),
    file_version(File, Stamp),
    (   store_graph_version(OntoGraph, Recorded),
        catch(atom_number(Recorded, Stamp), _, fail)
    ->  true                    % unchanged since it was loaded (KnowRob: ontology_detected)
    ;   store_drop_graph(OntoGraph),
        gensym(kb_db_load_, Graph),
        use_module(library(semweb/turtle), []),   % rdf_load/2 then reads Turtle files too
        setup_call_cleanup(
            rdf_load(File, [graph(Graph), silent(true)]),
            load_graph(Graph, OntoGraph, File, Stamp),
            rdf_unload_graph(Graph))
    ),
    add_subgraph(OntoGraph, Parent).

%!  load_owl(+URL, +Scope, +ParentGraph) is det.
%   KnowRob's load_owl/3: the file into its own graph, below ParentGraph; Scope is checked
%   (ontology statements are universal here, as in every NEEM).
load_owl(URL, Scope, Parent) :-
    must_be(nonvar, Scope),
    load_owl(URL, [parent_graph(Parent)]).

%   A package's folder: the hook, else the search path of $KNOWROB_PACKAGE_PATH.
package_dir(Pkg, Dir) :-
    package_path(Pkg, Dir), !.
package_dir(Pkg, Dir) :-
    getenv('KNOWROB_PACKAGE_PATH', Path),
    atomic_list_concat(Dirs, ':', Path),
    member(D, Dirs), D \== '',
    (   file_base_name(D, Pkg), exists_directory(D) -> Dir = D
    ;   atomic_list_concat([D, '/', Pkg], Dir), exists_directory(Dir)
    ), !.

%   KnowRob's file_version/2 of a local file: its modification time (the number KnowRob
%   compares a graph's recorded version with, after reading that version as a number).
file_version(File, Stamp) :-
    set_time_file(File, [modified(Stamp)], []).

owl_file(URL, _) :-
    var(URL), !,
    instantiation_error(URL).
owl_file(URL, File) :-
    text_to_string(URL, S),
    (   string_concat("package://", Rest, S)
    ->  (   sub_string(Rest, B, _, A, "/"), !,
            sub_string(Rest, 0, B, _, Pkg), sub_string(Rest, _, A, 0, Path),
            atom_string(PkgA, Pkg), package_dir(PkgA, Dir)
        ->  atomic_list_concat([Dir, '/', Path], File0)
        ;   domain_error(ros_package_url, URL)
        )
    ;   string_concat("file://", Path, S)
    ->  atom_string(File0, Path)
    ;   atom_string(File0, S)
    ),
    (   exists_file(File0)
    ->  File = File0
    ;   existence_error(owl_file, URL)
    ).

load_graph(Graph, OntoGraph, File, Stamp) :-
    findall(S-P-O, rdf(S, P, O, Graph), Statements),
    foldl(statement, Statements, []-[], Ts-As),
    Inf is inf,
    findall(triple(S, P, O, 0.0, Inf), member(t(S, P, O), Ts), Triples0),
    reverse(Triples0, Triples),
    reverse(As, Annotations),
    store_insert(Triples, union, OntoGraph),
    store_insert_annotations(Annotations),
    (   rdf(Ontology, 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type',
            'http://www.w3.org/2002/07/owl#Ontology', Graph)
    ->  true
    ;   atom_concat('file://', File, Ontology)  % KnowRob refuses a file without one
    ),
    atom_number(Version, Stamp),
    store_set_graph_version(Ontology, Version, OntoGraph).

%   A statement as a triple t(S,P,O) or an annotation(S,P,V), or dropped (non-English
%   annotation values, as KnowRob).
statement(S-P-O, Ts-As, Ts1-As1) :-
    (   annotation_property(P, O)
    ->  Ts1 = Ts,
        (   annotation_value(O, V) -> As1 = [annotation(S, P, V)|As] ; As1 = As )
    ;   value(O, V),
        Ts1 = [t(S, P, V)|Ts], As1 = As
    ).

annotation_property(P, _) :-
    memberchk(P, ['http://www.w3.org/2000/01/rdf-schema#label',
                  'http://www.w3.org/2000/01/rdf-schema#comment',
                  'http://www.w3.org/2000/01/rdf-schema#seeAlso',
                  'http://www.w3.org/2002/07/owl#versionInfo']), !.
annotation_property(P, _) :-
    rdf(P, 'http://www.w3.org/1999/02/22-rdf-syntax-ns#type',
        'http://www.w3.org/2002/07/owl#AnnotationProperty', _), !.

annotation_value(literal(lang(L, V)), V) :- !, memberchk(L, [en, 'en-US', 'en-GB']).
annotation_value(literal(type(_, V)), V) :- !.
annotation_value(literal(V), V) :- !.
annotation_value(IRI, IRI).

%   An RDF object as the store's value.
value(literal(type(Type, Lex)), V) :- !, typed_value(Type, Lex, V).
value(literal(lang(_, V)), V) :- !.
value(literal(V), V) :- !.
value(V, V).

typed_value(Type, Lex, V) :-
    atom_concat('http://www.w3.org/2001/XMLSchema#', Local, Type),
    xsd_kind(Local, Kind),
    catch(convert(Kind, Lex, V), _, fail), !.
typed_value(_, Lex, Lex).

xsd_kind(L, integer) :-
    memberchk(L, [integer, int, long, short, byte, nonNegativeInteger, positiveInteger,
                  nonPositiveInteger, negativeInteger, unsignedInt, unsignedLong,
                  unsignedShort, unsignedByte]), !.
xsd_kind(L, float) :- memberchk(L, [decimal, double, float]), !.
xsd_kind(boolean, boolean).

convert(integer, Lex, V) :- atom_number(Lex, N), V is integer(N).
convert(float, Lex, V) :- atom_number(Lex, N), V is float(N).
convert(boolean, Lex, V) :- ( memberchk(Lex, [true, '1']) -> V = true ; V = false ).

%!  annotation(?Subject, ?Property, ?Value) is nondet.
%   An annotation value of Subject (labels, comments, ...), from the annotations collection.
annotation(S0, P0, V) :-
    kb_iri(S0, S), kb_iri(P0, P),
    store_annotation(S, P, V).

%!  has_label(?Resource, ?Label) is nondet.
has_label(R, L) :- annotation(R, rdfs:label, L).

%!  has_comment(?Resource, ?Comment) is nondet.
has_comment(R, C) :- annotation(R, rdfs:comment, C).
