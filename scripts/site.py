#!/usr/bin/env python3
"""Assemble and check the documentation site (scripts/docs calls it).

    site.py SITE SAMPLAB_BINARY

SITE already holds report/ (samplab reproduce) and atlas/ (samplab atlas). This adds:
the guide and performance pages (docs/*.md through Python-Markdown), one page per CLI
command (its --help), the Python API reference (pdoc, numpy docstring style), the Rust API
(target/doc, from cargo doc), docs/img; then runs every example of the Python docstrings as
a doctest and checks the whole site: every local link and anchor resolves, every image
exists and decodes, and every sampler of the registry has an atlas page. Prints each
problem and exits 1 if there is any.
"""
import doctest
import html
import html.parser
import pathlib
import re
import shutil
import struct
import subprocess
import sys

import markdown
import pdoc
import pdoc.render

ROOT = pathlib.Path(__file__).resolve().parent.parent
STYLE = """body{font-family:system-ui,sans-serif;max-width:980px;margin:2em auto;padding:0 1em;color:#222;line-height:1.5}
h1,h2,h3{line-height:1.2}table{border-collapse:collapse;margin:.8em 0;font-size:.92em}
th,td{border:1px solid #ccc;padding:.3em .6em}th{background:#f3f3f3}
code{background:#f3f3f3;padding:0 .2em}pre{background:#f6f6f6;padding:.6em;overflow-x:auto}
pre code{background:none;padding:0}img{max-width:100%}nav{margin-bottom:1em}nav a{margin-right:1em}
"""
NAV = [
    ("index.html", "home"),
    ("guide/install.html", "install"),
    ("guide/concepts.html", "concepts"),
    ("guide/cli.html", "CLI"),
    ("guide/python.html", "Python"),
    ("atlas/index.html", "atlas"),
    ("report/index.html", "report"),
    ("performance.html", "performance"),
    ("cli/index.html", "CLI reference"),
    ("python/samplab.html", "Python API"),
    ("rust/samplab/index.html", "Rust API"),
]


def page(title, body, depth):
    up = "../" * depth
    nav = "".join(f'<a href="{up}{href}">{name}</a>' for href, name in NAV)
    return (
        f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>'
        f'<link rel="stylesheet" href="{up}site.css"></head>\n<body><nav>{nav}</nav>\n{body}</body></html>\n'
    )


def guide(site):
    """docs/**/*.md -> SITE/**/*.html, links to .md pages made links to .html."""
    for md in sorted((ROOT / "docs").rglob("*.md")):
        rel = md.relative_to(ROOT / "docs")
        text = md.read_text()
        text = re.sub(r"\]\(([^)#]+)\.md(#[^)]*)?\)", lambda m: f"]({m.group(1)}.html{m.group(2) or ''})", text)
        body = markdown.markdown(text, extensions=["tables", "fenced_code", "toc"])
        title = text.splitlines()[0].lstrip("# ").strip()
        out = site / rel.with_suffix(".html")
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(page(title, body, len(rel.parts) - 1))
    shutil.copytree(ROOT / "docs/img", site / "img", dirs_exist_ok=True)
    (site / "site.css").write_text(STYLE)


def cli_pages(site, binary):
    """One page per command, from its --help; an index of them from the top-level help."""
    top = subprocess.run([binary, "--help"], capture_output=True, text=True, check=True).stdout
    commands = re.findall(r"^  ([a-z][a-z-]+)  ", top.split("Commands:")[1].split("Options:")[0], re.M)
    commands = [c for c in commands if c != "help"]
    (site / "cli").mkdir(exist_ok=True)
    items = ""
    for c in commands:
        text = subprocess.run([binary, c, "--help"], capture_output=True, text=True, check=True).stdout
        first = text.splitlines()[0]
        body = f"<h1>samplab {c}</h1>\n<p>{html.escape(first)}</p>\n<pre>{html.escape(text)}</pre>\n"
        (site / "cli" / f"{c}.html").write_text(page(f"samplab {c}", body, 1))
        items += f'<li><a href="{c}.html"><code>samplab {c}</code></a>: {html.escape(first)}</li>\n'
    body = f"<h1>The command line</h1>\n<pre>{html.escape(top)}</pre>\n<ul>\n{items}</ul>\n"
    (site / "cli" / "index.html").write_text(page("samplab: the command line", body, 1))
    return commands


def python_api(site):
    import samplab

    pdoc.render.configure(docformat="numpy", footer_text="samplab")
    pdoc.pdoc("samplab", "samplab.qmc", "samplab.study", output_directory=site / "python")
    return samplab


def doctests(samplab):
    """Every example of the package's docstrings, run; returns the failures."""
    import numpy

    finder, runner = doctest.DocTestFinder(), doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    modules = [samplab, samplab.qmc, samplab.study]
    seen, tests = set(), []
    for module in modules:
        for name in getattr(module, "__all__", dir(module)):
            obj = getattr(module, name, None)
            if not (getattr(obj, "__module__", None) or "").startswith("samplab"):
                continue
            if obj is None or id(obj) in seen or not (getattr(obj, "__doc__", None) or "").count(">>>"):
                continue
            seen.add(id(obj))
            tests += finder.find(obj, f"{module.__name__}.{name}", globs={"samplab": samplab, "np": numpy})
    for t in tests:
        runner.run(t)
    result = runner.summarize(verbose=False)
    print(f"doctests: {result.attempted} examples in {len(tests)} docstrings, {result.failed} failed")
    return result.failed


class Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.images, self.ids = [], [], set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and a.get("name"):
            self.ids.add(a["name"])
        if tag == "a" and a.get("href"):
            self.links.append(a["href"])
        if tag == "img" and a.get("src") is not None:
            self.images.append(a["src"])
        if tag == "link" and a.get("href") and a.get("rel") == "stylesheet":
            self.links.append(a["href"])


def image_ok(path):
    data = path.read_bytes() if path.is_file() else b""
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        w, h = struct.unpack(">II", data[16:24])
        return w > 0 and h > 0
    return data.lstrip().startswith(b"<svg") or data.lstrip().startswith(b"<?xml")


def check(site, binary):
    """Every problem of the site (rustdoc's own pages apart: cargo doc checks its links)."""
    problems, parsed = [], {}
    pages = [p for p in site.rglob("*.html") if not p.relative_to(site).parts[0] == "rust"]

    def parse(p):
        if p not in parsed:
            links = Links()
            links.feed(p.read_text(errors="replace"))
            parsed[p] = links
        return parsed[p]

    for p in pages:
        links = parse(p)
        for href in links.links:
            if re.match(r"^[a-z]+:", href) or href.startswith("//"):
                continue
            target, _, anchor = href.partition("#")
            dest = (p.parent / target).resolve() if target else p
            if target.endswith("/"):
                dest = dest / "index.html"
            if not dest.exists():
                problems.append(f"{p.relative_to(site)}: broken link {href}")
            elif anchor and dest.suffix == ".html" and dest.is_relative_to(site.resolve()) and "rust" not in dest.relative_to(site.resolve()).parts[:1]:
                if anchor not in parse(dest).ids:
                    problems.append(f"{p.relative_to(site)}: no anchor #{anchor} in {target or 'itself'}")
        for src in links.images:
            if src.startswith("data:"):
                continue
            if not image_ok((p.parent / src).resolve()):
                problems.append(f"{p.relative_to(site)}: broken image {src}")
    listing = subprocess.run([binary, "list", "samplers"], capture_output=True, text=True, check=True).stdout
    names = re.findall(r"^([a-z0-9.+-]+)  —", listing, re.M)
    for name in names:
        if not (site / "atlas" / "samplers" / f"{name}.html").is_file():
            problems.append(f"atlas: no page for the sampler entry {name}")
    print(f"site: {len(pages)} pages checked, {len(names)} sampler entries in the atlas")
    return problems


def main():
    site, binary = pathlib.Path(sys.argv[1]), sys.argv[2]
    rustdoc = pathlib.Path(sys.argv[3]) if len(sys.argv) > 3 else ROOT / "target/doc"
    guide(site)
    commands = cli_pages(site, binary)
    samplab = python_api(site)
    shutil.copytree(rustdoc, site / "rust", dirs_exist_ok=True)
    failed = doctests(samplab)
    problems = check(site, binary)
    for p in problems:
        print(p)
    print(f"{len(commands)} command pages; {len(problems)} problems; {failed} failed doctests")
    sys.exit(1 if problems or failed else 0)


if __name__ == "__main__":
    main()
