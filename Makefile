# neem-oracle: the two commands a newcomer needs are `make setup` and `make test`.
SHELL := /bin/bash
VENV ?= .venv
PY := $(VENV)/bin/python
PLT := $(sort $(shell find prolog -name '*.plt'))

.PHONY: setup test lint test-python test-prolog bench fuzz demo results up up-host down test-mongo clean help

help:
	@echo "make setup      install python3-venv and SWI-Prolog (Debian) if missing, create $(VENV), install the package"
	@echo "make test       pytest, lint and the plunit suites at once (the tests marked slow too where CI is set, or with SLOW=1)"
	@echo "make lint       ruff and mypy (config in pyproject.toml)"
	@echo "make bench      benchmarks (printed figures)"
	@echo "make fuzz       atheris on every fuzz target (FUZZ_SECONDS each, default 600) and a longer schemathesis run"
	@echo "make demo       the main job on the embedded default store"
	@echo "make results    regenerate docs/results.md's figures into out/ (13-30 min; SHARED=DIR: the real datasets; experiments/README.md)"
	@echo "make up/down    docker compose dev stack with MongoDB (needs a Docker engine); make up-host: MongoDB also on 127.0.0.1"
	@echo "make test-mongo the whole suite against the MongoDB at NEEM_MONGO_URI"

setup:
	@sh scripts/setup-prereqs.sh
	@swipl --version
	@if ! command -v chromium >/dev/null 2>&1 && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	  echo "installing chromium from Debian (the tablet page's browser test)"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium \
	    || echo "chromium not installed: the page's browser test will skip"; \
	fi
	@if ! /usr/bin/python3 -c "import rospy, genpy, rosgraph" >/dev/null 2>&1 && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	  echo "installing ROS 1's rospy and rosmaster from Debian (the rosprolog door, docs/knowrob.md)"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
	    python3-rospy python3-rosmaster python3-genpy python3-rosgraph \
	    || echo "ROS 1 not installed: python -m oracle rosprolog and its tests will say so"; \
	fi
	@test -x $(PY) || python3 -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -e '.[dev]'
	@# bytecode of the package now, as a wheel install has it: a shell with PYTHONDONTWRITEBYTECODE set
	@# would otherwise compile every module on every call (~0.1 s of each CLI call)
	$(PY) -m compileall -q python
	@$(PY) -c "import oracle, pyswip, rdflib, owlready2, numpy, yaml, pymongo; print('neem-oracle', oracle.__version__, 'ready')"

# lint, the plunit suites and pytest run at once, pytest first and the other two at a lower
# priority: the suite is CPU-bound, and mypy (one core, ~20 s without a cache) and plunit fill the
# moments pytest's workers wait instead of running before it. Each one's output is printed whole
# when it ends (make --output-sync); any failure fails make test once the others have ended.
test:
	@echo "make test: pytest, lint and plunit run at once; each one's output is printed when it ends"
	@$(MAKE) --no-print-directory -j3 --output-sync=target test-python lint test-prolog BESIDE="nice -n 10"

# BESIDE: how lint and plunit run while pytest runs beside them (make test); nothing on their own.
BESIDE ?=
lint:
	$(BESIDE) $(VENV)/bin/ruff check python tests
	$(BESIDE) $(VENV)/bin/mypy

# Each plunit suite runs in its own swipl, one per core; a failing suite prints its output and
# the target fails once all have run.
test-prolog:
	@printf '%s\n' $(PLT) | $(BESIDE) xargs -P "$$(nproc)" -n 1 sh scripts/plunit.sh

# The tests marked slow (a 10,000-action NEEM imported and ranked, a wheel built) run in a second
# invocation, in CI (where CI is set: .ci/run sets it) or when asked: make test SLOW=1.
# The tests' temporary files go to memory (/dev/shm) where it is a tmpfs with 4 GB free: on a disk
# mounted with `discard` each test store's fsyncs and deletes cost more than the test itself
# (TEST_TMP= keeps pytest's own choice; what a failed test left stays there until the next run).
TEST_TMP ?= $(shell df -Pk /dev/shm 2>/dev/null | awk -v uid="$$(id -u)" 'NR == 2 && $$4 > 4000000 { print "/dev/shm/neem-oracle-test-" uid }')
# pytest may keep its assertion-rewritten test modules in __pycache__ even where the shell sets
# PYTHONDONTWRITEBYTECODE: otherwise every worker rewrites and compiles all ~280 of them each run.
PYTEST := env -u PYTHONDONTWRITEBYTECODE $(PY) -m pytest
test-python:
	@$(if $(TEST_TMP),mkdir -p -m 700 $(TEST_TMP))
	$(PYTEST) -q -n auto -m "not slow" $(if $(TEST_TMP),--basetemp=$(TEST_TMP)/fast)
	@if [ -n "$(SLOW)$$CI" ]; then echo "slow tests:"; $(PYTEST) -q -n auto -m slow $(if $(TEST_TMP),--basetemp=$(TEST_TMP)/slow); \
	else echo "slow tests skipped here (they run in CI; make test SLOW=1 runs them)"; fi

bench:
	$(PY) -m oracle bench

# make test runs each atheris target 10 s and schemathesis ~600 requests (in CI: 30 s, ~1,000; tests/fuzz); this runs
# them longer. A crash is left in pytest's temporary folder: save it under tests/fuzz/regressions/.
FUZZ_SECONDS ?= 600
SCHEMATHESIS_EXAMPLES ?= 200
fuzz:
	NEEM_FUZZ_SECONDS=$(FUZZ_SECONDS) NEEM_SCHEMATHESIS_EXAMPLES=$(SCHEMATHESIS_EXAMPLES) $(PY) -m pytest -q -n 0 -p no:cacheprovider tests/fuzz

demo:
	$(PY) -m oracle demo

# The reproduction of docs/results.md (experiments/make-results.sh --help); the other reproductions,
# each with its command, are listed in experiments/README.md.
results:
	PY=$(PY) $(if $(SHARED),SHARED=$(SHARED)) bash experiments/make-results.sh

COMPOSE = docker compose -f docker/docker-compose.yml
up up-host:
	@command -v docker >/dev/null 2>&1 || { echo "make $@: docker not found; install Docker Engine with the compose plugin (docs/docker.md)" >&2; exit 1; }
	@docker compose version >/dev/null 2>&1 || { echo "make $@: the docker compose plugin is missing (docs/docker.md)" >&2; exit 1; }
	@test -f docker/.env || { cp docker/.env.example docker/.env && echo "make $@: made docker/.env from docker/.env.example (no secrets in it)"; }
	@! grep -q 'PASSWORD=' docker/.env || { echo "make $@: docker/.env holds a password; move it into docker/secrets/ (docs/docker.md) and delete the line" >&2; exit 1; }
	@python3 scripts/docker-secrets.py docker/secrets
	$(COMPOSE) $(if $(filter up-host,$@),-f docker/host-port.yml) --env-file docker/.env up -d --build
	@echo "NEEMs in the stack's MongoDB:"
	@$(COMPOSE) --env-file docker/.env run --rm --no-deps oracle neems

down:
	@command -v docker >/dev/null 2>&1 || { echo "make down: docker not found" >&2; exit 1; }
	$(COMPOSE) -f docker/host-port.yml --env-file $$( [ -f docker/.env ] && echo docker/.env || echo docker/.env.example ) down

test-mongo:
	@$(PY) scripts/check-mongo.py -- $(PY) -m pytest -q

clean:
	rm -rf build dist *.egg-info python/*.egg-info .pytest_cache
