:- module(neem_store,
    [ store_backend/1,          % ?Backend
      store_use_memory/0,
      store_use_python/1,       % +NeemId
      store_current_neem/1,     % ?NeemId
      store_assert/1,           % +Triple
      store_assert/3,           % +Triple, +Since, +Until
      store_reset/0,
      store_match/2,            % +Patterns, +Scope
      store_match/3,            % +Patterns, +Scope, +Options
      store_match_scoped/3,     % +Patterns, +Scope, -FactScope
      store_in_graphs/2,        % +Graphs, :Goal
      store_insert/1,           % +Triples
      store_insert/2,           % +Triples, +Merge
      store_insert/3,           % +Triples, +Merge, +Graph
      store_graph_version/2,    % +Graph, -Version
      store_set_graph_version/3, % +Ontology, +Version, +Graph
      store_drop_graph/1,       % +Graph
      store_retract/1,          % +Patterns
      store_annotation/3,       % ?Subject, ?Property, ?Value
      store_insert_annotations/1, % +Annotations
      store_pose/4,             % +Frame, +At, -Pose, -Stamp
      store_assert_pose/3,      % +Frame, +Stamp, +Pose
      store_poses/4,            % +Frame, +Begin, +End, -Trajectory
      store_taxonomic/1,        % ?Property
      store_scope_now/1,        % -Scope
      store_python_request/1,   % -Request
      store_set_request/1       % +Request
    ]).
/** <module> NEEM store access: the only module that touches the Python store

Every triple lookup of the Prolog side goes through store_match/2, which evaluates a list of
triple patterns `t(S,P,O)` as ONE conjunction with KnowRob 2.x's `p*`/`o*` semantics
(knowrob-2x-facts §5):

  - a taxonomic property (rdf:type, rdfs:subClassOf, rdfs:subPropertyOf) matches the
    asserted property exactly and a bound object against the class closure `o*`;
  - any other property matches the property closure `p*`, the object exactly.

Two backends implement it:

  - `python`: the Python bridge (python/oracle/bridge.py) registered the foreign predicate
    py_match/2 in this module; the conjunction crosses into Python once and becomes one SQL
    join (SQLite) or one aggregation pipeline (MongoDB). Results come back in chunks.
  - `memory`: triples asserted with store_assert/1,3, evaluated in Prolog. It lets every
    module above this one be tested with plunit, without Python.

A question scope is `scope(Since, Until)`: a fact is visible when its own scope contains
`[Since, Until]` (KnowRob's `since =< Since, until >= Until`), or `any` for no time filter.
Whatever the question scope, a fact is seen only where its scope has an extent
(`since < until`) and a conjunction only where its facts' scopes share one, as mongolog drops
every row whose running scope intersection `v_scope` is empty (KnowRob's triple.pl).
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module(library(pairs)).
:- use_module(json_text, [json_data_text/2]).

:- meta_predicate store_in_graphs(+, 0).

:- dynamic backend_/1.
:- dynamic mem_triple/6.        % S, P, O, Since, Until, Graph
:- dynamic mem_annotation/3.    % S, P, Value
:- dynamic mem_tf/3.            % ChildFrame, Stamp, [RefFrame, [X,Y,Z], [QX,QY,QZ,QW]]
:- dynamic mem_version/3.       % Graph, Ontology, Version

backend_(memory).

rdf_type('http://www.w3.org/1999/02/22-rdf-syntax-ns#type').
subclass_of_iri('http://www.w3.org/2000/01/rdf-schema#subClassOf').
subproperty_of_iri('http://www.w3.org/2000/01/rdf-schema#subPropertyOf').

%!  store_taxonomic(?Property) is nondet.
%   Property is one of the three taxonomic properties whose object is closed over `o*`.
store_taxonomic(P) :- rdf_type(P).
store_taxonomic(P) :- subclass_of_iri(P).
store_taxonomic(P) :- subproperty_of_iri(P).

%!  store_backend(?Backend) is det.
%   Backend is `memory` or `python(NeemId)`.
store_backend(B) :- backend_(B).

%!  store_use_memory is det.
%   Answer from the asserted triples (the default).
store_use_memory :-
    retractall(backend_(_)),
    assertz(backend_(memory)).

%!  store_use_python(+NeemId) is det.
%   Answer from the Python store, NEEM NeemId. Called by the bridge after it registered
%   py_match/2 and py_insert/2 in this module.
store_use_python(NeemId) :-
    must_be(atom, NeemId),
    (   current_predicate(neem_store:py_match/2)
    ->  true
    ;   existence_error(foreign_predicate, neem_store:py_match/2)
    ),
    retractall(backend_(_)),
    assertz(backend_(python(NeemId))).

%!  store_current_neem(?NeemId) is semidet.
%   The NEEM the Python backend reads; `memory` for the asserted triples.
store_current_neem(Id) :-
    (   backend_(python(Id0)) -> Id = Id0 ; Id = memory ).

%!  store_scope_now(-Scope) is det.
%   KnowRob's default question scope: the facts true now.
store_scope_now(scope(Now, Now)) :- get_time(Now).

%!  store_assert(+Triple) is det.
%!  store_assert(+Triple, +Since, +Until) is det.
%   Add `triple(S,P,O)` to the memory backend, universal scope unless given.
store_assert(Triple) :-
    Inf is inf,
    store_assert(Triple, 0.0, Inf).
store_assert(triple(S, P, O), Since, Until) :-
    !,
    must_be(atom, S), must_be(atom, P), must_be(atomic, O),
    must_be(number, Since), must_be(number, Until),
    assertz(mem_triple(S, P, O, Since, Until, user)).
store_assert(Triple, _, _) :-
    type_error(triple, Triple).

%!  store_reset is det.
%   Forget every asserted triple and go back to the memory backend.
store_reset :-
    retractall(mem_triple(_,_,_,_,_,_)),
    retractall(mem_annotation(_,_,_)),
    retractall(mem_tf(_,_,_)),
    retractall(mem_version(_,_,_)),
    store_use_memory.

%!  store_insert(+Triples) is det.
%!  store_insert(+Triples, +Merge) is det.
%   Write a list of `triple(S,P,O,Since,Until)` into the current backend (kb_project/1).
%   Merge says what happens to a stored triple with the same S, P, O whose scope overlaps
%   the new one: `union` (the default, KnowRob's kb_project) replaces both by one triple
%   over the union of their scopes; `intersect` (KnowRob's `until`/`since` projection)
%   narrows the stored triple to the intersection instead of adding the new one. Both
%   backends do it (the Python stores in python/oracle/store/project.py).
store_insert(Triples) :-
    store_insert(Triples, union).

store_insert(Triples, Merge) :-
    store_insert(Triples, Merge, user).

%!  store_insert(+Triples, +Merge, +Graph) is det.
%   store_insert/2 into the named graph Graph (KnowRob's `graph` of a document: `user` for
%   kb_project, the ontology's name for load_owl). A fact merges with its copies in the same
%   graph.
store_insert(Triples, Merge, Graph) :-
    must_be(list, Triples),
    must_be(oneof([union, intersect]), Merge),
    must_be(atom, Graph),
    maplist(check_insert, Triples),
    (   backend_(python(Neem))
    ->  maplist(insert_row, Triples, Rows),
        neem_store:py_insert([Neem, Merge, Graph|Rows], Reply),
        reply_rows(Reply, _)
    ;   forall(member(T, Triples), mem_insert(Merge, Graph, T))
    ).

%!  store_graph_version(+Graph, -Version) is semidet.
%   Version is the `tripledbVersionString` marker of named graph Graph (KnowRob's
%   get_ontology_version/2): what load_owl compares with the file's version.
store_graph_version(Graph, Version) :-
    must_be(atom, Graph),
    (   backend_(python(Neem))
    ->  neem_store:py_graph([Neem, get, Graph, '', ''], Reply),
        reply_rows(Reply, [[_, Version]|_])
    ;   once(mem_version(Graph, _, Version))
    ).

%!  store_set_graph_version(+Ontology, +Version, +Graph) is det.
%   Record that Graph holds version Version of ontology Ontology (KnowRob's
%   set_ontology_version/3: a document without scope or closures).
store_set_graph_version(Ontology, Version, Graph) :-
    must_be(atom, Ontology), must_be(atomic, Version), must_be(atom, Graph),
    (   backend_(python(Neem))
    ->  neem_store:py_graph([Neem, set, Graph, Ontology, Version], Reply),
        reply_rows(Reply, _)
    ;   assertz(mem_version(Graph, Ontology, Version))
    ).

%!  store_drop_graph(+Graph) is det.
%   Delete every triple of named graph Graph, its version marker with them (KnowRob's
%   drop_graph/1).
store_drop_graph(Graph) :-
    must_be(atom, Graph),
    (   backend_(python(Neem))
    ->  neem_store:py_graph([Neem, drop, Graph, '', ''], Reply),
        reply_rows(Reply, _)
    ;   retractall(mem_version(Graph, _, _)),
        retractall(mem_triple(_, _, _, _, _, Graph))
    ).

mem_insert(Merge, G, triple(S, P, O, Since, Until)) :-
    findall(S1-U1, ( mem_triple(S, P, O, S1, U1, G), S1 =< Until, U1 >= Since ), Overlaps),
    (   Overlaps == []
    ->  assertz(mem_triple(S, P, O, Since, Until, G))
    ;   Merge == union
    ->  retractall_overlapping(S, P, O, Since, Until, G),
        pairs_keys_values(Overlaps, Ss, Us),
        foldl(num_min, Ss, Since, Since1), foldl(num_max, Us, Until, Until1),
        assertz(mem_triple(S, P, O, Since1, Until1, G))
    ;   retractall_overlapping(S, P, O, Since, Until, G),
        forall(member(S1-U1, Overlaps),
               ( num_max(S1, Since, Since1), num_min(U1, Until, Until1),
                 assertz(mem_triple(S, P, O, Since1, Until1, G)) ))
    ).

%   min/max by comparison: `is max(inf, inf)` raises float_overflow in SWI-Prolog.
num_min(A, B, M) :- ( A =< B -> M = A ; M = B ).
num_max(A, B, M) :- ( A >= B -> M = A ; M = B ).

retractall_overlapping(S, P, O, Since, Until, G) :-
    forall(( clause(mem_triple(S, P, O, S1, U1, G), true, Ref), S1 =< Until, U1 >= Since ),
           erase(Ref)).

%!  store_retract(+Patterns) is det.
%   Delete every stored triple matching one of the `t(S,P,O)` patterns (kb_unproject/1);
%   an unbound term matches any value.
store_retract(Patterns) :-
    must_be(list, Patterns),
    maplist(check_pattern, Patterns),
    (   backend_(python(Neem))
    ->  maplist(retract_row, Patterns, Rows),
        neem_store:py_retract([Neem|Rows], Reply),
        reply_rows(Reply, _)
    ;   forall(member(t(S, P, O), Patterns), retractall(mem_triple(S, P, O, _, _, _)))
    ).

retract_row(t(S, P, O), [S1, P1, O1]) :-
    maplist(retract_term, [S, P, O], [S1, P1, O1]).

retract_term(T, R) :-
    (   var(T) -> R = []
    ;   atomic(T) -> R = [T]
    ;   domain_error(retract_value, T)
    ).

%!  store_annotation(?Subject, ?Property, ?Value) is nondet.
%   A label, comment or other annotation value: KnowRob keeps these in the `annotations`
%   collection, apart from the triples (no scopes, no closures).
store_annotation(S, P, V) :-
    check_term(S), check_term(P),
    (   backend_(python(Neem))
    ->  ( atom(S) -> S1 = S ; S1 = '' ),
        ( atom(P) -> P1 = P ; P1 = '' ),
        neem_store:py_annotations([Neem, S1, P1], Reply),
        reply_rows(Reply, Rows),
        member([S, P, V], Rows)
    ;   mem_annotation(S, P, V)
    ).

%!  store_insert_annotations(+Annotations) is det.
%   Store a list of `annotation(S, P, Value)` in the annotations collection.
store_insert_annotations(As) :-
    must_be(list, As),
    maplist(check_annotation, As),
    (   backend_(python(Neem))
    ->  findall([S, P, V], member(annotation(S, P, V), As), Rows),
        neem_store:py_annotate([Neem|Rows], Reply),
        reply_rows(Reply, _)
    ;   forall(member(annotation(S, P, V), As),
               ( mem_annotation(S, P, V) -> true ; assertz(mem_annotation(S, P, V)) ))
    ).

%!  store_pose(+Frame, +At, -Pose, -Stamp) is semidet.
%   The latest transform of tf frame Frame stamped at or before At (`any`: the latest of
%   all): Pose is `[RefFrame, [X,Y,Z], [QX,QY,QZ,QW]]`, from the NEEM's tf collection.
store_pose(Frame, At, Pose, Stamp) :-
    must_be(atom, Frame),
    (   At == any -> true ; must_be(number, At) ),
    (   backend_(python(Neem))
    ->  ( At == any -> A = -1 ; A = At ),
        neem_store:py_tf([Neem, Frame, A], Reply),
        reply_rows(Reply, [[Stamp, Ref, X, Y, Z, QX, QY, QZ, QW]]),
        Pose = [Ref, [X, Y, Z], [QX, QY, QZ, QW]]
    ;   findall(St-P, ( mem_tf(Frame, St, P), ( At == any -> true ; St =< At ) ), Ps),
        Ps \== [],
        keysort(Ps, Sorted),
        last(Sorted, Stamp-Pose)
    ).

%!  store_assert_pose(+Frame, +Stamp, +Pose) is det.
%   Add a transform of Frame stamped Stamp to the NEEM's tf collection (KnowRob's
%   tf_set_pose/3 and the tf logger write them).
store_assert_pose(Frame, Stamp, Pose) :-
    must_be(atom, Frame), must_be(number, Stamp),
    (   Pose = [Ref, [X, Y, Z], [QX, QY, QZ, QW]], atom(Ref),
        maplist(number, [X, Y, Z, QX, QY, QZ, QW])
    ->  (   backend_(python(Neem))
        ->  neem_store:py_tf([Neem, Frame, Stamp, Ref, X, Y, Z, QX, QY, QZ, QW, write], Reply),
            reply_rows(Reply, _)
        ;   assertz(mem_tf(Frame, Stamp, Pose))
        )
    ;   type_error(pose, Pose)
    ).

%!  store_poses(+Frame, +Begin, +End, -Trajectory) is det.
%   Every transform of Frame stamped in [Begin, End], as `Stamp-Pose` pairs in time order.
store_poses(Frame, Begin, End, Trajectory) :-
    must_be(atom, Frame), must_be(number, Begin), must_be(number, End),
    (   backend_(python(Neem))
    ->  neem_store:py_tf([Neem, Frame, Begin, End], Reply),
        reply_rows(Reply, Rows),
        findall(St-[Ref, [X, Y, Z], [QX, QY, QZ, QW]], member([St, Ref, X, Y, Z, QX, QY, QZ, QW], Rows), Trajectory)
    ;   findall(St-P, ( mem_tf(Frame, St, P), St >= Begin, St =< End ), Ps),
        keysort(Ps, Trajectory)
    ).

check_annotation(annotation(S, P, V)) :- !,
    must_be(atom, S), must_be(atom, P), must_be(atomic, V).
check_annotation(A) :-
    type_error(annotation, A).

check_insert(triple(S,P,O,Since,Until)) :-
    !,
    must_be(atom, S), must_be(atom, P), must_be(atomic, O),
    must_be(number, Since), must_be(number, Until).
check_insert(T) :-
    type_error(triple, T).

insert_row(triple(S,P,O,Since,Until), [S,P,O,Since,Until]).

%!  store_match(+Patterns, +Scope) is nondet.
%!  store_match(+Patterns, +Scope, +Options) is nondet.
%   Solve the conjunction of `t(S,P,O)` patterns in ONE store query, binding their
%   variables. Options: `limit(N)`, `order(Keys)` (with a limit, solutions equal in every
%   key come in no fixed order: the store's top-N scan stops at its Nth row) and
%   `select(Term)`: only the variables of
%   Term are bound by a solution (the store does not send the others back; the memory
%   backend binds them all), for callers that collect a few variables of many rows;
%   `group(Var, Values)` (with select(Term), no limit or order): one solution per distinct
%   binding of Term's other variables, Var left free and Values the list of its values in
%   those rows (duplicates kept, in no fixed order), grouped by the store; `plan(written)`:
%   the store joins the patterns in the order written (SQLite has no statistics to plan a
%   long join by; MongoDB's pipeline is always in that order), with `order(Keys)` too (the
%   rows are then sorted after the join, not scanned in the key's order). Terms must be variables or
%   atomic values.
store_match(Patterns, Scope) :-
    store_match(Patterns, Scope, []).

store_match(Patterns0, Scope, Options) :-
    checked_query(Patterns0, Scope, Patterns, Backend),
    match(Backend, Patterns, Scope, Options).

%   A store query checked (non-empty list of patterns, a scope) with its comparisons bound,
%   and the backend that answers it.
checked_query(Patterns0, Scope, Patterns, Backend) :-
    must_be(list, Patterns0),
    Patterns0 \== [],
    maplist(check_pattern, Patterns0),
    check_scope(Scope),
    maplist(bound_comparison, Patterns0, Patterns),
    backend_(Backend).

%!  store_match_scoped(+Patterns, +Scope, -FactScope) is nondet.
%   store_match/2 that also says when the matched facts hold together: FactScope is
%   `scope(Since, Until)`, the intersection of the scopes of the documents matched (one
%   solution per combination of documents, as mongolog's `v_scope`; empty intersections
%   are dropped). What `G during [S,U]` with S and U free and kb_call/3 report.
store_match_scoped(Patterns0, Scope, FactScope) :-
    checked_query(Patterns0, Scope, Patterns, Backend),
    Inf is inf,
    (   Backend == memory
    ->  mem_conj_scoped(Patterns, Scope, scope(0.0, Inf), FactScope)
    ;   match(Backend, Patterns, Scope, []),
        Backend = python(Neem),
        foldl(doc_scope(Neem, Scope), Patterns, scope(0.0, Inf), FactScope)
    ).

%!  store_in_graphs(+Graphs, :Goal) is nondet.
%   Goal with every store query (store_match/2,3, store_match_scoped/3) reading only the
%   documents of the named graphs in the list Graphs (KnowRob's `graph` field filter,
%   `$in` its super-graphs); `all` reads every graph. Queries outside Goal are not
%   filtered: the filter is undone when Goal exits and restored when it is retried.
store_in_graphs(Graphs, Goal) :-
    (   Graphs == all -> true
    ;   must_be(list(atom), Graphs),
        ( Graphs == [] -> domain_error(non_empty_graph_list, Graphs) ; true )
    ),
    (   nb_current(neem_store_graphs, Old) -> true ; Old = all ),
    b_setval(neem_store_graphs, Graphs),
    call(Goal),
    b_setval(neem_store_graphs, Old).

%   The graphs the current query reads; fails when it reads all of them. (A key first
%   created by b_setval/2 reads `[]` once backtracked over: no filter either.)
query_graphs(Graphs) :-
    nb_current(neem_store_graphs, Graphs),
    Graphs \== all, Graphs \== [].

%   The scope of one matched (now ground) pattern's document, intersected with Acc.
doc_scope(Neem, Scope, t(S, P, O0), Acc, FS) :-
    (   nonvar(O0), O0 = cmp(_, _, O) -> true ; O = O0 ),
    (   query_graphs(Graphs) -> Request = [Neem, S, P, O, Graphs] ; Request = [Neem, S, P, O] ),
    neem_store:py_scopes(Request, Reply),
    reply_rows(Reply, Rows),
    member([Since, Until], Rows),
    in_scope(Scope, Since, Until),
    scope_intersection(Acc, Since, Until, FS).

scope_intersection(scope(S0, U0), S1, U1, scope(S, U)) :-
    num_max(S0, S1, S),
    num_min(U0, U1, U),
    S < U.

%   A comparison whose value is already bound is that value, if it passes.
bound_comparison(t(S, P, C), t(S, P, O)) :-
    nonvar(C), C = cmp(Op, A, X), nonvar(X), !,
    number(X), compare_value(Op, X, A),
    O = X.
bound_comparison(T, T).

check_pattern(t(S,P,O)) :-
    !,
    check_term(S), check_term(P), check_object(O).
check_pattern(X) :-
    type_error(triple_pattern, X).

%   cmp(Op, Number, X): the object compared with a number in the database; X binds it.
check_object(C) :-
    nonvar(C), C = cmp(Op, A, _), !,
    must_be(oneof([<, =<, >, >=]), Op),
    must_be(number, A).
check_object(O) :-
    check_term(O).

check_term(X) :- var(X), !.
check_term(X) :- atomic(X), !.
check_term(X) :- type_error(atomic_or_var, X).

check_scope(any) :- !.
check_scope(scope(S, U)) :- number(S), number(U), !.
check_scope(X) :- type_error(scope, X).

match(Backend, Patterns, Scope, Options) :-
    memberchk(group(Var, Values), Options), !,
    group_option(Options, Patterns, Var, Keep, Keys),
    (   Backend = python(_)
    ->  maplist(replace_var(Var, Values), Patterns, Patterns1),
        (   memberchk(plan(written), Options) -> Plan = [plan(written)] ; Plan = [] ),
        match(Backend, Patterns1, Scope, [select(Keep-Values), group_last|Plan])
    ;   findall(Keys-Var, mem_conj(Patterns, Scope), Pairs),
        msort(Pairs, Sorted),
        group_pairs_by_key(Sorted, Groups),
        member(Keys-Values, Groups)
    ).
match(memory, Patterns, Scope, Options) :-
    option_order(Options, Keys),
    Keys \== [], !,
    term_variables(Patterns, Vars),
    findall(Row, ( mem_conj(Patterns, Scope), order_row(Keys, Vars, Row) ), Rows0),
    length(Keys, NKeys),
    sort_rows(NKeys, Keys, Rows0, Rows1),
    VarsArg is NKeys+1,
    (   option_limit(Options, N)
    ->  limit(N, ( member(Row, Rows1), arg(VarsArg, Row, Vars) ))
    ;   member(Row, Rows1), arg(VarsArg, Row, Vars)
    ).
match(memory, Patterns, Scope, Options) :-
    (   option_limit(Options, N)
    ->  limit(N, mem_conj(Patterns, Scope))
    ;   mem_conj(Patterns, Scope)
    ).
match(python(Neem), Patterns, Scope, Options) :-
    term_variables(Patterns, All),
    selected_first(Options, All, Vars, Order0),
    maplist(encode_pattern(Order0), Patterns, Encoded0),
    (   query_graphs(Graphs)
    ->  maplist(graph_cells(Graphs), Encoded0, Encoded)
    ;   Encoded = Encoded0
    ),
    encode_scope(Scope, S0, S1),
    (   option_limit(Options, N) -> true ; N = -1 ),
    option_order(Options, Keys),
    maplist(encode_key(Order0), Keys, Order),
    length(Vars, NVars),
    (   memberchk(group_last, Options) -> Group is NVars-1 ; Group = -1 ),
    (   memberchk(plan(written), Options) -> Plan = written ; Plan = store ),
    Request = [Neem, S0, S1, N, NVars, Order, Group, Plan|Encoded],
    % As JSON text: pyswip turns a list into Python one node at a time (~0.5 ms a request);
    % a constant JSON cannot hold (a rational number, a blob) goes as the term.
    (   catch(json_data_text(Request, Text), error(_, _), fail)
    ->  neem_store:py_match(Text, Reply)
    ;   neem_store:py_match(Request, Reply)
    ),
    match_reply(Reply, Table, Rows),
    member(Row, Rows),
    row_values(Row, Table, Vars).

%   replace_var(+Var, +New, +Term, -Term1): Term with the variable Var replaced by New (the
%   grouped variable of the python backend, selected last, comes back bound to its list of
%   values; Var itself stays free, as on the memory backend).
replace_var(Var, New, T, New) :-
    T == Var, !.
replace_var(Var, New, T, T1) :-
    compound(T), !,
    T =.. [F|As],
    maplist(replace_var(Var, New), As, As1),
    T1 =.. [F|As1].
replace_var(_, _, T, T).

%   group(Var, Values) checked: Var a variable of the patterns, kept by select(Term), and
%   neither limit nor order given; Keep is Term without Var, Keys its variables.
group_option(Options, Patterns, Var, Keep, Keys) :-
    (   var(Var), term_variables(Patterns, All), occurs_in(All, Var)
    ->  true
    ;   domain_error(pattern_variable, Var)
    ),
    (   memberchk(select(Term), Options)
    ->  term_variables(Term, TermVars),
        (   occurs_in(TermVars, Var) -> true ; domain_error(selected_variable, Var) )
    ;   TermVars = All
    ),
    (   ( memberchk(limit(_), Options) ; memberchk(order(_), Options) )
    ->  domain_error(group_without_limit_or_order, Options)
    ;   true
    ),
    exclude(==(Var), TermVars, KeyVars0),
    include(occurs_in(All), KeyVars0, KeyVars),
    Keep = KeyVars,
    Keys = KeyVars.

%   select(Keep): only the variables of Keep come back (the bridge returns the first NVars
%   variables of the numbering, so these are numbered first); the others are existential.
selected_first(Options, All, Vars, Numbering) :-
    (   memberchk(select(Keep), Options)
    ->  term_variables(Keep, KeepVars),
        include(occurs_in(All), KeepVars, Vars),
        exclude(occurs_in(Vars), All, Rest),
        append(Vars, Rest, Numbering)
    ;   Vars = All,
        Numbering = All
    ).

occurs_in(Vars, V) :- member(X, Vars), X == V, !.

option_limit(Options, N) :-
    memberchk(limit(N), Options),
    must_be(positive_integer, N).

%   order(Keys): Keys is a list of asc(Var) and desc(Var) over numeric variables of the
%   patterns, applied before limit(N) (by the database on the python backend).
option_order(Options, Keys) :-
    (   memberchk(order(Keys), Options)
    ->  must_be(list, Keys),
        maplist(check_key, Keys)
    ;   Keys = []
    ).

check_key(asc(V)) :- var(V), !.
check_key(desc(V)) :- var(V), !.
check_key(K) :- type_error(order_key, K).

encode_key(Vars, Key, [I, Dir]) :-
    Key =.. [Dir, V],
    nth0_var(Vars, V, 0, I).

order_row(Keys, Vars, Row) :-
    maplist(key_value, Keys, Vs),
    append(Vs, [Vars], Args),
    Row =.. [row|Args].

key_value(K, V) :- arg(1, K, V).

%   Stable sorts from the last key to the first give the lexicographic order.
sort_rows(0, _, Rows, Rows) :- !.
sort_rows(I, Keys, Rows0, Rows) :-
    nth1(I, Keys, Key),
    (   Key = asc(_) -> Ord = @=< ; Ord = @>= ),
    sort(I, Ord, Rows0, Rows1),
    I1 is I-1,
    sort_rows(I1, Keys, Rows1, Rows).

%   Scope ends as numbers; -1, -1 for no time filter. The bridge turns them into the
%   store's Scope (see python/oracle/bridge.py).
encode_scope(any, -1, -1).
encode_scope(scope(S, U), S, U).

%   The graph filter as two more cells of an encoded pattern: `g` and the list of graphs.
graph_cells(Graphs, Cells0, Cells) :- append(Cells0, [g, Graphs], Cells).

%   A pattern slot as two list cells: kind (v, c) and value (variable index or constant).
encode_pattern(Vars, t(S,P,O), [SK,SV,PK,PV,OK,OV]) :-
    encode_term(Vars, S, SK, SV),
    encode_term(Vars, P, PK, PV),
    encode_term(Vars, O, OK, OV).

encode_term(Vars, X, v, I) :-
    var(X), !,
    nth0_var(Vars, X, 0, I).
encode_term(Vars, cmp(Op, A, X), cmp, [Op, A, I]) :- !,
    nth0_var(Vars, X, 0, I).
encode_term(_, X, c, X).

nth0_var([V|Vs], X, I0, I) :-
    (   V == X -> I = I0 ; I1 is I0+1, nth0_var(Vs, X, I1, I) ).

%   A chunk of py_match/2 solutions arrives as the text `r(d(V1, ..., Vk), Rows)`: each
%   distinct value (quoted atom or number) once, and each row a list of positions in d/k.
%   A history read repeats each IRI many times; small integers are read 7x faster than the
%   quoted atoms. A grouped request's chunk is `r(d(V1, ..., Vk), g(S1, ..., Sm), Rows)`:
%   each distinct group of values once, as a list of positions in d/k, and a row's last
%   position k+j names the group Sj; Table is then d/k+m, its last m values the groups' value
%   lists (each built once, shared by the rows naming it). It is read as data, never called;
%   an error arrives as `error(Message)`.
match_reply(Reply, Table, Rows) :-
    term_string(T, Reply),
    (   T = r(Table, Rows), ground(T), is_list(Rows)
    ->  true
    ;   T = r(Values, Groups, Rows), ground(T), is_list(Rows), functor(Values, d, _),
        functor(Groups, g, _)
    ->  Values =.. [d|Vs],
        Groups =.. [g|Gs],
        maplist(group_values(Values), Gs, Lists),
        append(Vs, Lists, All),
        Table =.. [d|All]
    ;   T = error(Message)
    ->  throw(error(neem_store_error(Message), _))
    ;   throw(error(neem_store_error(unexpected_reply(T)), _))
    ).

group_values(Values, Positions, List) :-
    (   is_list(Positions)
    ->  row_values(Positions, Values, List)
    ;   throw(error(neem_store_error(unexpected_reply(Positions)), _))
    ).

%   The values of one compact row; a position outside the table is a broken reply.
row_values([], _, []).
row_values([I|Is], Table, [V|Vs]) :-
    cell_value(I, Table, V),
    row_values(Is, Table, Vs).

cell_value(I, Table, V) :-
    integer(I), !,
    (   arg(I, Table, V0) -> V = V0 ; throw(error(neem_store_error(unexpected_reply(I)), _)) ).
cell_value(Is, Table, Vs) :-
    is_list(Is), !,
    row_values(Is, Table, Vs).
cell_value(X, _, _) :-
    throw(error(neem_store_error(unexpected_reply(X)), _)).

%   Other replies arrive as the text of a list of rows, each row a list of quoted atoms and
%   numbers (5x cheaper than a pyswip list, toolchain-facts §2). It is read as data, never
%   called, and must be a ground list; an error arrives as `error(Message)`.
reply_rows(Reply, Rows) :-
    term_string(T, Reply),
    (   T = error(Message)
    ->  throw(error(neem_store_error(Message), _))
    ;   is_list(T), ground(T)
    ->  Rows = T
    ;   throw(error(neem_store_error(unexpected_reply(T)), _))
    ).

:- dynamic request_/1.

%!  store_python_request(-Request) is det.
%   The request the Python bridge handed over for the current query (a list of atoms,
%   numbers and lists): how values reach Prolog without becoming query text.
store_python_request(R) :-
    (   retract(request_(R0))
    ->  R = R0
    ;   current_predicate(neem_store:py_request/1)
    ->  neem_store:py_request(R0),
        R = R0
    ;   existence_error(python_request, neem_store)
    ).

%!  store_set_request(+Request) is det.
%   Hand over a request from Prolog (tests and the memory backend).
store_set_request(R) :-
    retractall(request_(_)),
    assertz(request_(R)).

                 /*******************************
                 *        MEMORY BACKEND        *
                 *******************************/

mem_conj(Patterns, Scope) :-
    Inf is inf,
    mem_conj_scoped(Patterns, Scope, scope(0.0, Inf), _).

mem_conj_scoped([], _, FS, FS).
mem_conj_scoped([t(S,P,O)|Ps], Scope, FS0, FS) :-
    mem_pattern(S, P, O, Scope, Since, Until),
    scope_intersection(FS0, Since, Until, FS1),
    mem_conj_scoped(Ps, Scope, FS1, FS).

%   mem_pattern(?S, ?P, ?O, +Scope, -Since, -Until): a stored triple and its scope.
mem_pattern(S, P, C, Scope, Since, Until) :-
    nonvar(C), C = cmp(Op, A, X), !,
    mem_pattern(S, P, X, Scope, Since, Until),
    number(X),
    compare_value(Op, X, A).
mem_pattern(S, P, O, Scope, Since, Until) :-
    atom(P), store_taxonomic(P), !,
    (   var(O)
    ->  mem_visible(S, P, O, Since, Until)
    ;   mem_visible(S, P, O0, Since, Until),
        mem_closure(O0, Closure),
        memberchk(O, Closure)
    ),
    in_scope(Scope, Since, Until).
mem_pattern(S, P, O, Scope, Since, Until) :-
    atom(P), !,
    mem_visible(S, P0, O, Since, Until),
    (   P0 == P
    ->  true
    ;   \+ store_taxonomic(P0),
        mem_closure(P0, Closure),
        memberchk(P, Closure)
    ),
    in_scope(Scope, Since, Until).
mem_pattern(S, P, O, Scope, Since, Until) :-
    mem_visible(S, P, O, Since, Until),
    in_scope(Scope, Since, Until).

%   A stored triple in one of the graphs the query reads (store_in_graphs/2).
mem_visible(S, P, O, Since, Until) :-
    (   query_graphs(Graphs)
    ->  mem_triple(S, P, O, Since, Until, G),
        memberchk(G, Graphs)
    ;   mem_triple(S, P, O, Since, Until, _)
    ).

compare_value(<, X, A) :- X < A.
compare_value(=<, X, A) :- X =< A.
compare_value(>, X, A) :- X > A.
compare_value(>=, X, A) :- X >= A.

%   KnowRob's rule (src/lang/terms/triple.pl, scope_intersect/5): a fact is seen only where
%   its scope has an extent, `Since < Until`, whatever the question scope; a question scope
%   `scope(QS, QU)` further asks that it contain [QS, QU].
in_scope(any, Since, Until) :- !,
    Since < Until.
in_scope(scope(QS, QU), Since, Until) :-
    Since < Until,
    Since =< QS,
    Until >= QU.

%   The term and its ancestors over asserted subClassOf/subPropertyOf edges (KnowRob's o*).
mem_closure(Term, Closure) :-
    mem_closure_([Term], [Term], Rev),
    reverse(Rev, Closure).

mem_closure_([], Seen, Seen).
mem_closure_([T|Ts], Seen0, Seen) :-
    findall(Parent,
            ( ( subclass_of_iri(E) ; subproperty_of_iri(E) ),
              mem_triple(T, E, Parent, _, _, _),
              \+ memberchk(Parent, Seen0) ),
            Parents0),
    list_to_set(Parents0, Parents),
    reverse(Parents, RevParents),
    append(RevParents, Seen0, Seen1),
    append(Ts, Parents, Queue),
    mem_closure_(Queue, Seen1, Seen).
