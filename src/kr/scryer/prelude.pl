:- use_module(library(lists)).
:- use_module(library(between)).
:- use_module(library(iso_ext)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(library(error)).
:- set_prolog_flag(unknown, fail).

not(G) :- \+ call(G).

% The engine's entry: every answer (Cap 0) or the first (Cap 1) of G as instances of T, under
% an inference budget; errors come back as err(E), an exhausted budget as budget.
'$goal_run'(T, G, Cap, Lim, R) :-
    catch(call_with_inference_limit('$goal_collect'(Cap, T, G, L), Lim, LR), E, true),
    flush_output,
    (   nonvar(E) -> R = err(E)
    ;   LR == inference_limit_exceeded -> R = budget
    ;   R = ok(L)
    ).
'$goal_collect'(0, T, G, L) :- findall(T, G, L).
'$goal_collect'(1, T, G, L) :- ( call(G) -> L = [T] ; L = [] ).

% Meta-calls go through '$goal_call': goals built at run time may not reach files, processes,
% the network or the machine itself.
'$goal_call'(G) :- '$goal_check'(G), call(G).
'$goal_call'(G, A) :- '$goal_check'(G, 1), call(G, A).
'$goal_call'(G, A, B) :- '$goal_check'(G, 2), call(G, A, B).
'$goal_call'(G, A, B, C) :- '$goal_check'(G, 3), call(G, A, B, C).
'$goal_call'(G, A, B, C, D) :- '$goal_check'(G, 4), call(G, A, B, C, D).
'$goal_call'(G, A, B, C, D, E) :- '$goal_check'(G, 5), call(G, A, B, C, D, E).
'$goal_call'(G, A, B, C, D, E, F) :- '$goal_check'(G, 6), call(G, A, B, C, D, E, F).
'$goal_check'(G) :- '$goal_check'(G, 0).
'$goal_check'(G, Extra) :-
    (   var(G) -> throw(error(instantiation_error, call/1))
    ;   callable(G) -> functor(G, N, A0), A is A0 + Extra,
        (   '$goal_denied'(N, A) -> throw(error(permission_error(access, private_procedure, N/A), call/1))
        ;   true
        )
    ;   throw(error(type_error(callable, G), call/1))
    ).
ignore(G) :- ( call(G) -> true ; true ).

atom_number(A, N) :- var(A), !, number(N), number_chars(N, Cs), atom_chars(A, Cs).
atom_number(A, N) :- atom_chars(A, Cs), catch(number_chars(N0, Cs), _, fail), N = N0.

'$goal_is'(X, E) :- '$goal_eval'(E, V), X = V.
'$goal_cmp'(Op, A, B) :- '$goal_eval'(A, VA), '$goal_eval'(B, VB), G =.. [Op, VA, VB], call(G).
'$goal_eval'(E, V) :- var(E), !, V is E.
'$goal_eval'(A / B, V) :- !, '$goal_eval'(A, VA), '$goal_eval'(B, VB),
    ( integer(VA), integer(VB), VB =\= 0, VA mod VB =:= 0 -> V is VA // VB ; V is VA / VB ).
'$goal_eval'(A ** B, V) :- !, '$goal_eval'(A, VA), '$goal_eval'(B, VB),
    ( integer(VA), integer(VB), VB >= 0 -> V is VA ^ VB ; V is VA ** VB ).
'$goal_eval'(E, V) :- compound(E), E \= [_|_], !, E =.. [F|Args], '$goal_eval_args'(Args, Vs),
    E2 =.. [F|Vs], V is E2.
'$goal_eval'(E, V) :- V is E.
'$goal_eval_args'([], []).
'$goal_eval_args'([A|As], [V|Vs]) :- '$goal_eval'(A, V), '$goal_eval_args'(As, Vs).

'$goal_softcut'(C, T, E) :- ( \+ call(C) -> call(E) ; call(C), call(T) ).

last([X], X) :- !.
last([_|T], X) :- last(T, X).

msort(L, S) :- '$goal_keys'(L, K), keysort(K, KS), pairs_values(KS, S).
'$goal_keys'([], []).
'$goal_keys'([X|Xs], [X-X|Ks]) :- '$goal_keys'(Xs, Ks).

sort(0, O, L, S) :- !, '$goal_sort_whole'(O, L, S).
sort(K, O, L, S) :- '$goal_key_pairs'(L, K, P), '$goal_sort_pairs'(O, P, SP), pairs_values(SP, S).
'$goal_sort_whole'(@<, L, S) :- sort(L, S).
'$goal_sort_whole'(@=<, L, S) :- msort(L, S).
'$goal_sort_whole'(@>, L, S) :- sort(L, S0), reverse(S0, S).
'$goal_sort_whole'(@>=, L, S) :- msort(L, S0), reverse(S0, S).
'$goal_key_pairs'([], _, []).
'$goal_key_pairs'([X|Xs], K, [Y-X|Ps]) :- arg(K, X, Y), '$goal_key_pairs'(Xs, K, Ps).
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
aggregate_all(max(E), G, M) :- !, findall(E, G, L), L = [H|T], '$goal_max'(T, H, M).
aggregate_all(min(E), G, M) :- !, findall(E, G, L), L = [H|T], '$goal_min'(T, H, M).
aggregate_all(bag(E), G, L) :- !, findall(E, G, L).
aggregate_all(set(E), G, S) :- !, findall(E, G, L), sort(L, S).
'$goal_sum'([], S, S).
'$goal_sum'([X|Xs], A, S) :- A1 is A + X, '$goal_sum'(Xs, A1, S).
'$goal_max'([], M, M).
'$goal_max'([X|Xs], A, M) :- ( X > A -> A1 = X ; A1 = A ), '$goal_max'(Xs, A1, M).
'$goal_min'([], M, M).
'$goal_min'([X|Xs], A, M) :- ( X < A -> A1 = X ; A1 = A ), '$goal_min'(Xs, A1, M).

% Belief views: retract then assert facts (all ground).
'$goal_sync'(Rs, As) :- '$goal_retract'(Rs), '$goal_assert'(As).
'$goal_retract'([]).
'$goal_retract'([F|Fs]) :- ( retract(F) -> true ; true ), '$goal_retract'(Fs).
'$goal_assert'([]).
'$goal_assert'([F|Fs]) :- assertz(F), '$goal_assert'(Fs).
