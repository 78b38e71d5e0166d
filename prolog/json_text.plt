:- begin_tests(json_text).

:- use_module(json_text).
:- use_module(library(http/json)).   % the reference the text is read back with

% The value a JSON text stands for, read by library(http/json).
read_back(Text, Value) :-
    setup_call_cleanup(open_string(Text, In), json_read_dict(In, Value, []), close(In)).

% Our text and library(http/json)'s text of Term stand for the same value.
same_as_library(Term) :-
    json_text(Term, Ours),
    with_output_to(string(Theirs), json_write_dict(current_output, Term, [width(0)])),
    read_back(Ours, A),
    read_back(Theirs, B),
    A =@= B.

test(an_answer_shaped_dict) :-
    same_as_library(_{question: why_not, task: "pick(banana)", at: 1740988350.332759,
                      reasons: [_{reason: ranked_lower, rank: 2, score: 0.5,
                                  higher: [_{task: "pour(thermos,green_mug)", rank: 1, score: 0.25}]},
                                _{reason: user_chose, task: "open(fridge)", time: 17}]}).

test(literals_strings_and_atoms) :-
    json_text([true, false, null, "true", 'null x', ''], T),
    T == "[true,false,null,\"true\",\"null x\",\"\"]".

test(empty_containers) :-
    json_text(_{a: [], b: _{}}, T),
    T == "{\"a\":[],\"b\":{}}".

test(numbers) :-
    forall(member(N, [0, -7, 12345678901234567890123, 0.1, -0.0, 1.0e20, 1.5e-7, 3.0]),
           ( json_text([N], T), read_back(T, [M]), M =:= N )),
    same_as_library(_{n: [0.1, 1.0e20, 1.5e-7, 12345678901234567890123]}).

test(every_code_below_300_and_some_beyond) :-
    numlist(1, 300, Low),
    append(Low, [0x2028, 0x1F600, 0'", 0'\\, 0'/], Codes),
    string_codes(S, Codes),
    json_text(_{s: S, 'key "quoted"\n': S}, T),
    read_back(T, D),
    get_dict(s, D, S1), S1 == S,
    same_as_library(_{s: S}).

test(keys_in_standard_order) :-
    json_text(_{b: 1, a: 2, 3: x}, T),
    T == "{\"3\":\"x\",\"a\":2,\"b\":1}".

test(a_compound_is_no_json, [error(type_error(json, f(x)))]) :-
    json_text([f(x)], _).

test(an_infinite_float_is_no_json, [error(domain_error(finite_float, _))]) :-
    X is inf,
    json_text([X], _).

test(a_variable_is_no_json, [error(instantiation_error)]) :-
    json_text(_{a: _}, _).

test(data_text_keeps_every_atom_a_string) :-
    json_data_text([true, false, null, 'x y', "s", 3, [a]], T),
    T == "[\"true\",\"false\",\"null\",\"x y\",\"s\",3,[\"a\"]]".

test(data_text_writes_the_non_finite_floats_as_pythons_json_reads_them) :-
    Inf is inf, NegInf is -inf, NaN is nan,
    json_data_text([Inf, NegInf, NaN, 0.5], T),
    T == "[Infinity,-Infinity,NaN,0.5]".

test(data_text_of_a_compound_is_an_error, [error(type_error(json, f(x)))]) :-
    json_data_text([f(x)], _).

:- end_tests(json_text).
