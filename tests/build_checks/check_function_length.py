#!/usr/bin/env python3
"""Fails naming every function body longer than a limit (150 lines) in the given folders.

A function that long glues several concepts (docs/architecture.md, "The render loop"): split
it along them. Bodies are found by brace matching after a parameter list's ")" (comments,
string and character literals removed first, so their braces do not count); lambdas inside a
function count towards it, and control statements (if, for, while, switch, catch) are not
functions.
"""
import pathlib
import re
import sys

LIMIT = 150


def stripped(src):
    """The source with comments and literals blanked (newlines kept, so lines stay lines)."""
    out = []
    i, n = 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif src.startswith("/*", i):
            j = src.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * src.count("\n", i, j))
            i = j
        elif src.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', src[i:])
            end = src.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + "\n" * src.count("\n", i, j))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and src[i - 1].isalnum():  # a digit separator (1'000)
                i += 1
                continue
            j = i + 1
            while j < n and src[j] != c:
                j += 2 if src[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


HEAD = re.compile(r"\)\s*(const\s*)?(override\s*)?(noexcept\s*)?(->\s*[\w:<>,\s\*&]+)?\s*\{")
CONTROL = re.compile(r"\b(if|for|while|switch|catch)\s*\($")


def long_functions(path):
    src = stripped(path.read_text(encoding="utf-8", errors="replace"))
    found, covered = [], -1
    for m in HEAD.finditer(src):
        start = m.end() - 1
        if start <= covered:
            continue  # inside a body already measured (a lambda, a local class)
        # The statement's head: from the matching "(" backwards.
        depth, k = 0, m.start()
        while k >= 0:
            if src[k] == ")":
                depth += 1
            elif src[k] == "(":
                depth -= 1
                if depth == 0:
                    break
            k -= 1
        if CONTROL.search(src[max(0, k - 12) : k + 1]):
            continue
        depth, j = 0, start
        while j < len(src):
            if src[j] == "{":
                depth += 1
            elif src[j] == "}":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        first, last = src.count("\n", 0, start) + 1, src.count("\n", 0, j) + 1
        covered = j
        if last - first + 1 > LIMIT:
            line = src[src.rfind("\n", 0, k) + 1 : m.start()].strip()
            found.append((path, first, last - first + 1, line[-70:]))
    return found


def main(argv):
    root = pathlib.Path(argv[1])
    failures = []
    for folder in argv[2:]:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix in (".h", ".cpp"):
                failures += long_functions(path)
    for path, line, length, head in failures:
        print(f"functions: {path.relative_to(root)}:{line}: a body of {length} lines "
              f"(at most {LIMIT}): {head}")
    if not failures:
        print(f"functions: none longer than {LIMIT} lines in {', '.join(argv[2:])}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
