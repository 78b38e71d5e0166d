:- module(soma_action,
    [ action_status/2,          % ?Action, ?Status
      action_succeeded/1,       % ?Action
      action_failed/1,          % ?Action
      action_active/1,          % ?Action
      action_paused/1,          % ?Action
      action_pending/1,         % ?Action
      action_cancelled/1        % ?Action
    ]).
/** <module> Action execution status (KnowRob 2.x src/model/SOMA.pl)

An action's status is its soma:hasExecutionState (soma:ExecutionState_Succeeded, _Failed,
_Active, _Paused, _Pending, _Cancelled; the logger writes what the robot reports:
succeeded, failed or cancelled). Each predicate queries through kb_call/1 and projects through
kb_project/1 (`kb_project(action_succeeded(A))`).
*/

:- use_module('../lang/query', [kb_call/1]).

:- multifile kb_query:kb_rule/2.
kb_query:kb_rule(action_status(A, S), holds(A, soma:hasExecutionState, S)).
kb_query:kb_rule(action_succeeded(A), action_status(A, soma:'ExecutionState_Succeeded')).
kb_query:kb_rule(action_failed(A), action_status(A, soma:'ExecutionState_Failed')).
kb_query:kb_rule(action_active(A), action_status(A, soma:'ExecutionState_Active')).
kb_query:kb_rule(action_paused(A), action_status(A, soma:'ExecutionState_Paused')).
kb_query:kb_rule(action_pending(A), action_status(A, soma:'ExecutionState_Pending')).
kb_query:kb_rule(action_cancelled(A), action_status(A, soma:'ExecutionState_Cancelled')).

%!  action_status(?Action, ?Status) is nondet.
action_status(A, S) :- kb_call(action_status(A, S)).
%!  action_succeeded(?Action) is nondet.
action_succeeded(A) :- kb_call(action_succeeded(A)).
%!  action_failed(?Action) is nondet.
action_failed(A) :- kb_call(action_failed(A)).
%!  action_active(?Action) is nondet.
action_active(A) :- kb_call(action_active(A)).
%!  action_paused(?Action) is nondet.
action_paused(A) :- kb_call(action_paused(A)).
%!  action_pending(?Action) is nondet.
action_pending(A) :- kb_call(action_pending(A)).
%!  action_cancelled(?Action) is nondet.
action_cancelled(A) :- kb_call(action_cancelled(A)).
