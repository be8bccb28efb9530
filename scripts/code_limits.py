#!/usr/bin/python3
"""The house limits of cpp/, checked (the test code_limits):

  - no .cpp file over 600 lines;
  - no function over 120 lines, but the scene-key table (make_keys);
  - no string look-up of a scene key outside cpp/scene/: modules take their
    typed part of the scene (scene/SceneParts.h), never the dictionary;
  - the project cites no file outside itself (no "STYLE.md", no "../shared").

  scripts/code_limits.py [--list N]   (--list N: the N longest functions)
Exits 1 if a limit is broken, naming the file, line and size.
"""
import argparse
import os
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MAX_CPP_LINES = 600
MAX_FUNCTION_LINES = 120
FUNCTION_EXCEPTIONS = {"make_keys"}  # the key table: one entry per key
# Scene look-ups by key name: scene.number("geometry.width") and the like.
SCENE_LOOKUP = re.compile(r'\.(number|integer|boolean|string|numbers|find)\("[a-z_]+\.[a-z_.]+"\)')
OUTSIDE_REFERENCE = re.compile(r"STYLE\.md|\.\./shared|DESIGN\.md")


def strip_comments_and_strings(text: str) -> str:
    """The code with comments, string and character literals blanked (line
    breaks kept, so that line numbers stay)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path: Path):
    """(name, first line, lines) of each function body at namespace or class
    level: a brace whose header (the code since the previous ; { or }) has a
    parameter list and is not a class, namespace, enum or initializer."""
    code = strip_comments_and_strings(path.read_text())
    stack = []  # for each open brace: True if it is a scope (namespace, class)
    start = 0   # where the current header starts
    found = []
    for i, c in enumerate(code):
        if c == "{":
            header = code[start:i]
            in_scope = all(e is True for e in stack)
            words = header.split()
            is_scope = bool(re.search(r"\b(namespace|class|struct|union|enum)\b", header)) and "(" not in header.split(":")[0]
            is_function = (in_scope and not is_scope and "(" in header
                           and not re.search(r"=\s*$", header.strip()) and words)
            if is_function:
                m = re.search(r"([~\w:]+|operator\S+)\s*\(", header)
                name = m.group(1) if m else "?"
                # From the signature's first line (template and return type
                # included) to the closing brace.
                first = start + len(header) - len(header.lstrip())
                stack.append(("function", name, code.count("\n", 0, first) + 1))
            else:
                stack.append(is_scope or not in_scope)
            start = i + 1
        elif c == "}":
            if stack:
                top = stack.pop()
                if isinstance(top, tuple):
                    end = code.count("\n", 0, i) + 1
                    found.append((top[1], top[2], end - top[2] + 1))
            start = i + 1
        elif c == ";":
            start = i + 1
    return found


def project_files():
    """The files under ROOT but .git and the build folder. Those two are
    pruned before they are read: ctest runs this beside the tests that
    write and delete folders under build/ (os.walk passes over a folder
    that vanishes; ROOT.rglob raised FileNotFoundError)."""
    for folder, subfolders, files in os.walk(ROOT):
        if Path(folder) == ROOT:
            subfolders[:] = [d for d in subfolders if d not in (".git", "build")]
        elif ".git" in subfolders:
            subfolders.remove(".git")
        for name in files:
            yield Path(folder) / name


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--list", type=int, default=0, metavar="N", help="also print the N longest functions")
    count = ap.parse_args().list
    problems = []
    sources = sorted(p for p in (ROOT / "cpp").rglob("*") if p.suffix in (".h", ".cpp"))
    all_functions = []
    for path in sources:
        rel = path.relative_to(ROOT)
        text = path.read_text()
        lines = text.count("\n")
        if path.suffix == ".cpp" and lines > MAX_CPP_LINES:
            problems.append(f"{rel}: {lines} lines (at most {MAX_CPP_LINES})")
        for name, line, length in functions(path):
            all_functions.append((length, f"{rel}:{line} {name}"))
            if length > MAX_FUNCTION_LINES and name.split("::")[-1] not in FUNCTION_EXCEPTIONS:
                problems.append(f"{rel}:{line}: {name} is {length} lines (at most "
                                f"{MAX_FUNCTION_LINES})")
        if rel.parts[1] != "scene":
            for k, text_line in enumerate(text.splitlines(), 1):
                m = SCENE_LOOKUP.search(text_line)
                if m:
                    problems.append(f"{rel}:{k}: looks up the scene key {m.group(0)[1:]} "
                                    "(take the typed part, scene/SceneParts.h)")
    tracked = [p for p in project_files()
               if p.suffix in (".h", ".cpp", ".py", ".md", ".txt", ".sh", ".toml", ".geo")
               and p.resolve() != Path(__file__).resolve()]
    for path in sorted(tracked):
        for k, text_line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            if OUTSIDE_REFERENCE.search(text_line):
                problems.append(f"{path.relative_to(ROOT)}:{k}: cites a file outside the project")
    if count:
        for length, where in sorted(all_functions, reverse=True)[:count]:
            print(f"{length:5d}  {where}")
    for p in problems:
        print(p, file=sys.stderr)
    if not problems:
        print(f"{len(sources)} files: .cpp at most {MAX_CPP_LINES} lines, functions at most "
              f"{MAX_FUNCTION_LINES} (but {', '.join(sorted(FUNCTION_EXCEPTIONS))}), no scene "
              "look-up outside scene/, no file cited from outside")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
