"""The documentation's code blocks and links, checked against the repository and the built
`impact` binary. Reference: the pages themselves (README.md and docs/*.md), the files of this
checkout, and `target/release/impact` and `impact-bench` as `.ci/run` builds them
(`cargo build --workspace --all-targets --release`) before it runs these tests.

What is verified, for README.md and every docs/*.md:

- Fenced blocks marked `bash`, `sh`, `shell` or `console` (for `console`, the lines that start
  with `$ `):
  - every command's program exists: `impact` and `impact-bench`, bare or as
    `target/release/NAME`, in the target folder (`$CARGO_TARGET_DIR`, else `<repo>/target`)
    under `release/`; a program given by a path inside the repository (`scripts/main-job.sh`,
    `.venv/bin/python`) there; a bare name among `EXTERNAL_PROGRAMS` or the shell's builtins;
  - every repository path named in a command resolves (`{a,b}` and globs expanded; `out/...`,
    paths outside the repository and words holding a shell variable are not repository
    paths; comments are not read);
  - the block runs, as `bash -eu -o pipefail`, in a scratch folder whose entries are symlinks
    to the repository's top level (so `out/` is scratch and `target` is the target folder),
    with the target's `release/` first on PATH, and exits 0 within `RUN_SECONDS`;
    unless it is marked parse-only (below).
- Fenced blocks marked `yaml` parse (PyYAML). A scene, a mapping with `plate:`, runs through
  `impact simulate --quiet` and exits 0. A case, a mapping with `requirement:` and `checks:`,
  is put in a throw-away repository (`verification/cases/docs/<id>/case.yaml`, beside
  symlinks to this checkout's `verification/scenes/` and `reference-data/`) where
  `impact lint --root` and `impact verify --root` exit 0. Other YAML (fragments of a scene or
  a case) is parsed only. Parse-only blocks are parsed only.
- Fenced blocks marked `python` compile, and the repository paths in their string literals
  resolve. None runs: the package `impact` they import is built into the venv after these
  tests in `.ci/run`.
- Every Markdown link or image to a file of the repository resolves, inside the repository;
  an `#anchor` into a Markdown file names one of its headings (GitHub's slugs).

The parse-only convention: the line `<!-- snippet: parse-only -->` before a fenced block
(blank lines between allowed; indented alike inside a list) marks a block that takes long or
changes the machine (a build, the main job, `.ci/run`, an installation, a matrix run, a Slurm
script, commands that need a second checkout). Its programs and paths are still checked; it
is not run. Every block without the marker runs, so it must take seconds. A marker that is
misspelt or not followed by a block fails.

A missing binary is a failure, not a skip: build it with `cargo build --release --workspace
--bins`.
"""
from __future__ import annotations

import ast
import fnmatch
import glob
import os
import re
import shlex
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
TARGET = Path(os.environ.get("CARGO_TARGET_DIR") or ROOT / "target").resolve()
RELEASE = TARGET / "release"
BINARIES = ("impact", "impact-bench")
MARKER = "<!-- snippet: parse-only -->"
RUN_SECONDS = 180
SHELL_LANGS = {"bash", "sh", "shell", "console"}
# Programs the pages call by bare name, besides the repository's own: a typo of one of them
# (or a new one) must be added here on purpose.
EXTERNAL_PROGRAMS = {"bash", "cargo", "git", "pip", "python", "python3", "sbatch", "dask"}
SHELL_BUILTINS = {"cd", "echo", "export", "set", "source", ".", "test", "[", "true", "false",
                  "exit", "wait", "read", "for", "do", "done", "if", "then", "else", "fi",
                  "while", "in"}


def pages() -> list[Path]:
    return [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))


@dataclass
class Block:
    page: Path
    line: int          # 1-based line of the opening fence
    lang: str
    body: str
    parse_only: bool

    @property
    def name(self) -> str:
        return f"{self.page.relative_to(ROOT)}:{self.line}:{self.lang}"


FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([\w+-]*)")


def blocks_of(page: Path) -> tuple[list[Block], list[str]]:
    """The fenced blocks of a page and the problems of its markers."""
    lines = page.read_text(encoding="utf-8").split("\n")
    out, problems = [], []
    pending_marker = None  # line number of a marker waiting for its block
    i = 0
    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        m = FENCE.match(line)
        if m:
            indent, fence, lang = len(m.group(1)), m.group(2), m.group(3).lower()
            body = []
            j = i + 1
            while j < len(lines):
                close = lines[j].strip()
                if close.startswith(fence[0] * len(fence)) and close.strip(fence[0]) == "":
                    break
                body.append(lines[j][indent:] if lines[j][:indent].strip() == "" else lines[j])
                j += 1
            out.append(Block(page, i + 1, lang, "\n".join(body) + "\n", pending_marker is not None))
            pending_marker = None
            i = j + 1
            continue
        if stripped.startswith("<!--") and "snippet" in stripped:
            if stripped != MARKER:
                problems.append(f"{page.name}:{i + 1}: unknown snippet marker {stripped!r} (the one marker is {MARKER!r})")
            else:
                if pending_marker is not None:
                    problems.append(f"{page.name}:{pending_marker}: marker not followed by a block")
                pending_marker = i + 1
        elif stripped and pending_marker is not None:
            problems.append(f"{page.name}:{pending_marker}: marker not followed by a block")
            pending_marker = None
        i += 1
    if pending_marker is not None:
        problems.append(f"{page.name}:{pending_marker}: marker not followed by a block")
    return out, problems


ALL_BLOCKS = [b for p in pages() for b in blocks_of(p)[0]]


def of_langs(langs) -> list[Block]:
    return [b for b in ALL_BLOCKS if b.lang in langs]


def need_binary(name: str = "impact") -> Path:
    path = RELEASE / name
    if not path.is_file():
        pytest.fail(f"{path} is missing: the documentation's commands run the built binary. "
                    "Build it first: cargo build --release --workspace --bins "
                    "(or set CARGO_TARGET_DIR to the target folder that holds it)")
    return path


# ---------------------------------------------------------------- repository paths

def top_level() -> list[str]:
    names = [n for n in os.listdir(ROOT) if n not in ("target", "out", ".git", ".venv")]
    return sorted(n for n in names if not n.startswith(".") or n == ".ci")


PATH_WORD = re.compile(
    r"(?<![\w./$-])((?:\./)?(?:" + "|".join(re.escape(n) for n in top_level())
    + r")(?:/[\w.{},*?-]*)*)(?![\w-])")


def expand_braces(word: str) -> list[str]:
    m = re.search(r"\{([^{}]*)\}", word)
    if not m:
        return [word]
    return [v for alt in m.group(1).split(",")
            for v in expand_braces(word[:m.start()] + alt + word[m.end():])]


def path_resolves(word: str) -> bool:
    word = word.rstrip(".,:;")
    for w in expand_braces(word):
        w = w[2:] if w.startswith("./") else w
        if any(c in w for c in "*?"):
            if not glob.glob(str(ROOT / w)):
                return False
        elif not (ROOT / w).exists():
            return False
    return True


def repository_paths(text: str) -> list[str]:
    return [w for w in PATH_WORD.findall(text) if "$" not in w]


# ---------------------------------------------------------------- shell commands

SEPARATORS = {";", "&&", "||", "|", "&", "(", ")", ";;", "|&"}


def shell_text(block: Block) -> str:
    if block.lang != "console":
        return block.body
    return "\n".join(l[2:] for l in block.body.split("\n") if l.startswith("$ ")) + "\n"


def commands(text: str) -> list[list[str]]:
    """The simple commands of a shell text (comments dropped, continuations joined)."""
    joined = re.sub(r"\\\n", " ", text)
    out = []
    for line in joined.split("\n"):
        lex = shlex.shlex(line, posix=True, punctuation_chars=True)
        lex.whitespace_split = True
        lex.commenters = "#"
        try:
            tokens = list(lex)
        except ValueError as e:
            raise AssertionError(f"cannot split the shell line {line!r}: {e}")
        cmd: list[str] = []
        for t in tokens + [";"]:
            if t in SEPARATORS:
                if cmd:
                    out.append(cmd)
                cmd = []
            else:
                cmd.append(t)
    return out


def program_problem(cmd: list[str]) -> str | None:
    words = list(cmd)
    while words and re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*=.*", words[0]):
        words.pop(0)  # VAR=value before the program
    if not words:
        return None
    prog = words[0]
    if "$" in prog or prog.startswith(("..", "/", "~")):
        return None  # a variable, or outside the repository
    name = Path(prog).name
    if prog in BINARIES or (prog.startswith(("target/release/", "./target/release/")) and name in BINARIES):
        path = RELEASE / name
        return None if path.is_file() else (
            f"{prog}: {path} is missing; build it first: cargo build --release --workspace --bins")
    if "/" in prog:
        return None if (ROOT / prog).is_file() else f"{prog}: no such file in the repository"
    if prog in EXTERNAL_PROGRAMS or prog in SHELL_BUILTINS:
        return None
    return f"{prog}: not a program of the repository, nor one of EXTERNAL_PROGRAMS"


def scratch_root(tmp_path: Path) -> Path:
    """A folder that looks like the checkout (symlinks) but whose out/ is scratch."""
    root = tmp_path / "repo"
    root.mkdir()
    for name in os.listdir(ROOT):
        if name in ("out", "target"):
            continue
        (root / name).symlink_to(ROOT / name)
    (root / "target").symlink_to(TARGET)
    return root


def run(args, cwd: Path, timeout: int = RUN_SECONDS, env=None) -> subprocess.CompletedProcess:
    try:
        return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired as e:
        pytest.fail(f"{args!r} took more than {timeout} s: mark its block {MARKER} "
                    f"or make it shorter\n{e.stdout or ''}\n{e.stderr or ''}")


def failed(what: str, p: subprocess.CompletedProcess) -> str:
    return (f"{what}: exit {p.returncode}\n--- stdout (end)\n{p.stdout[-3000:]}\n"
            f"--- stderr (end)\n{p.stderr[-3000:]}")


@pytest.mark.parametrize("block", of_langs(SHELL_LANGS), ids=lambda b: b.name)
def test_shell_programs_and_paths_exist(block):
    text = shell_text(block)
    problems = []
    for cmd in commands(text):
        if (p := program_problem(cmd)) is not None:
            problems.append(p)
        for word in cmd:
            for path in repository_paths(word):
                if not path_resolves(path):
                    problems.append(f"{path}: no such path in the repository (in {' '.join(cmd)!r})")
    assert problems == [], f"{block.name}:\n" + "\n".join(problems)


@pytest.mark.parametrize("block", [b for b in of_langs(SHELL_LANGS) if not b.parse_only],
                         ids=lambda b: b.name)
def test_shell_block_runs(block, tmp_path):
    text = shell_text(block)
    if any(c[0] in BINARIES or Path(c[0]).name in BINARIES for c in commands(text) if c):
        need_binary()
    root = scratch_root(tmp_path)
    env = dict(os.environ, PATH=f"{RELEASE}{os.pathsep}{os.environ.get('PATH', '')}")
    p = run(["bash", "-eu", "-o", "pipefail", "-c", text], cwd=root, env=env)
    assert p.returncode == 0, failed(f"{block.name} (run in {root})", p)


# ---------------------------------------------------------------- YAML

def load_yaml(block: Block):
    try:
        return yaml.safe_load(block.body)
    except yaml.YAMLError as e:
        pytest.fail(f"{block.name}: does not parse as YAML: {e}")


def parsed_or_none(block: Block):
    """For choosing the tests of a block: a block that does not parse fails test_yaml_parses."""
    try:
        return yaml.safe_load(block.body)
    except yaml.YAMLError:
        return None


def is_scene(doc) -> bool:
    return isinstance(doc, dict) and "plate" in doc


def is_case(doc) -> bool:
    return isinstance(doc, dict) and "requirement" in doc and "checks" in doc


@pytest.mark.parametrize("block", of_langs({"yaml", "yml"}), ids=lambda b: b.name)
def test_yaml_parses(block):
    load_yaml(block)


@pytest.mark.parametrize("block", [b for b in of_langs({"yaml", "yml"})
                                   if not b.parse_only and is_scene(parsed_or_none(b))],
                         ids=lambda b: b.name)
def test_scene_runs(block, tmp_path):
    impact = need_binary()
    scene = tmp_path / "scene.yaml"
    scene.write_text(block.body)
    p = run([impact, "simulate", scene, "--out", tmp_path / "out", "--quiet"], cwd=ROOT)
    assert p.returncode == 0, failed(f"{block.name}: impact simulate", p)
    assert (tmp_path / "out" / "summary.json").is_file()


@pytest.mark.parametrize("block", [b for b in of_langs({"yaml", "yml"})
                                   if not b.parse_only and is_case(parsed_or_none(b))],
                         ids=lambda b: b.name)
def test_case_lints_and_passes(block, tmp_path):
    impact = need_binary()
    doc = load_yaml(block)
    root = tmp_path / "repo"
    case_dir = root / "verification" / "cases" / "docs" / str(doc["id"])
    case_dir.mkdir(parents=True)
    (case_dir / "case.yaml").write_text(block.body)
    (root / "verification" / "scenes").symlink_to(ROOT / "verification" / "scenes")
    (root / "reference-data").symlink_to(ROOT / "reference-data")
    p = run([impact, "lint", "--root", root], cwd=tmp_path)
    assert p.returncode == 0, failed(f"{block.name}: impact lint", p)
    p = run([impact, "verify", "--root", root, "--out", tmp_path / "out"], cwd=tmp_path)
    assert p.returncode == 0, failed(f"{block.name}: impact verify", p)


# ---------------------------------------------------------------- Python

@pytest.mark.parametrize("block", of_langs({"python", "py"}), ids=lambda b: b.name)
def test_python_compiles_and_names_existing_paths(block):
    try:
        tree = compile(block.body, block.name, "exec", flags=ast.PyCF_ONLY_AST)
    except SyntaxError as e:
        pytest.fail(f"{block.name}: does not compile: {e}")
    compile(tree, block.name, "exec")
    missing = [w for node in ast.walk(tree)
               if isinstance(node, ast.Constant) and isinstance(node.value, str)
               for w in repository_paths(node.value) if not path_resolves(w)]
    assert missing == [], f"{block.name}: no such paths in the repository: {missing}"


# ---------------------------------------------------------------- links

LINK = re.compile(r"!?\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
CODE_SPAN = re.compile(r"`+[^`]*`+")


def slug(heading: str) -> str:
    """GitHub's anchor of a heading's text."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link: its text
    text = text.replace("`", "").replace("*", "").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    seen: dict[str, int] = {}
    out = set()
    in_fence = False
    for line in page.read_text(encoding="utf-8").split("\n"):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        m = None if in_fence else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            base = slug(m.group(1))
            n = seen.get(base, 0)
            seen[base] = n + 1
            out.add(base if n == 0 else f"{base}-{n}")
    return out


def links_of(page: Path) -> list[tuple[int, str]]:
    out = []
    in_fence = False
    for i, line in enumerate(page.read_text(encoding="utf-8").split("\n"), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        for m in LINK.finditer(CODE_SPAN.sub(lambda c: " " * len(c.group(0)), line)):
            out.append((i, m.group(2)))
    return out


@pytest.mark.parametrize("page", pages(), ids=lambda p: str(p.relative_to(ROOT)))
def test_links_resolve(page):
    problems = []
    for line, target in links_of(page):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):
            continue  # http:, https:, mailto:
        path_part, _, anchor = target.partition("#")
        dest = (page.parent / path_part).resolve() if path_part else page
        where = f"{page.relative_to(ROOT)}:{line}: {target}"
        try:
            rel = dest.relative_to(ROOT)
        except ValueError:
            problems.append(f"{where}: outside the repository")
            continue
        if not dest.exists():
            problems.append(f"{where}: {rel} does not exist")
            continue
        if anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            problems.append(f"{where}: no heading with the anchor #{anchor} in {rel}")
    assert problems == [], "\n".join(problems)


# ---------------------------------------------------------------- the rules themselves

def test_markers_are_well_formed():
    problems = [p for page in pages() for p in blocks_of(page)[1]]
    assert problems == []


def test_the_pages_have_blocks_of_every_kind():
    langs = {b.lang for b in ALL_BLOCKS}
    assert {"sh", "yaml", "python"} <= langs, langs
    assert any(not b.parse_only for b in of_langs(SHELL_LANGS))
    assert any(is_scene(parsed_or_none(b)) for b in of_langs({"yaml"}))
    assert any(is_case(parsed_or_none(b)) for b in of_langs({"yaml"}))


def test_the_binary_is_built():
    for name in BINARIES:
        need_binary(name)


def test_the_checks_can_fail(tmp_path):
    """The helpers catch what they are for: a missing path, an unknown program, a bad link, a
    stray marker."""
    assert path_resolves("verification/scenes/paper-{elastic,plastic}.yaml")
    assert not path_resolves("verification/scenes/paper-{elastic,nothing}.yaml")
    assert not path_resolves("scripts/no-such-script.sh")
    assert repository_paths('--out out/x "./python[dask]" $HOME/scripts') == ["./python"]
    assert program_problem(["impcat", "simulate"]) is not None
    assert program_problem(["scripts/nothing.sh"]) is not None
    assert program_problem(["X=1", "scripts/main-job.sh"]) is None
    assert commands("a --x 1 \\\n  --y 2 # note\n(cd b && c d) | e\n") == [
        ["a", "--x", "1", "--y", "2"], ["cd", "b"], ["c", "d"], ["e"]]
    assert slug("3. Physics options") == "3-physics-options"
    assert slug("Surface contact of the rigid nose (`load.impactor.contact: surface`)") == \
        "surface-contact-of-the-rigid-nose-loadimpactorcontact-surface"
    page = tmp_path / "p.md"
    page.write_text(f"# T\n\n{MARKER}\n\ntext\n\n<!-- snippet: parseonly -->\n```sh\nls\n```\n"
                    f"[x](nowhere.md) [y](#t) [z](#u)\n")
    blocks, problems = blocks_of(page)
    assert len(problems) == 2 and not blocks[0].parse_only
    assert links_of(page) == [(11, "nowhere.md"), (11, "#t"), (11, "#u")]
    assert anchors(page) == {"t"}
