#!/usr/bin/env python3
"""Members per class in core/ (issue 26, acceptance 3: no class above 40).

A rough C++ reader, enough for this code base: in each `class`/`struct`
body it counts the declarations at the body's own level (data members and
member functions; one declaration of several names, `int a, b;`, counts
each name) and the nested types. Comments and access specifiers are
skipped. Prints the classes sorted by member count.

    bench/redesign/class_members.py [--min N]
"""
import argparse
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]


def strip(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r'"(\\.|[^"\\])*"', '""', text)


def names_in(decl):
    decl = re.sub(r"<[^<>]*>", "<>", re.sub(r"<[^<>]*>", "<>", decl))  # template arguments
    if "(" in decl.split("=")[0]:
        return 1  # a function
    depth, parts, cur = 0, [], ""
    for ch in decl:
        depth += ch in "({["
        depth -= ch in ")}]"
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    parts.append(cur)
    return len(parts)


def classes(text):
    for m in re.finditer(r"\b(class|struct)\s+(\w+)\s*(final\s*)?(:[^{;]*)?\{", text):
        start = m.end()
        depth, i, stmt, members, nested = 1, start, "", 0, 0
        while i < len(text) and depth > 0:
            ch = text[i]
            if ch == "{":
                if depth == 1:
                    head = stmt.strip()
                    if re.match(r"^(class|struct|union|enum)\b", head) or re.search(r"\b(class|struct|enum)\s+\w*\s*(:[^{]*)?$", head):
                        nested += 1
                        head = None
                    elif head and head != "=" and not head.endswith("="):
                        members += 1  # a function defined in the body
                        head = None
                    stmt = "" if head is None else stmt + ch
                else:
                    stmt += ch
                depth += 1
            elif ch == "}":
                depth -= 1
                if depth == 1:
                    stmt = "" if not stmt.strip().endswith("=") and "=" not in stmt else stmt + ch
            elif ch == ";" and depth == 1:
                s = re.sub(r"^(public|private|protected)\s*:", "", stmt.strip()).strip()
                s = re.sub(r"\b(public|private|protected)\s*:", "", s).strip()
                if s and not s.startswith(("friend", "using", "static_assert", "typedef")) and not re.match(r"^(class|struct|union|enum)\b", s):
                    members += names_in(s)
                stmt = ""
            elif depth == 1:
                stmt += ch
                stmt = re.sub(r"^\s*(public|private|protected)\s*:", "", stmt)
            else:
                stmt += ch
            i += 1
        yield m.group(2), members, nested


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--min", type=int, default=15)
    args = ap.parse_args()
    rows = []
    for path in sorted((ROOT / "core").rglob("*.hpp")) + sorted((ROOT / "core").rglob("*.h")):
        for name, members, nested in classes(strip(path.read_text())):
            rows.append((members, name, nested, path.relative_to(ROOT)))
    rows.sort(reverse=True)
    for members, name, nested, path in rows:
        if members >= args.min:
            print(f"{members:4d} members {nested:3d} nested types  {name:24s} {path}")
    worst = rows[0][0] if rows else 0
    print(f"largest: {worst} members")


if __name__ == "__main__":
    main()
