//! The library predicates written in Prolog, compiled once per process (standard definitions
//! as in SWI-Prolog's `lists`, `apply`, `aggregate` and `pairs` libraries).

use crate::syntax::prolog::Reader;
use crate::term::Term;

const PRELUDE: &str = r#"
append([], L, L).
append([H|T], L, [H|R]) :- append(T, L, R).
append(Ls, L) :- '$append_all'(Ls, L).
'$append_all'([], []).
'$append_all'([L|Ls], As) :- append(L, Ws, As), '$append_all'(Ls, Ws).
'$length_enum'(L, N0, N) :- '$length_enum_'(L, N0, N).
'$length_enum_'([], N, N).
'$length_enum_'([_|T], N0, N) :- N1 is N0 + 1, '$length_enum_'(T, N1, N).
'$nth_enum'([H|T], B, I, E) :- '$nth_enum_'(T, H, B, I, E).
'$nth_enum_'(_, H, B, B, H).
'$nth_enum_'([H|T], _, B0, I, E) :- B1 is B0 + 1, '$nth_enum_'(T, H, B1, I, E).
'$reverse'([], Ys, Ys, []).
'$reverse'([X|Xs], Rs, Ys, [_|Bound]) :- '$reverse'(Xs, [X|Rs], Ys, Bound).
last([X|Xs], Last) :- '$last'(Xs, X, Last).
'$last'([], Last, Last).
'$last'([X|Xs], _, Last) :- '$last'(Xs, X, Last).
nextto(X, Y, [X,Y|_]).
nextto(X, Y, [_|T]) :- nextto(X, Y, T).
select(X, [X|T], T).
select(X, [H|T], [H|R]) :- select(X, T, R).
selectchk(X, L, R) :- select(X, L, R), !.
select(X, Xs, Y, Ys) :- '$select4'(Xs, X, Y, Ys).
'$select4'([X|T], X, Y, [Y|T]).
'$select4'([H|T], X, Y, [H|T2]) :- '$select4'(T, X, Y, T2).
subtract([], _, []).
subtract([H|T], L, R) :- memberchk(H, L), !, subtract(T, L, R).
subtract([H|T], L, [H|R]) :- subtract(T, L, R).
intersection([], _, []).
intersection([H|T], L, R) :- memberchk(H, L), !, R = [H|R1], intersection(T, L, R1).
intersection([_|T], L, R) :- intersection(T, L, R).
union([], L, L).
union([H|T], L, R) :- memberchk(H, L), !, union(T, L, R).
union([H|T], L, [H|R]) :- union(T, L, R).
exclude(_, [], []).
exclude(P, [H|T], R) :- ( call(P, H) -> R = R1 ; R = [H|R1] ), exclude(P, T, R1).
include(_, [], []).
include(P, [H|T], R) :- ( call(P, H) -> R = [H|R1] ; R = R1 ), include(P, T, R1).
partition(_, [], [], []).
partition(P, [H|T], I, E) :- ( call(P, H) -> I = [H|I1], E = E1 ; I = I1, E = [H|E1] ), partition(P, T, I1, E1).
partition(_, [], [], [], []).
partition(P, [H|T], L, E, G) :- call(P, H, O), '$partition5'(O, H, L, E, G, L1, E1, G1), partition(P, T, L1, E1, G1).
'$partition5'(<, H, [H|L], E, G, L, E, G).
'$partition5'(=, H, L, [H|E], G, L, E, G).
'$partition5'(>, H, L, E, [H|G], L, E, G).
maplist(_, []).
maplist(P, [A|As]) :- call(P, A), maplist(P, As).
maplist(_, [], []).
maplist(P, [A|As], [B|Bs]) :- call(P, A, B), maplist(P, As, Bs).
maplist(_, [], [], []).
maplist(P, [A|As], [B|Bs], [C|Cs]) :- call(P, A, B, C), maplist(P, As, Bs, Cs).
maplist(_, [], [], [], []).
maplist(P, [A|As], [B|Bs], [C|Cs], [D|Ds]) :- call(P, A, B, C, D), maplist(P, As, Bs, Cs, Ds).
foldl(G, L, V0, V) :- '$foldl'(L, G, V0, V).
'$foldl'([], _, V, V).
'$foldl'([X|Xs], G, V0, V) :- call(G, X, V0, V1), '$foldl'(Xs, G, V1, V).
foldl(G, L1, L2, V0, V) :- '$foldl'(L1, L2, G, V0, V).
'$foldl'([], [], _, V, V).
'$foldl'([X|Xs], [Y|Ys], G, V0, V) :- call(G, X, Y, V0, V1), '$foldl'(Xs, Ys, G, V1, V).
foldl(G, L1, L2, L3, V0, V) :- '$foldl'(L1, L2, L3, G, V0, V).
'$foldl'([], [], [], _, V, V).
'$foldl'([X|Xs], [Y|Ys], [Z|Zs], G, V0, V) :- call(G, X, Y, Z, V0, V1), '$foldl'(Xs, Ys, Zs, G, V1, V).
nth0(I, L, E, R) :- integer(I), !, I >= 0, '$nth_del'(I, L, E, R).
nth0(I, L, E, R) :- var(I), '$nth_gen'(L, E, R, 0, I).
nth1(I, L, E, R) :- integer(I), !, I0 is I - 1, I0 >= 0, '$nth_del'(I0, L, E, R).
nth1(I, L, E, R) :- var(I), '$nth_gen'(L, E, R, 1, I).
'$nth_del'(0, [E|R], E, R) :- !.
'$nth_del'(I, [H|T], E, [H|R]) :- I1 is I - 1, '$nth_del'(I1, T, E, R).
'$nth_gen'([E|R], E, R, B, B).
'$nth_gen'([H|T], E, [H|R], B0, I) :- B1 is B0 + 1, '$nth_gen'(T, E, R, B1, I).
proper_length(L, N) :- is_list(L), length(L, N).
is_set(Set) :- is_list(Set), length(Set, N), sort(Set, Sorted), length(Sorted, N).
subset([], _) :- !.
subset([E|R], Set) :- memberchk(E, Set), subset(R, Set).
selectchk(X, Xs, Y, Ys) :- select(X, Xs, Y, Ys), !.
subseq([], [], []).
subseq([H|T], [H|S], R) :- subseq(T, S, R).
subseq([H|T], S, [H|R]) :- subseq(T, S, R).
max_member(P, M, [H|T]) :- '$max_member'(T, P, H, M).
'$max_member'([], _, M, M).
'$max_member'([H|T], P, M0, M) :- ( call(P, M0, H) -> M1 = H ; M1 = M0 ), '$max_member'(T, P, M1, M).
min_member(P, M, [H|T]) :- '$min_member'(T, P, H, M).
'$min_member'([], _, M, M).
'$min_member'([H|T], P, M0, M) :- ( call(P, H, M0) -> M1 = H ; M1 = M0 ), '$min_member'(T, P, M1, M).
clumped([], []).
clumped([H|T0], [H-C|T]) :- '$clump_run'(T0, H, 1, C, T1), clumped(T1, T).
'$clump_run'([H|T0], E, C0, C, T) :- E == H, !, C1 is C0 + 1, '$clump_run'(T0, E, C1, C, T).
'$clump_run'(L, _, C, C, L).
maplist(_, [], [], [], [], []).
maplist(P, [A|As], [B|Bs], [C|Cs], [D|Ds], [E|Es]) :- call(P, A, B, C, D, E), maplist(P, As, Bs, Cs, Ds, Es).
divmod(Dividend, Divisor, Q, R) :- Q is div(Dividend, Divisor), R is Dividend mod Divisor.
permutation([], []).
permutation(L, [H|T]) :- '$perm_len'(L, [H|T]), select(H, L, R), permutation(R, T).
'$perm_len'(L, P) :- ( is_list(L) -> length(L, N), length(P, N) ; is_list(P) -> length(P, N), length(L, N) ; true ).
same_length([], []).
same_length([_|T1], [_|T2]) :- same_length(T1, T2).
predsort(P, L, Sorted) :- length(L, N), ( N < 2 -> '$predsort_small'(P, L, Sorted) ; '$predsort'(P, N, L, _, Sorted1), Sorted = Sorted1 ).
'$predsort_small'(_, [], []).
'$predsort_small'(_, [X], [X]).
'$predsort'(P, 2, [X1,X2|L], L, R) :- !, call(P, Delta, X1, X2), '$sort2'(Delta, X1, X2, R).
'$predsort'(_, 1, [X|L], L, [X]) :- !.
'$predsort'(_, 0, L, L, []) :- !.
'$predsort'(P, N, L1, L3, R) :- N1 is N // 2, plus(N1, N2, N), '$predsort'(P, N1, L1, L2, R1), '$predsort'(P, N2, L2, L3, R2), '$predmerge'(P, R1, R2, R).
'$sort2'(<, X1, X2, [X1,X2]).
'$sort2'(=, X1, _, [X1]).
'$sort2'(>, X1, X2, [X2,X1]).
'$predmerge'(_, [], R, R) :- !.
'$predmerge'(_, R, [], R) :- !.
'$predmerge'(P, [H1|T1], [H2|T2], Result) :- call(P, Delta, H1, H2), !, '$predmerge_'(Delta, P, H1, H2, T1, T2, Result).
'$predmerge_'(<, P, H1, H2, T1, T2, [H1|R]) :- '$predmerge'(P, T1, [H2|T2], R).
'$predmerge_'(=, P, H1, _, T1, T2, [H1|R]) :- '$predmerge'(P, T1, T2, R).
'$predmerge_'(>, P, H1, H2, T1, T2, [H2|R]) :- '$predmerge'(P, [H1|T1], T2, R).
bagof(T, G, L) :- '$bagof_prep'(T, G, W, G1), ( W == '$w' -> findall(T, G1, L), L \== [] ; findall(W-T, G1, Ps), Ps \== [], '$bagof_groups'(Ps, Gs), member(W-Ms, Gs), '$bagof_items'(Ms, W, L) ).
'$bagof_items'([], _, []).
'$bagof_items'([W1-T|Ms], W, [T|Ts]) :- W1 = W, '$bagof_items'(Ms, W, Ts).
setof(T, G, S) :- bagof(T, G, L), sort(L, S).
aggregate_all(count, G, C) :- !, findall(x, G, L), length(L, C).
aggregate_all(count(T), G, C) :- !, findall(T, G, L), length(L, C).
aggregate_all(sum(E), G, S) :- !, findall(E, G, L), '$sum_eval'(L, S).
aggregate_all(max(E), G, M) :- !, findall(E, G, L), '$max_eval'(L, max, M).
aggregate_all(min(E), G, M) :- !, findall(E, G, L), '$max_eval'(L, min, M).
aggregate_all(max(E, W), G, max(M, MW)) :- !, findall(E-W, G, L), '$arg_extreme'(L, max, M, MW).
aggregate_all(min(E, W), G, min(M, MW)) :- !, findall(E-W, G, L), '$arg_extreme'(L, min, M, MW).
aggregate_all(bag(E), G, L) :- !, findall(E, G, L).
aggregate_all(set(E), G, S) :- !, findall(E, G, L), sort(L, S).
aggregate_all(count, D, G, C) :- !, findall(D, G, L0), sort(L0, L), length(L, C).
aggregate_all(sum(E), D, G, S) :- !, findall(D-E, G, L0), sort(L0, L), pairs_values(L, Vs), '$sum_eval'(Vs, S).
aggregate_all(max(E), D, G, M) :- !, findall(D-E, G, L0), sort(L0, L), pairs_values(L, Vs), '$max_eval'(Vs, max, M).
aggregate_all(min(E), D, G, M) :- !, findall(D-E, G, L0), sort(L0, L), pairs_values(L, Vs), '$max_eval'(Vs, min, M).
aggregate_all(bag(E), D, G, B) :- !, findall(D-E, G, L0), sort(L0, L), pairs_values(L, B).
aggregate_all(set(E), D, G, S) :- !, findall(D-E, G, L0), sort(L0, L), pairs_values(L, B), sort(B, S).
'$arg_extreme'([E-W|T], Dir, M, MW) :- '$arg_extreme'(T, Dir, E, W, M, MW).
'$arg_extreme'([], _, M, W, M, W).
'$arg_extreme'([E-W|T], Dir, M0, W0, M, MW) :- ( ( Dir == max, E > M0 ; Dir == min, E < M0 ) -> '$arg_extreme'(T, Dir, E, W, M, MW) ; '$arg_extreme'(T, Dir, M0, W0, M, MW) ).
aggregate(count, G, C) :- !, bagof(x, G, L), length(L, C).
aggregate(count(T), G, C) :- !, '$aggr_template'(G, T, G1, T1), bagof(T1, G1, L), length(L, C).
aggregate(sum(E), G, S) :- !, '$aggr_template'(G, E, G1, E1), bagof(E1, G1, L), '$sum_eval'(L, S).
aggregate(max(E), G, M) :- !, '$aggr_template'(G, E, G1, E1), bagof(E1, G1, L), '$max_eval'(L, max, M).
aggregate(min(E), G, M) :- !, '$aggr_template'(G, E, G1, E1), bagof(E1, G1, L), '$max_eval'(L, min, M).
aggregate(max(E, W), G, max(M, MW)) :- !, '$aggr_template'(G, E-W, G1, T1), bagof(T1, G1, L), '$arg_extreme'(L, max, M, MW).
aggregate(min(E, W), G, min(M, MW)) :- !, '$aggr_template'(G, E-W, G1, T1), bagof(T1, G1, L), '$arg_extreme'(L, min, M, MW).
aggregate(bag(E), G, L) :- !, '$aggr_template'(G, E, G1, E1), bagof(E1, G1, L).
aggregate(set(E), G, S) :- !, '$aggr_template'(G, E, G1, E1), setof(E1, G1, S).
'$aggr_template'(G, T, G, T).
aggregate(count, D, G, C) :- !, setof(D-x, G, Ps), length(Ps, C).
aggregate(sum(E), D, G, S) :- !, setof(D-E, G, Ps), pairs_values(Ps, Vs), '$sum_eval'(Vs, S).
aggregate(max(E), D, G, M) :- !, setof(D-E, G, Ps), pairs_values(Ps, Vs), '$max_eval'(Vs, max, M).
aggregate(min(E), D, G, M) :- !, setof(D-E, G, Ps), pairs_values(Ps, Vs), '$max_eval'(Vs, min, M).
aggregate(bag(E), D, G, B) :- !, setof(D-E, G, Ps), pairs_values(Ps, B).
aggregate(set(E), D, G, S) :- !, setof(D-E, G, Ps), pairs_values(Ps, B), sort(B, S).
"#;

/// The prelude clauses.
pub(crate) fn clauses() -> Vec<Term> {
    let mut reader = Reader::new("<kr prelude>");
    let (mut items, errors) = reader.clauses(PRELUDE, 0);
    debug_assert!(errors.is_empty(), "prelude: {errors:?}");
    // The content language's constraint tests (`satisfies/2`), kept with the language.
    let (clamr, errors) = reader.clauses(crate::clamr::content::LIBRARY, 0);
    debug_assert!(errors.is_empty(), "clamr library: {errors:?}");
    items.extend(clamr);
    items.into_iter().map(|l| l.term).collect()
}
