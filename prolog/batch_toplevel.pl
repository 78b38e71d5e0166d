:- module(batch_toplevel,
          [ batch_queries/3,   % +In, +Max, -Status
            batch_goal/2       % +GoalText, -Status
          ]).

/** <module> Queries from a pipe or a script, answered without asking

SWI-Prolog's interactive toplevel asks after each answer whether the user wants
another; read from a pipe, it takes the next query's text as that reply. This
module reads the queries one by one, prints every answer (or the first Max) the
way the toplevel writes them, and reports in Status whether any query raised an
error, so a script can exit non-zero. `-g Goal` runs one goal as `swipl -g` does.
*/

:- use_module(library(error)).
:- use_module(library(solution_sequences)).

%!  batch_queries(+In, +Max, -Status) is det.
%
%   Answer each query read from stream In until end of file. Max is a positive
%   integer or `inf`: how many answers of each query to print. Status is 0, or 1
%   when a query could not be read or raised an error (each printed on
%   user_error). A query `halt.` ends the batch.
batch_queries(In, Max, Status) :-
    must_be(stream, In),
    (   Max == inf -> true ; must_be(positive_integer, Max) ),
    State = status(0),
    batch_loop(In, Max, State),
    arg(1, State, Status).

batch_loop(In, Max, State) :-
    catch(read_term(In, Query, [variable_names(Names)]), Error, true),
    (   nonvar(Error)
    ->  print_message(error, Error),
        nb_setarg(1, State, 1),
        (   at_end_of_stream(In) -> true ; batch_loop(In, Max, State) )
    ;   Query == end_of_file
    ->  true
    ;   Query == halt
    ->  true
    ;   answer_query(Query, Names, Max, State),
        batch_loop(In, Max, State)
    ).

answer_query(Query, Names, Max, State) :-
    Count = count(0),
    catch(forall(limited(Max, user:Query), print_answer(Names, Count)), Error, true),
    arg(1, Count, N),
    (   nonvar(Error)
    ->  (N > 0 -> format(".~n") ; true),
        print_message(error, Error),
        nb_setarg(1, State, 1)
    ;   N =:= 0
    ->  format("false.~n")
    ;   format(".~n")
    ),
    flush_output.

limited(inf, Goal) :- !, call(Goal).
limited(Max, Goal) :- limit(Max, Goal).

print_answer(Names, Count) :-
    arg(1, Count, N0),
    (N0 > 0 -> format(" ;~n") ; true),
    N is N0 + 1,
    nb_setarg(1, Count, N),
    include(shown, Names, Shown),
    (   Shown == []
    ->  format("true")
    ;   print_bindings(Shown, Names)
    ).

shown(Name = _) :- \+ sub_atom(Name, 0, _, _, '_').

print_bindings([], _).
print_bindings([Name = Value | More], Names) :-
    format("~w = ", [Name]),
    write_term(Value, [quoted(true), portray(true), variable_names(Names), max_depth(0)]),
    (More == [] -> true ; format(",~n")),
    print_bindings(More, Names).

%!  batch_goal(+GoalText, -Status) is det.
%
%   Run GoalText once, as `swipl -g GoalText` does: Status 0 when it succeeds,
%   1 when it fails or cannot be read, 2 when it raises an error (printed on
%   user_error).
batch_goal(GoalText, Status) :-
    must_be(text, GoalText),
    catch(term_string(Goal, GoalText), Error, true),
    (   nonvar(Error)
    ->  print_message(error, Error),
        Status = 1
    ;   goal_status(Goal, GoalText, Status)
    ),
    flush_output.

goal_status(Goal, GoalText, Status) :-
    catch(( user:Goal
          ->  Status = 0
          ;   print_message(error, format("-g ~w: false", [GoalText])),
              Status = 1
          ),
          Error,
          ( print_message(error, Error), Status = 2 )).
