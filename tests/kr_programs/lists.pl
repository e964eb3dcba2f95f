% List manipulation in plain Prolog, compared between the native engine and scryer.
my_append([], L, L).
my_append([H|T], L, [H|R]) :- my_append(T, L, R).

my_reverse(L, R) :- my_reverse(L, [], R).
my_reverse([], A, A).
my_reverse([H|T], A, R) :- my_reverse(T, [H|A], R).

my_length([], 0).
my_length([_|T], N) :- my_length(T, N0), N is N0 + 1.

my_last([X], X) :- !.
my_last([_|T], X) :- my_last(T, X).

quicksort([], []).
quicksort([P|Xs], S) :-
    split(P, Xs, Small, Big),
    quicksort(Small, S1), quicksort(Big, S2),
    my_append(S1, [P|S2], S).
split(_, [], [], []).
split(P, [X|Xs], [X|S], B) :- X =< P, !, split(P, Xs, S, B).
split(P, [X|Xs], S, [X|B]) :- split(P, Xs, S, B).

prefix([], _).
prefix([H|T], [H|L]) :- prefix(T, L).

sublist(S, L) :- my_append(_, R, L), prefix(S, R).

flat([], []) :- !.
flat([H|T], F) :- !, flat(H, FH), flat(T, FT), my_append(FH, FT, F).
flat(X, [X]).

count_occ(_, [], 0).
count_occ(X, [X|T], N) :- !, count_occ(X, T, N0), N is N0 + 1.
count_occ(X, [_|T], N) :- count_occ(X, T, N).

pairs([], []).
pairs([X|Xs], Ps) :- findall(X-Y, member(Y, Xs), P1), pairs(Xs, P2), my_append(P1, P2, Ps).

sum_sq(L, S) :- findall(Y, (member(X, L), Y is X * X), Ys), sum_list(Ys, S).

range(N, N, [N]) :- !.
range(I, N, [I|T]) :- I < N, I1 is I + 1, range(I1, N, T).

nums([3, 1, 4, 1, 5, 9, 2, 6, 5, 3, 5]).
word(apple). word(banana). word(cherry). word(date). word(elder).
score(apple, 3). score(banana, 7). score(cherry, 7). score(date, 1). score(elder, 5).
small(X) :- X < 4.
