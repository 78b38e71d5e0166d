#!/bin/sh
# Runs one plunit suite (a .plt beside its module) in its own swipl; prints "ok" or the suite's
# output, and exits non-zero when a test fails. `make test-prolog` runs one per core.
# Only the units the given .plt defines run: load_test_files/1 also loads the .plt of every module
# the module loads, and running all of them ran kb_query's suite some 40 times and history.plt's
# (11 s) again in past.plt's run. A .plt that defines no unit fails.
t="$1"; m="${t%.plt}.pl"
if out=$(swipl -q -g "load_files(['$m'],[]),load_test_files([]),absolute_file_name('$t',F,[access(read)]),findall(U,plunit:unit_file(U,F),Us),Us\\==[],(run_tests(Us)->halt(0);halt(1))" -t 'halt(1)' 2>&1); then
  echo "plunit: $t ok"
else
  printf 'plunit: %s FAILED\n%s\n' "$t" "$out"; exit 1
fi
