/*  KnowRob 2.x's own plunit tests for the predicates mirrored in prolog/, restated case by
    case (same names, same questions, same expected answers) over this repository's
    modules and fixtures. 60 tests: lang_triple 28, lang_temporal 6, lang_holds 4,
    model_RDFS 9, model_NEEM 9, model_terms 4. KnowRob marks two of them: 'non utf8
    character' fixme, 'holds/1 with ns' blocked; both run here and are not counted
    (knowrob_2x:knowrob_marked/2).
*/
:- use_module(knowrob_2x).
:- use_module('../neem_store', [store_reset/0]).
:- use_module('../lang/query').
:- use_module('../lang/scope').
:- use_module('../lang/temporal').
:- use_module('../lang/holds').
:- use_module('../lang/triple').
:- use_module('../lang/db').
:- use_module('../model/rdfs').
:- use_module('../model/event').
:- use_module('../model/object').
:- use_module('../model/situation').
:- use_module('../model/action').
:- use_module(library(semweb/rdf_prefixes)).

:- rdf_register_prefix(swrl_tests, 'http://knowrob.org/kb/swrl_test#', [keep(true)]).
:- rdf_register_prefix(test_datatype, 'http://knowrob.org/kb/datatype_test#', [keep(true)]).

iri(T, I) :- rdf_global_id(T, I).

                 /*******************************
                 *   lang/terms/triple.plt (28)  *
                 *******************************/

:- begin_tests(knowrob_lang_triple, [ setup(knowrob_suite_setup(none, 'http://knowrob.org/kb/swrl_test#')),
                              cleanup(store_reset) ]).

test('project(assign(C,c), triple(a,b,C))') :-
    assert_true(kb_project(( ask(assign(C, g)), triple(e, f, C) ))).

test('assert triple(a,b,c)') :-
    assert_true(kb_project(triple(a, b, c))).

test('assert triple(a,b,_)', [throws(error(instantiation_error, project(triple(a, b, _))))]) :-
    kb_project(triple(a, b, _)).

test('triple(a,b,c)') :-
    assert_true(kb_call(triple(a, b, c))),
    assert_false(kb_call(triple(x, b, c))),
    assert_false(kb_call(triple(a, x, c))),
    assert_false(kb_call(triple(a, b, x))).

test('triple(A,b,c)') :-
    kb_call(triple(A, b, c)),
    assert_equals(A, a),
    assert_false(kb_call(triple(_, x, c))).

test('triple(a,B,c)') :-
    kb_call(triple(a, B, c)),
    assert_equals(B, b),
    assert_false(kb_call(triple(x, _, c))).

test('triple(a,b,C)') :-
    kb_call(triple(a, b, C)),
    assert_equals(C, c),
    assert_false(kb_call(triple(a, x, _))).

test('triple(A,b,C)') :-
    kb_call(triple(A, b, C)),
    assert_equals(A, a),
    assert_equals(C, c),
    assert_false(kb_call(triple(_, x, _))).

test('load local owl file') :-
    knowrob_fixture(family, F1), knowrob_fixture(lecturers, F2),
    assert_true(load_owl(F1, [parent_graph(test)])),
    assert_true(load_owl(F2, [parent_graph(test)])).

test('query triple') :-
    assert_true(kb_call(triple(swrl_tests:'Adult', rdfs:subClassOf, swrl_tests:'TestThing'))).

test('retract triple') :-
    assert_true(kb_unproject(triple(swrl_tests:'Adult', rdfs:subClassOf, swrl_tests:'TestThing'))),
    assert_false(kb_call(triple(swrl_tests:'Adult', rdfs:subClassOf, swrl_tests:'TestThing'))).

test('assert to triplestore and check if triple exists') :-
    assert_true(kb_project(triple(swrl_tests:'Adult', rdfs:subClassOf, swrl_tests:'TestThing'))),
    assert_true(kb_call(triple(swrl_tests:'Adult', rdfs:subClassOf, swrl_tests:'TestThing'))),
    assert_false(kb_call(triple(swrl_tests:'Adult', rdfs:subClassOf, swrl_tests:'Car'))).

test('assert XSD') :-
    iri(test_datatype:'Lecturer3', S),
    assert_true(kb_project(triple(S, test_datatype:first_name, 'Johana$'))),
    assert_true(kb_project(triple(S, test_datatype:last_name, 'Muller'))),
    assert_true(kb_project(triple(S, test_datatype:studentId, 212123))),
    assert_true(kb_project(triple(S, test_datatype:height, 5.10))).

test('query XSD') :-
    assert_true(forall(kb_call(triple(_, test_datatype:studentId, X)), number(X))),
    assert_true(forall(kb_call(triple(_, test_datatype:first_name, Y)), atom(Y))),
    assert_true(forall(kb_call(triple(_, test_datatype:last_name, Z)), atom(Z))),
    assert_true(forall(kb_call(triple(_, test_datatype:height, H)), float(H))).

test('assert list') :-
    iri(test_datatype:'Lecturer3', S),
    Hair = [255, 99, 71],
    assert_true(kb_project(triple(S, test_datatype:hasHairColor, term(Hair)))),
    assert_true(kb_call(triple(S, test_datatype:hasHairColor, term(Hair)))),
    kb_call(triple(S, test_datatype:hasHairColor, term(Actual))),
    assert_equals(Actual, Hair).

test('assert with scope') :-
    iri(test_datatype:'Lecturer4', S), iri(test_datatype:last_name, P),
    time_scope(=(double(5)), =(double(10)), Scope1),
    time_scope(=(double(5)), =(double(20)), Scope2),
    kb_project(triple(S, P, 'Spiendler'), Scope1),
    assert_true(kb_call(triple(S, P, 'Spiendler'), Scope1, _)),
    assert_false(kb_call(triple(S, P, 'Spiendler'), Scope2, _)).

test('extend time scope') :-
    iri(test_datatype:'Lecturer4', S), iri(test_datatype:last_name, P),
    time_scope(=(double(10)), =(double(20)), Scope1),
    time_scope(=(double(5)), =(double(20)), Scope2),
    kb_project(triple(S, P, 'Spiendler'), Scope1),
    assert_true(kb_call(triple(S, P, 'Spiendler'), Scope2, _)).

test('query value operators') :-
    R = swrl_tests:'RectangleSmall', H = swrl_tests:hasHeightInMeters,
    assert_true(kb_call(triple(R, H, =(6)))),
    assert_true(kb_call(triple(R, H, =<(9)))),
    assert_true(kb_call(triple(R, H, <(7)))),
    assert_true(kb_call(triple(R, H, >=(5)))),
    assert_true(kb_call(triple(R, H, >(3.5)))),
    assert_false(kb_call(triple(R, H, <(3)))).

test('query operator in') :-
    findall(Last,
            kb_call(triple(in(array([string(test_datatype:'Lecturer3'), string(test_datatype:'Lecturer4')])),
                           test_datatype:last_name, Last)),
            Names),
    assert_equals(Names, ['Muller']).

test('query operator in + ->') :-
    findall([L, Last],
            kb_call(triple(in(array([string(test_datatype:'Lecturer3'), string(test_datatype:'Lecturer4')])) -> L,
                           test_datatype:last_name, Last)),
            Rows),
    assert_equals(Rows, [[test_datatype:'Lecturer3', 'Muller']]).

test('non alphabetic character') :-
    assert_true(kb_project(triple(test_datatype:normal_user_test_new, test_datatype:'last@*~!#?_name', umlaut))),
    assert_true(kb_call(triple(test_datatype:normal_user_test_new, test_datatype:'last@*~!#?_name', umlaut))).

test('non utf8 character') :-          % KnowRob: fixme (its BSON reader)
    kb_project(triple(test_datatype:'Lecturer3', test_datatype:last_name, 'Müller')),
    assert_true(kb_call(triple(test_datatype:'Lecturer3', test_datatype:last_name, 'Müller'))).

test('non existant') :-
    assert_false(kb_call(triple(test_datatype:xyz, test_datatype:last_name, _))).

test('triple(+,transitive(+),+') :-
    assert_true(kb_call(triple(swrl_tests:'Rex', transitive(swrl_tests:isParentOf), swrl_tests:'Ernest'))),
    assert_true(kb_call(triple(swrl_tests:'Rex', transitive(swrl_tests:isParentOf), swrl_tests:'Lea'))),
    assert_false(kb_call(triple(swrl_tests:'Rex', transitive(swrl_tests:isParentOf), swrl_tests:'Person'))).

test('triple(-,transitive(+),+') :-
    findall(X, kb_call(triple(X, transitive(swrl_tests:isParentOf), swrl_tests:'Lea')), Ancestors),
    assert_unifies(Ancestors, [_, _]),
    assert_true(member(swrl_tests:'Fred', Ancestors)),
    assert_true(member(swrl_tests:'Rex', Ancestors)),
    assert_false(member(swrl_tests:'Ernest', Ancestors)).

test('triple(+,reflexive(transitive(+)),-)') :-
    findall(X, kb_call(triple(swrl_tests:'Rex', transitive(reflexive(swrl_tests:isParentOf)), X)), Reached),
    length(Reached, N),
    assert_equals(N, 4),
    assert_true(member(swrl_tests:'Rex', Reached)),
    assert_true(member(swrl_tests:'Ernest', Reached)),
    assert_true(member(swrl_tests:'Fred', Reached)),
    assert_true(member(swrl_tests:'Lea', Reached)).

test('call(+Triple)') :-
    assert_true(kb_call(call(triple(swrl_tests:'Rex', swrl_tests:isParentOf, swrl_tests:'Ernest')))),
    assert_false(kb_call(call(triple(swrl_tests:'Rex', swrl_tests:isParentOf, test_datatype:'Lecturer3')))).

test('call_with_context(+Triple,+Context)') :-
    assert_true(test_call(
        call_with_context(triple(swrl_tests:'Rex', swrl_tests:isParentOf, swrl_tests:'Ernest'),
                          [scope(dict{time: dict{since: =<(T), until: >=(T)}})]), T, 999)),
    assert_false(test_call(
        call_with_context(triple(swrl_tests:'Rex', swrl_tests:isParentOf, swrl_tests:'Rex'),
                          [scope(dict{time: dict{since: =<(T), until: >=(T)}})]), T, 999)).

:- end_tests(knowrob_lang_triple).

                 /*******************************
                 *  lang/terms/temporal.pl (6)  *
                 *******************************/

:- begin_tests(knowrob_lang_temporal, [ setup(knowrob_suite_setup(family, 'http://knowrob.org/kb/swrl_test#')),
                                cleanup(store_reset) ]).

test('during(+Triple,+Interval)') :-
    N = test:hasNumber,
    assert_true(kb_project(triple(test:'Lea', N, '+493455247') during [10, 34])),
    assert_true(kb_call(triple(test:'Lea', N, '+493455247') during [10, 34])),
    assert_true(kb_call(triple(test:'Lea', N, '+493455247') during [14, 24])),
    assert_false(kb_call(triple(test:'Lea', N, '+999999999') during [5, 20])),
    assert_false(kb_call(triple(test:'Lea', N, '+493455249') during [12, 20])),
    assert_false(kb_call(triple(test:'Lea', N, '+493455247') during [5, 20])),
    assert_false(kb_call(triple(test:'Lea', N, '+493455247') during [34, 44])).

test('during(+Triple,+Overlapping)') :-
    N = test:hasNumber,
    assert_true(kb_project(triple(test:'Lea', N, '+493455249') during [44, 84])),
    assert_true(kb_project(triple(test:'Lea', N, '+493455249') during [24, 54])),
    assert_true(kb_call(triple(test:'Lea', N, '+493455249') during [34, 44])),
    assert_true(kb_call(triple(test:'Lea', N, '+493455249') during [38, 80])),
    assert_false(kb_call(triple(test:'Lea', N, '+493455247') during [140, 240])).

test('during(+Triple,[-Since,-Until])') :-
    N = test:hasNumber,
    assert_true(kb_call(triple(test:'Lea', N, '+493455247') during [_, _])),
    kb_call(triple(test:'Lea', N, '+493455247') during [Since, Until]),
    assert_equals([Since, Until], [10.0, 34.0]).

test('during(+Triple,-Interval)') :-
    N = test:hasNumber,
    assert_true(kb_call(triple(test:'Lea', N, '+493455247') during _)),
    kb_call(triple(test:'Lea', N, '+493455247') during X),
    assert_equals(X, [10.0, 34.0]).

test('since(+Triple,+Instant)') :-
    N = test:hasNumber,
    assert_false(kb_call(triple(test:'Lea', N, '+499955247') since 800)),
    assert_true(kb_project(triple(test:'Lea', N, '+499955247') since 800)),
    assert_true(kb_call(triple(test:'Lea', N, '+499955247') since 800)),
    assert_true(kb_call(triple(test:'Lea', N, '+499955247') since 1000)),
    assert_false(kb_call(triple(test:'Lea', N, '+499955247') since 600)).

test('until(+Triple,+Instant)') :-
    N = test:hasNumber,
    assert_true(kb_call(triple(test:'Lea', N, '+499955247') until 1000)),
    assert_true(kb_project(triple(test:'Lea', N, '+499955247') until 900)),
    assert_true(kb_call(triple(test:'Lea', N, '+499955247') until 900)),
    assert_false(kb_call(triple(test:'Lea', N, '+499955247') until 1000)).

:- end_tests(knowrob_lang_temporal).

                 /*******************************
                 *   lang/terms/holds.pl (4)    *
                 *******************************/

:- begin_tests(knowrob_lang_holds, [ setup(knowrob_suite_setup(family, 'http://knowrob.org/kb/swrl_test#')),
                             cleanup(store_reset) ]).

test('holds/1 with ns') :-             % KnowRob: blocked ('holds/1 cannot handle namespaces')
    assert_true(holds(test:'hasHeightInMeters'(test:'RectangleBig', 13))).

test('holds(+S,+P,+O)') :-
    assert_true(holds(test:'Ernest', test:hasSibling, test:'Fred')).

test('project(holds(+S,+P,+O))') :-
    assert_false(holds(test:'Lea', test:hasNumber, '+493564754647')),
    assert_true(kb_project(holds(test:'Lea', test:hasNumber, '+493564754647'))),
    assert_true(holds(test:'Lea', test:hasNumber, '+493564754647')).

test('holds(+S,+P,+Unit(+O))') :-
    H = test:hasHeightInMeters,
    assert_false(holds(test:'Lea', H, _)),
    assert_true(kb_project(holds(test:'Lea', H, m(6.5)))),
    assert_true(holds(test:'Lea', H, cm(650))),
    assert_true(holds(test:'Lea', H, cm(650.0))),
    assert_false(holds(test:'Lea', H, cm(750.0))),
    assert_false(holds(test:'Lea', H, cm(600.0))),
    assert_true(holds(test:'Lea', H, cm(_))),
    holds(test:'Lea', H, cm(X)),
    assert_equals(X, 650.0).

:- end_tests(knowrob_lang_holds).

                 /*******************************
                 *       model/RDFS.pl (9)      *
                 *******************************/

:- begin_tests(knowrob_model_rdfs, [ setup(knowrob_suite_setup(family, 'http://knowrob.org/kb/swrl_test#')),
                             cleanup(store_reset) ]).

test('is_resource(+Resource)') :-
    assert_true(is_resource(test:'Adult')),
    assert_false(is_resource(test:'Lea')),
    assert_false(is_resource(test:hasNumber)),
    assert_false(is_resource(test:'NotExisting')).

test('is_property(+Property)') :-
    assert_true(is_property(test:hasNumber)),
    assert_false(is_property(test:'Lea')),
    assert_false(is_property(test:'NotExisting')).

test('instance_of(+,+)') :-
    assert_true(instance_of(test:'Rex', test:'Man')),
    assert_false(instance_of(test:'Rex', test:'Adult')),
    assert_true(kb_project(instance_of(test:'Rex', test:'Adult'))),
    assert_true(instance_of(test:'Rex', test:'Adult')).

test('subproperty_of(+Sub,+Sup)') :-
    assert_true(subproperty_of(test:hasParent, test:hasAncestor)),
    assert_false(subproperty_of(test:hasBrother, test:hasSibling)),
    assert_true(kb_project(subproperty_of(test:hasBrother, test:hasSibling))),
    assert_true(subproperty_of(test:hasBrother, test:hasSibling)).

chain(L) :- kb_call(triple(test:testchain, owl:propertyChainAxiom, L)).

test('rdf_list(+,+)') :-
    chain(L),
    assert_true(rdf_list(L, [test:hasParent, test:hasAncestor])),
    assert_false(rdf_list(L, [test:hasAncestor, test:hasParent])),
    assert_false(rdf_list(L, [test:hasParent])).

test('rdf_list(+,-)') :-
    chain(L),
    assert_true(rdf_list(L, _)),
    rdf_list(L, Xs),
    assert_equals(Xs, [test:hasParent, test:hasAncestor]).

test('rdf_list(-,+)') :-
    chain(L1),
    assert_true(rdf_list(_, [test:hasParent, test:hasAncestor])),
    rdf_list(L2, [test:hasParent, test:hasAncestor]),
    assert_equals(L1, L2).

test('rdf_list(+,-),length(+,-)') :-
    kb_call(( triple(test:testchain, owl:propertyChainAxiom, L),
              rdf_list(L, Xs),
              length(Xs, N) )),
    assert_equals(N, 2).

test('rdf_list_head(+,-)') :-
    chain(L1),
    kb_call(triple(Sub, rdf:first, test:hasAncestor)),
    assert_true(kb_call(rdf_list_head(Sub, _))),
    kb_call(rdf_list_head(Sub, L2)),
    assert_equals(L2, L1).

:- end_tests(knowrob_model_rdfs).

                 /*******************************
                 *       model/NEEM.pl (9)      *
                 *******************************/

:- dynamic neem_episode/1, neem_action/1.

:- begin_tests(knowrob_model_neem, [ setup(knowrob_suite_setup(episode, 'http://knowrob.org/kb/mem-test.owl#')),
                             cleanup(( store_reset, retractall(neem_episode(_)), retractall(neem_action(_)) )) ]).

test('is_episode') :-
    kb_call(new_iri(E, dul:'Situation')),
    kb_project(is_episode(E)),
    assert_true(ground(E)),
    assert_true(is_episode(E)),
    assertz(neem_episode(E)).

test('is_setting_for') :-
    neem_episode(E),
    kb_call(new_iri(A, dul:'Action')),
    kb_project(is_action(A)),
    assert_true(ground(A)),
    assert_true(is_action(A)),
    assert_false(is_setting_for(E, A)),
    assert_true(kb_project(is_setting_for(E, A))),
    assert_true(is_setting_for(E, A)),
    assertz(neem_action(A)).

test('occurs') :-
    neem_action(A),
    assert_false(occurs(A) during [24, 464]),
    assert_true(kb_project(occurs(A) during [24, 464])),
    assert_true(occurs(A) during [24, 464]).

test('executes_task') :-
    neem_action(A),
    kb_call(new_iri(T, test:'TestTask')),
    kb_project(has_type(T, test:'TestTask')),
    assert_true(ground(T)),
    assert_true(is_task(T)),
    assert_false(executes_task(A, T)),
    assert_true(kb_project(executes_task(A, T))),
    assert_true(executes_task(A, T)).

test('has_participant') :-
    neem_action(A),
    iri(test:'Substance_0', O),
    assert_false(has_participant(A, O)),
    assert_true(kb_project(has_participant(A, O))),
    assert_true(has_participant(A, O)).

test('has_role') :-
    neem_action(A),
    iri(test:'Substance_0', O),
    kb_call(new_iri(R, test:'ARole')),
    kb_project(has_type(R, test:'ARole')),
    assert_false(has_role(O, R) during A),
    assert_true(kb_project(has_role(O, R) during A)),
    assert_true(has_role(O, R) during A).

test('has_transition') :-
    iri(test:'TestColor_0', Q),
    assert_true(kb_project(has_region(Q, test:'TEST_GREEN') until 300)),
    assert_true(kb_project(has_region(Q, test:'TEST_RED') since 300)),
    assert_true(has_region(Q, test:'TEST_RED')),
    assert_false(has_region(Q, test:'TEST_GREEN')),
    assert_true(has_region(Q, test:'TEST_GREEN') during [200, 250]).

test('action_succeeded') :-
    neem_action(A),
    assert_false(action_succeeded(A)),
    assert_true(kb_project(action_succeeded(A))),
    assert_true(action_succeeded(A)).

test('is_masterful') :-
    neem_episode(E),
    kb_call(new_iri(M)),
    kb_project(has_type(M, test:'Masterful')),
    assert_true(ground(M)),
    assert_true(is_diagnosis(M)),
    assert_false(satisfies(E, M)),
    assert_true(kb_project(satisfies(E, M))),
    assert_true(satisfies(E, M)).

:- end_tests(knowrob_model_neem).

                 /*******************************
                 *      model/terms.pl (4)      *
                 *******************************/

:- begin_tests(knowrob_model_terms, [ setup(knowrob_suite_setup(events, 'http://knowrob.org/kb/test_events.owl#')),
                              cleanup(store_reset) ]).

test('during(occurs(+),+Interval)') :-
    assert_true(occurs(test:'Short4') during [1377777009, 1377777011]),
    assert_true(occurs(test:'Short4') during [1377777010, 1377777011]),
    assert_true(occurs(test:'Short4') during [1377777001, 1377777009]),
    assert_true(occurs(test:'Short4') during [1377777011, 1377777019]),
    assert_false(occurs(test:'Short4') during [1377777012, 1377777019]),
    assert_false(occurs(test:'Short4') during [1377777001, 1377777004]).

test('assert(during(occurs(+),+Interval))') :-
    assert_false(occurs(a) during [8, 12]),
    assert_true(kb_project(occurs(a) during [8, 12])),
    assert_true(occurs(a) during [8, 12]),
    assert_true(occurs(a) during [10, 20]),
    assert_false(occurs(a) during [5, 7]).

test('during(occurs(+),+Event)') :-
    assert_true(occurs(test:'Short1') during test:'Short1'),
    assert_true(occurs(test:'Long') during test:'Short1'),
    assert_true(occurs(test:'Long') during test:'Short3'),
    assert_true(occurs(test:'Long') during test:'Short4'),
    assert_false(occurs(test:'Short1') during test:'Short3'),
    assert_false(occurs(test:'Short1') during test:'Short4').

test('assert(during(occurs(+),+Event))') :-
    assert_true(kb_project(occurs(test:'Event6') during test:'Short1')),
    assert_true(occurs(test:'Event6') during test:'Short1').

:- end_tests(knowrob_model_terms).

                 /*******************************
                 *      lang/scope.pl (14)      *
                 *******************************/

:- begin_tests(knowrob_lang_scope).

test('scope_data([3,20])') :-
    time_scope(=(3), =(20), S),
    time_scope_data(S, Data),
    assertion(ground(Data)),
    assertion(Data = [3, 20]).

test('scope_data([3,>=20])') :-
    time_scope(=(3), >=(20), S),
    time_scope_data(S, Data),
    assertion(ground(Data)),
    assertion(Data = [3, >=(20)]).

test('scope_data([=<3,20])') :-
    time_scope(=<(3), =(20), S),
    time_scope_data(S, Data),
    assertion(ground(Data)),
    assertion(Data = [=<(3), 20]).

test('subscope_of(current,universal)') :-
    universal_scope(S1),
    current_scope(S2),
    assertion(subscope_of(S2, S1)).

test('subscope_of([15,18],[10,20])') :-
    time_scope(=(10), =(20), S1), time_scope(=(15), =(18), S2),
    assertion(subscope_of(S2, S1)),
    assertion(\+ subscope_of(S1, S2)).

test('subscope_of([15,18],[15,20])') :-
    time_scope(=(15), =(20), S1), time_scope(=(15), =(18), S2),
    assertion(subscope_of(S2, S1)),
    assertion(\+ subscope_of(S1, S2)).

test('subscope_of([15,18],[15,18])') :-
    time_scope(=(15), =(18), S1), time_scope(=(15), =(18), S2),
    assertion(subscope_of(S2, S1)),
    assertion(subscope_of(S1, S2)).

test('subscope_of([15,18],[10,>=20])') :-
    time_scope(=(10), >=(20), S1), time_scope(=(15), =(18), S2),
    assertion(subscope_of(S2, S1)),
    assertion(\+ subscope_of(S1, S2)).

test('intersect_scope([5,18],[10,20])') :-
    time_scope(=(5), =(18), S1), time_scope(=(10), =(20), S2),
    scope_intersect(S1, S2, S3),
    time_scope_data(S3, Data),
    assertion(ground(Data)),
    assertion(Data = [10, 18]).

test('intersect_scope([5,10],[10,20])') :-
    time_scope(=(5), =(10), S1), time_scope(=(10), =(20), S2),
    scope_intersect(S1, S2, S3),
    time_scope_data(S3, Data),
    assertion(ground(Data)),
    assertion(Data = [10, 10]).

test('intersect_scope([5,9],[10,20])') :-
    time_scope(=(5), =(9), S1), time_scope(=(10), =(20), S2),
    assertion(\+ scope_intersect(S1, S2, _)).

test('intersect_scope([5,18],[10,>=20])') :-
    time_scope(=(5), =(18), S1), time_scope(=(10), >=(20), S2),
    scope_intersect(S1, S2, S3),
    time_scope_data(S3, Data),
    assertion(ground(Data)),
    assertion(Data = [10, 18]).

test('intersect_scope([5,>=18],[10,>=20])') :-
    time_scope(=(5), >=(18), S1), time_scope(=(10), >=(20), S2),
    scope_intersect(S1, S2, S3),
    time_scope_data(S3, Data),
    assertion(ground(Data)),
    assertion(Data = [10, >=(18)]).

:- end_tests(knowrob_lang_scope).
