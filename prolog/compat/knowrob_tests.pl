:- module(knowrob_tests,
    [ begin_rdf_tests/2,        % +Unit, +URL
      begin_rdf_tests/3,        % +Unit, +URL, +Options
      end_rdf_tests/1,          % +Unit
      knowrob_units_score/2,     % +Unit, -Score
      assert_true/1,            % :Goal
      assert_false/1,           % :Goal
      assert_equals/2,          % +Actual, +Expected
      assert_unifies/2,         % ?Actual, ?Expected
      test_call/3               % :Goal, ?Var, +Value
    ]).
/** <module> What KnowRob 2.x's own test files need to run unchanged over prolog/

KnowRob writes its tests as plunit units inside its modules (`:- begin_rdf_tests(Unit,
'package://knowrob/owl/test/swrl.owl', [namespace(NS)])` ... `:- end_rdf_tests(Unit).`) and
in `.plt` files. tests/prolog/test_knowrob_own_tests.py takes those units' text from a
KnowRob source, as it is, and loads it after this module, which gives them:

- `begin_rdf_tests/2,3` and `end_rdf_tests/1` (KnowRob's lang/rdf_tests.pl): a unit whose
  set-up starts from a fresh store (the memory backend's reset, or `fresh_store_hook/0` when
  a caller runs them on the Python stores), registers the `test` prefix and loads the unit's
  OWL file with load_owl/2 into graph `test` (a `package://knowrob/...` URL resolved along
  `$KNOWROB_PACKAGE_PATH`, kb_db);
- rosprolog's assertions and mongolog's `test_call/3` (compat/knowrob_2x.pl);
- the set-up helpers KnowRob's units name in KnowRob's own modules (`lang_query:test_setup`,
  `computable:test_setup`, `mongolog:test_call/3`, ...), written here over this project's
  predicates: query backends generating 1..9, squares and doubles, computable predicates
  with the same answers.

knowrob_units_score/2 counts a unit's tests as plunit ran them: passed, failed, and the
tests KnowRob marks blocked or fixme, which are reported as such, never as passes.
*/

:- use_module(library(plunit)).
:- use_module(library(aggregate)).
:- use_module(library(option)).
:- use_module(library(semweb/rdf_prefixes)).

%   KnowRob's units declare `:- rdf_meta Head.` in their own text and call rdf_equal/2 and
%   rdf_global_term/2, which KnowRob's modules import from library(semweb/rdf_db).
:- op(1150, fx, user:rdf_meta).
:- use_module(user:library(semweb/rdf_prefixes), [rdf_global_term/2, rdf_global_id/2]).
:- use_module(user:library(semweb/rdf_db), [rdf_equal/2]).
:- use_module(knowrob_2x, [assert_true/1, assert_false/1, assert_equals/2, assert_unifies/2, test_call/3]).
:- use_module('../neem_store', [store_reset/0]).
:- use_module('../lang/db', [load_owl/2]).
:- use_module('../lang/query', [kb_call/1]).
:- use_module('../lang/computable', [add_computable_predicate/2, drop_computable_predicate/2]).

%!  begin_rdf_tests(+Unit, +URL) is det.
%!  begin_rdf_tests(+Unit, +URL, +Options) is det.
%   Open plunit Unit whose set-up loads the OWL file at URL into a fresh store; Options are
%   plunit's, with `namespace(NS)` the IRI prefix `test` stands for (default URL#).
begin_rdf_tests(Unit, URL) :-
    begin_rdf_tests(Unit, URL, []).
begin_rdf_tests(Unit, URL, Options0) :-
    (   select_option(namespace(NS), Options0, Options1) -> true
    ;   atom_concat(URL, '#', NS), Options1 = Options0
    ),
    rdf_register_prefix(test, NS, [force(true)]),
    Setup = knowrob_tests:rdf_setup(URL, NS),
    (   select_option(setup(Own), Options1, Options2) -> Setup1 = (Setup, Own) ; Setup1 = Setup, Options2 = Options1 ),
    begin_tests(Unit, [setup(Setup1)|Options2]).

%!  end_rdf_tests(+Unit) is det.
end_rdf_tests(Unit) :-
    end_tests(Unit).

%   A fresh store holding the unit's OWL file, `test` its namespace.
rdf_setup(URL, NS) :-
    fresh_store,
    rdf_register_prefix(test, NS, [force(true)]),
    load_owl(URL, [graph(test)]).

fresh_store :-
    (   clause(knowrob_2x:fresh_store_hook, _) -> knowrob_2x:fresh_store_hook ; store_reset ).

%!  knowrob_units_score(+Unit, -Score) is det.
%   Score is `score(Passed, Failed, Blocked, Fixme)` of the last run of Unit (a set-up that
%   failed fails its tests).
knowrob_units_score(Unit, score(P, F, B, X)) :-
    aggregate_all(count, plunit:current_test(Unit, _, _, _, _), All),
    aggregate_all(count, plunit:passed(Unit, _, _, _, _), P),
    aggregate_all(count, plunit:blocked(Unit, _, _, _), B),
    aggregate_all(count, plunit:fixme(Unit, _, _, _, _), X),
    F is max(0, All - P - B - X).

                 /*******************************
                 *   KNOWROB'S TEST HELPERS     *
                 *******************************/

%   lang/query.pl's units ask two query backends: test_a generates 1..9 (and, endlessly,
%   1, 2, ...), test_b squares; test_dual is answered by both (a square and a double).
lang_query:test_setup :-
    maplist(assertz, [ kb_query:is_callable_with(test_a, test_gen(_)),
                       kb_query:is_callable_with(test_a, test_gen_inf(_)),
                       kb_query:is_callable_with(test_b, test_single(_, _)),
                       kb_query:is_callable_with(test_a, test_dual(_, _)),
                       kb_query:is_callable_with(test_b, test_dual(_, _)),
                       (kb_query:call_with(test_a, test_gen(X), _) :- between(1, 9, X)),
                       (kb_query:call_with(test_a, test_gen_inf(X), _) :- between(1, inf, X)),
                       (kb_query:call_with(test_b, test_single(X, Y), _) :- Y is X * X),
                       (kb_query:call_with(test_a, test_dual(X, Y), _) :- Y is X * X),
                       (kb_query:call_with(test_b, test_dual(X, Y), _) :- Y is X + X) ]).
lang_query:test_cleanup :-
    retractall(kb_query:is_callable_with(test_a, _)),
    retractall(kb_query:is_callable_with(test_b, _)),
    retractall((kb_query:call_with(test_a, _, _) :- _)),
    retractall((kb_query:call_with(test_b, _, _) :- _)).

%   lang/computable.pl's unit: comp_gen/1 generates 1..9, comp_map/2 squares.
computable:test_setup :-
    add_computable_predicate(comp_gen/1, computable:test_comp_gen),
    add_computable_predicate(comp_map/2, computable:test_comp_map).
computable:test_cleanup :-
    drop_computable_predicate(computable, comp_gen/1),
    drop_computable_predicate(computable, comp_map/2).
computable:test_comp_gen(X) :- between(1, 9, X).
computable:test_comp_map(X, Y) :- Y is X * X.

%   lang/terms/annotation.pl's unit: its annotations go with the store.
lang_annotation:test_cleanup :- fresh_store.

%   lang/terms/triple.plt's unit names KnowRob's default graph and rdf_tests' clean-up.
lang_query:set_default_graph(_) :- fresh_store.
rdf_tests:cleanup :- fresh_store.

%   model/OWL.plt asks for an internal predicate of KnowRob's OWL module by its name.
model_OWL:disjoint_with_indirect(A, B) :- model_owl:disjoint_indirect(A, B).

%   The mongolog builtins' units: one kb_call with Var assigned Value first; KnowRob types
%   the value as it is stored (`double(4.5)`, `int(3)`, `string(s)`).
mongolog:test_call(Goal, Var, Value) :-
    plain_value(Value, Plain),
    test_call(user:Goal, Var, Plain).

plain_value(V, V) :- var(V), !.
plain_value(double(X), V) :- number(X), !, V is float(X).
plain_value(int(X), V) :- number(X), !, V is integer(X).
plain_value(integer(X), V) :- number(X), !, V is integer(X).
plain_value(string(X), V) :- !, ( atom(X) -> V = X ; atom_string(V, X) ).
plain_value(L, Vs) :- is_list(L), !, maplist(plain_value, L, Vs).
plain_value(V, V).
