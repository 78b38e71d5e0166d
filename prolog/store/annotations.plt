:- begin_tests(store_annotations).

:- use_module(annotations).
:- use_module(neem, [store_reset/0, store_use_python/1]).

% The python backend, stood in for: py_annotations/2 and py_annotate/2 keep the request
% they got and answer Reply (made at run time, see python.plt).
python_stub(Reply) :-
    forall(member(Name, [py_annotations, py_annotate]),
           ( Head =.. [Name, Request, Reply],
             assertz((store_python:Head :- nb_setval(store_sent, Request))) )),
    Match =.. [py_match, _, "r(d,[])"],
    assertz(store_python:Match),
    store_use_python(n1).

python_unstub :-
    forall(member(Name, [py_annotations, py_annotate, py_match]), abolish(store_python:Name/2)),
    store_reset.

test(annotations_of_a_subject, [cleanup(store_reset)]) :-
    store_reset,
    store_insert_annotations([annotation(cup, label, 'Cup'), annotation(cup, comment, "a cup"),
                              annotation(plate, label, 'Plate'), annotation(cup, label, 'Cup')]),
    findall(P-V, store_annotation(cup, P, V), L),
    L == [label-'Cup', comment-"a cup"],
    findall(S, store_annotation(S, label, _), [cup, plate]).

test(annotation_checked, [error(type_error(annotation, label(cup, 'Cup')))]) :-
    store_insert_annotations([label(cup, 'Cup')]).

test(annotation_value_atomic, [error(type_error(atomic, [a]))]) :-
    store_insert_annotations([annotation(cup, label, [a])]).

test(query_terms_atomic, [error(type_error(atomic_or_var, f(x)))]) :-
    store_annotation(f(x), _, _).

test(python_read_filters_on_what_is_bound, [cleanup(python_unstub)]) :-
    python_stub("[[cup, label, 'Cup'], [cup, comment, 'a cup']]"),
    findall(V, store_annotation(cup, label, V), ['Cup']),
    nb_getval(store_sent, [n1, cup, label]),
    findall(P, store_annotation(cup, P, _), [label, comment]),
    nb_getval(store_sent, [n1, cup, '']).

test(python_write, [cleanup(python_unstub)]) :-
    python_stub("[]"),
    store_insert_annotations([annotation(cup, label, 'Cup')]),
    nb_getval(store_sent, [n1, [cup, label, 'Cup']]).

:- end_tests(store_annotations).
