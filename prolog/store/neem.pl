:- module(store_neem,
    [ store_backend/1,          % ?Backend
      store_use_memory/0,
      store_use_python/1,       % +NeemId
      store_current_neem/1,     % ?NeemId
      store_reset/0
    ]).
/** <module> Which backend answers the store's questions, and for which NEEM

Two backends answer every store predicate:

  - `python(NeemId)`: the Python store (through store_python, the request channel), NEEM
    NeemId: a conjunction becomes one SQL join (SQLite) or one aggregation pipeline (MongoDB);
  - `memory` (the default): facts asserted in Prolog, so that every module above the store
    can be tested with plunit, without Python.

The modules that keep memory facts (triples, annotations, tf, graph versions) name them in
memory_facts/1, so that store_reset/0 forgets them all.
*/

:- use_module(library(error)).
:- use_module(python, [store_python_ready/0]).

:- dynamic backend_/1.

backend_(memory).

%   memory_facts(?Head): a dynamic predicate of the memory backend, module-qualified, that
%   store_reset/0 wipes; each module keeping memory facts adds its line.
:- multifile memory_facts/1.
:- dynamic memory_facts/1.

%!  store_backend(?Backend) is det.
%   Backend is `memory` or `python(NeemId)`.
store_backend(B) :- backend_(B).

%!  store_use_memory is det.
%   Answer from the asserted facts (the default).
store_use_memory :-
    retractall(backend_(_)),
    assertz(backend_(memory)).

%!  store_use_python(+NeemId) is det.
%   Answer from the Python store, NEEM NeemId. Called by the bridge after it registered its
%   foreign predicates in store_python.
store_use_python(NeemId) :-
    must_be(atom, NeemId),
    store_python_ready,
    retractall(backend_(_)),
    assertz(backend_(python(NeemId))).

%!  store_current_neem(?NeemId) is semidet.
%   The NEEM the Python backend reads; `memory` for the asserted facts.
store_current_neem(Id) :-
    (   backend_(python(Id0)) -> Id = Id0 ; Id = memory ).

%!  store_reset is det.
%   Forget every asserted fact (memory_facts/1) and go back to the memory backend.
store_reset :-
    forall(memory_facts(Head), retractall(Head)),
    store_use_memory.
