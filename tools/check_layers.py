#!/usr/bin/env python3
"""Checks that every #include "folder/..." in the project goes down the layer
order (the same order as the libraries in CMakeLists.txt):

  core -> geometry -> mesh -> problems -> solver, integrators -> energies -> contact
       -> sim -> io -> apps, bench, tests, examples

A folder may include its own headers and those of the folders it is allowed
below. Exit 1 with one line per upward include, 0 if there is none.
Usage: python3 tools/check_layers.py [project root]
"""
import os
import re
import sys

ALLOWED = {
    "core": {"core"},
    "geometry": {"core", "geometry"},
    "mesh": {"core", "geometry", "mesh"},
    "problems": {"core", "geometry", "mesh", "problems"},
    "solver": {"core", "geometry", "solver"},
    "integrators": {"core", "geometry", "integrators"},
    "energies": {"core", "geometry", "mesh", "problems", "energies"},
    "contact": {"core", "geometry", "mesh", "problems", "energies", "contact"},
    "sim": {"core", "geometry", "mesh", "problems", "energies", "contact", "solver", "integrators",
            "sim"},
    "io": {"core", "geometry", "mesh", "problems", "energies", "contact", "solver", "integrators",
           "sim", "io"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


def check(root):
    problems = []
    for folder, allowed in sorted(ALLOWED.items()):
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if not name.endswith((".h", ".cc")):
                    continue
                path = os.path.join(dirpath, name)
                with open(path, encoding="utf-8") as f:
                    for number, line in enumerate(f, 1):
                        match = INCLUDE.match(line)
                        if match and match.group(1) in ALLOWED and match.group(1) not in allowed:
                            problems.append("%s:%d: %s/ includes %s/ (a higher layer)" % (
                                os.path.relpath(path, root), number, folder, match.group(1)))
    return problems


def self_test():
    """The check finds an upward include and accepts a downward one."""
    import tempfile
    with tempfile.TemporaryDirectory() as root:
        for folder, text in (("core", '#include "sim/simulation.h"\n'),
                             ("sim", '#include "core/state.h"\n')):
            os.makedirs(os.path.join(root, folder))
            with open(os.path.join(root, folder, "x.h"), "w") as f:
                f.write(text)
        found = check(root)
        assert len(found) == 1 and "core/ includes sim/" in found[0], found


def main():
    self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(
        os.path.dirname(os.path.abspath(__file__)))
    problems = check(root)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
