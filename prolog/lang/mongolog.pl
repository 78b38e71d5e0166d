:- module(kb_mongolog,
    [ mongolog_call/1,          % :Goal
      mongolog_call/2,          % :Goal, +Context
      is_mongolog_predicate/1   % +Indicator
    ]).
/** <module> mongolog's entry points (KnowRob 2.x src/lang/mongolog/mongolog.pl)

In KnowRob, mongolog_call/1,2 compile a goal into one MongoDB aggregation pipeline. Here
kb_call/1,2 compile it into one store query on every backend (SQLite, MongoDB, the memory
backend), so mongolog_call is kb_call. is_mongolog_predicate/1 tells whether the compiler
knows a predicate (a model rule, triple/3, holds/1,3, the scope operators, ...), rather than
calling it as plain Prolog.
*/

:- use_module(library(error)).
:- use_module(query, [kb_call/1, kb_call/2]).

:- meta_predicate mongolog_call(0), mongolog_call(0, +).

%!  mongolog_call(:Goal) is nondet.
mongolog_call(Goal) :- kb_call(Goal).

%!  mongolog_call(:Goal, +Context) is nondet.
%   Context is mongolog's option list: `scope(Scope)` sets the question scope (default now).
mongolog_call(Goal, Context) :-
    must_be(list, Context),
    (   memberchk(scope(Scope), Context) -> kb_call(Goal, Scope) ; kb_call(Goal) ).

%!  is_mongolog_predicate(+Indicator) is semidet.
%   Name/Arity (or a goal of it) is compiled by kb_call/1 rather than called as Prolog.
is_mongolog_predicate(Ind) :-
    must_be(nonvar, Ind),
    (   Ind = Name/Arity -> must_be(atom, Name), must_be(nonneg, Arity), functor(G, Name, Arity)
    ;   G = Ind
    ),
    (   functor(G, F, N), memberchk(F/N, [triple/3, holds/1, holds/3, has_type/2, occurs/1, during/2, since/2,
                                          until/2, call_with_context/2, assign/2, pragma/1])
    ->  true
    ;   functor(G, F, N), functor(G0, F, N), once(kb_query:kb_rule(G0, _))
    ).
