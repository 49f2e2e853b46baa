#!/usr/bin/env python3
"""No function or lambda in the given folders runs over a length limit (issue #29: the baker reads as steps).

  check_function_length.py FOLDER... [--limit N] [--allow FILE:NAME ...] [--top K]

Scans every C++ (.cpp/.hpp/.h/.cc) and GLSL (.comp/.glsl) file under the folders with a brace-matching
pass over the code (comments, string literals and preprocessor lines blanked first), and counts a function
from the line of its name (a lambda from its capture list) to the line of its closing brace. Prints
FILE:LINE: NAME N lines for each one over the limit (80) and exits 1 when there is any that --allow does
not name; --top K lists the K longest as well.
Exits 2 on bad arguments and on a file whose brackets do not pair up (code inside macros is not measured).
"""
import argparse
import os
import re
import sys

# "layout" opens a GLSL interface block: layout(set = 0, binding = 1) readonly buffer Atoms { ... };
NOT_CALLS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "alignof", "decltype", "requires",
             "static_assert", "noexcept", "alignas", "layout"}
# What may stand between a parameter list's ')' and the body's '{': qualifiers and a trailing return type.
BETWEEN = {"const", "noexcept", "override", "final", "mutable", "constexpr", "volatile", "&", "&&", "->", "::", "<",
           ">", ",", "*"}
TOKEN = re.compile(r"[A-Za-z_]\w*|::|->|&&|\S")
SOURCES = (".cpp", ".hpp", ".h", ".cc", ".comp", ".glsl")


class Unreadable(Exception):
    """Brackets that do not pair up (say each branch of a #if opens its own brace): the lengths would be wrong."""


def blank(text):
    """The text with comments, string and character literals replaced by spaces (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i)
            end = ")" + text[i + 2:k] + '"'
            j = text.find(end, k)
            j = n if j < 0 else j + len(end)
        elif c in "\"'":
            if c == "'" and 0 < i < n - 1 and text[i - 1].isalnum() and text[i + 1].isalnum():
                out.append(" ")  # a digit separator: 1'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j += 1
        else:
            out.append(c)
            i += 1
            continue
        out.append(re.sub(r"[^\n]", " ", text[i:j]))
        i = j
    return "".join(out)


def blank_directives(text):
    """The text with preprocessor lines (and their continuations) replaced by spaces: a macro's braces
    (#define NANO_BEGIN namespace nano::gpu {) are not the code's, and the parentheses of #define F(x) or
    #if defined(X) would name the struct or block that follows."""
    lines = text.split("\n")
    continued = False
    for i, line in enumerate(lines):
        if continued or line.lstrip().startswith("#"):
            continued = line.rstrip().endswith("\\")
            lines[i] = " " * len(line)
    return "\n".join(lines)


def definitions(path):
    """(lines, name, first line) of every function and lambda body in the file."""
    with open(path, encoding="utf-8") as f:
        text = blank_directives(blank(f.read()))
    toks, line = [], 1
    last = 0
    for m in TOKEN.finditer(text):
        line += text.count("\n", last, m.start())
        last = m.start()
        toks.append((m.group(), line))
    opener, pending = {}, []
    for i, (t, line) in enumerate(toks):
        if t in "([{":
            pending.append(i)
        elif t in ")]}":
            if not pending or toks[pending[-1]][0] != "([{"[")]}".index(t)]:
                raise Unreadable(f"{path}:{line}: '{t}' does not close what is open there")
            opener[i] = pending.pop()
    if pending:
        raise Unreadable(f"{path}:{toks[pending[-1]][1]}: '{toks[pending[-1]][0]}' is never closed")

    def named(close_paren):
        """The name before the parameter list that ends at close_paren, or None (a call, a control statement)."""
        p = opener[close_paren] - 1
        if p < 0:
            return None, 0
        name = toks[p][0]
        if name == "]" and p in opener:
            return "lambda", toks[opener[p]][1]
        # operator(), operator==, ...
        for back in (1, 2, 3):
            if p - back >= 0 and toks[p - back][0] == "operator":
                return "operator" + "".join(t for t, _ in toks[p - back + 1:p + 1]), toks[p - back][1]
        if not re.match(r"[A-Za-z_]\w*$", name) or name in NOT_CALLS:
            return None, 0
        # A constructor's member initialisers: walk back over "a(x), b{y}" to the ':' after the parameters.
        q = p - 1
        while q >= 1 and toks[q][0] == ",":
            q -= 1
            if toks[q][0] in (")", "}") and q in opener:
                q = opener[q] - 2
            else:
                break
        if q >= 1 and toks[q][0] == ":" and toks[q - 1][0] == ")" and (q - 1) in opener:
            return named(q - 1)
        return name, toks[p][1]

    found, bodies = [], []
    for i, (t, line) in enumerate(toks):
        if t == "{":
            name, start = None, 0
            if i > 0 and toks[i - 1][0] == "]" and (i - 1) in opener:  # [&] { ... }
                name, start = "lambda", toks[opener[i - 1]][1]
            else:
                j = i - 1
                while j >= 0 and i - j <= 12 and toks[j][0] != ")" and (
                        toks[j][0] in BETWEEN or re.match(r"\w", toks[j][0])):
                    j -= 1
                if j >= 0 and toks[j][0] == ")" and j in opener:
                    name, start = named(j)
            bodies.append((name, start))
        elif t == "}" and bodies:
            name, start = bodies.pop()
            if name:
                found.append((line - start + 1, name, start))
    return found


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--limit", type=int, default=80)
    ap.add_argument("--allow", action="append", default=[], help="FILE:NAME (FILE as printed) allowed over the limit")
    ap.add_argument("--top", type=int, default=0)
    a = ap.parse_args()
    for folder in a.folders:
        if not os.path.isdir(folder):
            print(f"check_function_length: {folder}: not a folder", file=sys.stderr)
            return 2
    everything = []
    for folder in a.folders:
        for root, dirs, names in os.walk(folder):
            dirs.sort()
            for n in sorted(names):
                if n.endswith(SOURCES):
                    path = os.path.join(root, n)
                    shown = os.path.relpath(path, os.path.dirname(os.path.abspath(folder.rstrip("/"))))
                    try:
                        everything += [(lines, name, shown, start) for lines, name, start in definitions(path)]
                    except Unreadable as e:
                        print(f"check_function_length: {e}", file=sys.stderr)
                        return 2
    everything.sort(key=lambda d: (-d[0], d[2], d[3]))
    for lines, name, shown, start in everything[:a.top]:
        print(f"{lines:5d}  {shown}:{start}: {name}")
    over = [d for d in everything if d[0] > a.limit and f"{d[2]}:{d[1]}" not in a.allow]
    for lines, name, shown, start in over:
        print(f"{shown}:{start}: {name} is {lines} lines (more than {a.limit}): split it into named steps")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
