"""The results record's JSON Schema (experiments/results.schema.json) and a small validator of the
part of JSON Schema it uses: type (one or a list), required, properties, additionalProperties
(false or a schema), items, minimum, minLength, enum, oneOf and "$ref": "#/$defs/NAME". Debian's
python3 has no jsonschema package unless installed, and the schema needs no more than this.

validate_record(record) returns the problems, each "path: what", empty when the record is valid."""
import json
import os
import sys

SCHEMA_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiments", "results.schema.json")

_TYPES = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "boolean": lambda v: isinstance(v, bool),
    "null": lambda v: v is None,
    # JSON has one number type; a bool is not one.
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "integer": lambda v: (isinstance(v, int) and not isinstance(v, bool)) or (isinstance(v, float) and v.is_integer()),
}


def load_schema(path=SCHEMA_PATH):
    with open(path) as f:
        return json.load(f)


def problems(value, schema, root, path="$"):
    """Every way `value` breaks `schema` (root: the whole schema document, for $ref)."""
    if "$ref" in schema:
        prefix = "#/$defs/"
        if not schema["$ref"].startswith(prefix):
            raise ValueError("unsupported $ref " + schema["$ref"])
        return problems(value, root["$defs"][schema["$ref"][len(prefix):]], root, path)
    if "oneOf" in schema:
        matching = [s for s in schema["oneOf"] if not problems(value, s, root, path)]
        return [] if len(matching) == 1 else [f"{path}: matches {len(matching)} of the oneOf alternatives, expected 1"]
    found = []
    if "type" in schema:
        types = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        if not any(_TYPES[t](value) for t in types):
            return [f"{path}: expected {' or '.join(types)}, got {type(value).__name__} {json.dumps(value)[:40]}"]
    if "enum" in schema and value not in schema["enum"]:
        found.append(f"{path}: expected one of {schema['enum']}")
    if "minimum" in schema and _TYPES["number"](value) and value < schema["minimum"]:
        found.append(f"{path}: {value} is below the minimum {schema['minimum']}")
    if "minLength" in schema and isinstance(value, str) and len(value) < schema["minLength"]:
        found.append(f"{path}: shorter than {schema['minLength']} characters")
    if isinstance(value, dict):
        for key in schema.get("required", []):
            if key not in value:
                found.append(f"{path}: missing required '{key}'")
        properties = schema.get("properties", {})
        extra = schema.get("additionalProperties", True)
        for key, item in value.items():
            if key in properties:
                found += problems(item, properties[key], root, f"{path}.{key}")
            elif extra is False:
                found.append(f"{path}: unexpected '{key}'")
            elif isinstance(extra, dict):
                found += problems(item, extra, root, f"{path}.{key}")
    if isinstance(value, list) and "items" in schema:
        for i, item in enumerate(value):
            found += problems(item, schema["items"], root, f"{path}[{i}]")
    return found


def validate_record(record, schema=None):
    schema = schema or load_schema()
    return problems(record, schema, schema)


def validate_results(records, schema=None):
    """The problems of every record of a results.json, each prefixed by the record's index."""
    schema = schema or load_schema()
    return [f"record {i}: {p}" for i, r in enumerate(records) for p in problems(r, schema, schema)]


def main(argv):
    """results_schema.py RESULT_DIR: validates its results.json; exit status 1 with the problems."""
    if len(argv) != 2:
        print("usage: results_schema.py RESULT_DIR", file=sys.stderr)
        return 2
    with open(os.path.join(argv[1], "results.json")) as f:
        found = validate_results(json.load(f))
    for p in found:
        print(p)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
