#!/usr/bin/env python3
"""Writes the key table of docs/scenes.md from demo/scenes/scene.schema.json (one source of truth for the
keys, types, ranges and defaults; the loader's key table is checked against the same schema by tests/scene).

    /usr/bin/python3 scripts/scene_schema_table.py            # print the table
    /usr/bin/python3 scripts/scene_schema_table.py --write    # replace it in docs/scenes.md
    /usr/bin/python3 scripts/scene_schema_table.py --check    # exit 1 when docs/scenes.md is out of date
"""
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCHEMA = os.path.join(ROOT, "demo", "scenes", "scene.schema.json")
DOC = os.path.join(ROOT, "docs", "scenes.md")
BEGIN, END = "<!-- scene-keys:begin (scripts/scene_schema_table.py) -->", "<!-- scene-keys:end -->"


def ref_name(node):
    return node["$ref"].split("/")[-1] if "$ref" in node else None


def resolve(schema, node):
    """The node merged over the definition it references (the node's own keywords win)."""
    name = ref_name(node)
    if not name:
        return dict(node)
    merged = dict(resolve(schema, schema["$defs"][name]))
    merged.update({k: v for k, v in node.items() if k != "$ref"})
    return merged


def number(x):
    return ("%g" % x) if isinstance(x, (int, float)) else str(x)


def interval(node):
    lo = ("(" + number(node["exclusiveMinimum"])) if "exclusiveMinimum" in node else \
         ("[" + number(node["minimum"])) if "minimum" in node else None
    hi = (number(node["exclusiveMaximum"]) + ")") if "exclusiveMaximum" in node else \
         (number(node["maximum"]) + "]") if "maximum" in node else None
    if lo is None and hi is None:
        return ""
    return "%s, %s" % (lo or "(-inf", hi or "inf)")


def describe_type(schema, node):
    """(type text, range text) of one property."""
    name = ref_name(node)
    n = resolve(schema, node)
    if "oneOf" in n:
        parts = [describe_type(schema, alt) for alt in n["oneOf"]]
        return " or ".join(p[0] for p in parts), " / ".join(p[1] for p in parts if p[1])
    if "const" in n:
        return '`"%s"`' % n["const"], ""
    if n.get("type") == "array":
        item = resolve(schema, n.get("items", {}))
        if n.get("minItems") == 3 and n.get("maxItems") == 3:
            return "3 numbers", interval(item) and "each in " + interval(item)
        if name == "keys" or "$ref" in n.get("items", {}):
            return "array of `%s`" % ref_name(n["items"]), ("at least %d" % n["minItems"]) if "minItems" in n else ""
        return "array of %s" % item.get("type", "values"), interval(item) and "each in " + interval(item)
    if "$ref" in node and ref_name(node) in schema["$defs"] and "properties" in schema["$defs"][ref_name(node)]:
        return "`%s` object" % ref_name(node), ""
    t = n.get("type", "")
    if t == "string" and n.get("minLength"):
        t = "non-empty string"
    return t, interval(n)


def kinds(schema):
    yield "scene", schema
    for name, d in schema["$defs"].items():
        if "properties" in d:
            yield name, d


def table(schema):
    rows = ["| object | key | type | range | default | required | meaning |",
            "|---|---|---|---|---|---|---|"]
    for kind, d in kinds(schema):
        required = set(d.get("required", []))
        for key, prop in d["properties"].items():
            typ, rng = describe_type(schema, prop)
            merged = resolve(schema, prop)
            default = json.dumps(merged["default"]) if "default" in merged else ""
            meaning = prop.get("description", merged.get("description", "")).replace("|", "\\|")
            rows.append("| `%s` | `%s` | %s | %s | %s | %s | %s |" % (
                kind, key, typ, rng, "`%s`" % default if default else "", "yes" if key in required else "",
                meaning))
    return "\n".join(rows) + "\n"


def main(argv):
    with open(SCHEMA) as f:
        schema = json.load(f)
    text = table(schema)
    if len(argv) == 1:
        sys.stdout.write(text)
        return 0
    if argv[1] not in ("--write", "--check"):
        sys.stderr.write("scene_schema_table.py: unknown argument %s (use --write or --check)\n" % argv[1])
        return 2
    with open(DOC) as f:
        doc = f.read()
    if BEGIN not in doc or END not in doc:
        sys.stderr.write("scene_schema_table.py: %s lacks the markers %s ... %s\n" % (DOC, BEGIN, END))
        return 1
    head, rest = doc.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    new = head + BEGIN + "\n" + text + END + tail
    if argv[1] == "--check":
        if new != doc:
            sys.stderr.write("scene_schema_table.py: docs/scenes.md's key table is out of date "
                             "(run /usr/bin/python3 scripts/scene_schema_table.py --write)\n")
            return 1
        return 0
    tmp = DOC + ".tmp"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, DOC)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
