:- module(test_episode, [load_test_episode/0]).
/** <module> A small logged episode in the memory backend, for the plunit suites

Two decisions of the robot (t=100 and t=200), each an imagined situation and an imagined
preference, the actions the user chose after them, and an idle gap:

  - t=100: available pick(apple) and pour(thermos, green_mug); preference ranks
    pour(thermos, green_mug) 1st (score 0.2) and pick(apple) 2nd (0.7); the user had the
    robot pour during [101, 110] (morning);
  - [110, 200]: idle;
  - t=200: available pick(apple) only, ranked 1st; picked during [201, 205].
*/

:- use_module(neem_store).
:- use_module(knowrob_model).
:- use_module(odb_model).

x(Local, IRI) :- atom_concat('http://example.org/neem#', Local, IRI).

t(S, P, O) :-
    maplist(iri, [S, P, O], [S1, P1, O1]),
    store_assert(triple(S1, P1, O1)).

iri(X, X) :- number(X), !.
iri(P:L, I) :- !, kb_iri(P:L, I).
iri(L, I) :- x(L, I).

%!  load_test_episode is det.
%   Reset the memory backend and assert the episode.
load_test_episode :-
    store_reset,
    kb_iri(odb:pour, Pour), kb_iri(soma:'RecipientRole', Target), kb_iri(soma:'PouredObject', Ref),
    odb_set_task_roles(Pour, Target, Ref),
    kb_iri(odb:pick, Pick), kb_iri(soma:'MovedObject', Moved),
    odb_set_task_roles(Pick, Moved, none),
    forall(member([C, P], [[dul:'Action', dul:'Event'], [soma:'PhysicalAction', dul:'Action'],
                           [soma:'MentalAction', dul:'Action'], [odb:pick, soma:'PickingUp'],
                           [soma:'PickingUp', dul:'Task'], [odb:pour, dul:'Task'],
                           [odb:'IdleTask', soma:'PhysicalTask'], [soma:'PhysicalTask', dul:'Task']]),
           t(C, rdfs:subClassOf, P)),
    t(rdfs_dummy, rdf:type, owl:'NamedIndividual'),
    objects,
    decision(1, 100, [pick1-pick-[apple1], pour1-pour-[thermos1, mug1]],
             [pour1-1-0.2, pick1-2-0.7]),
    action(a1, 101, 110, pour1, 'Morning'),
    task(idle1, 'IdleTask', []),
    action(a2, 110, 200, idle1, 'Morning'),
    decision(2, 200, [pick2-pick-[apple1]], [pick2-1-0.1]),
    task(pick3, pick, [apple1]),
    action(a3, 201, 205, pick3, 'Midday').

objects :-
    forall(member(O-C, [apple1-apple, thermos1-thermos, mug1-green_mug]),
           ( t(O, rdf:type, odb:C), t(O, rdf:type, owl:'NamedIndividual') )).

task(T, Class, Objects) :-
    t(T, rdf:type, odb:Class),
    t(T, rdf:type, owl:'NamedIndividual'),
    forall(nth1(I, Objects, O),
           ( role_class(Class, I, Objects, RC),
             atomic_list_concat([T, '_role', I], R),
             t(T, dul:isTaskOf, R), t(R, dul:classifies, O), t(R, rdf:type, RC) )).

role_class(pour, 1, [_, _], soma:'PouredObject') :- !.
role_class(pour, 2, [_, _], soma:'RecipientRole') :- !.
role_class(_, _, _, soma:'MovedObject').

interval(E, B, End, Part) :-
    atom_concat(E, '_ti', I),
    t(E, dul:hasTimeInterval, I),
    t(I, rdf:type, odb:Part),
    t(I, soma:hasIntervalBegin, B),
    t(I, soma:hasIntervalEnd, End).

action(A, B, E, T, Part) :-
    t(A, rdf:type, soma:'PhysicalAction'),
    t(A, dul:executesTask, T),
    t(A, soma:isPerformedBy, edan),
    forall(( kb_call(( task_role(T1, R), has_role(O, R) ), any), x(T, T1) ),
           ( x(O0, O), t(A, dul:hasParticipant, O0) )),
    Part0 = Part,
    interval(A, B, E, Part0).

decision(N, B, Available, Ranked) :-
    End is B + 0.5,
    atomic_list_concat([imagining, N], M),
    atomic_list_concat([imagine_task, N], MT),
    t(M, rdf:type, soma:'MentalAction'),
    t(M, dul:executesTask, MT), t(MT, rdf:type, soma:'Imagining'),
    interval(M, B, End, 'Morning'),
    forall(member(T-C-Os, Available),
           ( task(T, C, Os),
             atom_concat(T, '_plan', P),
             t(P, rdf:type, soma:'ActionExecutionPlan'),
             t(M, odb:imagines_situation, P), t(P, soma:isPlanFor, T) )),
    atomic_list_concat([reasoning, N], R),
    atomic_list_concat([reason_task, N], RT),
    atomic_list_concat([preference, N], PO),
    t(R, rdf:type, soma:'MentalAction'),
    t(R, dul:executesTask, RT), t(RT, rdf:type, soma:'Reasoning'),
    interval(R, B, End, 'Morning'),
    t(R, odb:imagines_preference, PO), t(PO, rdf:type, soma:'PreferenceOrder'),
    forall(member(T-Rank-Score, Ranked),
           ( t(PO, soma:orders, T), t(T, odb:hasPreferenceRank, Rank),
             t(T, odb:hasPreferenceScore, Score) )).
