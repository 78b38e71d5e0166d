:- module(store_python,
    [ store_python_ready/0,
      store_python_call/3,      % +Foreign, +Request, -Rows
      store_python_rows/2,      % +Request, -Values
      store_python_request/1,   % -Request
      store_set_request/1       % +Request
    ]).
/** <module> The Python request channel: the only module that touches the Python store

The Python bridge (python/oracle/bridge/, its foreign.py) registers its foreign predicates in this module
(py_match/2, py_insert/2, py_retract/2, py_graph/2, py_scopes/2, py_annotations/2,
py_annotate/2, py_tf/2, py_dump/2, py_request/1); nothing else calls them. A request goes
to Python as a list of atoms, numbers and lists (a match request as its JSON text); a reply
comes back as text, read here as data and never called: a list of rows, the compact table
of a match, or `error(Message)`, raised as `error(neem_store_error(Message), _)`.
*/

:- use_module(library(error)).
:- use_module(library(lists)).
:- use_module(library(apply)).
:- use_module('../json_text', [json_data_text/2]).

%!  store_python_ready is det.
%   The bridge has registered its foreign predicates; raises an existence error otherwise.
store_python_ready :-
    (   current_predicate(store_python:py_match/2)
    ->  true
    ;   existence_error(foreign_predicate, store_python:py_match/2)
    ).

%!  store_python_call(+Foreign, +Request, -Rows) is det.
%   One crossing into Python: the foreign predicate Foreign (`insert`, `retract`, `graph`,
%   `scopes`, `annotations`, `annotate`, `tf` or `dump`) with Request; Rows is its reply, a
%   ground list of rows.
store_python_call(Foreign, Request, Rows) :-
    (   memberchk(Foreign, [insert, retract, graph, scopes, annotations, annotate, tf, dump])
    ->  foreign(Foreign, Request, Reply)
    ;   domain_error(store_foreign_predicate, Foreign)
    ),
    reply_rows(Reply, Rows).

foreign(insert, Request, Reply) :- py_insert(Request, Reply).
foreign(retract, Request, Reply) :- py_retract(Request, Reply).
foreign(graph, Request, Reply) :- py_graph(Request, Reply).
foreign(scopes, Request, Reply) :- py_scopes(Request, Reply).
foreign(annotations, Request, Reply) :- py_annotations(Request, Reply).
foreign(annotate, Request, Reply) :- py_annotate(Request, Reply).
foreign(tf, Request, Reply) :- py_tf(Request, Reply).
foreign(dump, Request, Reply) :- py_dump(Request, Reply).

%!  store_python_rows(+Request, -Values) is nondet.
%   One conjunction of triple patterns answered by Python in ONE store query (py_match/2,
%   whose solutions are chunks of rows): Values is the list of the selected variables'
%   values of each row in turn (a grouped variable's value is the list of its values).
store_python_rows(Request, Values) :-
    % As JSON text: pyswip turns a list into Python one node at a time (~0.5 ms a request);
    % a constant JSON cannot hold (a rational number, a blob) goes as the term.
    (   catch(json_data_text(Request, Text), error(_, _), fail)
    ->  py_match(Text, Reply)
    ;   py_match(Request, Reply)
    ),
    match_reply(Reply, Table, Rows),
    member(Row, Rows),
    row_values(Row, Table, Values).

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
    ;   current_predicate(store_python:py_request/1)
    ->  py_request(R0),
        R = R0
    ;   existence_error(python_request, store_python)
    ).

%!  store_set_request(+Request) is det.
%   Hand over a request from Prolog (tests and the memory backend).
store_set_request(R) :-
    retractall(request_(_)),
    assertz(request_(R)).
