:- begin_tests(mng_client).

:- use_module(client).
:- use_module('../../../../neem_store').

test(drop_triples_is_the_user_graph, [setup(store_reset), cleanup(store_reset)]) :-
    Inf is inf, store_insert([triple(a, p, b, 0.0, Inf)], union, user),
    mng_drop(roslog, triples),
    \+ store_match([t(a, p, _)], any).

test(tf_is_kept, [setup(store_reset), cleanup(store_reset)]) :-
    mng_drop(roslog, tf), mng_db_name(roslog).

test(unknown_collection, [error(domain_error(neem_collection, people))]) :-
    mng_drop(roslog, people).

:- end_tests(mng_client).
