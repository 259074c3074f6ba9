#!/usr/bin/env python3
"""Checks that the library names options, not the programs' flags: no source
of a library folder (core mesh problems solver integrators energies contact
sim io) throws InputError("flag", ...) or has a string literal naming a flag
("--name"). The library reports "options: <Struct>.<field>: ..." and apps/
maps those names to flags in one table (apps/flag_names.h).

Exit 1 with one line per finding, 0 if there is none.
Usage: python3 tools/check_option_names.py [project root]
"""
import os
import re
import sys

LIBRARY_FOLDERS = ("core", "mesh", "problems", "solver", "integrators", "energies", "contact",
                   "sim", "io")
FLAG_ERROR = re.compile(r'InputError\(\s*"flag"')
# A string literal (no escaped quotes inside, as in this code base) and a
# flag inside it: "--" then a letter.
LITERAL = re.compile(r'"(?:[^"\\\n]|\\.)*"')
FLAG_IN_LITERAL = re.compile(r'--[A-Za-z]')
LINE_COMMENT = re.compile(r'//[^\n]*')


def code_without_comments(text):
    """`text` with // comments blanked (string literals containing // kept)."""
    out = []
    for line in text.split("\n"):
        literals = [(m.start(), m.end()) for m in LITERAL.finditer(line)]
        cut = None
        for m in LINE_COMMENT.finditer(line):
            if not any(a <= m.start() < b for a, b in literals):
                cut = m.start()
                break
        out.append(line if cut is None else line[:cut])
    return "\n".join(out)


def check(root):
    problems = []
    for folder in LIBRARY_FOLDERS:
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if not name.endswith((".h", ".cc")):
                    continue
                path = os.path.join(dirpath, name)
                with open(path, encoding="utf-8") as f:
                    code = code_without_comments(f.read())
                relative = os.path.relpath(path, root)
                for match in FLAG_ERROR.finditer(code):
                    line = code.count("\n", 0, match.start()) + 1
                    problems.append('%s:%d: InputError("flag", ...) in the library: name the '
                                    'option ("options", "<Struct>.<field>")' % (relative, line))
                for match in LITERAL.finditer(code):
                    if FLAG_IN_LITERAL.search(match.group(0)):
                        line = code.count("\n", 0, match.start()) + 1
                        problems.append("%s:%d: a flag in a library string: %s" %
                                        (relative, line, match.group(0)))
    return problems


def self_test():
    """The check finds a flag error and a flag in a string, and accepts an
    option name and a flag in a comment."""
    import tempfile
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "solver"))
        with open(os.path.join(root, "solver", "x.cc"), "w") as f:
            f.write('throw InputError(\n    "flag", "--tolerance", "bad");  // --tolerance\n'
                    'throw InputError("options", "OptimizerOptions.tolerance", "bad");\n'
                    'const char* hint = "use --integrator=newmark";\n'
                    'const char* url = "http://x";  // see --help\n')
        found = check(root)
        assert len(found) == 3, found
        assert "x.cc:1: InputError" in found[0] and "x.cc:2: a flag" in found[1], found
        assert "x.cc:4: a flag" in found[2], found


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
