"""Functions stay short: every function of the C++ sources (cpp/src, cpp/include, cpp/bindings) and
of the Python packages (python/robokin, sim) is at most MAX_LINES lines, from the first line of its
signature to its closing line. A long multi-phase function is split into named steps (as
cpp/src/rrr3_plan.cpp is). The allowlist below names the few exceptions, each with its reason.

The C++ scanner is a brace matcher over the source with its comments, string and character
literals and preprocessor lines blanked (newlines kept, so line numbers hold): a `{` at namespace,
class or file scope whose header (the text since the last `;`, `{` or `}` there) has a parameter list
opens a function, and everything up to its matching `}` (lambdas, local classes) belongs to it. The
Python scanner is `ast`: `end_lineno - lineno + 1` of every `def` (decorators excluded), nested ones
too. The scanners are tested on small snippets below, so a broken scanner cannot pass silently.
"""

from __future__ import annotations

import ast
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
MAX_LINES = 80

# "path:function" -> why it may be longer than MAX_LINES: only a true kernel (its length the unrolled
# maths). None is today; an entry that is no longer long fails test_the_allowlist_has_no_stale_entries.
ALLOWLIST: dict = {}

CPP_DIRS = ("cpp/src", "cpp/include", "cpp/bindings")
CPP_SUFFIXES = {".cpp", ".hpp", ".h", ".cc"}
PY_DIRS = ("python/robokin", "sim")


# ------------------------------------------------------------------------------------------------
# C++


def _blank(text: str, start: int, end: int, out: list) -> None:
    """out[start:end] as spaces, newlines kept."""
    for i in range(start, end):
        if text[i] != "\n":
            out[i] = " "


def strip_cpp(text: str) -> str:
    """The source with comments, string / character literals (raw strings too) and preprocessor
    lines blanked; only the first branch of #if / #ifdef ... #elif / #else ... #endif is kept, so each
    brace is counted once. Same length, same newlines."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            i += 1
            continue
        if line_start and c == "#":
            i = _preprocessor(text, i, out)
            continue
        line_start = c == "\n"
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            _blank(text, i, j, out)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            _blank(text, i, j, out)
            i = j
        elif c == '"' or (c == "R" and text.startswith('R"', i) and not _ident_char(text, i - 1)):
            i = _string(text, i, out)
        elif c == "'" and not _digit_separator(text, i):
            j = i + 1
            while j < n and text[j] != "'" and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            _blank(text, i + 1, j, out)
            i = j + 1
        else:
            i += 1
    return "".join(out)


def _ident_char(text: str, i: int) -> bool:
    return 0 <= i < len(text) and (text[i].isalnum() or text[i] == "_")


def _digit_separator(text: str, i: int) -> bool:
    """A ' between digits of a number (C++14's 20'000'000), not a character literal."""
    if not (_ident_char(text, i - 1) and i + 1 < len(text) and text[i + 1].isalnum()):
        return False
    j = i - 1
    while j >= 0 and (_ident_char(text, j) or text[j] in ".'"):
        j -= 1
    return text[j + 1].isdigit()


def _string(text: str, i: int, out: list) -> int:
    """Blanks the string literal at i (its quotes kept); returns the index after it."""
    n = len(text)
    if text[i] == "R":  # R"delim( ... )delim"
        open_paren = text.find("(", i)
        delim = text[i + 2:open_paren]
        close = text.find(")" + delim + '"', open_paren)
        end = n if close < 0 else close + len(delim) + 2
        _blank(text, i + 2, end - 1, out)
        return end
    j = i + 1
    while j < n and text[j] != '"' and text[j] != "\n":
        j += 2 if text[j] == "\\" else 1
    _blank(text, i + 1, j, out)
    return j + 1


def _preprocessor(text: str, i: int, out: list) -> int:
    """Blanks the directive at i (with its continuation lines) and, for #elif / #else, the
    branch up to the matching #endif; returns the index after what was blanked."""
    end = _directive_end(text, i)
    word = re.match(r"#\s*(\w*)", text[i:end]).group(1)
    _blank(text, i, end, out)
    if word not in ("elif", "else"):
        return end
    depth = 0
    for m in re.finditer(r"^[ \t]*#\s*(\w+)", text[end:], re.M):
        at = end + m.start()
        if m.group(1) in ("if", "ifdef", "ifndef"):
            depth += 1
        elif m.group(1) == "endif":
            if depth == 0:
                stop = _directive_end(text, at)
                _blank(text, end, stop, out)
                return stop
            depth -= 1
    _blank(text, end, len(text), out)
    return len(text)


def _directive_end(text: str, i: int) -> int:
    j = i
    while True:
        k = text.find("\n", j)
        if k < 0:
            return len(text)
        if text[k - 1] != "\\":
            return k
        j = k + 1


def _matching(code: str, i: int) -> int:
    """Index of the } matching the { at i (stripped code); -1 when unbalanced."""
    depth = 0
    for j in range(i, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return -1


def _without_templates(header: str) -> str:
    """The header with `template <...>` prefixes removed (their `class` is not a class)."""
    while True:
        m = re.search(r"\btemplate\s*<", header)
        if not m:
            return header
        depth, j = 0, m.end() - 1
        while j < len(header):
            depth += {"<": 1, ">": -1}.get(header[j], 0)
            if depth == 0:
                break
            j += 1
        header = header[:m.start()] + " " + header[j + 1:]


def _top_level(header: str) -> str:
    """The header with the insides of (...) and [...] removed (the parentheses kept)."""
    out, depth = [], 0
    for c in header:
        if c in ")]":
            depth -= 1
        if depth == 0:
            out.append(c)
        if c in "([":
            depth += 1
    return "".join(out)


def _function_name(header: str) -> str | None:
    """The name of the function whose header (signature) this is, or None when the header opens
    something else (namespace, class, enum, initializer)."""
    h = _without_templates(header)
    if re.search(r"\bnamespace\b|\bextern\s+\"", h):
        return None
    top = _top_level(h)
    # The parameter list: the first (...) that is not an attribute's, decltype's or alignas'.
    opens = [m.start() for m in re.finditer(r"\(", top)
             if not re.search(r"\b(__attribute__|decltype|alignas|__declspec)\s*$", top[:m.start()])]
    if not opens:
        return None  # class, struct, enum, union or a braced initializer without a call
    before = re.sub(r"\b(__attribute__|decltype|alignas|__declspec)\s*\(\)", " ", top[:opens[0]])
    if "=" in before.replace("operator=", "").replace("==", ""):
        return None  # an initializer: `T x = f(...) {` cannot be, `auto f = [](...) {` is data
    if re.search(r"\b(class|struct|union|enum)\b[^;]*$", before) and not re.search(r"\w\s*$", before):
        return None
    m = re.search(r"(operator\s*(\(\s*\)|[^\s(]+)|~?[A-Za-z_]\w*(\s*::\s*~?[A-Za-z_]\w*)*)\s*$", before)
    return re.sub(r"\s+", "", m.group(1)) if m else None


def cpp_functions(text: str):
    """(name, first line, last line) of every function defined in the C++ source text (1-based)."""
    code = strip_cpp(text)
    found = []
    _scan_scope(code, 0, len(code), found)
    return found


def _scan_scope(code: str, start: int, stop: int, found: list) -> None:
    """Functions in a namespace / class / file scope code[start:stop]."""
    header_start = start
    i = start
    while i < stop:
        c = code[i]
        if c == ";":
            header_start = i + 1
        elif c == "}":
            header_start = i + 1
        elif c == "{":
            close = _matching(code, i)
            if close < 0:
                raise ValueError(f"unbalanced braces from line {code.count(chr(10), 0, i) + 1}")
            header = re.sub(r"^\s*((public|private|protected)\s*:\s*)+", " ", code[header_start:i])
            name = _function_name(header)
            if name is not None and _ctor_brace_init(header):
                i = close + 1  # `: member_{x}` of a constructor's initializer list: still the header
                continue
            if name is None:
                if not re.search(r"=\s*$|\w\s*$", _top_level(_without_templates(header))) or re.search(
                        r"\b(namespace|class|struct|union)\b", _without_templates(header)):
                    _scan_scope(code, i + 1, close, found)  # namespace or class body
                header_start = close + 1
                i = close + 1
                continue
            first = i - len(header.lstrip()) if header.strip() else i
            found.append((name, code.count("\n", 0, first) + 1, code.count("\n", 0, close) + 1))
            header_start = close + 1
            i = close + 1
            continue
        i += 1


def _ctor_brace_init(header: str) -> bool:
    """The { ends `Type(...) : a_(x), b_` (a member's braced initializer), not the body."""
    top = _top_level(_without_templates(header))
    tail = top[top.index(")") + 1:] if ")" in top else ""  # after the parameter list
    return bool(re.match(r"\s*:[^:]", tail)) and bool(re.search(r"[\w>]\s*$", tail))


# ------------------------------------------------------------------------------------------------
# Python


def py_functions(text: str):
    """(qualified name, first line, last line) of every def (nested and methods too)."""
    found = []

    def walk(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                found.append((prefix + child.name, child.lineno, child.end_lineno))
                walk(child, prefix + child.name + ".")
            elif isinstance(child, ast.ClassDef):
                walk(child, prefix + child.name + ".")
            else:
                walk(child, prefix)

    walk(ast.parse(text), "")
    return found


# ------------------------------------------------------------------------------------------------
# The project


def project_functions():
    """{"path:name": lines} of every function of the project's sources (the longest of overloads)."""
    lengths = {}
    files = [(p, cpp_functions) for d in CPP_DIRS for p in sorted((ROOT / d).rglob("*")) if p.suffix in CPP_SUFFIXES]
    files += [(p, py_functions) for d in PY_DIRS for p in sorted((ROOT / d).rglob("*.py"))]
    for path, scan in files:
        rel = path.relative_to(ROOT).as_posix()
        for name, first, last in scan(path.read_text(encoding="utf-8")):
            key = f"{rel}:{name}"
            lengths[key] = max(lengths.get(key, 0), last - first + 1)
    return lengths


def test_no_function_is_longer_than_the_limit():
    long = {k: v for k, v in project_functions().items() if v > MAX_LINES and k not in ALLOWLIST}
    listing = "\n".join(f"  {k}: {v} lines" for k, v in sorted(long.items(), key=lambda kv: -kv[1]))
    assert not long, (f"{len(long)} function(s) over {MAX_LINES} lines; split them into named steps "
                      f"(see cpp/src/rrr3_plan.cpp):\n{listing}")


def test_the_allowlist_has_no_stale_entries():
    lengths = project_functions()
    stale = [k for k in ALLOWLIST if lengths.get(k, 0) <= MAX_LINES]
    assert not stale, f"allowlisted but missing or at most {MAX_LINES} lines now; remove: {stale}"


def test_the_scan_sees_the_sources():
    lengths = project_functions()
    # Functions every part of the project has: a scan that silently found nothing would pass above.
    for key in ("cpp/src/rrr3_plan.cpp:plan_path", "cpp/src/rrr3.cpp:RRR3::RRR3", "cpp/bindings/module.cpp:PYBIND11_MODULE",
                "cpp/include/robokin/rrr3.hpp:check_mode", "python/robokin/postures.py:track_postures"):
        assert key in lengths, key
    assert sum(k.startswith("sim/") for k in lengths) > 20
    assert len(lengths) > 500


# ------------------------------------------------------------------------------------------------
# The scanners on snippets


def _body(lines: int) -> str:
    return "".join(f"  x += {k};\n" for k in range(lines))


def _by_name(found):
    return {name: last - first + 1 for name, first, last in found}


def test_cpp_scanner_finds_a_long_function_and_not_a_short_one():
    src = "int small(int x) {\n" + _body(3) + "  return x;\n}\n\nint big(int x) {\n" + _body(90) + "  return x;\n}\n"
    got = _by_name(cpp_functions(src))
    assert got == {"small": 6, "big": 93}


def test_cpp_scanner_multiline_signature_template_namespace_class():
    src = """namespace a {
namespace {
template <class Cost>
std::vector<long> programme(long count,
                            const Grid& g,
                            const Cost& cost) {
  return {};
}
}  // namespace

struct Cell {
  bool reachable = false;
  int leg() const { return leg_; }
  Cell(int a, int b) : a_(a), b_{b} {
    a_ += 1;
  }
};
class Foo : public Bar {
 public:
  void run() override {
    auto f = [&](int i) {
      return i;
    };
  }
};
const int table[3] = {1, 2, 3};
std::string Foo::name() const { return "x"; }
inline __attribute__((always_inline)) bool hot(int a,
                                              int b) {
  return a < b;
}
decltype(auto) deduced(int a) { return a; }
}  // namespace a
"""
    got = {name: (first, last) for name, first, last in cpp_functions(src)}
    assert got == {"programme": (3, 8), "leg": (13, 13), "Cell": (14, 16), "run": (20, 24),
                   "Foo::name": (27, 27), "hot": (28, 31), "deduced": (32, 32)}


def test_cpp_scanner_counts_lambdas_in_their_function():
    src = "void outer() {\n  auto f = [&](int i) {\n" + _body(85) + "  };\n  f(1);\n}\n"
    assert _by_name(cpp_functions(src)) == {"outer": 90}


def test_cpp_scanner_ignores_braces_in_strings_comments_and_preprocessor():
    src = r"""// a comment with a { brace
int f() {
  const char* s = "}}} not a brace {";
  const char c = '}';
  const char* r = R"x(raw } string { )x";
  /* block } comment
     { */
  constexpr long big = 20'000'000;
#define OPEN {
#if defined(X)
  if (a) {
#else
  if (b) {
#endif
    return 1;
  }
  return 0;
}
int g() { return '{'; }
"""
    assert _by_name(cpp_functions(src)) == {"f": 17, "g": 1}


def test_cpp_scanner_refuses_unbalanced_code():
    with pytest.raises(ValueError, match="unbalanced"):
        cpp_functions("int f() {\n  if (x) {\n  return 0;\n}\n")


def test_python_scanner():
    src = "def small():\n    return 1\n\n\nclass C:\n    def big(self):\n" + "".join(
        f"        x = {k}\n" for k in range(85)) + "        def inner():\n            pass\n        return x\n"
    got = _by_name(py_functions(src))
    assert got == {"small": 2, "C.big": 89, "C.big.inner": 2}
