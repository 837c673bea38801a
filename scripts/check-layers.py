#!/usr/bin/env python3
"""Fails when an #include crosses the layering of DESIGN.md §2 (issue 17).

Modules, bottom-up (an arrow may only point down):

    station -> sim -> hal -> base
    station -> core -> base

Inside a module, folders form layers too: no two folders may include each
other (directly or through a longer cycle), and hal's folders keep the order
below. Run from the repository root (or give --root DIR); prints every offending include line and
exits 1, or prints the module map and exits 0.
"""
import os
import re
import sys
from collections import defaultdict

MODULES = ["base", "core", "hal", "sim", "station"]
ALLOWED = {
    "base": set(),
    "core": {"base"},
    "hal": {"base"},
    "sim": {"hal", "base"},
    "station": {"core", "hal", "sim", "base"},
}
# hal's folders from the bottom: basic types, then what reads them, then what
# assembles readers. A folder may include its own layer or any lower one.
HAL_LAYERS = [
    {"types"},
    {"parsers", "normalizer", "pose", "stroke", "force"},
    {"backends", "input", "haptics"},
    {"registry"},
]
# The station without a screen (sculpt::station_app): these folders see no
# window, GL renderer or command line, and no GL, GLFW or ImGui header.
STATION_APP_FOLDERS = {"app", "project", "view", "settings", "render", "haptics"}
STATION_SCREEN_FOLDERS = {"window", "render/gl", "cli"}
SCREEN_HEADERS = re.compile(r"^(GLFW/|GL/|imgui|backends/imgui|glad/)")
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]')


def folder_of(parts):
    """The folder of a path's parts below a module's src/ or include/sculpt/<module>/:
    the first part, except that render/gl is a folder of its own (the GL
    renderer beside the software one)."""
    if len(parts) < 2:
        return ""
    if parts[0] == "render" and len(parts) > 2 and parts[1] == "gl":
        return "render/gl"
    return parts[0]


def module_folder_of_file(path):
    """('hal', 'parsers') for hal/src/parsers/x.cpp or hal/include/sculpt/hal/parsers/x.h."""
    parts = path.split(os.sep)
    module = parts[0]
    if len(parts) > 4 and parts[1] == "include":
        return module, folder_of(parts[4:])
    if len(parts) > 2 and parts[1] == "src":
        return module, folder_of(parts[2:])
    return module, ""


def module_folder_of_include(target, src_module):
    """The module and folder an include names, or None for a system header.

    Public headers are sculpt/<module>/<folder>/<file>; a module's private
    headers are named from its src/ folder ("render/gl/shader.h")."""
    parts = target.split("/")
    if parts[0] == "sculpt" and len(parts) > 2 and parts[1] in MODULES:
        return parts[1], folder_of(parts[2:])
    if os.path.exists(os.path.join(src_module, "src", target)):
        return src_module, folder_of(parts)
    return None


def hal_layer(folder):
    for index, layer in enumerate(HAL_LAYERS):
        if folder in layer:
            return index
    return None


def main():
    # --root DIR checks another tree (the test's deliberately broken one).
    if len(sys.argv) == 3 and sys.argv[1] == "--root":
        os.chdir(sys.argv[2])
    problems = []
    folder_edges = defaultdict(set)  # (module, folder) -> {(module, folder)}
    module_edges = defaultdict(set)
    for module in MODULES:
        for root, _, files in os.walk(module):
            for name in files:
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(root, name)
                src_module, src_folder = module_folder_of_file(path)
                with open(path, encoding="utf-8") as source:
                    for number, line in enumerate(source, 1):
                        match = INCLUDE.match(line)
                        if not match:
                            continue
                        where = f"{path}:{number}: includes {match.group(1)}"
                        station_app = src_module == "station" and src_folder in STATION_APP_FOLDERS
                        if station_app and SCREEN_HEADERS.match(match.group(1)):
                            problems.append(f"{where}: station/{src_folder} is screen-free")
                        named = module_folder_of_include(match.group(1), src_module)
                        if named is None:
                            continue
                        dst_module, dst_folder = named
                        if dst_module != src_module:
                            module_edges[src_module].add(dst_module)
                            if dst_module not in ALLOWED.get(src_module, set()):
                                problems.append(f"{where}: {src_module} may not see {dst_module}")
                            continue
                        if station_app and dst_module == "station" and dst_folder in STATION_SCREEN_FOLDERS:
                            problems.append(f"{where}: station/{src_folder} may not see station/{dst_folder}")
                        if dst_folder == src_folder:
                            continue
                        folder_edges[(src_module, src_folder)].add((dst_module, dst_folder))
                        if src_module == "hal":
                            src_layer, dst_layer = hal_layer(src_folder), hal_layer(dst_folder)
                            if src_layer is None or dst_layer is None:
                                problems.append(f"{where}: hal folder not in HAL_LAYERS")
                            elif dst_layer > src_layer:
                                problems.append(f"{where}: hal/{src_folder} is below hal/{dst_folder}")
    # Folder cycles anywhere: depth-first search for a back edge.
    state = {}
    def visit(node, stack):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(folder_edges.get(node, ())):
            if state.get(nxt) == "open":
                cycle = stack[stack.index(nxt):] + [nxt]
                problems.append("folder cycle: " + " -> ".join(f"{m}/{f}" for m, f in cycle))
            elif nxt not in state:
                visit(nxt, stack)
        stack.pop()
        state[node] = "done"
    for node in sorted(folder_edges):
        if node not in state:
            visit(node, [])
    if problems:
        print("\n".join(problems))
        print(f"check-layers: {len(problems)} include(s) break the layering (scripts/check-layers.py)")
        return 1
    for module in MODULES:
        print(f"{module:8} -> {', '.join(sorted(module_edges[module])) or '(nothing)'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
