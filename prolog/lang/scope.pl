:- module(kb_scope,
    [ universal_scope/1,        % -Scope
      current_scope/1,          % -Scope
      scope_check/1,            % +Scope
      scope_overlaps/3,         % +Scope, +Begin, +End
      runtime_scope/3,          % +Kind, +Argument, -Scope
      scope_term/2,             % +ScopeOrDict, -Scope
      scope_dict/2,             % +Scope, -Dict
      wildcard_scope/1,         % -Dict
      time_scope/3,             % ?Since, ?Until, ?Dict
      time_scope_data/2,        % +Scope, -[Since, Until]
      subscope_of/2,            % +Sub, +Sup
      scope_intersect/3         % +A, +B, -Intersection
    ]).
/** <module> Question scopes (KnowRob 2.x src/lang/scope.pl)

A question scope says which facts a query sees: `scope(Since, Until)` sees a fact whose
own time scope contains `[Since, Until]`, `any` sees every fact. KnowRob's default is
"now" (current_scope/1); NEEM narrative facts have universal scope, so they are seen at
any time. The temporal modifiers (kb_temporal) build scopes through runtime_scope/3 when
their argument is only known when the goal runs.
*/

:- use_module(library(error)).
:- use_module('../neem_store', [store_scope_now/1, store_match/2]).
:- use_module(triple, [kb_iri/2]).

%!  universal_scope(-Scope) is det.
%   The scope of a fact true at every time, `scope(0, inf)`.
universal_scope(scope(0.0, Inf)) :- Inf is inf.

%!  current_scope(-Scope) is det.
%   The question scope "now".
current_scope(Scope) :- store_scope_now(Scope).

%!  scope_check(+Scope) is det.
%   Scope is `any` or `scope(Since, Until)` with numbers; a type error otherwise.
scope_check(Scope) :-
    must_be(ground, Scope),
    (   Scope == any -> true
    ;   Scope = scope(S, U), number(S), number(U) -> true
    ;   type_error(scope, Scope)
    ).

%!  scope_overlaps(+Scope, +Begin, +End) is semidet.
%   The interval [Begin, End] overlaps the question scope.
scope_overlaps(any, _, _) :- !.
scope_overlaps(scope(S, U), B, End) :-
    B =< U,
    End >= S.

%!  runtime_scope(+Kind, +Argument, -Scope) is det.
%   The question scope of `G during Argument` (Kind `during`: `[T0,T1]`, `[_,_]` for any
%   time, or an event with an interval), `G since T` (true since T and still now; a free T
%   is now), `G until T` (true at T; a free T is any time) and mongolog's
%   `call_with_context(G, [scope(Dict)])` (Kind `context`, see scope_term/2).
runtime_scope(during, I, any) :-
    I = [T0, T1], var(T0), var(T1), !.
runtime_scope(during, [T0, T1], scope(T0, T1)) :- !,
    must_be(number, T0), must_be(number, T1).
runtime_scope(during, E, scope(B, End)) :-
    kb_iri(E, E1),
    must_be(atomic, E1),
    event_bounds(E1, B, End).
runtime_scope(since, T, scope(T1, Now)) :-
    get_time(Now),
    ( number(T) -> T1 = T ; T1 = Now ).
runtime_scope(context, D, Scope) :- !,
    scope_term(D, Scope).
runtime_scope(until, T, Scope) :-
    (   var(T) -> Scope = any ; must_be(number, T), Scope = scope(T, T) ).

event_bounds(E, B, End) :-
    maplist(kb_iri, [dul:hasTimeInterval, soma:hasIntervalBegin, soma:hasIntervalEnd], [HI, Begin, EndP]),
    once(store_match([t(E, HI, I), t(I, Begin, B), t(I, EndP, End)], any)).

%!  scope_term(+ScopeOrDict, -Scope) is det.
%   A question scope from `any`, `scope(S,U)` or a KnowRob scope dictionary:
%   `dict{}` (no time filter), `dict{time: dict{since: Op(T0), until: Op(T1)}}` where
%   Op is `=<`, `>=`, `=`, `<` or `>` and T may be wrapped as `double(T)`; a missing end is
%   open (0 or inf).
scope_term(S, S) :- S == any, !.
scope_term(scope(A, B), scope(A, B)) :- !.
scope_term(D, Scope) :-
    is_dict(D), !,
    (   get_dict(time, D, Time)
    ->  must_be(dict, Time),
        ( get_dict(since, Time, S0) -> bound_value(S0, S) ; S = 0.0 ),
        ( get_dict(until, Time, U0) -> bound_value(U0, U) ; U is inf ),
        Scope = scope(S, U)
    ;   Scope = any
    ).
scope_term(X, _) :-
    type_error(scope, X).

bound_value(V, _) :- var(V), !, instantiation_error(V).
bound_value(double(V), X) :- !, bound_value(V, X).
bound_value(V, X) :-
    compound(V), V =.. [Op, A], memberchk(Op, [=<, >=, =, <, >]), !,
    bound_value(A, X).
bound_value(V, X) :-
    must_be(number, V), X = V.

%!  scope_dict(+Scope, -Dict) is det.
%   Scope as KnowRob's dictionary `dict{time: dict{since: S, until: U}}` (`dict{}` for any).
scope_dict(any, dict{}) :- !.
scope_dict(scope(S, U), dict{time: dict{since: S, until: U}}).

                 /*******************************
                 *  KNOWROB'S SCOPE DICTIONARIES *
                 *******************************/

%!  wildcard_scope(-Dict) is det.
%   The scope dictionary that sees every fact, `dict{}`.
wildcard_scope(dict{}).

%!  time_scope(?Since, ?Until, ?Dict) is det.
%   `dict{time: dict{since: Since, until: Until}}`, ends as KnowRob writes them (`=(5)`,
%   `=<(double(T))`, ...); also reads a dictionary without the `time` key.
time_scope(Since, Until, Scope) :-
    (   nonvar(Scope), is_dict(Scope), \+ get_dict(time, Scope, _)
    ->  Scope = dict{since: Since, until: Until}
    ;   Scope = dict{time: dict{since: Since, until: Until}}
    ).

%!  time_scope_data(+Scope, -Ends) is det.
%   Ends is `[Since, Until]` of a scope dictionary (or `scope(S,U)`): an `=` end as its
%   number, another comparison kept as `Op(Number)`, `double(...)` dropped, a missing end
%   left unbound.
time_scope_data(scope(S, U), [S, U]) :- !.
time_scope_data(Scope, [Since, Until]) :-
    must_be(dict, Scope),
    (   get_dict(time, Scope, Time) -> true ; Time = Scope ),
    end_data(since, Time, Since),
    end_data(until, Time, Until).

end_data(Key, Time, Value) :-
    (   get_dict(Key, Time, V0)
    ->  end_value(V0, Value)
    ;   true
    ).

end_value(V, _) :- var(V), !.
end_value(double(V), X) :- !, end_value(V, X).
end_value(V, X) :-
    compound(V), V =.. [Op, A], polarity(Op, _), !,
    end_value(A, A1),
    (   Op == (=) -> X = A1 ; X =.. [Op, A1] ).
end_value('Infinity', X) :- !, X is inf.
end_value(V, V).

%!  subscope_of(+Sub, +Sup) is semidet.
%   Every time of Sub is in Sup: Sup begins no later and ends no earlier.
subscope_of(Sub, Sup) :-
    time_scope_data(Sub, [S0, U0]),
    time_scope_data(Sup, [S1, U1]),
    earliest(S0, S1, E), E == S1,
    latest(U0, U1, L), L == U1.

%!  scope_intersect(+A, +B, -Intersection) is semidet.
%   The scope both hold in (fails when they do not meet); the wildcard `dict{}` is neutral.
scope_intersect(A, B, B) :- A == dict{}, !.
scope_intersect(A, B, A) :- B == dict{}, !.
scope_intersect(A, B, dict{time: Time}) :-
    time_scope_data(A, [S0, U0]),
    time_scope_data(B, [S1, U1]),
    latest(S0, S1, S), ground(S),
    earliest(U0, U1, U),
    (   var(U) -> true ; earliest(S, U, E), E == S ),
    (   ground(U) -> Time = dict{since: S, until: U} ; Time = dict{since: S} ).

%   The earlier / later of two ends. A plain number is an exact end; `=<(T)` is "at T or
%   before", `>=(T)` "at T or after", so at the same time `=<(T)` is earlier and `>=(T)` later;
%   an unbound end is open (never the earlier one, always the later one).
earliest(A, B, M) :- var(A), !, M = B.
earliest(A, B, M) :- var(B), !, M = A.
earliest(A, B, M) :-
    end_key(A, VA, PA), end_key(B, VB, PB),
    (   VA < VB -> M = A ; VB < VA -> M = B ; PA =< PB -> M = A ; M = B ).

latest(A, _, M) :- var(A), !, M = A.
latest(_, B, M) :- var(B), !, M = B.
latest(A, B, M) :-
    end_key(A, VA, PA), end_key(B, VB, PB),
    (   VA > VB -> M = A ; VB > VA -> M = B ; PA >= PB -> M = A ; M = B ).

end_key(E, V, P) :-
    (   compound(E), E =.. [Op, V0], polarity(Op, P0) -> V = V0, P = P0 ; V = E, P = 0 ).

polarity(<, -1).
polarity(=<, -1).
polarity(=, 0).
polarity(>, 1).
polarity(>=, 1).
