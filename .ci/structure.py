#!/usr/bin/env python3
"""Structure limits (docs/ARCHITECTURE.md, "Conventions").

- Source files above 700 lines outside #[cfg(test)], unless the file is in
  ALLOWED_LONG with a one-line reason: a file that is one thing may be long,
  and a split made only to pass the limit is worse than the length.
- Functions above 120 lines (a closure counts in its function).
- Import circles between the modules of a crate, at file granularity: an
  edge for every `crate::a::b` path and every `super::x` / `super::super::x`
  path (also inside `use` groups), comments ignored; an edge between a
  module and its own parent or child is not counted (a parent declares its
  children, a child may use its parent's items).
- Integration tests, one binary a crate: every .rs file under a `tests/it`
  tree (crates/*/tests/it and the workspace's tests/it) is declared by a
  `mod` line of its parent module, and no other .rs file lies under a
  tests folder: cargo builds each loose tests/*.rs as a binary of its own,
  and silently never compiles a file under tests/it that no `mod` declares.

Prints what breaks a limit and exits 1; prints nothing when all hold.
Run from the repository root: python3 .ci/structure.py
`--root DIR` checks DIR/crates instead; `--self-test` plants a circle of each
kind of edge, an undeclared test module and a loose test file in scratch
trees and fails unless all are found.
"""
import os
import re
import sys
import tempfile

# file (relative to the root) -> why it may exceed 700 lines.
ALLOWED_LONG = {}

FN_RE = re.compile(r'\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?fn\s+(\w+)')


def code_lines(path):
    """The file's lines up to its first `#[cfg(test)]`."""
    lines = open(path, encoding='utf-8').read().split('\n')
    for i, line in enumerate(lines):
        if line.startswith('#[cfg(test)]'):
            return lines[:i]
    return lines


def long_files_and_functions(root):
    big, fns = [], []
    for top, _, files in os.walk(os.path.join(root, 'crates')):
        if '/tests' in top or '/benches' in top or 'target' in top:
            continue
        for f in files:
            if not f.endswith('.rs') or f == 'tests.rs':
                continue
            p = os.path.join(top, f)
            lines = code_lines(p)
            n = len(lines)
            rel = os.path.relpath(p, root)
            if n > 700 and rel not in ALLOWED_LONG:
                big.append((n, rel))
            i = 0
            while i < n:
                m = FN_RE.match(lines[i])
                if not m:
                    i += 1
                    continue
                depth, started, j = 0, False, i
                while j < n:
                    for ch in lines[j]:
                        if ch == '{':
                            depth += 1
                            started = True
                        elif ch == '}':
                            depth -= 1
                    if started and depth == 0:
                        break
                    if not started and lines[j].rstrip().endswith(';'):
                        break
                    j += 1
                if started and j - i + 1 > 120:
                    fns.append((j - i + 1, rel, m.group(6), i + 1))
                i = j + 1 if started else i + 1
    return big, fns


def crate_modules(src):
    """Module path ('a::b') -> its code without comments and tests."""
    mods = {}
    for top, _, files in os.walk(src):
        for f in files:
            if not f.endswith('.rs'):
                continue
            p = os.path.join(top, f)
            rel = os.path.relpath(p, src)[:-3].split('/')
            if rel[-1] in ('mod', 'lib', 'main'):
                rel = rel[:-1]
            if rel and rel[-1] == 'tests':
                continue
            txt = '\n'.join(line for line in open(p, encoding='utf-8').read().split('\n')
                            if not line.strip().startswith('//'))
            i = txt.find('#[cfg(test)]')
            if i >= 0:
                txt = txt[:i]
            mods['::'.join(rel)] = txt
    return mods


def paths_after(prefix_re, txt):
    """Every path that follows a prefix (`crate::` or a run of `super::`),
    with `{a::b, c}` groups expanded one level: (prefix text, [segments])."""
    out = []
    for m in re.finditer(prefix_re + r'((?:\w+::)*)(\{[^}]*\}|\w+)', txt):
        head = [s for s in m.group(2).split('::') if s]
        tail = m.group(3)
        if tail.startswith('{'):
            for item in tail[1:-1].split(','):
                item = item.strip().split(' as ')[0]
                if item and item != 'self':
                    out.append((m.group(1), head + item.split('::')))
                elif item == 'self':
                    out.append((m.group(1), head))
        else:
            out.append((m.group(1), head + [tail]))
    return out


def module_graph(mods):
    names = set(mods)
    g = {m: set() for m in mods}

    def add(m, parts):
        for k in range(len(parts), 0, -1):
            c = '::'.join(parts[:k])
            if c in names:
                if c != m and not m.startswith(c + '::') and not c.startswith(m + '::'):
                    g[m].add(c)
                return

    for m, txt in mods.items():
        for _, parts in paths_after(r'\b(crate::)', txt):
            add(m, parts)
        here = m.split('::') if m else []
        for prefix, parts in paths_after(r'(?<![\w:])((?:super::)+)', txt):
            up = prefix.count('super::')
            if up > len(here):
                continue
            add(m, here[:len(here) - up] + parts)
    return g


def circles(g):
    idx, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        idx[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in g[v]:
            if w not in idx:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], idx[w])
        if low[v] == idx[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(g):
        if v not in idx:
            visit(v)
    return out


def test_trees(root):
    """Findings of the one-binary test layout: `TEST-LOOSE path` for a .rs
    file under a tests folder but outside tests/it, `TEST-UNDECLARED path`
    for a file under tests/it that its parent module does not declare."""
    dirs = [os.path.join(root, 'tests')]
    crates = os.path.join(root, 'crates')
    if os.path.isdir(crates):
        dirs += [os.path.join(crates, c, 'tests') for c in sorted(os.listdir(crates))]
    out = []
    for tests in dirs:
        if not os.path.isdir(tests):
            continue
        it = os.path.join(tests, 'it')
        for top, _, files in sorted(os.walk(tests)):
            for f in sorted(files):
                if not f.endswith('.rs'):
                    continue
                p = os.path.join(top, f)
                rel = os.path.relpath(p, root)
                if not (top == it or top.startswith(it + os.sep)):
                    out.append(f'TEST-LOOSE {rel}')
                    continue
                if p == os.path.join(it, 'main.rs'):
                    continue
                if f == 'mod.rs':
                    name, parent_dir = os.path.basename(top), os.path.dirname(top)
                else:
                    name, parent_dir = f[:-3], top
                if parent_dir == it:
                    parents = [os.path.join(it, 'main.rs')]
                else:
                    parents = [os.path.join(parent_dir, 'mod.rs'), parent_dir + '.rs']
                decl = re.compile(r'(?m)^\s*(pub(\([^)]*\))?\s+)?mod\s+' + name + r'\s*;')
                if not any(os.path.isfile(q) and decl.search(open(q, encoding='utf-8').read())
                           for q in parents):
                    out.append(f'TEST-UNDECLARED {rel}')
    return out


def check(root):
    """The findings as printable lines."""
    big, fns = long_files_and_functions(root)
    lines = [f'FILE {n} {p}' for n, p in sorted(big)]
    lines += [f'FN {n} {p} {name} {line}' for n, p, name, line in sorted(fns)]
    crates = os.path.join(root, 'crates')
    for crate in sorted(os.listdir(crates)):
        src = os.path.join(crates, crate, 'src')
        if os.path.isdir(src):
            for c in circles(module_graph(crate_modules(src))):
                lines.append(f'CIRCLE {crate} {c}')
    return lines + test_trees(root)


def self_test():
    """A planted circle through `super::` edges and one through `crate::`
    edges must both be found, and a tree without circles must pass."""
    with tempfile.TemporaryDirectory() as root:
        src = os.path.join(root, 'crates', 'demo', 'src')
        os.makedirs(os.path.join(src, 'data'))
        files = {
            'lib.rs': 'pub mod data;\npub mod a;\npub mod b;\n',
            'a.rs': 'use crate::b::Thing;\n',
            'b.rs': '// use crate::a::Other; (a comment is no edge)\npub struct Thing;\n',
            'data/mod.rs': 'mod cell;\nmod source;\nmod dialect;\n',
            'data/cell.rs': 'use super::source::Source;\n',
            'data/source.rs': 'fn f() { super::dialect::decimal_comma(); }\n',
            'data/dialect.rs': 'use super::{cell::{Cell, Row}, source};\n',
        }
        for name, text in files.items():
            with open(os.path.join(src, name), 'w') as f:
                f.write(text)
        found = check(root)
        if found != ["CIRCLE demo ['data::cell', 'data::dialect', 'data::source']"]:
            return f'super:: circle: expected one circle of data::cell, dialect, source; found {found}'
        with open(os.path.join(src, 'data/dialect.rs'), 'w') as f:
            f.write('pub fn decimal_comma() {}\n')
        with open(os.path.join(src, 'b.rs'), 'w') as f:
            f.write('use crate::{a::Other};\npub struct Thing;\n')
        found = check(root)
        if found != ["CIRCLE demo ['a', 'b']"]:
            return f'crate:: circle: expected one circle of a and b; found {found}'
    with tempfile.TemporaryDirectory() as root:
        it = os.path.join(root, 'crates', 'demo', 'tests', 'it')
        os.makedirs(os.path.join(it, 'common'))
        files = {
            'main.rs': '//! mod forgotten;\nmod common;\nmod declared;\n',
            'declared.rs': '',
            'forgotten.rs': '',
            'common/mod.rs': 'pub mod fixtures;\n',
            'common/fixtures.rs': '',
            '../loose.rs': '',
        }
        for name, text in files.items():
            with open(os.path.join(it, name), 'w') as f:
                f.write(text)
        found = check(root)
        expected = ['TEST-LOOSE crates/demo/tests/loose.rs',
                    'TEST-UNDECLARED crates/demo/tests/it/forgotten.rs']
        if sorted(found) != expected:
            return f'test layout: expected {expected}; found {found}'
    return None


if __name__ == '__main__':
    if '--self-test' in sys.argv:
        err = self_test()
        if err:
            print('structure.py self-test failed:', err)
            sys.exit(1)
        print('structure.py self-test: planted circles and test files found')
        sys.exit(0)
    root = '.'
    if '--root' in sys.argv:
        root = sys.argv[sys.argv.index('--root') + 1]
    found = check(root)
    for line in found:
        print(line)
    sys.exit(1 if found else 0)
