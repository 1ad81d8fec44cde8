#!/usr/bin/env python3
"""Fails (exit 1) when a file under src/ includes a project header its layer may not include.

Usage: check_layers.py SRC_DIR

The layers and the one-way dependencies between them (docs/design.md, Source layout). A file's
layer is its folder below src/ (core/<concept>, io, scene, render, app); it may include headers
of its own layer and of the layers listed for it. Includes are the quoted ones ("core/rbf/hrbf.h"),
written relative to src/.
"""
import os
import re
import sys

CORE = ["core/base", "core/points", "core/rbf", "core/pu", "core/patch", "core/mesh", "core/shapes",
        "core/trace"]

ALLOWED = {
    "core/base": [],
    "core/points": ["core/base"],
    "core/rbf": ["core/base", "core/points"],
    "core/pu": ["core/base", "core/points", "core/rbf"],
    "core/patch": ["core/base"],
    "core/mesh": ["core/base", "core/points", "core/rbf"],
    "core/shapes": ["core/base", "core/points", "core/mesh"],
    "core/trace": ["core/base", "core/points", "core/rbf"],
    "io": CORE,
    "scene": CORE + ["io"],
    "render": CORE,
    "app": CORE + ["io", "scene", "render"],
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def layer_of(relative_path):
    """The layer a path below src/ belongs to (the longest matching folder prefix), or None."""
    best = None
    for layer in ALLOWED:
        if relative_path == layer or relative_path.startswith(layer + "/"):
            if best is None or len(layer) > len(best):
                best = layer
    return best


def main():
    if len(sys.argv) != 2:
        print("usage: check_layers.py SRC_DIR", file=sys.stderr)
        return 2
    src = sys.argv[1]
    problems = []
    unplaced = []
    for folder, _, files in os.walk(src):
        for name in sorted(files):
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.join(folder, name)
            relative = os.path.relpath(path, src).replace(os.sep, "/")
            layer = layer_of(relative)
            if layer is None:
                unplaced.append(relative)
                continue
            allowed = [layer] + ALLOWED[layer]
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    target = m.group(1)
                    target_layer = layer_of(target)
                    if target_layer is None:  # a header beside the file, e.g. a shader table
                        continue
                    if target_layer not in allowed:
                        problems.append(f"{relative}:{number}: layer {layer} may not include \"{target}\" "
                                        f"(layer {target_layer}); it may include {', '.join(allowed)}")
    for relative in unplaced:
        problems.append(f"{relative}: not in any layer folder (core/<concept>, io, scene, render, app)")
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_layers: {len(problems)} include(s) break the layering; see docs/design.md", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
