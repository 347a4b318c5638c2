#!/usr/bin/env python3
"""The JSON Schema describes real scene files, independently of the loader (python3-jsonschema, Draft 2020-12):
every built-in scene, every variation and validation scene (demo/scenes/variations/, validation/) and the worked
example of docs/scenes.md validate; scenes broken the way the loader's error tests break them do not (one per class
the schema can express). Exit 0 on success, 1 with the reasons.

    /usr/bin/python3 tests/scene/validate_with_schema.py ROOT
"""
import copy
import glob
import json
import os
import sys

from jsonschema import Draft202012Validator


def main(root):
    with open(os.path.join(root, "demo", "scenes", "scene.schema.json")) as f:
        schema = json.load(f)
    Draft202012Validator.check_schema(schema)  # the schema itself is a valid 2020-12 schema
    validator = Draft202012Validator(schema)
    failures = []

    scenes = {}
    for path in sorted(glob.glob(os.path.join(root, "demo", "scenes", "*.json"))):
        if os.path.basename(path) == "scene.schema.json":
            continue
        with open(path) as f:
            scenes[os.path.basename(path)] = json.load(f)
    with open(os.path.join(root, "docs", "scenes.md")) as f:
        doc = f.read()
    start = doc.index("```json\n") + len("```json\n")
    scenes["docs/scenes.md example"] = json.loads(doc[start:doc.index("```", start)])
    if len(scenes) < 9:
        failures.append("expected 8 built-in scenes and the example, found %d" % len(scenes))
    # The variation and validation scenes sit one folder down so that --list-scenes keeps to the eight built-in
    # ones; they declare the same schema and must validate just the same.
    for folder, least in (("variations", 8), ("validation", 2)):
        paths = sorted(glob.glob(os.path.join(root, "demo", "scenes", folder, "*.json")))
        if len(paths) < least:
            failures.append("expected %d scenes in demo/scenes/%s, found %d" % (least, folder, len(paths)))
        for path in paths:
            with open(path) as f:
                scene = json.load(f)
            name = folder + "/" + os.path.basename(path)
            if scene.get("$schema") != "../scene.schema.json":
                failures.append("%s: $schema is not ../scene.schema.json" % name)
            scenes[name] = scene
    for name, scene in scenes.items():
        for error in validator.iter_errors(scene):
            failures.append("%s: %s: %s" % (name, "/" + "/".join(str(p) for p in error.absolute_path), error.message))

    # Broken copies of light-off.json: each must be rejected.
    base = scenes["light-off.json"]

    def broken(description, edit):
        scene = copy.deepcopy(base)
        edit(scene)
        if validator.is_valid(scene):
            failures.append("the schema accepts a scene with " + description)

    def setter(*path_and_value):
        *path, key, value = path_and_value

        def edit(scene):
            node = scene
            for p in path:
                node = node[p]
            node[key] = value
        return edit

    broken("a typo'd key", setter("lights", 1, "colour", [1, 1, 1]))
    broken("a key of another light type", setter("lights", 0, "position", [0, 1, 0]))
    broken("a string intensity", setter("lights", 1, "intensity", "bright"))
    broken("a negative mean free path", setter("materials", 0, "mean_free_path_mm", [-1, 1, 1]))
    broken("fov 180", setter("camera", "fov_y_degrees", 180))
    broken("albedo above 1", setter("materials", 0, "albedo", [0.5, 1.2, 0.5]))
    broken("a zero scale", setter("objects", 0, "transform", {"scale": 0}))
    broken("an unknown light type", setter("lights", 0, "type", "area"))
    broken("an unknown curve type", setter("lights", 0, "intensity", {"type": "ramp", "value": 1}))
    broken("a fractional frame count", setter("frames", 2.5))
    broken("a two-component vector", setter("camera", "position", [0, 1]))
    broken("no camera", lambda s: s.pop("camera"))
    broken("an SSS material without a mean free path", lambda s: s["materials"][0].pop("mean_free_path_mm"))
    broken("a curve key of another curve type", setter("lights", 0, "intensity", "period_frames", 3))
    broken("no objects", setter("objects", []))

    for f in failures:
        sys.stderr.write("validate_with_schema: " + f + "\n")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.stderr.write("usage: validate_with_schema.py ROOT\n")
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
