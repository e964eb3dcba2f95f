#!/bin/sh
# Naive reverse, whole process, same file: `goal prolog` against SWI-Prolog (installed here if
# missing; this script is for benchmark machines, not CI). Prints wall and CPU time of each.
# Usage: benches/nrev.sh [Q]   (Q queries of bench(20000), 20,000 reversals of a 30-element
# list each; default 15). One query stays under goal's default budget of 10 M inferences.
set -e
Q=${1:-15}
DIR=$(dirname "$0")
GOAL=${GOAL:-$DIR/../target/release/goal}
if ! command -v swipl >/dev/null 2>&1; then
    apt-get install -y swi-prolog-nox >/dev/null 2>&1 || echo "swipl not installed: SWI-Prolog row skipped" >&2
fi
run() {
    name=$1
    shift
    /usr/bin/time -f "$name: %e s wall, %U s user + %S s system CPU, %M KiB peak" "$@" >/dev/null
}
yes 'bench(20000).' | head -n "$Q" | run goal "$GOAL" prolog "$DIR/nrev/nrev.pl"
if command -v swipl >/dev/null 2>&1; then
    run swipl swipl -q -g "forall(between(1, $Q, _), bench(20000))" -t halt "$DIR/nrev/nrev.pl"
fi
echo "$Q x 20000 reversals x 496 logical inferences = $((Q * 20000 * 496)) LI"
