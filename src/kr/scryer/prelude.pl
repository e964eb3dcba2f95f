:- use_module(library(lists)).
:- use_module(library(between)).
:- use_module(library(iso_ext)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(library(error)).
:- use_module(library(format)).
:- set_prolog_flag(unknown, fail).

not(G) :- \+ call(G).

% The engine's entry: every answer (Cap 0) or the first (Cap 1) of G as instances of T, under
% an inference budget; errors come back as err(E), an exhausted budget as budget. What goes
% back must be acyclic and of bounded size (scryer panics on cyclic answers, and turning a
% huge term, e.g. a deeply shared one, into text takes time without end).
'$goal_run'(T, G, Cap, Lim, R) :-
    catch(call_with_inference_limit('$goal_collect'(Cap, T, G, L), Lim, LR), E, true),
    flush_output,
    (   nonvar(E) -> R0 = err(E)
    ;   LR == inference_limit_exceeded -> R0 = budget
    ;   R0 = ok(L)
    ),
    (   \+ acyclic_term(R0) -> R = err(error(representation_error(cyclic_term), _))
    ;   '$goal_plain'(R0, 1000000, _, R1) -> R = R1
    ;   R = err(error(resource_error(memory), answer))
    ),
    write('\x1\goal-answer\x1\'), '$goal_write'(R), flush_output.
% The answer goes back as text the engine reads (scryer 0.10's Rust API reads lists of
% characters back wrong): functional notation, lists in brackets (not nested '.'/2 cells).
'$goal_write'(T) :-
    (   var(T) -> write_canonical(T)
    ;   T = [H|Tl] -> write('['), '$goal_write'(H), '$goal_write_tail'(Tl)
    ;   compound(T) -> T =.. [F|As], '$goal_write_name'(F), write('('), '$goal_write_args'(As), write(')')
    ;   atom(T), current_op(_, _, T) -> '$goal_write_quoted'(T)
    ;   write_canonical(T)
    ).
% A functor name the engine reads as a name, not as an operator (`':-'(a,b)`).
'$goal_write_name'(F) :-
    (   ( current_op(_, _, F) ; F == '{}' ; F == '[]' ) -> '$goal_write_quoted'(F)
    ;   writeq(F)
    ).
'$goal_write_quoted'(A) :-
    atom_chars(A, Cs), char_code(Q, 39), put_char(Q), '$goal_write_escaped'(Cs), put_char(Q).
% A backslash before every backslash and quote (written by code: no escapes to misread).
'$goal_write_escaped'([]).
'$goal_write_escaped'([C|Cs]) :-
    (   char_code(C, K), ( K =:= 92 ; K =:= 39 ) -> char_code(B, 92), put_char(B) ; true ),
    put_char(C), '$goal_write_escaped'(Cs).
'$goal_write_tail'(T) :-
    (   T == [] -> write(']')
    ;   nonvar(T), T = [H|Tl] -> write(','), '$goal_write'(H), '$goal_write_tail'(Tl)
    ;   write('|'), '$goal_write'(T), write(']')
    ).
'$goal_write_args'([A|As]) :-
    '$goal_write'(A), ( As == [] -> true ; write(','), '$goal_write_args'(As) ).
'$goal_collect'(0, T, G, L) :- findall(P, (call(G), '$goal_answer'(T, P)), L).
'$goal_collect'(1, T, G, L) :- ( call(G) -> '$goal_answer'(T, P), L = [P] ; L = [] ).
'$goal_answer'(T, P) :-
    (   '$goal_plain'(T, 1000000, _, P) -> true
    ;   acyclic_term(T) -> throw(error(resource_error(memory), answer))
    ;   throw(error(representation_error(cyclic_term), _))
    ).
% A copy of T whose lists are plain cells: scryer 0.10 keeps lists of characters packed, and
% copies them wrong (findall/3) and reads them back wrong (its Rust API).
'$goal_plain'(T, N0, N, P) :-
    N0 > 0, N1 is N0 - 1,
    (   var(T) -> P = T, N = N1
    ;   T = [H|Tl] -> P = [PH|PT], '$goal_plain'(H, N1, N2, PH), '$goal_plain'(Tl, N2, N, PT)
    ;   compound(T) -> T =.. [F|As], '$goal_plain_args'(As, N1, N, Ps), P =.. [F|Ps]
    ;   P = T, N = N1
    ).
'$goal_plain_args'([], N, N, []).
'$goal_plain_args'([A|As], N0, N, [P|Ps]) :-
    '$goal_plain'(A, N0, N1, P), '$goal_plain_args'(As, N1, N, Ps).

% Meta-calls go through '$goal_call': a goal built at run time gets the checks and rewrites
% that text.rs gives goals written in the program ('$goal_safe'), so it cannot reach files,
% processes, the network or the machine itself, nor escape the guards of big built-ins.
'$goal_call'(G) :- '$goal_check'(G), '$goal_safe'(G, S), call(S).
'$goal_call'(G, A) :- '$goal_extend'(G, [A], G1), '$goal_call'(G1).
'$goal_call'(G, A, B) :- '$goal_extend'(G, [A, B], G1), '$goal_call'(G1).
'$goal_call'(G, A, B, C) :- '$goal_extend'(G, [A, B, C], G1), '$goal_call'(G1).
'$goal_call'(G, A, B, C, D) :- '$goal_extend'(G, [A, B, C, D], G1), '$goal_call'(G1).
'$goal_call'(G, A, B, C, D, E) :- '$goal_extend'(G, [A, B, C, D, E], G1), '$goal_call'(G1).
'$goal_call'(G, A, B, C, D, E, F) :- '$goal_extend'(G, [A, B, C, D, E, F], G1), '$goal_call'(G1).
'$goal_extend'(G, Xs, G1) :-
    length(Xs, Extra), '$goal_check'(G, Extra),
    G =.. L0, append(L0, Xs, L1), G1 =.. L1.
'$goal_check'(G) :- '$goal_check'(G, 0).
'$goal_check'(G, Extra) :-
    (   var(G) -> throw(error(instantiation_error, call/1))
    ;   callable(G) -> functor(G, N, A0), A is A0 + Extra,
        (   '$goal_denied'(N, A) -> throw(error(permission_error(access, private_procedure, N/A), call/1))
        ;   true
        )
    ;   throw(error(type_error(callable, G), call/1))
    ).
% The run-time twin of text.rs's goal rewriting: control constructs are walked, every other
% goal is checked, guarded built-ins are renamed, and goal and closure arguments of
% meta-predicates ('$goal_meta'/4, from text.rs's table) are rewritten in turn.
'$goal_safe'(G, S) :- var(G), !, S = '$goal_call'(G).
'$goal_safe'((A, B), (SA, SB)) :- !, '$goal_safe'(A, SA), '$goal_safe'(B, SB).
'$goal_safe'((A ; B), S) :- nonvar(A), A = '*->'(C, T), !,
    '$goal_safe'(C, SC), '$goal_safe'(T, ST), '$goal_safe'(B, SB), S = '$goal_softcut'(SC, ST, SB).
'$goal_safe'((A ; B), (SA ; SB)) :- !, '$goal_safe'(A, SA), '$goal_safe'(B, SB).
'$goal_safe'((A -> B), (call(SA) -> SB)) :- !, '$goal_safe'(A, SA), '$goal_safe'(B, SB).
'$goal_safe'('*->'(A, B), (SA, SB)) :- !, '$goal_safe'(A, SA), '$goal_safe'(B, SB).
'$goal_safe'(G, S) :- '$goal_check'(G), functor(G, N, A), '$goal_leaf'(N, A, G, S).
'$goal_leaf'(call, A, G, S) :- A > 1, !, G =.. [call|Args], S =.. ['$goal_call'|Args].
'$goal_leaf'(N, 3, G, S) :- ( N == bagof ; N == setof ), !,
    G =.. [N, T, Q, L], '$goal_carets'(Q, SQ),
    ( '$goal_renamed'(N, 3, R) -> S =.. [R, T, SQ, L] ; S =.. [N, T, SQ, L] ).
'$goal_leaf'(N, A, G, S) :- '$goal_renamed'(N, A, R), !, G =.. [_|Args],
    ( R == '$goal_cmp' -> S =.. [R, N|Args] ; S =.. [R|Args] ).
'$goal_leaf'(N, A, G, S) :- '$goal_meta'(N, A, _, _), !,
    G =.. [N|Args], findall(P-X, '$goal_meta'(N, A, P, X), Ms), '$goal_meta_args'(Ms, Args, SArgs),
    S =.. [N|SArgs].
'$goal_leaf'(_, _, G, G).
'$goal_carets'(Q, S) :- nonvar(Q), Q = V^Q1, !, '$goal_carets'(Q1, S1), S = V^S1.
'$goal_carets'(Q, S) :- '$goal_safe'(Q, S).
'$goal_meta_args'([], Args, Args).
'$goal_meta_args'([P-X|Ms], Args0, Args) :-
    nth0(P, Args0, Arg), '$goal_meta_arg'(X, Arg, SArg),
    '$goal_replace'(P, Args0, SArg, Args1), '$goal_meta_args'(Ms, Args1, Args).
'$goal_meta_arg'(0, Arg, S) :- nonvar(Arg), !, '$goal_safe'(Arg, S).
'$goal_meta_arg'(_, Arg, '$goal_call'(Arg)) :- var(Arg), !.
'$goal_meta_arg'(X, Arg, S) :- '$goal_check'(Arg, X), functor(Arg, N, A0), A is A0 + X,
    ( '$goal_renamed'(N, A, _) -> S = '$goal_call'(Arg) ; S = Arg ).
'$goal_replace'(0, [_|T], X, [X|T]) :- !.
'$goal_replace'(P, [H|T], X, [H|T1]) :- P1 is P - 1, '$goal_replace'(P1, T, X, T1).

% length/2 as SWI's: a list longer than the memory budget of a query is refused before
% scryer builds it, and what is not a (partial) list is a type error.
'$goal_length'(L, N) :-
    (   integer(N), N > 100000000 -> throw(error(domain_error(list_length, N), length/2))
    ;   integer(N), N > 8000000 -> throw(error(resource_error(memory), length/2))
    ;   '$goal_tail'(L, T), nonvar(T), T \== [] -> throw(error(type_error(list, L), length/2))
    ;   length(L, N)
    ).
'$goal_tail'(L, T) :- ( nonvar(L), L = [_|L1] -> '$goal_tail'(L1, T) ; T = L ).

% number_codes/2 as SWI's: the text may be given as a string (here a list of characters).
'$goal_number_codes'(N, L) :-
    catch(( nonvar(L), L = [C|_], atom(C) -> number_chars(N, L) ; number_codes(N, L) ),
          error(syntax_error(_), _),
          throw(error(syntax_error(illegal_number), number_codes/2))).

% The standard order of terms as SWI's (and the native engine's): numbers compare by value,
% a float before an integer of the same value (scryer puts every float before every
% integer). A term's key is ordered by scryer as the term is by SWI.
'$goal_key'(X, K) :-
    (   var(X) -> K = X
    ;   number(X) -> '$goal_float'(X, F), ( integer(X) -> R = 1 ; R = 0 ), K = k(1, F, R, X)
    ;   atomic(X) -> K = k(2, X, 0, 0)
    ;   X = [H|T] -> '$goal_key'(H, KH), '$goal_key'(T, KT), K = k(3, [KH|KT], 0, 0)
    ;   X =.. [F|As], '$goal_keys_of'(As, Ks), C =.. [F|Ks], K = k(3, C, 0, 0)
    ).
'$goal_keys_of'([], []).
'$goal_keys_of'([X|Xs], [K|Ks]) :- '$goal_key'(X, K), '$goal_keys_of'(Xs, Ks).
'$goal_float'(X, F) :- catch(F is float(X), _, ( X > 0 -> F = 1.0e308 ; F = -1.0e308 )).
'$goal_compare'(O, A, B) :- '$goal_key'(A, KA), '$goal_key'(B, KB), compare(O, KA, KB).
'$goal_before'(A, B) :- '$goal_compare'(<, A, B).
'$goal_after'(A, B) :- '$goal_compare'(>, A, B).
'$goal_not_after'(A, B) :- \+ '$goal_compare'(>, A, B).
'$goal_not_before'(A, B) :- \+ '$goal_compare'(<, A, B).
'$goal_sort'(L, S) :- msort(L, S0), '$goal_dedup'(S0, S).
'$goal_dedup'([], []).
'$goal_dedup'([X], [X]) :- !.
'$goal_dedup'([X, Y|T], S) :- X == Y, !, '$goal_dedup'([X|T], S).
'$goal_dedup'([X|T], [X|S]) :- '$goal_dedup'(T, S).
'$goal_keysort'(Ps, S) :- must_be(list, Ps), '$goal_pair_keys'(Ps, KPs), keysort(KPs, S0), pairs_values(S0, S).
'$goal_pair_keys'([], []).
'$goal_pair_keys'([P|Ps], [K-P|Ks]) :-
    ( var(P) -> throw(error(instantiation_error, keysort/2)) ; true ),
    ( P = Key-_ -> '$goal_key'(Key, K) ; throw(error(type_error(pair, P), keysort/2)) ),
    '$goal_pair_keys'(Ps, Ks).
'$goal_setof'(T, G, S) :- bagof(T, G, L), '$goal_sort'(L, S).
ignore(G) :- ( call(G) -> true ; true ).

atom_number(A, N) :- var(A), !, number(N), number_chars(N, Cs), atom_chars(A, Cs).
atom_number(A, N) :- atom_chars(A, Cs), catch(number_chars(N0, Cs), _, fail), N = N0.

% SWI arithmetic, and integers of at most about a million bits (scryer would compute
% 3^(2^100) until memory runs out): products, powers and shifts are checked before they are
% computed, every other result after.
'$goal_is'(X, E) :- '$goal_eval'(E, V), X = V.
'$goal_cmp'(Op, A, B) :- '$goal_eval'(A, VA), '$goal_eval'(B, VB), G =.. [Op, VA, VB], call(G).
'$goal_eval'(E, V) :- var(E), !, V is E.
'$goal_eval'(A / B, V) :- !, '$goal_eval'(A, VA), '$goal_eval'(B, VB),
    ( integer(VA), integer(VB), VB =\= 0, VA mod VB =:= 0 -> V is VA // VB ; V is VA / VB ).
'$goal_eval'(A ** B, V) :- !, '$goal_eval'(A, VA), '$goal_eval'(B, VB),
    ( integer(VA), integer(VB), VB >= 0 -> '$goal_big'(^, VA, VB), V is VA ^ VB ; V is VA ** VB ).
'$goal_eval'(E, V) :- compound(E), E \= [_|_], !, E =.. [F|Args], '$goal_eval_args'(Args, Vs),
    (   Vs = [VA, VB] -> '$goal_big'(F, VA, VB) ; true ),
    E2 =.. [F|Vs], V is E2, '$goal_bounded'(V).
'$goal_eval'(E, V) :- V is E.
'$goal_eval_args'([], []).
'$goal_eval_args'([A|As], [V|Vs]) :- '$goal_eval'(A, V), '$goal_eval_args'(As, Vs).
% Refuses an integer operation whose result would pass the bound.
'$goal_big'(F, A, B) :-
    (   integer(A), integer(B), '$goal_big_bits'(F, A, B, Bits), Bits > 1048640
    ->  throw(error(resource_error(big_integer), (is)/2))
    ;   true
    ).
'$goal_big_bits'(*, A, B, Bits) :- '$goal_bits'(A, BA), '$goal_bits'(B, BB), Bits is BA + BB.
'$goal_big_bits'(^, A, B, Bits) :- B > 0, abs(A) > 1, '$goal_bits'(A, BA), Bits is (BA - 1) * B.
'$goal_big_bits'(<<, A, B, Bits) :- A =\= 0, '$goal_bits'(A, BA), Bits is BA + B.
'$goal_big_bits'(>>, A, B, Bits) :- B < 0, A =\= 0, '$goal_bits'(A, BA), Bits is BA - B.
'$goal_bounded'(V) :-
    (   integer(V), ( V > 9223372036854775807 ; V < -9223372036854775808 ),
        '$goal_bits'(V, Bits), Bits > 1048640
    ->  throw(error(resource_error(big_integer), (is)/2))
    ;   true
    ).
% The number of bits of |A| (for integers made under the bound: a binary search on shifts).
'$goal_bits'(A0, Bits) :- A is abs(A0),
    (   A < 4503599627370496 -> ( A =:= 0 -> Bits = 0 ; Bits is truncate(log(A) / log(2)) + 1 )
    ;   '$goal_bits'(A, 52, 2097152, Bits)
    ).
'$goal_bits'(A, Lo, Hi, Bits) :-
    (   Hi - Lo =< 1 -> Bits = Hi
    ;   Mid is (Lo + Hi) // 2,
        (   A >> Mid =:= 0 -> '$goal_bits'(A, Lo, Mid, Bits) ; '$goal_bits'(A, Mid, Hi, Bits) )
    ).

'$goal_softcut'(C, T, E) :- ( \+ call(C) -> call(E) ; call(C), call(T) ).

last([X], X) :- !.
last([_|T], X) :- last(T, X).

msort(L, S) :- must_be(list, L), '$goal_keys'(L, K), keysort(K, KS), pairs_values(KS, S).
'$goal_keys'([], []).
'$goal_keys'([X|Xs], [K-X|Ks]) :- '$goal_key'(X, K), '$goal_keys'(Xs, Ks).

sort(0, O, L, S) :- !, '$goal_sort_whole'(O, L, S).
sort(K, O, L, S) :- '$goal_key_pairs'(L, K, P), '$goal_sort_pairs'(O, P, SP), pairs_values(SP, S).
'$goal_sort_whole'(@<, L, S) :- '$goal_sort'(L, S).
'$goal_sort_whole'(@=<, L, S) :- msort(L, S).
'$goal_sort_whole'(@>, L, S) :- '$goal_sort'(L, S0), reverse(S0, S).
'$goal_sort_whole'(@>=, L, S) :- msort(L, S0), reverse(S0, S).
'$goal_key_pairs'([], _, []).
'$goal_key_pairs'([X|Xs], K, [KY-X|Ps]) :- arg(K, X, Y), '$goal_key'(Y, KY), '$goal_key_pairs'(Xs, K, Ps).
'$goal_sort_pairs'(@=<, P, S) :- keysort(P, S).
'$goal_sort_pairs'(@<, P, S) :- keysort(P, S0), '$goal_dedup_keys'(S0, S).
'$goal_sort_pairs'(@>=, P, S) :- '$goal_rev_keysort'(P, S).
'$goal_sort_pairs'(@>, P, S) :- '$goal_rev_keysort'(P, S0), '$goal_dedup_keys'(S0, S).
'$goal_rev_keysort'(P, S) :- reverse(P, R), keysort(R, S0), reverse(S0, S).
'$goal_dedup_keys'([], []).
'$goal_dedup_keys'([P], [P]) :- !.
'$goal_dedup_keys'([K1-V1, K2-V2|T], S) :- K1 == K2, !, '$goal_dedup_keys'([K1-V1|T], S).
'$goal_dedup_keys'([P|T], [P|S]) :- '$goal_dedup_keys'(T, S).

delete([], _, []).
delete([E|T], X, R) :- E \= X, !, R = [E|R1], delete(T, X, R1).
delete([_|T], X, R) :- delete(T, X, R).

subtract([], _, []).
subtract([E|T], D, R) :- memberchk(E, D), !, subtract(T, D, R).
subtract([H|T], D, [H|R]) :- subtract(T, D, R).

union([], L, L).
union([H|T], L, R) :- memberchk(H, L), !, union(T, L, R).
union([H|T], L, [H|R]) :- union(T, L, R).

intersection([], _, []).
intersection([X|T], L, I) :- memberchk(X, L), !, I = [X|R], intersection(T, L, R).
intersection([_|T], L, R) :- intersection(T, L, R).

exclude(_, [], []).
exclude(P, [X|Xs], R) :- ( '$goal_call'(P, X) -> R = R1 ; R = [X|R1] ), exclude(P, Xs, R1).
include(_, [], []).
include(P, [X|Xs], R) :- ( '$goal_call'(P, X) -> R = [X|R1] ; R = R1 ), include(P, Xs, R1).
partition(_, [], [], []).
partition(P, [H|T], I, E) :- ( '$goal_call'(P, H) -> I = [H|I1], E = E1 ; I = I1, E = [H|E1] ), partition(P, T, I1, E1).

sumlist(L, S) :- sum_list(L, S).
max_list(L, M) :- list_max(L, M).
min_list(L, M) :- list_min(L, M).

nextto(X, Y, [X,Y|_]).
nextto(X, Y, [_|Zs]) :- nextto(X, Y, Zs).

selectchk(E, L, R) :- select(E, L, R), !.

plus(X, Y, Z) :- integer(X), integer(Y), !, Z is X + Y.
plus(X, Y, Z) :- integer(X), integer(Z), !, Y is Z - X.
plus(X, Y, Z) :- integer(Y), integer(Z), !, X is Z - Y.

aggregate_all(count, G, C) :- !, findall(x, G, L), length(L, C).
aggregate_all(count(T), G, C) :- !, findall(T, G, L), length(L, C).
aggregate_all(sum(E), G, S) :- !, findall(E, G, L), '$goal_sum'(L, 0, S).
aggregate_all(max(E, W), G, max(M, MW)) :- !, findall(E-W, G, L), L = [H|T], '$goal_max_w'(T, H, M-MW).
aggregate_all(min(E, W), G, min(M, MW)) :- !, findall(E-W, G, L), L = [H|T], '$goal_min_w'(T, H, M-MW).
aggregate_all(max(E), G, M) :- !, findall(E, G, L), L = [H|T], '$goal_max'(T, H, M).
aggregate_all(min(E), G, M) :- !, findall(E, G, L), L = [H|T], '$goal_min'(T, H, M).
aggregate_all(bag(E), G, L) :- !, findall(E, G, L).
aggregate_all(set(E), G, S) :- !, findall(E, G, L), '$goal_sort'(L, S).
'$goal_sum'([], S, S).
'$goal_sum'([X|Xs], A, S) :- A1 is A + X, '$goal_sum'(Xs, A1, S).
'$goal_max'([], M, M).
'$goal_max'([X|Xs], A, M) :- ( X > A -> A1 = X ; A1 = A ), '$goal_max'(Xs, A1, M).
'$goal_max_w'([], M, M).
'$goal_max_w'([X-W|Xs], A-AW, M) :- ( X > A -> '$goal_max_w'(Xs, X-W, M) ; '$goal_max_w'(Xs, A-AW, M) ).
'$goal_min_w'([], M, M).
'$goal_min_w'([X-W|Xs], A-AW, M) :- ( X < A -> '$goal_min_w'(Xs, X-W, M) ; '$goal_min_w'(Xs, A-AW, M) ).
'$goal_min'([], M, M).
'$goal_min'([X|Xs], A, M) :- ( X < A -> A1 = X ; A1 = A ), '$goal_min'(Xs, A1, M).

% Belief views: retract then assert facts (all ground).
'$goal_sync'(Rs, As) :- '$goal_retract'(Rs), '$goal_assert'(As).
'$goal_retract'([]).
'$goal_retract'([F|Fs]) :- ( retract(F) -> true ; true ), '$goal_retract'(Fs).
'$goal_assert'([]).
'$goal_assert'([F|Fs]) :- assertz(F), '$goal_assert'(Fs).

% SWI's list and term built-ins scryer 0.10 lacks or defines otherwise.
predsort(P, L, Sorted) :- length(L, N), ( N =:= 0 -> Sorted = [] ; '$goal_predsort'(P, N, L, _, Sorted1), !, Sorted = Sorted1 ).
'$goal_predsort'(P, 2, [X1, X2|L], L, R) :- !, '$goal_call'(P, Delta, X1, X2), '$goal_sort2'(Delta, X1, X2, R).
'$goal_predsort'(_, 1, [X|L], L, [X]) :- !.
'$goal_predsort'(_, 0, L, L, []) :- !.
'$goal_predsort'(P, N, L1, L3, R) :-
    N1 is N // 2, plus(N1, N2, N), '$goal_predsort'(P, N1, L1, L2, R1),
    '$goal_predsort'(P, N2, L2, L3, R2), '$goal_predmerge'(P, R1, R2, R).
'$goal_sort2'(<, X1, X2, [X1, X2]).
'$goal_sort2'(=, X1, _, [X1]).
'$goal_sort2'(>, X1, X2, [X2, X1]).
'$goal_predmerge'(_, [], R, R) :- !.
'$goal_predmerge'(_, R, [], R) :- !.
'$goal_predmerge'(P, [H1|T1], [H2|T2], Result) :-
    '$goal_call'(P, Delta, H1, H2), !, '$goal_predmerge_'(Delta, P, H1, H2, T1, T2, Result).
'$goal_predmerge_'(<, P, H1, H2, T1, T2, [H1|R]) :- '$goal_predmerge'(P, T1, [H2|T2], R).
'$goal_predmerge_'(=, P, H1, _, T1, T2, [H1|R]) :- '$goal_predmerge'(P, T1, T2, R).
'$goal_predmerge_'(>, P, H1, H2, T1, T2, [H2|R]) :- '$goal_predmerge'(P, [H1|T1], T2, R).
'$goal_arg'(N, T, A) :-
    (   var(N), compound(T) -> functor(T, _, Ar), between(1, Ar, N), arg(N, T, A)
    ;   arg(N, T, A)
    ).
'$goal_between'(L, H, X) :-
    (   H == inf -> must_be(integer, L), ( integer(X) -> X >= L ; '$goal_count_from'(L, X) )
    ;   H == infinite -> '$goal_between'(L, inf, X)
    ;   between(L, H, X)
    ).
'$goal_count_from'(L, L).
'$goal_count_from'(L, X) :- L1 is L + 1, '$goal_count_from'(L1, X).
'=@='(A, B) :-
    \+ \+ ( copy_term(A, A1), copy_term(B, B1), term_variables(A1, V1), term_variables(B1, V2),
             '$goal_name_vars'(V1, 0), '$goal_name_vars'(V2, 0), A1 == B1 ).
'$goal_name_vars'([], _).
'$goal_name_vars'([V|Vs], I) :- V = '$goal_var'(I), I1 is I + 1, '$goal_name_vars'(Vs, I1).
% format/3 into atom(A), string(S), codes(Cs) and chars(Cs) (scryer writes only to streams).
'$goal_format'(Sink, F, Args0) :-
    ( nonvar(Args0), ( Args0 == [] ; Args0 = [_|_] ) -> Args = Args0 ; Args = [Args0] ),
    (   nonvar(Sink), '$goal_text_sink'(Sink) ->
        catch(phrase(format_(F, Args), Cs), error(E, _), '$goal_format_error'(E)),
        '$goal_sink'(Sink, Cs)
    ;   format(Sink, F, Args)
    ).
% A directive scryer's format_//2 lacks (its error term holds the format text, which scryer
% 0.10 copies wrong): said without the text.
'$goal_format_error'(E) :-
    (   E = domain_error(format_string, _) -> throw(error(format(unsupported_directive), format/3))
    ;   throw(error(E, format/3))
    ).
'$goal_text_sink'(atom(_)).
'$goal_text_sink'(string(_)).
'$goal_text_sink'(codes(_)).
'$goal_text_sink'(chars(_)).
'$goal_sink'(atom(A), Cs) :- atom_chars(A, Cs).
'$goal_sink'(string(S), Cs) :- S = Cs.
'$goal_sink'(chars(S), Cs) :- S = Cs.
'$goal_sink'(codes(S), Cs) :- '$goal_codes'(Cs, S).
'$goal_codes'([], []).
'$goal_codes'([C|Cs], [K|Ks]) :- char_code(C, K), '$goal_codes'(Cs, Ks).
