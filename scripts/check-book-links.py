#!/usr/bin/env python3
"""Offline link check of the built book: every relative href/src of every page names a file of the book
and, with a #fragment, an id on that page. Links to other sites are not fetched.

Usage: check-book-links.py BOOK_HTML_DIR
"""
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit


class Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids = set()
        self.links = []

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if name in ("id", "name") and value:
                self.ids.add(value)
            if name in ("href", "src") and value:
                self.links.append((tag, value))


def main(root: Path) -> int:
    pages = {}
    for path in root.rglob("*.html"):
        page = Page()
        page.feed(path.read_text(encoding="utf-8"))
        pages[path.resolve()] = page
    broken = []
    for path, page in pages.items():
        if path.name == "404.html":  # its links start at the site's root (site-url)
            continue
        for tag, link in page.links:
            parts = urlsplit(link)
            if parts.scheme or link.startswith("//"):
                continue
            target = path if not parts.path else (path.parent / unquote(parts.path)).resolve()
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                broken.append(f"{path.relative_to(root.resolve())}: {link} (no such file)")
                continue
            if parts.fragment and target.suffix == ".html" and target.name != "print.html":
                if unquote(parts.fragment) not in pages[target].ids:
                    broken.append(f"{path.relative_to(root.resolve())}: {link} (no such anchor)")
    for line in sorted(set(broken)):
        print(line)
    checked = sum(len(p.links) for p in pages.values())
    print(f"check-book-links: {len(pages)} pages, {checked} links, {len(set(broken))} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
