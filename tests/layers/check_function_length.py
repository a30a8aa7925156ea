#!/usr/bin/env python3
"""Lists every C++ function body longer than a limit (60 lines by default), signature to closing
brace, in the files given or in core/, server/ and bench/ below ROOT; exits 1 if there is one.

    tests/layers/check_function_length.py [--limit N] [ROOT | FILE...]

A brace scanner, not a parser: comments, string and character literals (raw strings included)
are blanked first; a brace opened at namespace or class scope after a ')' starts a function."""
import argparse
import os
import pathlib
import re
import sys


def blank(source):
    """The source with comments and literals emptied, line breaks kept."""
    pattern = re.compile(r'//[^\n]*|/\*.*?\*/|R"\((?:.*?)\)"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
                         re.S)
    return pattern.sub(lambda m: '\n' * m.group(0).count('\n'), source)


def kind_of(head, in_scope):
    if re.search(r'\bnamespace\b', head) or head.startswith('extern'):
        return 'scope'
    if in_scope and re.search(r'\b(struct|class|union|enum)\b', head) and not head.endswith(')'):
        return 'scope'
    if in_scope and ')' in head and not head.endswith('='):
        return 'function'
    return 'block'


def long_functions(path, limit):
    text = blank(path.read_text())
    stack, line, last, found = [], 1, 0, []
    for i, c in enumerate(text):
        if c == '\n':
            line += 1
        elif c == ';':
            last = i + 1
        elif c == '{':
            head = text[last:i]
            lead = head[:len(head) - len(head.lstrip())]
            first = line - head.count('\n') + lead.count('\n')  # the head's first line
            in_scope = all(kind == 'scope' for kind, _ in stack)
            stack.append((kind_of(head.strip(), in_scope), first))
            last = i + 1
        elif c == '}':
            if stack:
                kind, first = stack.pop()
                if kind == 'function' and line - first + 1 > limit:
                    found.append((line - first + 1, f'{os.path.relpath(path)}:{first}'))
            last = i + 1
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--limit', type=int, default=60)
    parser.add_argument('paths', nargs='*', default=[str(pathlib.Path(__file__).parents[2])])
    args = parser.parse_args()
    files = []
    for p in map(pathlib.Path, args.paths):
        if p.is_dir():
            files += sorted(f for d in ('core', 'server', 'bench') for f in (p / d).rglob('*')
                            if f.suffix in ('.h', '.cpp'))
        else:
            files.append(p)
    found = sorted((f for path in files for f in long_functions(path, args.limit)), reverse=True)
    for lines, where in found:
        print(f'{where}: a function of {lines} lines (limit {args.limit})')
    print(f'{len(files)} files, {len(found)} functions over {args.limit} lines')
    return 1 if found else 0


if __name__ == '__main__':
    sys.exit(main())
