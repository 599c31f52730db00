"""The documentation travels with the code.

- The Sphinx site in docs/ builds with warnings as errors (broken links, anchors and references, a
  docstring that does not parse, a CLI command without a reference entry all fail it).
- Every ```python block of the site and of README.md runs, page by page, in a fresh folder: blocks of
  one page share one process, in order. A block may be left out only with a reason, by the line
  ``<!-- docs-test skip: REASON -->`` right before it; ``<!-- docs-test setup: COMMAND -->`` runs a
  shell command in that folder before the page's blocks (e.g. a small ``fricgen run`` whose outputs
  a block reads).
- Every ``fricgen CMD --flag`` written in the docs names a command and flags that exist.
- Every pointer into docs/physics.md from the code names a section that exists.
- The built pages load nothing from the network (math renders offline), every tutorial page shows its
  figures (the notebooks' outputs of the ``executed_notebooks`` fixture), and every internal link and
  anchor resolves.
"""

import os
import re
import subprocess
import sys
import time
import zlib
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = sorted(p for p in DOCS.rglob("*.md") if "_build" not in p.parts)
FENCE = re.compile(r"^(`{3,})(\S*)[^\n]*\n(.*?)^\1[ \t]*$", re.MULTILINE | re.DOTALL)
SKIP = re.compile(r"<!-- docs-test skip: (.+?) -->\s*$")
SETUP = re.compile(r"<!-- docs-test setup: (.+?) -->")
ROLE = re.compile(r"\{(func|class|mod|meth|attr|data|exc)\}`~?([^`<]+?)(?:\s*<~?([^>]+)>)?`")


def _anchor(heading: str) -> str:
    """GitHub's anchor of a markdown heading: lower case, punctuation dropped, spaces as hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def _fences(text: str) -> list[tuple[str, str, str]]:
    """(language, code, the text before the fence) of each fenced block."""
    return [(m.group(2), m.group(3), text[: m.start()]) for m in FENCE.finditer(text)]


def _python_blocks(path: Path) -> tuple[list[str], list[str], list[str]]:
    """The page's runnable python blocks, its skipped blocks' reasons, and its setup commands."""
    text = path.read_text()
    run, skipped = [], []
    for language, code, before in _fences(text):
        if language != "python":
            continue
        lines = before.rstrip("\n").splitlines()
        marker = SKIP.search(lines[-1]) if lines else None
        (skipped.append(marker.group(1)) if marker else run.append(code))
    return run, skipped, SETUP.findall(text)


EXAMPLE_PAGES = [p for p in [*PAGES, ROOT / "README.md"] if _python_blocks(p)[0]]


@pytest.fixture(scope="module")
def site(tmp_path_factory, executed_notebooks):
    """The site built once (warnings as errors), its tutorials from the session's executed notebooks."""
    html = tmp_path_factory.mktemp("site") / "html"
    env = {**os.environ, "MPLBACKEND": "Agg", "FRICGEN_DOCS_NOTEBOOK_CACHE": str(executed_notebooks.cache)}
    start = time.perf_counter()
    build = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", "-q", str(DOCS), str(html)],
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
    )
    print(f"docs build: {time.perf_counter() - start:.0f} s")
    return build, html


def test_the_site_builds_without_warnings(site):
    build, html = site
    assert build.returncode == 0, build.stderr[-6000:]
    pages = {p.relative_to(html).as_posix() for p in html.rglob("*.html")}
    assert {"index.html", "guide/cli.html", "physics.html", "tutorials/define_a_friction_law.html", "api/langevin.html"} <= pages
    # Python references of the pages ({func}`fricgen.x`) name objects the API reference documents
    # (Sphinx only warns about those in nitpicky mode, which the code's internal docstrings would not pass).
    documented = _inventory(html / "objects.inv")
    assert {"fricgen.langevin.Simulation", "fricgen.kernels.load_law_kernels", "fricgen.derive.derive_noise"} <= documented
    for path in PAGES:
        for match in ROLE.finditer(path.read_text()):
            target = (match.group(3) or match.group(2)).strip()
            assert target in documented, f"{path.relative_to(ROOT)}: {match.group(0)} is not in the API reference"


class _Page(HTMLParser):
    """The ids, links, loaded resources and output images of an HTML page."""

    def __init__(self):
        super().__init__()
        self.ids, self.links, self.loads, self.figures, self.outputs = set(), [], [], [], 0
        self._in_output = 0

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self.ids.update(attrs[key] for key in ("id", "name") if attrs.get(key) and (key == "id" or tag == "a"))
        if tag == "a" and attrs.get("href"):
            self.links.append(attrs["href"])
        if tag in ("script", "img", "iframe") and attrs.get("src") or tag == "link" and attrs.get("href"):
            self.loads.append(attrs.get("src") or attrs["href"])
        classes = (attrs.get("class") or "").split()
        if tag == "div" and "cell_output" in classes:
            self.outputs += 1
        if tag == "img" and self.outputs:
            self.figures.append(attrs.get("src", ""))


def _pages(html: Path) -> dict[Path, _Page]:
    pages = {}
    for path in html.rglob("*.html"):
        if "_static" in path.parts or "_sources" in path.parts:
            continue
        page = _Page()
        page.feed(path.read_text())
        pages[path] = page
    return pages


def _broken_links(html: Path, pages: dict[Path, _Page]) -> list[str]:
    """Internal links (``page.html#anchor``) whose file or anchor does not exist."""
    broken = []
    for path, page in pages.items():
        for link in page.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith("mailto:"):
                continue
            target = (path.parent / unquote(parts.path)).resolve() if parts.path else path
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                broken.append(f"{path.relative_to(html)}: {link} (no file)")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else _pages_one(target)
                if unquote(parts.fragment) not in ids:
                    broken.append(f"{path.relative_to(html)}: {link} (no anchor)")
    return broken


def _pages_one(path: Path) -> set[str]:
    page = _Page()
    page.feed(path.read_text())
    return page.ids


def test_pages_work_offline_show_their_figures_and_link_right(site):
    _, html = site
    pages = _pages(html)
    assert len(pages) >= 30, len(pages)
    remote = [f"{path.relative_to(html)}: {load}" for path, page in pages.items() for load in page.loads if urlsplit(load).netloc]
    assert not remote, f"pages load from the network: {remote[:10]}"
    assert not [path for path in pages if re.search(r"cdn\.|jsdelivr|unpkg\.com", path.read_text())], "a page names a CDN"
    math = pages[html / "physics-modes.html"]
    assert any("mathjax" in load for load in math.loads), "MathJax is not loaded from _static"
    for notebook in (ROOT / "notebooks").glob("*.ipynb"):
        page = pages[html / "tutorials" / f"{notebook.stem}.html"]
        assert page.outputs >= 2, f"tutorials/{notebook.stem}: {page.outputs} cell outputs"
        assert page.figures and all((html / "tutorials" / src).exists() for src in page.figures), f"tutorials/{notebook.stem}: no figures"
    machine = [path.relative_to(html) for path in pages if str(ROOT) in path.read_text() and "_modules" not in path.parts]
    assert not machine, f"pages show this machine's path {ROOT}: {machine}"
    broken = _broken_links(html, pages)
    assert not broken, f"{len(broken)} broken internal links: {broken[:20]}"


def test_the_link_check_sees_a_broken_anchor(tmp_path):
    (tmp_path / "a.html").write_text('<p id="here"><a href="b.html#there">x</a><a href="#here">y</a><a href="c.html">z</a></p>')
    (tmp_path / "b.html").write_text('<p id="elsewhere"></p>')
    assert _broken_links(tmp_path, _pages(tmp_path)) == ["a.html: b.html#there (no anchor)", "a.html: c.html (no file)"]


def _inventory(path: Path) -> set[str]:
    """The object names in a Sphinx objects.inv (version 2: four header lines, then zlib text)."""
    header, _, body = path.read_bytes().partition(b"zlib.\n")
    assert header.startswith(b"# Sphinx inventory version 2"), header[:40]
    return {line.split(" ", 1)[0] for line in zlib.decompress(body).decode().splitlines() if line}


def test_examples_are_found_and_skips_give_reasons():
    runnable = sum(len(_python_blocks(p)[0]) for p in EXAMPLE_PAGES)
    assert runnable >= 8, runnable
    for path in [*PAGES, ROOT / "README.md"]:
        for reason in _python_blocks(path)[1]:
            assert len(reason.split()) >= 3, f"{path}: a skipped example needs a reason, got {reason!r}"


@pytest.mark.parametrize("path", EXAMPLE_PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_the_examples_of_a_page_run(path, tmp_path):
    blocks, _, setup = _python_blocks(path)
    env = {**os.environ, "MPLBACKEND": "Agg", "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    for command in setup:
        done = subprocess.run(command, shell=True, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, f"setup {command!r}: {done.stderr[-3000:]}"
    script = "\n\n".join(blocks)
    done = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, f"{path.name}:\n{script}\n--- stderr ---\n{done.stderr[-4000:]}"


def _cli():
    """{command: its parser} of the installed ``fricgen`` command (the docs' own extension finds it)."""
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import fricgen_cli
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    return {name: sub for name, (sub, _) in fricgen_cli.subcommands(fricgen_cli._parser_function(None)()).items()}


def _command_lines(text: str) -> list[str]:
    """Command lines that call ``fricgen``: lines of shell and text blocks, and inline code spans."""
    lines = []
    for language, code, _ in _fences(text):
        if language in ("bash", "text", "console", "sh", ""):
            lines += code.replace("\\\n", " ").splitlines()
    lines += re.findall(r"(?<!`)`(fricgen [^`]+)`", text)
    return [line.split(" #")[0] for line in lines if re.search(r"(^|[\s$])fricgen\s", line)]


def test_every_command_and_flag_in_the_docs_exists():
    commands = _cli()
    checked = 0
    for path in [*PAGES, ROOT / "README.md"]:
        for line in _command_lines(path.read_text()):
            for call in re.split(r"(?:^|[\s$;&|(])fricgen\s+", line)[1:]:
                name = call.split()[0].removesuffix(":") if call.split() else ""  # "fricgen run: ..." is an error message
                if name.startswith("-") or name.isupper():  # fricgen --help, fricgen CMD --help
                    continue
                assert name in commands, f"{path.name}: `fricgen {name}` is no command ({line.strip()})"
                known = {flag for action in commands[name]._actions for flag in action.option_strings}
                for flag in re.findall(r"(?<![\w-])--[A-Za-z][\w-]*", call):
                    assert flag in known, f"{path.name}: `fricgen {name}` has no flag {flag} ({line.strip()})"
                    checked += 1
    assert checked >= 40, checked


def test_every_path_of_the_repository_named_in_the_docs_exists():
    """`derive/law/expressions.py`, `tests/lammps`, ... in the docs name files and folders that exist
    (placeholders such as `generated/laws/<law>.py` or `generated/lammps/LAW` are left out)."""
    named = 0
    for path in [*PAGES, ROOT / "README.md"]:
        for name in re.findall(r"`((?:derive|fricgen|generated|tests|benchmarks|notebooks|docs)/[\w./-]*)`", path.read_text()):
            if any(part.isupper() for part in name.split("/")) or name.startswith("docs/_build"):  # generated/lammps/LAW, build output
                continue
            named += 1
            assert (ROOT / name.rstrip("/")).exists(), f"{path.relative_to(ROOT)} names {name}, which does not exist"
    assert named >= 30, named


def test_readme_keeps_the_two_commands_that_ci_runs():
    readme = (ROOT / "README.md").read_text()
    ci = (ROOT / ".ci" / "run").read_text()
    assert 'python3 -m venv .venv && . .venv/bin/activate && pip install -e ".[test]" && fricgen demo' in readme
    assert "\npython -m pytest\n" in readme
    assert 'pip install -e ".[test]"' in ci and "\nfricgen demo\n" in ci and "\npython -m pytest\n" in ci
    assert len(readme.splitlines()) <= 160


def test_every_pointer_into_the_physics_notes_exists():
    notes = (ROOT / "docs" / "physics.md").read_text()
    anchors = {_anchor(line.lstrip("#")) for line in notes.splitlines() if line.startswith("#")}
    sources = [*ROOT.glob("fricgen/**/*.py"), *ROOT.glob("derive/**/*.py"), *ROOT.glob("tests/**/*.py"), ROOT / "README.md"]
    cited = {}
    for path in sources:
        text = path.read_text()
        for match in re.finditer(r"docs/physics\.md((?:#[\w-]+)?(?:(?: and|,) #[\w-]+)*)", text):
            for anchor in re.findall(r"#([\w-]+)", match.group(1)):
                cited.setdefault(anchor, path.relative_to(ROOT))
    assert len(cited) >= 8, cited
    missing = {anchor: str(path) for anchor, path in cited.items() if anchor not in anchors}
    assert not missing, missing


def test_no_pointer_to_a_file_users_do_not_have():
    for path in [*ROOT.glob("fricgen/**/*.py"), *ROOT.glob("derive/**/*.py"), ROOT / "README.md", *PAGES]:
        assert "PHYSICS.md" not in path.read_text(), path
