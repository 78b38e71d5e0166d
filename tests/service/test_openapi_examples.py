"""Every route of the HTTP API has an example in /openapi.json (issue 58, "OpenAPI examples
for every route"): its request body's model and its answer's model each carry one, and each
example is valid for its own model."""

from __future__ import annotations

import pytest

from oracle.service import schemas
from oracle.service.examples import EXAMPLES


def _model(schema: dict, spec: dict) -> dict:
    """The component a schema names (itself, or the items of a list of it)."""
    ref = schema.get("$ref") or (schema.get("items") or {}).get("$ref")
    return spec["components"]["schemas"][ref.rsplit("/", 1)[1]] if ref else schema


def test_every_route_has_an_example_of_what_it_takes_and_answers(client):
    spec = client.get("/openapi.json").json()
    missing = []
    for path, methods in spec["paths"].items():
        for method, operation in methods.items():
            body = (operation.get("requestBody") or {}).get("content", {}).get("application/json")
            if body is not None and "examples" not in _model(body["schema"], spec):
                missing.append(f"{method} {path}: request")
            ok = next(code for code in operation["responses"] if code.startswith("2"))
            answer = operation["responses"][ok].get("content", {}).get("application/json")
            if answer is not None and answer["schema"] and "examples" not in _model(answer["schema"], spec):
                missing.append(f"{method} {path}: answer")
    assert not missing


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_each_example_is_valid_for_its_model(name):
    from oracle.service import routes

    model = getattr(schemas, name, None) or getattr(routes, name)
    model.model_validate(EXAMPLES[name])
