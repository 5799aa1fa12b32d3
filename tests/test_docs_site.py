"""The guides build into a site strictly (every warning, broken link or reference fails) and the
site loads nothing from the network: no stylesheet, script, font or image from elsewhere."""

from __future__ import annotations

import re
from html.parser import HTMLParser
from pathlib import Path

import pytest
from sphinx.cmd.build import build_main

ROOT = Path(__file__).parents[1]
DOCS = ROOT / "docs"
#: A URL that leaves the site: a scheme with a host, or a protocol-relative one.
_REMOTE = re.compile(r"^\s*(?:[a-z][a-z0-9+.-]*:)?//", re.I)
#: What a page loads (not what it links to: an <a href> elsewhere is fine).
_LOADS = {"link": "href", "script": "src", "img": "src", "iframe": "src", "source": "src", "video": "src",
          "audio": "src", "embed": "src", "object": "data"}
_CSS_URL = re.compile(r"""(?:url\(\s*['"]?|@import\s+['"])([^'")\s]+)""", re.I)


class _Loads(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.urls: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        if tag == "link" and (values.get("rel") or "") not in ("stylesheet", "preload", "icon", "modulepreload"):
            return  # rel=next/prev/index are navigation, not loads
        name = _LOADS.get(tag)
        if name and values.get(name):
            self.urls.append(values[name] or "")


def remote_loads(site: Path) -> list[str]:
    """Every URL elsewhere that a page or stylesheet of the built site loads."""
    found = []
    for page in site.rglob("*.html"):
        parser = _Loads()
        parser.feed(page.read_text(encoding="utf-8"))
        found += [f"{page.name}: {url}" for url in parser.urls if _REMOTE.match(url)]
    for sheet in site.rglob("*.css"):
        found += [f"{sheet.name}: {url}" for url in _CSS_URL.findall(sheet.read_text(encoding="utf-8"))
                  if _REMOTE.match(url)]
    return found


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("site")
    # -W: warnings are errors (broken references, unknown documents, bad headings); -n: nitpicky;
    # -E: no saved environment, every page read again.
    status = build_main(["-W", "-n", "--keep-going", "-E", "-q", "-b", "html", "-d", str(out / "doctrees"),
                         str(DOCS), str(out / "html")])
    assert status == 0, "the docs build failed or warned; see the output above"
    return out / "html"


def test_the_guides_build_strictly_with_every_page(site: Path) -> None:
    pages = {p.stem for p in DOCS.glob("*.md")}
    built = {p.stem for p in site.glob("*.html")}
    assert pages <= built, f"pages not built: {sorted(pages - built)}"


def test_the_site_loads_nothing_from_the_network(site: Path) -> None:
    assert remote_loads(site) == []


def test_a_remote_stylesheet_script_or_font_is_found(tmp_path: Path) -> None:
    # The check itself must see what it looks for.
    (tmp_path / "a.html").write_text('<link rel="stylesheet" href="https://cdn.example/x.css">'
                                     '<script src="//cdn.example/y.js"></script><a href="https://ok.example">x</a>')
    (tmp_path / "b.css").write_text("@font-face { src: url(https://fonts.example/f.woff2) }")
    assert sorted(remote_loads(tmp_path)) == ["a.html: //cdn.example/y.js", "a.html: https://cdn.example/x.css",
                                              "b.css: https://fonts.example/f.woff2"]
