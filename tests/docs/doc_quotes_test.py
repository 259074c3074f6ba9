#!/usr/bin/env python3
"""ctest doc_quotes: every code block of a doc that follows a line naming a
file ("`examples/tether/tether.h`:") is that file, verbatim, so that the doc
cannot drift from the example the test suite builds and runs.

  doc_quotes_test.py SOURCE_DIR DOC.md [DOC.md ...]
"""
import os
import re
import sys


def main():
    source, docs = sys.argv[1], sys.argv[2:]
    quoted = 0
    failures = []
    for doc in docs:
        lines = open(os.path.join(source, doc)).read().split("\n")
        for i, line in enumerate(lines):
            match = re.fullmatch(r".*`([\w./-]+)`:", line)
            if not match or i + 2 >= len(lines) or not lines[i + 2].startswith("```"):
                continue
            if lines[i + 1] != "":
                continue
            end = lines.index("```", i + 3)
            block = "\n".join(lines[i + 3:end]) + "\n"
            path = os.path.join(source, match.group(1))
            if not os.path.isfile(path):
                failures.append(f"{doc}:{i + 1}: quotes {match.group(1)}, which does not exist")
            elif open(path).read() != block:
                failures.append(f"{doc}:{i + 1}: the block differs from {match.group(1)}")
            quoted += 1
    for failure in failures:
        print(failure)
    if quoted == 0:
        print("no quoted files found")
        return 1
    print(f"{quoted} quoted files checked")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
