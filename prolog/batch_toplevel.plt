:- begin_tests(batch_toplevel).

:- use_module(batch_toplevel).

% Run batch_queries/3 on Text; Out is what it printed, Status its status.
batch(Text, Max, Out, Status) :-
    setup_call_cleanup(open_string(Text, In),
                       with_output_to(string(Out), with_quiet_errors(batch_queries(In, Max, Status))),
                       close(In)).

with_quiet_errors(Goal) :-
    setup_call_cleanup(asserta((user:message_hook(_, error, _) :- true), Ref), Goal, erase(Ref)).

test(every_answer_of_a_query) :-
    batch("member(X, [a,b,c]).\n", inf, Out, Status),
    Out == "X = a ;\nX = b ;\nX = c.\n", Status == 0.

test(first_answers_only) :-
    batch("member(X, [a,b,c]).\n", 2, Out, _),
    Out == "X = a ;\nX = b.\n".

test(several_queries_true_and_false) :-
    batch("X = 1, Y = f(X).\ntrue.\nfail.\n", inf, Out, Status),
    Out == "X = 1,\nY = f(1).\ntrue.\nfalse.\n", Status == 0.

test(an_error_sets_the_status_and_the_batch_goes_on) :-
    batch("no_such_predicate_here.\nX = 2.\n", inf, Out, Status),
    Out == "X = 2.\n", Status == 1.

test(a_syntax_error_sets_the_status) :-
    batch("foo(.\nX = 3.\n", inf, Out, Status),
    once(sub_string(Out, _, _, _, "X = 3.")), Status == 1.

test(halt_ends_the_batch) :-
    batch("X = 1.\nhalt.\nX = 2.\n", inf, Out, Status),
    Out == "X = 1.\n", Status == 0.

test(quoted_atoms_as_the_toplevel_writes_them) :-
    batch("X = 'it''s'.\n", inf, Out, _),
    Out == "X = 'it\\'s'.\n".

test(goal_statuses) :-
    with_quiet_errors(( batch_goal("true", S0), batch_goal("fail", S1),
                        batch_goal("throw(oops)", S2), batch_goal("foo(", S3) )),
    [S0, S1, S2, S3] == [0, 1, 2, 1].

test(bad_max, [error(type_error(positive_integer, 0))]) :-
    open_string("true.\n", In), batch_queries(In, 0, _).

:- end_tests(batch_toplevel).
