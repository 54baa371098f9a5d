#!/usr/bin/env python3
"""Runs the marked examples of README.md and docs/**/*.md and compares what they print with the page.

Usage: doc_examples_test.py [--idbench BIN] [--source DIR] [--python-module DIR] [--python EXE] [--jobs N] [NAME ...]
       doc_examples_test.py --check-output PAGE NAME FILE
BIN, DIR default to the environment's IDBENCH, IDBENCH_SOURCE_DIR and IDBENCH_PYTHON_MODULE_DIR (the folder of
the built Python module; without it the Python examples are skipped with a message). NAME runs only those
examples (an example that reads another's files needs that one named too). --check-output compares FILE with the output block NAME of PAGE (install_test.sh: the library
example's program, which this test cannot build). Exit 1 naming page:line, what the page says and what was
printed, on any difference.

Markers, HTML comment lines (invisible on GitHub) right before the block they govern; a block is fenced
(```) or indented by 4 spaces:

  <!-- example: NAME [OPTION ...] -->   the commands (```sh, ```console or indented: bash -e -o pipefail;
                                         ```python: python3 with the module on PYTHONPATH)
  <!-- output: NAME [file=PATH] [OPTION ...] -->
                                         what NAME prints (stdout and stderr as a terminal shows them),
                                         or with file=PATH the file it wrote
  <!-- file: NAME PATH -->               a block written to PATH before NAME runs
  <!-- not run: REASON -->               a command block that is not run; the page says why in its text
  <!-- run by: PATH -->                  a command block that the script PATH runs, each line verbatim

Options: exit=N (expected exit status, default 0), tol=R (relative tolerance of numbers), floor=A (absolute:
round-off-level numbers), roundoff=X,Y (those numbers of the page match any number: ratios of round-off),
timeout=S (default 120), needs=shared (skipped with a message when ../shared/data is absent; implied by a
command naming ../shared), needs=python (implied by ```python), external=TEST (not run here: TEST runs it
and compares through --check-output), sanitizers=TEST (skipped with a message in the sanitizer build, where
IDBENCH_SANITIZED=1: an example that takes minutes there, whose code TEST runs under the sanitizers),
source=PATH (the block must be the tree's file PATH, character for
character). Options of an output marker override its example's.

A fenced block of sh, bash, console or python, or any block whose first line is a command (idbench …,
./build/workbench/idbench …, cmake, ctest, bash, sudo, python3), must carry an example or a not-run marker.

Comparison: both texts are cut into words at whitespace (line wraps do not matter), words into numbers and
the text between them. Text must be equal; a number must agree within the larger of tol·|page|, floor and
half a unit in the last place printed by the page or by the command (0.0536 matches 0.05361). A word `…`
on its own matches any run of words (including none); `…` inside a word, any text within one word
(`(…);` matches `(B4.J33);`). The whole output must match: a page that shows part of it says so with `…`.
Unicode minus − is -. Examples of one page run in order, in one temporary directory laid out as the source
tree: its top-level folders (symbolic links), ./build/workbench/idbench, idbench on PATH, ../shared.
Nothing is written to the source tree (checked).
"""
import argparse
import concurrent.futures
import os
import pathlib
import pty
import re
import select
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SANITIZER_WARNING = re.compile(r"^==\d+==WARNING: [^\n]*\n", re.M)
MARKER = re.compile(r"^<!--\s*(example|output|file|not run|run by)\s*:\s*(.*?)\s*-->\s*$")
COMMAND_LIKE = re.compile(r"^\s*(\$ )?(\./build/workbench/)?(idbench|cmake|ctest|bash|sudo|python3|PYTHONPATH=\S*|K=\S*)(?=\s|$)")
NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
PIECE = re.compile(r"(?<![\w.])(" + NUMBER + r")(?![\w]|\.\d)")
ELLIPSIS = "…"


class Failure(Exception):
    pass


# ---- reading the pages ----------------------------------------------------------------------------------

class Block:
    def __init__(self, page, line, text, info):
        self.page, self.line, self.text, self.info = page, line, text, info


class Example:
    def __init__(self, page, line, name, options):
        self.page, self.line, self.name, self.options = page, line, name, options
        self.command = None  # Block
        self.outputs = []  # (Block, options)
        self.files = []  # (Block, path)


def read_block(lines, start):
    """The code block at or after lines[start] (blank lines skipped): (index of its first line, line number of
    its content, its text, the fence's info string), or None when the next non-blank line starts no block."""
    i = start
    while i < len(lines) and not lines[i].strip():
        i += 1
    if i == len(lines):
        return None
    fence = re.match(r"^(```+|~~~+)\s*(\S*)", lines[i])
    if fence:
        end = i + 1
        while end < len(lines) and not lines[end].startswith(fence.group(1)):
            end += 1
        if end == len(lines):
            raise Failure(f"line {i + 1}: a fence that is never closed")
        return i, i + 2, "\n".join(lines[i + 1:end]), fence.group(2)
    if lines[i].startswith("    "):
        end = i
        while end < len(lines) and (lines[end].startswith("    ") or not lines[end].strip()):
            end += 1
        while not lines[end - 1].strip():
            end -= 1
        return i, i + 1, "\n".join(line[4:] for line in lines[i:end]), ""
    return None


def block_starts(lines):
    """Index of the first line of every fenced block, and of every indented block after a blank line."""
    starts, in_fence = [], None
    for i, line in enumerate(lines):
        if in_fence:
            if line.startswith(in_fence):
                in_fence = None
            continue
        fence = re.match(r"^(```+|~~~+)", line)
        if fence:
            in_fence = fence.group(1)
            starts.append(i)
        elif line.startswith("    ") and line.strip() and i > 0 and not lines[i - 1].strip():
            starts.append(i)
    return starts


def parse_options(text, where):
    options = {}
    for word in shlex.split(text):
        key, eq, value = word.partition("=")
        if key not in ("exit", "tol", "floor", "roundoff", "timeout", "needs", "file", "external", "source",
                       "sanitizers"):
            raise Failure(f"{where}: unknown option '{key}'")
        options[key] = value if eq else "1"
    return options


def parse_page(root, page):
    """The page's examples, and the command-like blocks no marker governs."""
    rel = page.relative_to(root).as_posix()
    lines = page.read_text(encoding="utf-8").splitlines()
    examples, governed, pending_files = {}, set(), []
    for number, line in enumerate(lines):
        marker = MARKER.match(line)
        if not marker:
            continue
        kind, rest = marker.group(1), marker.group(2)
        where = f"{rel}:{number + 1}"
        block = read_block(lines, number + 1)
        if block is None:
            raise Failure(f"{where}: the marker governs no code block")
        first, content_line, text, info = block
        governed.add(first)
        if kind == "not run":
            if not rest:
                raise Failure(f"{where}: 'not run' needs its reason")
            continue
        if kind == "run by":  # a command another script runs verbatim (README's two commands: .ci/run)
            script = root / rest
            script_lines = script.read_text(encoding="utf-8").splitlines() if script.is_file() else []
            for command in (line.strip() for line in text.splitlines()):
                if command and not any(command == line.strip() for line in script_lines):
                    raise Failure(f"{where}: {rest} does not run this command verbatim: {command}")
            continue
        name, _, tail = rest.partition(" ")
        block = Block(rel, content_line, text, info)
        if kind == "example":
            if name in examples:
                raise Failure(f"{where}: a second example '{name}' on the page")
            example = Example(rel, number + 1, name, parse_options(tail, where))
            example.command = block
            example.files = [(b, path) for owner, b, path in pending_files if owner == name]
            pending_files = [f for f in pending_files if f[0] != name]
            examples[name] = example
        elif kind == "output":
            if name not in examples:
                raise Failure(f"{where}: output of '{name}', which no example marker above names")
            examples[name].outputs.append((block, parse_options(tail, where)))
        else:  # file
            if len(tail.split()) != 1:
                raise Failure(f"{where}: expected <!-- file: EXAMPLE PATH -->")
            pending_files.append((name, block, tail.strip()))
    if pending_files:
        raise Failure(f"{rel}: file blocks for examples the page does not have: "
                      + ", ".join(f[0] for f in pending_files))
    for example in examples.values():
        if "source" in example.options:
            path = root / example.options["source"]
            if not path.is_file() or path.read_text(encoding="utf-8").rstrip("\n") != example.command.text:
                raise Failure(f"{rel}:{example.command.line}: the block is not {example.options['source']} "
                              "(copy the file into the page)")
        if not example.outputs:
            raise Failure(f"{rel}:{example.line}: example '{example.name}' has no output block")
    unmarked = []
    for start in block_starts(lines):
        if start in governed:
            continue
        _, _, text, info = read_block(lines, start)
        first = next((line for line in text.splitlines() if line.strip() and not line.startswith("#")), "")
        if info in ("sh", "bash", "console", "python") or COMMAND_LIKE.match(first):
            unmarked.append(f"{rel}:{start + 1}")
    return list(examples.values()), unmarked


# ---- comparing ----------------------------------------------------------------------------------------

class Item:
    """A number or a piece of text of one word, with the line it came from."""

    def __init__(self, text, line, word, first):
        self.text, self.line, self.word, self.first = text, line, word, first
        self.number = None
        self.glob = None
        if ELLIPSIS in text:
            self.glob = re.compile("^" + ".*".join(re.escape(p) for p in text.split(ELLIPSIS)) + "$", re.S)
        elif PIECE.fullmatch(text):
            self.number = float(text)


WILD = "WILD"


def items_of(text, first_line=1, expected=False):
    """The words of text cut into numbers and text; `…` alone is WILD, inside a word a glob over that word."""
    out, words = [], []
    for offset, line in enumerate(text.replace("\r", "").replace("−", "-").splitlines()):
        for word in line.split():
            index = len(words)
            words.append(word)
            if expected and word == ELLIPSIS:
                out.append(WILD)
                continue
            if expected and ELLIPSIS in word:
                out.append(Item(word, first_line + offset, index, True))
                continue
            position, first = 0, True
            for m in PIECE.finditer(word):
                if m.start() > position:
                    out.append(Item(word[position:m.start()], first_line + offset, index, first))
                    first = False
                out.append(Item(m.group(1), first_line + offset, index, first))
                first = False
                position = m.end()
            if position < len(word):
                out.append(Item(word[position:], first_line + offset, index, first))
    return out, words


def half_ulp(text):
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.split(".", 1)[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** ((int(exponent) if exponent else 0) - decimals)


def allowed(expected, actual, options):
    if expected.text in options.get("roundoff", ()):
        return float("inf")
    return max(half_ulp(expected.text), half_ulp(actual.text), options["tol"] * abs(expected.number),
               options["floor"]) * (1 + 1e-12)


def step(expected, actual, index, words_count_of, options):
    """How many actual items expected matches at actual[index] (0: no match)."""
    item = actual[index]
    if expected.glob:
        if not item.first:
            return 0
        end = index + 1
        while end < len(actual) and actual[end].word == item.word:
            end += 1
        return end - index if expected.glob.match(words_count_of[item.word]) else 0
    if expected.number is not None:
        if item.number is None:
            return 0
        return 1 if abs(item.number - expected.number) <= allowed(expected, item, options) else 0
    return 1 if item.number is None and item.text == expected.text else 0


def compare(expected_text, expected_line, actual_text, options):
    """None when actual_text matches the page's block, else (expected item or None, actual item or None)."""
    pattern, _ = items_of(expected_text, expected_line, expected=True)
    actual, words = items_of(actual_text)
    p = i = 0
    star_p, star_i = -1, 0
    furthest = (-1, None, None)
    while i < len(actual):
        if p < len(pattern) and pattern[p] is WILD:
            star_p, star_i = p, i
            p += 1
            continue
        advance = step(pattern[p], actual, i, words, options) if p < len(pattern) else 0
        if advance:
            p += 1
            i += advance
            continue
        if p > furthest[0]:
            furthest = (p, pattern[p] if p < len(pattern) else None, actual[i])
        if star_p < 0:
            return furthest[1:]
        star_i += 1
        p, i = star_p + 1, star_i
    while p < len(pattern) and pattern[p] is WILD:
        p += 1
    if p == len(pattern):
        return None
    if p > furthest[0]:
        furthest = (p, pattern[p], None)
    if furthest[0] > 0 and pattern[furthest[0] - 1] is WILD:
        return furthest[1], None  # nothing after the … matched: no actual item to name
    return furthest[1:]


def describe(difference, block, actual_text, options, what):
    expected, actual = difference
    page_lines = block.text.splitlines()
    actual_lines = actual_text.replace("\r", "").splitlines()
    if expected is None:
        where = f"{block.page}:{block.line + len(page_lines) - 1}"
        head = f"{where}: the page's block ends, {what} goes on with '{actual.text}'"
    elif actual is None:
        head = (f"{block.page}:{expected.line}: expected '{expected.text}' (after …, on the line below), not found "
                f"in {what} where the lines above it match")
    elif expected.number is not None and actual.number is not None:
        head = (f"{block.page}:{expected.line}: expected {expected.text}, got {actual.text} (difference "
                f"{abs(actual.number - expected.number):.3g}, allowed {allowed(expected, actual, options):.3g})")
    else:
        head = f"{block.page}:{expected.line}: expected '{expected.text}', got '{actual.text}'"
    lines = [head]
    if expected is not None:
        lines.append(f"    page:    {page_lines[expected.line - block.line].strip()}")
    if actual is not None:
        lines.append(f"    printed: {actual_lines[actual.line - 1].strip()}  ({what}, line {actual.line})")
    return "\n".join(lines)


# ---- running ------------------------------------------------------------------------------------------

def run_in_terminal(argv, cwd, env, timeout):
    """Exit status and output of argv with stdout and stderr on one pseudo-terminal, as a user sees them."""
    master, slave = pty.openpty()
    process = subprocess.Popen(argv, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=slave, stderr=slave,
                               start_new_session=True)
    os.close(slave)
    chunks, deadline = [], time.monotonic() + timeout
    try:
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
                raise Failure(f"timed out after {timeout:g} s (timeout=S to raise)")
            ready, _, _ = select.select([master], [], [], min(remaining, 1.0))
            if not ready:
                continue
            try:
                data = os.read(master, 65536)
            except OSError:  # EIO: the last writer closed the terminal
                break
            if not data:
                break
            chunks.append(data)
    finally:
        os.close(master)
    status = process.wait()
    text = b"".join(chunks).decode("utf-8", "replace").replace("\r\n", "\n")
    # The sanitizer runtime's own warnings (CI's second stage: "==123==WARNING: invalid path to external
    # symbolizer!") are not the command's output; its errors still fail the example by the exit status.
    return status, SANITIZER_WARNING.sub("", text)


def lay_out(top, source, binary, module_dir):
    """top/bin/idbench, top/shared -> source/../shared; returns a function making a page's working folder."""
    (top / "bin").mkdir()
    (top / "bin" / "idbench").symlink_to(binary)
    (top / "pages").mkdir()
    shared = source.parent / "shared"
    if shared.exists():
        (top / "pages" / "shared").symlink_to(shared.resolve())

    def folder(slug):
        work = top / "pages" / slug
        work.mkdir()
        for entry in source.iterdir():
            if not is_tree_folder(entry) or entry.name == "build":
                continue
            (work / entry.name).symlink_to(entry.resolve())
        (work / "build" / "workbench").mkdir(parents=True)
        (work / "build" / "workbench" / "idbench").symlink_to(binary)
        if module_dir:
            (work / "build" / "workbench" / "python").symlink_to(module_dir)
        return work
    return folder


def run_page(page, examples, folder, env, shared_present, module_dir, top):
    """Runs the page's examples in order; a list of (example, seconds, status, message)."""
    results = []
    work = None
    for example in examples:
        options = {"exit": "0", "tol": "0", "floor": "0", "roundoff": "", "timeout": "120", "needs": ""}
        options.update(example.options)
        needs = set(filter(None, options["needs"].split(",")))
        if "../shared" in example.command.text:
            needs.add("shared")
        python = example.command.info == "python"
        if python:
            needs.add("python")
        where = f"{example.page}:{example.line} {example.name}"
        if "external" in options:
            results.append((where, 0.0, "skip", f"run and compared by {options['external']}"))
            continue
        if "sanitizers" in options and os.environ.get("IDBENCH_SANITIZED") == "1":
            results.append((where, 0.0, "skip", f"minutes under the sanitizers; {options['sanitizers']} runs its code there"))
            continue
        if "shared" in needs and not shared_present:
            results.append((where, 0.0, "skip", "needs ../shared/data, absent"))
            continue
        if "python" in needs and not module_dir:
            results.append((where, 0.0, "skip", "needs the Python module (IDBENCH_PYTHON_MODULE_DIR unset)"))
            continue
        slug = re.sub(r"[^\w]+", "_", page)
        if work is None:
            work = folder(slug)
        for block, path in example.files:
            target = work / path
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(block.text + "\n", encoding="utf-8")
        script = top / f"{slug}_{example.name}.{'py' if python else 'sh'}"
        script.write_text(example.command.text + "\n", encoding="utf-8")
        argv = [env["IDBENCH_DOC_PYTHON"], str(script)] if python else ["bash", "-e", "-o", "pipefail", str(script)]
        started = time.monotonic()
        try:
            status, output = run_in_terminal(argv, work, env, float(options["timeout"]))
        except Failure as error:
            results.append((where, time.monotonic() - started, "FAIL", str(error)))
            continue
        seconds = time.monotonic() - started
        problems = []
        if status != int(options["exit"]):
            tail = "\n".join("    | " + line for line in output.splitlines()[-15:])
            problems.append(f"{example.page}:{example.command.line}: exit status {status}, the page expects "
                            f"{options['exit']}; its last lines:\n{tail}")
        else:
            for block, block_options in example.outputs:
                compare_options = comparison_options({**options, **block_options})
                if "file" in block_options:
                    target = work / block_options["file"]
                    if not target.is_file():
                        problems.append(f"{block.page}:{block.line}: {block_options['file']} was not written")
                        continue
                    actual, what = target.read_text(encoding="utf-8", errors="replace"), block_options["file"]
                else:
                    actual, what = output, "the output"
                difference = compare(block.text, block.line, actual, compare_options)
                if difference is not None:
                    problems.append(describe(difference, block, actual, compare_options, what))
        results.append((where, seconds, "FAIL" if problems else "ok", "\n".join(problems)))
    return results


def comparison_options(options):
    return {"tol": float(options.get("tol", 0)), "floor": float(options.get("floor", 0)),
            "roundoff": set(filter(None, options.get("roundoff", "").split(",")))}


def is_tree_folder(entry):
    """Whether a top-level entry of the source is the project's: not hidden, not a build tree, not out/."""
    return not (entry.name.startswith(".") or entry.name == "out" or (entry / "CMakeCache.txt").exists())


def snapshot(source):
    """(mtime, size) of every file of the tree (__pycache__, which tests running beside this one write, left out)."""
    state = {}
    for folder, dirs, files in os.walk(source):
        if folder == str(source):
            dirs[:] = [d for d in dirs if is_tree_folder(source / d)]
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for name in files:
            path = os.path.join(folder, name)
            try:
                info = os.lstat(path)
            except OSError:
                continue
            state[path] = (info.st_mtime_ns, info.st_size)
    return state


def pages_of(source):
    return [source / "README.md", *sorted((source / "docs").rglob("*.md"))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--idbench", default=os.environ.get("IDBENCH"))
    parser.add_argument("--source", default=os.environ.get("IDBENCH_SOURCE_DIR",
                                                           pathlib.Path(__file__).resolve().parents[2]))
    parser.add_argument("--python-module", default=os.environ.get("IDBENCH_PYTHON_MODULE_DIR"))
    parser.add_argument("--python", default=os.environ.get("IDBENCH_PYTHON", sys.executable),
                        help="the interpreter of the Python examples (default: this one)")
    parser.add_argument("--jobs", type=int, default=min(os.cpu_count() or 1, 2))
    parser.add_argument("--check-output", nargs=3, metavar=("PAGE", "NAME", "FILE"))
    parser.add_argument("names", nargs="*")
    args = parser.parse_args()
    source = pathlib.Path(args.source).resolve()

    if args.check_output:
        page, name, file = args.check_output
        examples, _ = parse_page(source, source / page)
        example = next((e for e in examples if e.name == name), None)
        if example is None:
            raise Failure(f"{page}: no example '{name}'")
        actual = pathlib.Path(file).read_text(encoding="utf-8", errors="replace")
        for block, block_options in example.outputs:
            options = comparison_options({**example.options, **block_options})
            difference = compare(block.text, block.line, actual, options)
            if difference is not None:
                print(describe(difference, block, actual, options, file))
                return 1
        print(f"{page}: '{name}' matches {file}")
        return 0

    if not args.idbench:
        parser.error("the idbench binary: --idbench or IDBENCH")
    binary = pathlib.Path(args.idbench).resolve()
    module_dir = pathlib.Path(args.python_module).resolve() if args.python_module else None
    by_page, unmarked = {}, []
    for page in pages_of(source):
        examples, page_unmarked = parse_page(source, page)
        unmarked += page_unmarked
        if args.names:
            examples = [e for e in examples if e.name in args.names]
        if examples:
            by_page[page.relative_to(source).as_posix()] = examples
    shared_present = (source.parent / "shared" / "data").is_dir()
    before = snapshot(source)
    top = pathlib.Path(tempfile.mkdtemp(prefix="idbench-doc-examples-"))
    env = dict(os.environ)
    env["PATH"] = f"{top / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env.pop("IDBENCH_PYTHON_MODULE_DIR", None)
    if module_dir:
        env["PYTHONPATH"] = str(module_dir) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env.setdefault("LP_NUM_THREADS", "1")
    env["IDBENCH_DOC_PYTHON"] = args.python
    started = time.monotonic()
    results = []
    try:
        folder = lay_out(top, source, binary, module_dir)
        with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
            futures = [pool.submit(run_page, page, examples, folder, env, shared_present, module_dir, top)
                       for page, examples in by_page.items()]
            for future in futures:
                for result in future.result():
                    results.append(result)
                    where, seconds, status, message = result
                    print(f"{status:4s} {seconds:6.1f} s  {where}" + (f": {message}" if status == "skip" else ""),
                          flush=True)
    finally:
        shutil.rmtree(top, ignore_errors=True)
    failures = [r for r in results if r[2] == "FAIL"]
    after = snapshot(source)
    changed = sorted(os.path.relpath(path, source) for path in set(before) | set(after)
                     if before.get(path) != after.get(path))
    for where, _, _, message in failures:
        print(f"\nFAILED {where}\n{message}")
    if unmarked:
        print("\ncommand blocks with neither an example nor a 'not run' marker:\n  " + "\n  ".join(unmarked))
    if changed:
        print("\nthe examples changed the source tree:\n  " + "\n  ".join(changed))
    count = len(results)
    skipped = sum(1 for r in results if r[2] == "skip")
    print(f"\n{count} examples on {len(by_page)} pages: {count - skipped - len(failures)} ok, {len(failures)} "
          f"failed, {skipped} skipped, in {time.monotonic() - started:.1f} s")
    return 1 if failures or unmarked or changed else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as error:
        print(f"doc_examples_test: {error}")
        sys.exit(1)
