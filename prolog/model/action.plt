:- begin_tests(soma_action).

:- use_module(action).
:- use_module('../lang/query').
:- use_module('../neem_store').

test(succeeded, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    \+ action_succeeded(act),
    kb_project(action_succeeded(act)),
    action_succeeded(act), \+ action_failed(act),
    action_status(act, S), S == 'http://www.ease-crc.org/ont/SOMA.owl#ExecutionState_Succeeded'.

test(failed_and_active, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project((action_failed(a), action_active(b))),
    action_failed(a), action_active(b), \+ action_paused(b).

test(cancelled_and_pending, [nondet, setup(store_reset), cleanup(store_reset)]) :-
    kb_project((action_cancelled(c), action_pending(d))),
    action_cancelled(c), action_pending(d), \+ action_cancelled(d), \+ action_succeeded(c).

:- end_tests(soma_action).
