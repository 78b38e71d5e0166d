:- module(kb_scope,
    [ universal_scope/1,        % -Scope
      current_scope/1,          % -Scope
      scope_check/1,            % +Scope
      scope_overlaps/3,         % +Scope, +Begin, +End
      runtime_scope/3,          % +Kind, +Argument, -Scope
      scope_term/2,             % +ScopeOrDict, -Scope
      scope_dict/2              % +Scope, -Dict
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
