% Naive reverse of a 30-element list, the classic Prolog speed test (496 logical inferences
% per reversal). The same file runs on `goal prolog` and on SWI-Prolog: see benches/nrev.sh.

app([], L, L).
app([H|T], L, [H|R]) :- app(T, L, R).

nrev([], []).
nrev([H|T], R) :- nrev(T, RT), app(RT, [H], R).

range(N, N, [N]) :- !.
range(I, N, [I|T]) :- I < N, I1 is I + 1, range(I1, N, T).

% bench(N): N reversals of [1..30].
bench(N) :- range(1, 30, L), between(1, N, _), nrev(L, _), fail.
bench(_).
