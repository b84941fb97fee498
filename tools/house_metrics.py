# long-file: one stdlib-only file by design (a Rust lexer and item parser, two import graphs)
"""House metrics of the ARS repository: long files, long functions, import circles, `sim.` surface.

Run it with the repository root as the argument (default: the current directory):

    python3 tools/house_metrics.py                 # plain text
    python3 tools/house_metrics.py --json          # the same as JSON
    python3 tools/house_metrics.py --with-tests    # the lists take in test code too

Only Python 3's standard library is needed, and cargo is never run. The files looked at are the
git-tracked ones (`git ls-files`), less anything under a `fuzz/` or `target/` folder. Test code
(files under a `tests/` or `benches/` folder, and Rust items under `#[cfg(test)]` or `#[test]`)
is left out unless `--with-tests` is given; the long-file count is printed both ways regardless.

The metrics:

1. Source files (`.rs`, `.py`, `.js`, `.c`) over 800 lines, counted like `wc -l` (newlines).
2. Functions over 80 lines: Rust `fn` items (methods and nested fns too, not closures), from the
   `fn` line to the closing brace; Python `def`s, from the `def` line to the last line indented
   more than the `def` (blank lines ignored).
3. File import circles (strongly connected components of more than one file) in the Rust crates
   `ars-core/src`, `ars-viewer/src`, `python/src`, and in the Python package `python/ars`.
   A Rust file depends on the file of every module its `use` / `pub use` declarations and inline
   `crate::` / `super::` / `self::` / `child_module::` paths name (the deepest module file of
   the path; re-exports are followed to the file that defines the item; `mod child;` alone is no
   edge). Rust circles are also given without the edges between a file and the `mod.rs` /
   `lib.rs` of a module enclosing it. Python circles are given with every import, and with the
   module-level ones only (leaving out function-local and `if TYPE_CHECKING:` imports).
4. The functions reachable as `sim.` on `ars_core::Simulation`: the `pub fn` and `pub(crate) fn`
   items of `impl Simulation` blocks, and of `impl Scene` blocks when `Simulation` derefs to
   `Scene` (the private methods are counted apart).

Conventions (markers this script recognises):

* `long-file: <reason>` -- a comment in the first 15 lines of a file that is long on purpose,
  e.g. `// long-file: the MJCF schema, one match arm per element` or `# long-file: ...`.
  Such files are still listed, with the reason.
* `table: <reason>` -- a comment right above a function, or above or among its attributes,
  decorators and doc comment, e.g. `// table: the key bindings, one line each`, for a function
  that is a data table rather than logic. The comment must start with the marker. Such functions
  are listed apart as exempt, and not counted among the long ones.
"""

import argparse
import ast
import json
import os
import re
import subprocess
import sys
from collections import defaultdict

LONG_FILE_LINES = 800
LONG_FN_LINES = 80
MARKER_WINDOW = 15
SOURCE_EXTS = (".rs", ".py", ".js", ".c")
EXCLUDED_DIRS = {"fuzz", "target"}
TEST_DIRS = {"tests", "benches"}
RUST_CRATES = ["ars-core/src", "ars-viewer/src", "python/src"]
PY_PACKAGE = "python/ars"
SIM_CRATE = "ars-core/src"

LONG_FILE_RE = re.compile(r"(?://+!?|#|/\*+|^\s*\*)\s*long-file:\s*(.*?)\s*(?:\*/)?\s*$")
RUST_TABLE_RE = re.compile(r"(?://+!?|/\*+)\s*table:")
PY_TABLE_RE = re.compile(r"#\s*table:")

# ----------------------------------------------------------------------------- files


def tracked_files(root):
    out = subprocess.run(["git", "ls-files", "-z"], cwd=root, check=True, capture_output=True)
    files = []
    for path in out.stdout.decode("utf-8", "surrogateescape").split("\0"):
        if not path or not os.path.isfile(os.path.join(root, path)):
            continue
        if not EXCLUDED_DIRS.intersection(path.split("/")[:-1]):
            files.append(path)
    return sorted(files)


def is_test_path(path):
    return bool(TEST_DIRS.intersection(path.split("/")[:-1]))


def read_text(root, path):
    with open(os.path.join(root, path), "rb") as f:
        return f.read().decode("utf-8", "replace")


# ----------------------------------------------------------------------------- Rust lexer

RAW_STR_RE = re.compile(r'(?:br|cr|r)(#*)"')
IDENT_RE = re.compile(r"[A-Za-z_\u0080-\U0010ffff][A-Za-z0-9_\u0080-\U0010ffff]*")
NUM_RE = re.compile(r"[0-9][0-9A-Za-z_]*(?:\.[0-9][0-9A-Za-z_]*)?")


class Tok:
    __slots__ = ("kind", "line", "val")

    def __init__(self, kind, val, line):
        self.kind = kind  # id, num, str, char, life (lifetime or label), p (punctuation)
        self.val = val
        self.line = line


def _skip_quoted(text, j, quote):
    """The index just past the closing `quote`, from j inside the literal (escapes honoured)."""
    while j < len(text):
        if text[j] == "\\":
            j += 2
        elif text[j] == quote:
            return j + 1
        else:
            j += 1
    return len(text)


def _literal(text, i):
    """(kind, end) of the string, char or lifetime starting at i, or None."""
    m = RAW_STR_RE.match(text, i)
    if m:  # r"..", r#".."#, br"..", cr".."
        j = text.find('"' + m.group(1), m.end())
        return "str", len(text) if j < 0 else j + 1 + len(m.group(1))
    c, nxt = text[i], text[i + 1 : i + 2]
    if c == '"' or (c in "bc" and nxt == '"'):
        return "str", _skip_quoted(text, i + 1 + (c != '"'), '"')
    if c == "b" and nxt == "'":
        return "char", _skip_quoted(text, i + 2, "'")
    if c != "'":
        return None
    if nxt == "\\":  # '\n', '\'', '\u{1F600}'
        j = text.find("'", i + 3)
        return "char", len(text) if j < 0 else j + 1
    if text[i + 2 : i + 3] == "'":  # 'x', '{', '"'
        return "char", i + 3
    m = IDENT_RE.match(text, i + 1)  # 'a, 'static, 'outer
    return "life", m.end() if m else i + 1


def _block_comment_end(text, i):
    depth, j = 1, i + 2
    while j < len(text) and depth:
        if text.startswith("/*", j):
            depth, j = depth + 1, j + 2
        elif text.startswith("*/", j):
            depth, j = depth - 1, j + 2
        else:
            j += 1
    return j


def lex_rust(text):
    """Tokens of Rust source; comments dropped; strings, chars and lifetimes taken whole."""
    toks, i, n, line = [], 0, len(text), 1
    while i < n:
        c = text[i]
        if c.isspace():
            line += c == "\n"
            i += 1
            continue
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        if text.startswith("/*", i):
            j = _block_comment_end(text, i)
            line += text.count("\n", i, j)
            i = j
            continue
        lit = _literal(text, i) if c in "rbc\"'" else None
        if lit:
            toks.append(Tok(lit[0], text[i : lit[1]], line))
            line += text.count("\n", i, lit[1])
            i = lit[1]
            continue
        if text.startswith("r#", i) and IDENT_RE.match(text, i + 2):  # raw identifier
            i += 2
            c = text[i]
        m = NUM_RE.match(text, i) if c.isdigit() else None
        m = m or (IDENT_RE.match(text, i) if c == "_" or c.isalpha() else None)
        if m:
            toks.append(Tok("num" if c.isdigit() else "id", m.group(0), line))
            i = m.end()
            continue
        v = "::" if text.startswith("::", i) else c
        toks.append(Tok("p", v, line))
        i += len(v)
    return toks


# ----------------------------------------------------------------------------- Rust items

QUALIFIERS = {"const", "async", "unsafe", "extern", "default", "safe"}
DEF_KEYWORDS = {"struct", "enum", "trait", "type", "const", "static", "union"}
NOT_PATH_HEADS = {"Self", "std", "core", "alloc"}


def _attr_is_test(attr):
    vals = [t.val for t in attr]
    if vals[-1:] == ["test"] and (len(vals) == 1 or vals[-2] == "::"):
        return True  # #[test], #[tokio::test]
    return vals[:1] == ["cfg"] and "test" in vals and "not" not in vals


def parse_use_tree(toks, i, prefix, out):
    """Parse the use tree at toks[i] into (segments, binding) pairs; return the next index."""
    segs = list(prefix)
    while i < len(toks):
        t = toks[i]
        if t.val in ("::", "$"):
            if t.val == "::" and not segs:
                segs.append("::")  # a leading `::` names an outside crate
            i += 1
        elif t.val == "{":
            i += 1
            while i < len(toks) and toks[i].val != "}":
                i = i + 1 if toks[i].val == "," else parse_use_tree(toks, i, segs, out)
            return i + 1
        elif t.val == "*":
            out.append((segs, "*"))
            return i + 1
        elif t.kind != "id":
            return i + 1
        elif i + 1 < len(toks) and toks[i + 1].val == "::":
            segs = [*segs, t.val]
            i += 1
        else:
            full, binding = [*segs, t.val], t.val
            if t.val == "self" and segs:  # `a::b::{self}`
                full, binding = segs, segs[-1]
            if i + 2 < len(toks) and toks[i + 1].val == "as":
                binding = toks[i + 2].val
                i += 2
            out.append((full, binding))
            return i + 1
    return i


def impl_names(header):
    """(trait, self type) of an impl header: the last path segments, generics left out."""
    vals, d, parts = [t.val for t in header], 0, [[]]
    for k, x in enumerate(vals):
        arrow = x == ">" and k and vals[k - 1] == "-"
        if x == "<":
            d += 1
        elif x == ">" and not arrow:
            d -= 1
        elif x == "where" and d == 0:
            break
        elif x == "for" and d == 0:
            parts.append([])
        elif d == 0 and x not in ("::", "&", "mut", "dyn", "!", "-") and not arrow:
            parts[-1].append(x)
    names = [p[-1] if p else None for p in parts]
    return (None, names[0]) if len(names) == 1 else (names[0], names[-1])


class RustFile:
    """The items of one Rust file that the metrics need."""

    def __init__(self, path, text):
        self.path = path
        self.lines = text.split("\n")
        self.functions = []  # dicts: name, start, end, lines, test, table
        self.impls = []  # dicts: trait, type, fns [(name, vis, line)], test, body tokens
        self.uses = []  # (inline module chain, segments, binding, test)
        self.paths = []  # (inline module chain, segments, test): paths in code
        self.child_mods = set()  # `mod x;` and `mod x {..}` at file level
        self.defs = set()  # names of the items defined at file level
        self.imports = {}  # binding -> (chain, segments) of the file-level `use`s
        self.globs = []  # (chain, segments) of the file-level glob `use`s
        self._stack = []  # open braces: dicts with kind (mod/impl/fn/other) and test
        self._attrs = []  # attributes waiting for their item: (line, tokens)
        self._pending = None  # the fn/mod/impl waiting for its `{`
        self._depth = 0  # ( and [ nesting
        self.toks = lex_rust(text)
        i = 0
        while i < len(self.toks):
            kind = self.toks[i].kind
            i = self._punct(i) if kind == "p" else self._word(i) if kind == "id" else i + 1
        del self.toks

    def _chain(self):
        return tuple(f["name"] for f in self._stack if f["kind"] == "mod")

    def _test(self, with_attrs=False):
        attrs = with_attrs and any(_attr_is_test(a) for _, a in self._attrs)
        return attrs or bool(self._stack and self._stack[-1]["test"])

    def _punct(self, i):
        toks, v = self.toks, self.toks[i].val
        if v == "#":
            j = i + 1 + (i + 1 < len(toks) and toks[i + 1].val == "!")
            if j < len(toks) and toks[j].val == "[":
                return self._attribute(i, j)
        if v in "([":
            self._depth += 1
        elif v in ")]":
            self._depth -= 1
        elif v == "{":
            frame = {"kind": "other", "test": self._test()}
            if self._pending is not None and self._pending["depth"] == self._depth:
                frame, self._pending = self._pending, None
                frame["test"] = frame["test"] or self._test()
                frame["open"] = i
            self._stack.append(frame)
            self._attrs = []
        elif v == "}" and self._stack:
            self._close(self._stack.pop(), i)
            self._attrs = []
        elif v in ";,":
            pending = self._pending
            if v == ";" and pending is not None and pending["depth"] == self._depth:
                self._pending = None
            self._attrs = []
        return i + 1

    def _attribute(self, i, j):
        d, k = 0, j
        while k < len(self.toks):
            d += {"[": 1, "]": -1}.get(self.toks[k].val, 0)
            if d == 0:
                break
            k += 1
        if j == i + 1:  # outer attribute: kept for the item that follows
            self._attrs.append((self.toks[i].line, self.toks[j + 1 : k]))
        return k + 1

    def _close(self, frame, i):
        end = self.toks[i].line
        if frame["kind"] == "fn":
            fields = ("name", "start", "test", "table")
            fn = {key: frame[key] for key in fields}
            self.functions.append(dict(fn, end=end, lines=end - frame["start"] + 1))
        elif frame["kind"] == "impl":
            frame["info"]["body"] = self.toks[frame["open"] + 1 : i]

    def _word(self, i):
        toks, v = self.toks, self.toks[i].val
        nxt = toks[i + 1] if i + 1 < len(toks) else None
        prev = toks[i - 1].val if i else ";"
        if v == "use" and not (nxt and nxt.val == "<"):  # not `impl Trait + use<'a>`
            return self._use(i)
        if v in ("fn", "mod") and nxt and nxt.kind == "id":
            return self._fn(i) if v == "fn" else self._mod(i)
        if v == "impl" and prev in (";", "}", "{", "]", "unsafe"):
            return self._impl(i)
        if v in DEF_KEYWORDS and nxt and nxt.kind == "id" and not self._stack:
            self.defs.add(nxt.val)
        if v == "macro_rules" and i + 2 < len(toks) and not self._stack:
            self.defs.add(toks[i + 2].val)
        if nxt and nxt.val == "::" and prev not in ("::", ".") and v not in NOT_PATH_HEADS:
            segs, k = [v], i + 1
            while k + 1 < len(toks) and toks[k].val == "::" and toks[k + 1].kind == "id":
                segs.append(toks[k + 1].val)
                k += 2
            self.paths.append((self._chain(), segs, self._test()))
            return k
        return i + 1

    def _use(self, i):
        k = i + 1
        while k < len(self.toks) and self.toks[k].val != ";":
            k += 1
        entries = []
        parse_use_tree(self.toks[i + 1 : k], 0, [], entries)
        test, chain = self._test(True), self._chain()
        for segs, binding in entries:
            if not segs:
                continue
            self.uses.append((chain, segs, binding, test))
            if self._stack:
                continue
            if binding == "*":
                self.globs.append((chain, segs))
            elif binding != "_":
                self.imports[binding] = (chain, segs)
        self._attrs = []
        return k + 1

    def _qualifiers(self, i):
        """(visibility, first line) of the qualifiers before the `fn` at toks[i]."""
        toks, j, vis = self.toks, i - 1, None
        while j >= 0 and (
            (toks[j].kind == "id" and toks[j].val in QUALIFIERS) or toks[j].kind == "str"
        ):
            j -= 1
        if j >= 0 and toks[j].val == "pub":
            vis, j = "pub", j - 1
        elif j >= 0 and toks[j].val == ")":
            k = j
            while k > 0 and toks[k].val != "(":
                k -= 1
            if k >= 1 and toks[k - 1].val == "pub":
                vis = "pub(" + "".join(t.val for t in toks[k + 1 : j]) + ")"
                j = k - 2
        return vis, toks[j + 1].line

    def _fn(self, i):
        name = self.toks[i + 1].val
        vis, start = self._qualifiers(i)
        top = min([start] + [line for line, _ in self._attrs])
        if self._stack and self._stack[-1]["kind"] == "impl":
            self._stack[-1]["info"]["fns"].append((name, vis, start))
        if not self._stack:
            self.defs.add(name)
        self._pending = {
            "kind": "fn",
            "name": name,
            "start": start,
            "depth": self._depth,
            "test": self._test(True),
            "table": self._table_marker(top, start),
        }
        self._attrs = []
        return i + 2

    def _table_marker(self, top, start):
        """Whether a `// table:` comment is among the attributes or in the comments above."""
        k = top - 2  # the index of the line above the first attribute
        while k >= 0 and self.lines[k].strip().startswith(("//", "/*", "*", "#[")):
            k -= 1
        return any(RUST_TABLE_RE.search(self.lines[j]) for j in range(k + 1, start - 1))

    def _mod(self, i):
        name = self.toks[i + 1].val
        if not self._stack:
            self.child_mods.add(name)
            self.defs.add(name)
        self._pending = {
            "kind": "mod",
            "name": name,
            "depth": self._depth,
            "test": self._test(True),
        }
        self._attrs = []
        return i + 2

    def _impl(self, i):
        toks, k, d = self.toks, i + 1, 0
        while k < len(toks) and not (toks[k].val == "{" and d == 0) and toks[k].val != ";":
            d += {"(": 1, "[": 1, ")": -1, "]": -1}.get(toks[k].val, 0)
            k += 1
        trait, typ = impl_names(toks[i + 1 : k])
        test = self._test(True)
        info = {"trait": trait, "type": typ, "fns": [], "test": test, "line": toks[i].line}
        self.impls.append(info)
        self._pending = {"kind": "impl", "info": info, "depth": self._depth, "test": test}
        self._attrs = []
        return k


# ----------------------------------------------------------------------------- Rust graph


class RustCrate:
    """The module tree of one crate's `src` folder, and the file graph of its references."""

    def __init__(self, src, files):
        self.files = files  # path -> RustFile
        self.modules = {}  # module path (tuple) -> file
        self.module_of = {}
        for path in files:
            rel = path[len(src) + 1 : -3].split("/")
            if rel[0] == "bin":
                continue
            mod = () if rel in (["lib"], ["main"]) else tuple(rel[:-1] if rel[-1] == "mod" else rel)
            self.modules[mod] = path
            self.module_of[path] = mod

    def absolute(self, path, chain, segs, seen=0):
        """The crate-absolute form of a path written in file `path`, or None if outside."""
        info, head = self.files[path], segs[0]
        here = [*self.module_of[path], *chain]
        if seen > 12 or head == "::":
            return None
        if head in ("crate", "self"):
            return (here if head == "self" else []) + list(segs[1:])
        if head == "super":
            k = len(segs) - len([s for s in segs if s != "super"])
            return here[: max(0, len(here) - k)] + list(segs[k:])
        if chain:  # a name inside an inline module: its own items are not tracked
            return None
        if head in info.child_mods or head in info.defs:
            return here + list(segs)
        if head in info.imports and list(info.imports[head][1]) != [head]:
            base = self.absolute(path, *info.imports[head], seen + 1)
            return None if base is None else base + list(segs[1:])
        return None  # an outside crate or a prelude name

    def resolve(self, segs, seen=0):
        """(file, found) of a crate-absolute path: its deepest module file, re-exports followed.

        `found` is False when the item is not seen defined or imported there (a macro's item,
        say); the file is then the deepest module file all the same."""
        cur = ()
        for seg in segs:
            if (*cur, seg) not in self.modules:
                break
            cur = (*cur, seg)
        path, rest = self.modules.get(cur), segs[len(cur) :]
        if path is None or not rest or seen > 12:
            return path, path is not None
        info = self.files[path]
        if rest[0] in info.defs:
            return path, True
        if rest[0] in info.imports:
            target = self.absolute(path, *info.imports[rest[0]], seen + 1)
            if target is None:
                return None, True  # a re-export of an outside item: no file of this crate
            return self.resolve(target + list(rest[1:]), seen + 1)
        for glob in info.globs:
            target = self.absolute(path, *glob, seen + 1)
            if target is None:
                continue
            found_path, found = self.resolve(target + list(rest), seen + 1)
            if found and found_path:
                return found_path, True
        return path, False

    def nested(self, a, b):
        """Whether one file's module encloses the other's (`scene/mod.rs`, `scene/joints.rs`)."""
        ma, mb = self.module_of[a], self.module_of[b]
        return ma[: len(mb)] == mb or mb[: len(ma)] == ma

    def edges(self, with_tests=False):
        """{file: {dependency: [how]}} from `use` declarations and paths in code."""
        graph = {p: defaultdict(list) for p in self.files}
        for path, info in self.files.items():
            refs = [(ch, segs, test, "use") for ch, segs, _, test in info.uses]
            refs += [(ch, segs, test, "path") for ch, segs, test in info.paths]
            for chain, segs, test, how in refs:
                head = segs[0]
                relative = head in ("crate", "super", "self") or head in info.child_mods
                if (test and not with_tests) or (
                    not relative and (how == "path" or head not in info.imports)
                ):
                    continue  # test code, or an outside crate, a local name, a type
                target = self.absolute(path, chain, segs)
                dep = self.resolve(target)[0] if target is not None else None
                if dep and dep != path:
                    graph[path][dep].append(f"{how} {'::'.join(segs)}")
        return graph


def strongly_connected(succ):
    """Tarjan's algorithm, iterative: the components of more than one node, sorted."""
    index, low, on, stack, comps = {}, {}, set(), [], []
    for root in sorted(succ):
        if root in index:
            continue
        index[root] = low[root] = len(index)
        stack.append(root)
        on.add(root)
        work = [(root, iter(sorted(succ[root])))]
        while work:
            node, it = work[-1]
            nxt = next((x for x in it if x not in index or x in on), None)
            if nxt is not None and nxt not in index:
                index[nxt] = low[nxt] = len(index)
                stack.append(nxt)
                on.add(nxt)
                work.append((nxt, iter(sorted(succ.get(nxt, ())))))
                continue
            if nxt is not None:
                low[node] = min(low[node], index[nxt])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = [stack.pop()]
                while comp[-1] != node:
                    comp.append(stack.pop())
                on.difference_update(comp)
                if len(comp) > 1:
                    comps.append(sorted(comp))
    return sorted(comps)


# ----------------------------------------------------------------------------- Python


def py_module_name(path):
    parts = path[len(os.path.dirname(PY_PACKAGE)) + 1 :].rsplit(".", 1)[0].split("/")
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def py_imports(tree):
    """(import node, context): `module`, `function` or `type-checking`."""
    out = []

    def visit(node, ctx):
        test = getattr(node, "test", None) if isinstance(node, ast.If) else None
        guarded = getattr(test, "id", getattr(test, "attr", None)) == "TYPE_CHECKING"
        for child in ast.iter_child_nodes(node):
            sub = ctx
            if guarded and ctx == "module" and any(child is b for b in node.body):
                sub = "type-checking"
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                sub = "function"
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                out.append((child, sub))
            visit(child, sub)

    visit(tree, "module")
    return out


def _py_targets(node, name, is_pkg, known, top):
    """The dotted names of the package modules that one import statement reaches."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names if a.name.split(".")[0] == top]
    base = name.split(".")[: None if is_pkg else -1]
    if node.level:
        base = base[: len(base) - (node.level - 1)]
        mod = ".".join(base + ([node.module] if node.module else []))
    else:
        mod = node.module or ""
    if mod.split(".")[0] != top:
        return []
    return [f"{mod}.{a.name}" if f"{mod}.{a.name}" in known else mod for a in node.names]


def python_graph(root, files):
    """{file: {dependency: {contexts}}} of the package, and the files that did not parse."""
    mods = {
        py_module_name(p): p for p in files if p.startswith(PY_PACKAGE + "/") and p.endswith(".py")
    }
    stubs = set()  # compiled modules (ars._native): not files of the graph
    for dirpath, _, names in os.walk(os.path.join(root, PY_PACKAGE)):
        for fname in names:
            if fname.endswith((".pyi", ".so", ".pyd")):
                rel = os.path.relpath(os.path.join(dirpath, fname.split(".")[0]), root)
                stubs.add(py_module_name(rel.replace(os.sep, "/") + ".py"))
    top = os.path.basename(PY_PACKAGE)

    def deepest(dotted):
        parts = dotted.split(".")
        for k in range(len(parts), 0, -1):
            cand = ".".join(parts[:k])
            if cand in mods or cand in stubs:
                return mods.get(cand)
        return None

    edges, errors = {p: defaultdict(set) for p in mods.values()}, []
    for name, path in mods.items():
        try:
            tree = ast.parse(read_text(root, path), filename=path)
        except SyntaxError as e:
            errors.append(f"{path}: {e}")
            continue
        for node, ctx in py_imports(tree):
            known = mods.keys() | stubs
            for target in _py_targets(node, name, path.endswith("__init__.py"), known, top):
                dep = deepest(target)
                if dep and dep != path:
                    edges[path][dep].add(ctx)
    return edges, errors


def py_functions(path, text):
    """The `def`s of a Python file, from the `def` line to the last line indented under it."""
    lines = text.split("\n")
    try:
        tree = ast.parse(text, filename=path)
    except SyntaxError:
        return _py_functions_by_indent(lines)
    out = []
    for node in ast.walk(tree):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        start, end = node.lineno, node.end_lineno
        indent = len(lines[start - 1]) - len(lines[start - 1].lstrip())
        for k in range(end, len(lines)):  # comment lines still indented under the def
            s = lines[k]
            if s.strip() and not (s.lstrip().startswith("#") and len(s) - len(s.lstrip()) > indent):
                break
            end = k + 1 if s.strip() else end
        top = min([start] + [d.lineno for d in node.decorator_list])
        table = _py_table_marker(lines, top, start)
        out.append({"name": node.name, "start": start, "end": end, "lines": end - start + 1})
        out[-1]["table"] = table
    return out


def _py_table_marker(lines, top, start):
    k = top - 2
    while k >= 0 and lines[k].strip().startswith(("#", "@")):
        k -= 1
    return any(PY_TABLE_RE.search(lines[j]) for j in range(k + 1, start - 1))


def _py_functions_by_indent(lines):
    """A fallback for files this Python cannot parse: `def`s found by indentation alone."""
    out = []
    for idx, line in enumerate(lines):
        m = re.match(r"(\s*)(?:async\s+)?def\s+(\w+)", line)
        if not m:
            continue
        end = idx + 1
        for k in range(idx + 1, len(lines)):
            s = lines[k]
            dedented = s.strip() and len(s) - len(s.lstrip()) <= len(m.group(1))
            if dedented and not s.lstrip().startswith((")", "]")):
                break
            end = k + 1 if s.strip() else end
        table = _py_table_marker(lines, idx + 1, idx + 1)
        out.append({"name": m.group(2), "start": idx + 1, "end": end, "lines": end - idx})
        out[-1]["table"] = table
    return out


# ----------------------------------------------------------------------------- metrics


def metric_long_files(root, files, with_tests):
    rows = []
    for path in files:
        if not path.endswith(SOURCE_EXTS):
            continue
        text = read_text(root, path)
        if text.count("\n") <= LONG_FILE_LINES:
            continue
        head = text.split("\n")[:MARKER_WINDOW]
        reason = next(
            (m.group(1) or "(no reason given)" for m in map(LONG_FILE_RE.search, head) if m), None
        )
        rows.append(
            {
                "file": path,
                "lines": text.count("\n"),
                "test": is_test_path(path),
                "long_file": reason,
            }
        )
    rows.sort(key=lambda r: (-r["lines"], r["file"]))
    non_test = [r for r in rows if not r["test"]]
    shown = rows if with_tests else non_test
    return {
        "count": len(shown),
        "count_without_tests": len(non_test),
        "count_with_tests": len(rows),
        "explained": sum(1 for r in shown if r["long_file"]),
        "files": shown,
    }


def metric_long_functions(root, files, rust_files, with_tests):
    found = []
    for path in files:
        if is_test_path(path) and not with_tests:
            continue
        if path.endswith(".rs"):
            fns = rust_files[path].functions
        elif path.endswith(".py"):
            fns = py_functions(path, read_text(root, path))
        else:
            continue
        for f in fns:
            test = f.get("test", False) or is_test_path(path)
            if f["lines"] > LONG_FN_LINES and (with_tests or not test):
                found.append(dict(f, file=path, test=test))
    found.sort(key=lambda r: (-r["lines"], r["file"], r["start"]))
    long_ = [f for f in found if not f["table"]]
    exempt = [f for f in found if f["table"]]
    return {"count": len(long_), "exempt_count": len(exempt), "functions": long_, "exempt": exempt}


def _circles(graph, keep, label):
    """The circles of a {file: {dependency: how}} graph, with the edges inside each."""
    succ = {a: {b for b in deps if keep(a, b)} for a, deps in graph.items()}
    out = []
    for comp in strongly_connected(succ):
        edges = [
            {"from": a, "to": b, label: sorted(set(graph[a][b]))[:3]}
            for a in comp
            for b in sorted(succ[a])
            if b in comp
        ]
        out.append({"files": comp, "edges": edges})
    return out


def metric_circles(root, files, rust_files, with_tests):
    out = {"rust": [], "rust_without_nesting": [], "python": {}}
    for src in RUST_CRATES:
        crate_files = {
            p: rust_files[p] for p in files if p.startswith(src + "/") and p.endswith(".rs")
        }
        if not crate_files:
            continue
        crate = RustCrate(src, crate_files)
        graph = crate.edges(with_tests)
        for c in _circles(graph, lambda a, b: True, "via"):
            out["rust"].append(dict(c, where=src))
        for c in _circles(graph, lambda a, b, nested=crate.nested: not nested(a, b), "via"):
            out["rust_without_nesting"].append(dict(c, where=src))
    edges, out["python_errors"] = python_graph(root, files)
    views = {"all_imports": lambda a, b: True, "module_level": lambda a, b: "module" in edges[a][b]}
    for view, keep in views.items():
        out["python"][view] = [dict(c, where=PY_PACKAGE) for c in _circles(edges, keep, "kinds")]
    rust, nesting, python = out["rust"], out["rust_without_nesting"], out["python"]
    out["count"] = len(rust) + len(python["all_imports"])
    out["count_module_level"] = len(rust) + len(python["module_level"])
    out["count_without_nesting"] = len(nesting) + len(python["all_imports"])
    return out


def _deref_target(crate):
    for path, info in sorted(crate.items()):
        for imp in info.impls:
            if imp["trait"] == "Deref" and imp["type"] == "Simulation" and not imp["test"]:
                vals = [t.val for t in imp.get("body", [])]
                for k in range(len(vals) - 3):
                    if vals[k : k + 3] == ["type", "Target", "="]:
                        return {"file": path, "target": vals[k + 3]}
    return None


def metric_sim_surface(files, rust_files):
    crate = {p: rust_files[p] for p in files if p.startswith(SIM_CRATE + "/") and p.endswith(".rs")}
    deref = _deref_target(crate)
    types = ["Simulation"] + ([deref["target"]] if deref else [])
    rows, per_file = [], defaultdict(lambda: {"public": 0, "crate": 0, "private": 0})
    for path, info in sorted(crate.items()):
        for imp in info.impls:
            if imp["trait"] is not None or imp["type"] not in types or imp["test"]:
                continue
            for name, vis, line in imp["fns"]:
                kind = "private" if vis is None else "public" if vis == "pub" else "crate"
                row = {"type": imp["type"], "name": name, "vis": vis, "kind": kind}
                rows.append(dict(row, file=path, line=line))
                per_file[(path, imp["type"])][kind] += 1
    count = {k: sum(1 for r in rows if r["kind"] == k) for k in ("public", "crate", "private")}
    visible = [r for r in rows if r["kind"] != "private"]
    by_type = [
        {r["name"] for r in visible if (r["type"] == "Simulation") == own} for own in (True, False)
    ]
    return {
        "deref": deref,
        "public": count["public"],
        "crate_visible": count["crate"],
        "total": len(visible),
        "private": count["private"],
        "all_methods": len(rows),
        "distinct_names": len({r["name"] for r in visible}),
        "shadowed_by_simulation": sorted(by_type[0] & by_type[1]),
        "files": [
            {
                "file": f,
                "type": t,
                "public": c["public"],
                "crate_visible": c["crate"],
                "private": c["private"],
            }
            for (f, t), c in sorted(per_file.items())
        ],
        "functions": rows,
    }


def collect(root, with_tests):
    files = tracked_files(root)
    rust_files = {p: RustFile(p, read_text(root, p)) for p in files if p.endswith(".rs")}
    return {
        "root": os.path.abspath(root),
        "with_tests": with_tests,
        "long_files": metric_long_files(root, files, with_tests),
        "long_functions": metric_long_functions(root, files, rust_files, with_tests),
        "import_circles": metric_circles(root, files, rust_files, with_tests),
        "sim_surface": metric_sim_surface(files, rust_files),
    }


# ----------------------------------------------------------------------------- output


def _print_files(w, lf):
    w(
        f"1. Source files over {LONG_FILE_LINES} lines: {lf['count']} ({lf['count_without_tests']}"
        f" without tests, {lf['count_with_tests']} with tests; {lf['explained']} with a long-file:"
        " comment)\n"
    )
    for r in lf["files"]:
        note = f"long-file: {r['long_file']}" if r["long_file"] else "no long-file: comment"
        w(f"   {r['lines']:6d}  {r['file']}{' [test]' if r['test'] else ''}  ({note})\n")


def _print_functions(w, lfn):
    count, exempt = lfn["count"], lfn["exempt_count"]
    w(f"\n2. Functions over {LONG_FN_LINES} lines: {count} (and {exempt} exempt as table:)\n")
    for title, rows in (("", lfn["functions"]), ("   exempt (table:):\n", lfn["exempt"])):
        w(title if rows else "")
        for f in rows:
            test = " [test]" if f["test"] else ""
            w(f"   {f['lines']:6d}  {f['file']}:{f['start']}-{f['end']}  {f['name']}{test}\n")


def _print_circle_list(w, title, items, how):
    w(f"   {title}: {len(items)}\n")
    for c in items:
        cut = len(c["where"]) + 1
        w(f"   - {c['where']}/{{{', '.join(f[cut:] for f in c['files'])}}}\n")
        for e in c["edges"]:
            w(f"       {e['from'][cut:]} -> {e['to'][cut:]}  ({how(e)})\n")


def _print_circles(w, ic):
    py = ic["python"]
    w(
        f"\n3. File import circles: {ic['count']} ({len(ic['rust'])} Rust, {len(py['all_imports'])}"
        f" Python); {ic['count_module_level']} counting module-level Python imports only;"
        f" {ic['count_without_nesting']} without the Rust edges between a file and an enclosing"
        " module's mod.rs/lib.rs\n"
    )

    def via(e):
        return "; ".join(e["via"])

    def kinds(e):
        return ", ".join(e["kinds"]) + ("" if "module" in e["kinds"] else " only")

    _print_circle_list(
        w, "Rust, every edge (use, pub use, crate::/super::/self::/child:: paths)", ic["rust"], via
    )
    _print_circle_list(
        w,
        "Rust, without edges to or from an enclosing module's file",
        ic["rust_without_nesting"],
        via,
    )
    _print_circle_list(
        w, "Python, every import (module-level, function, TYPE_CHECKING)", py["all_imports"], kinds
    )
    _print_circle_list(w, "Python, module-level imports only", py["module_level"], kinds)
    for err in ic["python_errors"]:
        w(f"   (could not parse {err})\n")


def _print_sim(w, s):
    d = s["deref"]
    deref = f"Simulation derefs to {d['target']} in {d['file']}" if d else "no Deref for Simulation"
    w(
        f"\n4. Functions reachable as sim.: {s['total']} = {s['public']} public (pub fn) +"
        f" {s['crate_visible']} crate-visible (pub(crate)/pub(super) fn)\n   ({deref};"
        f" {s['distinct_names']} distinct names; and {s['private']} private methods,"
        f" {s['all_methods']} methods in all)\n"
    )
    if s["shadowed_by_simulation"]:
        names = ", ".join(s["shadowed_by_simulation"])
        w(f"   Scene methods a Simulation method shadows: {names}\n")
    w("   public  crate  private  file\n")
    for f in s["files"]:
        counts = f"{f['public']:6d} {f['crate_visible']:6d} {f['private']:8d}"
        w(f"   {counts}  {f['file']} (impl {f['type']})\n")


def print_text(m, w=sys.stdout.write):
    scope = "test code included" if m["with_tests"] else "non-test sources"
    w(f"House metrics of {m['root']} ({scope})\n\n")
    _print_files(w, m["long_files"])
    _print_functions(w, m["long_functions"])
    _print_circles(w, m["import_circles"])
    _print_sim(w, m["sim_surface"])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("root", nargs="?", default=".", help="the repository root (default: .)")
    ap.add_argument("--json", action="store_true", help="print the metrics as JSON")
    ap.add_argument("--with-tests", action="store_true", help="take in test files and test code")
    args = ap.parse_args(argv)
    metrics = collect(args.root, args.with_tests)
    if args.json:
        json.dump(metrics, sys.stdout, indent=2, default=sorted)
        sys.stdout.write("\n")
    else:
        print_text(metrics)
    return 0


if __name__ == "__main__":
    sys.exit(main())
