#!/usr/bin/python3
"""Lists the C++ functions longer than a limit (default 100 lines, signature to closing brace).

A small brace parser, no compiler: comments, string and character literals are blanked first; a
'{' at namespace or class scope opens a function body when the text before it (back to the last
';', '{' or '}') has a parameter list and is not a namespace, class, struct, union, enum or an
initializer. Lambdas and local classes count in the function that holds them.

usage: function_length_check.py [--limit N] ROOT [DIR...]
  DIRs relative to ROOT (default: common techniques metrics experiments tests). Exit status 1 when
  any function is over the limit.
"""
import argparse
import os
import re
import sys

SOURCE_EXTENSIONS = (".cpp", ".h", ".hpp", ".cc")
NOT_FUNCTIONS = re.compile(r"\b(namespace|class|struct|union|enum)\b")


def blank_comments_and_literals(text):
    """The text with comments, string and character literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i)
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum() and not text[i - 1].isalpha():
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def function_name(header):
    """The qualified name before the parameter list of a function header; TEST(Suite, Name) whole."""
    header = re.sub(r"\s+", " ", header).strip()
    test = re.match(r"(TEST(?:_F|_P)?) ?\(([^)]*)\)", header)
    if test:
        return f"{test.group(1)}({test.group(2).replace(' ', '')})"
    m = re.search(r"(operator\s*\S+?|[~\w:]+)\s*\(", header)
    return m.group(1).strip() if m else header[:60]


def long_functions(path, limit):
    text = blank_comments_and_literals(open(path, encoding="utf-8", errors="replace").read())
    found = []
    stack = []  # per open brace: "scope" (namespace, class, extern) or "body" or "other"
    last_stop = 0  # index after the last ';', '{' or '}' at the current level
    body_start = None  # (index of the header's start, name) of the function being read
    for i, c in enumerate(text):
        if c == "{":
            inside_body = any(kind == "body" for kind in stack)
            kind = "other"
            if not inside_body:
                header = text[last_stop:i]
                stripped = header.strip()
                if NOT_FUNCTIONS.search(stripped.split("(")[0]) or stripped.startswith("extern") or stripped == "":
                    kind = "scope"
                elif "(" in stripped and not re.search(r"=\s*$", stripped) and not stripped.endswith(","):
                    kind = "body"
                    # The header starts after any access specifier ("public:") before it.
                    specifier = re.match(r"\s*((public|private|protected)\s*:)?\s*", header)
                    start = last_stop + specifier.end()
                    body_start = (start, function_name(header[specifier.end():].strip()))
            stack.append(kind)
            last_stop = i + 1
        elif c == "}":
            kind = stack.pop() if stack else "other"
            if kind == "body" and body_start is not None:
                start, name = body_start
                first = text.count("\n", 0, start) + 1
                last = text.count("\n", 0, i) + 1
                if last - first + 1 > limit:
                    found.append((first, last - first + 1, name))
                body_start = None
            last_stop = i + 1
        elif c == ";" and not any(kind == "body" for kind in stack):
            last_stop = i + 1
        elif c == "#" and (i == 0 or text[i - 1] == "\n") and not any(kind == "body" for kind in stack):
            # A preprocessor line is not part of the next declaration.
            j = text.find("\n", i)
            while j > 0 and text[j - 1] == "\\":
                j = text.find("\n", j + 1)
            last_stop = (len(text) if j < 0 else j + 1)
    return found


def self_test():
    """The parser on a file of known function lengths: braces in comments, strings, raw strings and
    character literals, lambdas, classes, namespaces and initializers must not move them."""
    import tempfile
    body = lambda n: "\n".join(["    x += 1;"] * (n - 2))  # a function of n lines: header line, body, closing brace
    source = "\n".join([
        "#include <string>",
        "namespace hybridlab {",
        "namespace {",
        "const int kTable[] = {1, 2, 3};",
        "struct Point { int x = 0; int f() const { return x; } };",
        "}  // namespace",
        "int exactlyTheLimit(int x) {", body(100), "}",
        "int oneOver(int x) {", "    auto f = [&](int y) { return y + '{'; };  // {", '    const char* s = "}}}";',
        '    const char* r = R"x(})x";', "    /* { */", body(97), "}",
        "class Widget {",
        "public:",
        "    void method(int x)",
        "    {", body(100), "}",
        "};",
        "}  // namespace hybridlab",
    ])
    with tempfile.NamedTemporaryFile("w", suffix=".cpp", delete=False) as f:
        f.write(source)
    found = long_functions(f.name, 100)
    os.unlink(f.name)
    expected = [("oneOver", 101), ("method", 101)]
    got = [(name, length) for _, length, name in found]
    if got != expected:
        sys.exit(f"self-test: expected {expected}, found {got}")
    print("self-test passed:", got)


def main():
    self_test()  # the parser first, on lengths known in advance
    parser = argparse.ArgumentParser()
    parser.add_argument("--limit", type=int, default=100)
    parser.add_argument("root")
    parser.add_argument("dirs", nargs="*", default=["common", "techniques", "metrics", "experiments", "tests"])
    args = parser.parse_args()
    over = []
    for d in args.dirs:
        for folder, _, files in os.walk(os.path.join(args.root, d)):
            for f in sorted(files):
                if not f.endswith(SOURCE_EXTENSIONS):
                    continue
                path = os.path.join(folder, f)
                rel = os.path.relpath(path, args.root)
                for line, length, name in long_functions(path, args.limit):
                    over.append(f"{rel}:{name}")
                    print(f"{rel}:{line}: {name}: {length} lines")
    if over:
        print(f"{len(over)} function(s) over {args.limit} lines: split each into functions named for what they do")
        return 1
    print(f"no function over {args.limit} lines")
    return 0

if __name__ == "__main__":
    sys.exit(main())
