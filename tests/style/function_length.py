#!/usr/bin/env python3
"""Functions in C++ sources longer than a limit (docs/architecture.md, "Function length").

Usage: function_length.py SRC_DIR [--limit N] [--all]
Prints `path:line: name (N lines)` for every function of more than N lines (default 120),
signature to closing brace, whose comment right above the signature has no `long:` (the reason
it is long); --all lists the marked ones too. Exit status 1 if any is printed (with --all: if
any unmarked one is), 2 if a file's braces do not balance (the scanner misread it).

A scanner, not a parser: comments, string and character literals and preprocessor lines are
blanked first; then a `{` outside a function body opens a function when the text before it
since the last `;`, `{` or `}` ends like a signature (`)`, a qualifier such as `const`, or a
trailing return type), and a namespace, class or initialiser otherwise.
"""
import os
import re
import sys

QUALIFIERS = {"const", "noexcept", "override", "final", "mutable", "volatile", "try"}
CONTAINER = re.compile(r"^(template\s*<.*>\s*)?(inline\s+)?(namespace|class|struct|union|enum|extern)\b", re.S)
ACCESS = re.compile(r"^(public|private|protected)\s*:(?!:)")


def blank(text):
    """text with comments, literals and preprocessor lines replaced by spaces (newlines kept)."""
    out = list(text)
    n = len(text)
    i = 0
    at_line_start = True

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if c == "\n":
            at_line_start = True
            i += 1
            continue
        if at_line_start and c in " \t":
            i += 1
            continue
        if at_line_start and c == "#":  # preprocessor line, with its continuations
            j = i
            while j < n and (text[j] != "\n" or text[j - 1] == "\\"):
                j += 1
            wipe(i, j)
            i = j
            continue
        at_line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            wipe(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            wipe(i, j)
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")
                                                        or text[i - 1] in "uUL8"):
            m = re.match(r'R"([^(\s]{0,16})\(', text[i:])
            if not m:
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i + m.end())
            j = n if end < 0 else end + len(m.group(1)) + 2
            wipe(i, j)
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                i += 1  # digit separator: 10'000
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            wipe(i + 1, min(j, n))
            i = j + 1
        else:
            i += 1
    return "".join(out)


def looks_like_signature(header):
    h = header.strip()
    if not h or "(" not in h or CONTAINER.match(h):
        return False
    if "->" in h[h.rfind(")"):]:
        return True  # trailing return type
    last = re.split(r"\s+", h)[-1]
    if h.endswith(")") or last in QUALIFIERS:
        return True
    # a constructor whose initialiser list ends with a braced member: `: a_(x), b_{y} {`
    return h.endswith("}") and re.search(r"\)\s*:", h) is not None


def functions(text):
    """(first line, last line, name) of each function body at namespace or class level."""
    code = blank(text)
    found = []
    stack = []  # per open brace: ("fn", start line, name) / ("block",) / ("init",)
    header_start = 0
    line = 1
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
            continue
        if any(s[0] == "fn" for s in stack):
            if c == "{":
                stack.append(("block",))
            elif c == "}":
                top = stack.pop()
                if top[0] == "fn":
                    found.append((top[1], line, top[2]))
                    header_start = i + 1
            continue
        if c == ";":
            header_start = i + 1
        elif c == "{":
            header = code[header_start:i]
            stripped = header.lstrip()
            m = ACCESS.match(stripped)
            if m:  # `public: int f() {`: the signature starts after the label
                header_start += len(header) - len(stripped) + m.end()
                header = code[header_start:i]
                stripped = header.lstrip()
            if looks_like_signature(header):
                first = code.count("\n", 0, header_start + len(header) - len(stripped)) + 1
                name = re.findall(r"([~\w:]+(?:operator\s*\S+?)?)\s*\(", header)
                stack.append(("fn", first, name[0] if name else "?"))
            elif CONTAINER.match(stripped) or not stripped:
                stack.append(("block",))
                header_start = i + 1
            else:
                stack.append(("init",))  # `x = {`, `T x{...}`: part of a declaration
        elif c == "}":
            if not stack:
                return found, False
            top = stack.pop()
            if top[0] == "block":
                header_start = i + 1
    return found, not stack


def marked_long(lines, first):
    """Whether the // comment block right above line `first` (1-based) says `long:`."""
    k = first - 2
    while k >= 0 and lines[k].strip().startswith("//"):
        if "long:" in lines[k]:
            return True
        k -= 1
    return False


def main(argv):
    if len(argv) < 2:
        print(__doc__.splitlines()[2])
        return 2
    root, limit, show_all = argv[1], 120, "--all" in argv
    if "--limit" in argv:
        limit = int(argv[argv.index("--limit") + 1])
    status = 0
    for d, _, files in sorted(os.walk(root)):
        for f in sorted(files):
            if not f.endswith((".cpp", ".hpp", ".h", ".cc")):
                continue
            path = os.path.join(d, f)
            text = open(path, encoding="utf-8", errors="replace").read()
            found, balanced = functions(text)
            if not balanced:
                print(f"{path}: braces do not balance after blanking comments and literals (scanner misread)")
                status = max(status, 2)
                continue
            lines = text.split("\n")
            for first, last, name in found:
                n = last - first + 1
                if n <= limit:
                    continue
                marked = marked_long(lines, first)
                if marked and not show_all:
                    continue
                print(f"{path}:{first}: {name} ({n} lines{', marked long:' if marked else ''})")
                if not marked:
                    status = max(status, 1)
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
