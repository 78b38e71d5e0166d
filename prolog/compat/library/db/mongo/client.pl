:- module(mng_client,
    [ mng_db_name/1,            % -DB
      mng_drop/2                % +DB, +Collection
    ]).
/** <module> What `library('db/mongo/client')` gives robot code written for KnowRob 2.x

KnowRob's MongoDB client module (src/db/mongo/client.pl). Code such as neem-interface.pl
loads it with `:- use_module(library('db/mongo/client'))` and calls mng_drop/2 to clear a
collection; prolog/compat/neem_interface.pl puts this folder on the `library` search path so
that the directive finds this module. Only these two predicates are here (docs/prolog.md).
*/

:- use_module(library(error)).
:- use_module('../../../../store/graph', [store_drop_graph/1]).

%!  mng_db_name(-DB) is det.
%   The database KnowRob reads by default, `roslog` (a NEEM's dump folders are named after it).
mng_db_name(roslog).

%!  mng_drop(+DB, +Collection) is det.
%   KnowRob's mng_drop/2 clears a collection of the current database. `triples`: every fact
%   asserted at run time (graph `user`) of the current NEEM goes; `tf`, `annotations`,
%   `inferred`: kept (our stores drop those collections only with their NEEM; KnowRob code
%   calls this before an episode, where the NEEM is new). Another name is a domain error.
mng_drop(DB, Collection) :-
    must_be(atom, DB), must_be(atom, Collection),
    (   Collection == triples -> store_drop_graph(user)
    ;   memberchk(Collection, [tf, annotations, inferred]) -> true
    ;   domain_error(neem_collection, Collection)
    ).
