#!/bin/sh
# Naive reverse, whole process, same file: `goal prolog` against SWI-Prolog (installed here if
# missing; this script is for benchmark machines, not CI). Prints wall and CPU time of each.
# Usage: benches/nrev.sh [N]   (N reversals of a 30-element list, default 300000)
set -e
N=${1:-300000}
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
run goal "$GOAL" prolog "$DIR/nrev/nrev.pl" --query "bench($N)"
if command -v swipl >/dev/null 2>&1; then
    run swipl swipl -q -g "bench($N)" -t halt "$DIR/nrev/nrev.pl"
fi
echo "$N reversals x 496 logical inferences = $((N * 496)) LI"
