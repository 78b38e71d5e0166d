#!/bin/sh
# Runs one plunit suite (a .plt beside its module) in its own swipl; prints "ok" or the suite's
# output, and exits non-zero when a test fails. `make test-prolog` runs one per core.
t="$1"; m="${t%.plt}.pl"
if out=$(swipl -q -g "load_files(['$m'],[]),load_test_files([]),(run_tests->halt(0);halt(1))" -t 'halt(1)' 2>&1); then
  echo "plunit: $t ok"
else
  printf 'plunit: %s FAILED\n%s\n' "$t" "$out"; exit 1
fi
