#!/usr/bin/env python3
"""Check every internal link of a built documentation site (mkdocs build -d SITE).

MkDocs 1.4 --strict checks links between pages, but neither anchors (#section) nor links to
other files (pictures, downloads). This reads every HTML file of SITE and checks each relative
href/src: the file it names exists inside SITE and, for a #fragment, that file has an element
with that id (or an <a name>). It also refuses http(s) scripts, stylesheets and images: the
site must work offline. Plain python3 (standard library).

    tools/check_site_links.py SITE      exit 0: all links resolve; exit 1: one line per broken link
"""
import html.parser
import os
import sys
import urllib.parse


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids, self.links, self.remote = set(), [], []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and "name" in a:
            self.ids.add(a["name"])
        for key in ("href", "src"):
            v = a.get(key)
            if v is None:
                continue
            if urllib.parse.urlsplit(v).scheme in ("http", "https") or v.startswith("//"):
                if tag in ("script", "img") or (tag == "link" and "stylesheet" in (a.get("rel") or "")):
                    self.remote.append(v)
                continue
            self.links.append((tag, v))


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit("usage: check_site_links.py SITE_DIR")
    site = os.path.realpath(sys.argv[1])
    pages = {}
    for root, _, files in os.walk(site):
        for f in files:
            # 404.html is the web server's error page: MkDocs writes its links from the site's
            # root (/css/...), to be served at any missing URL; it is not part of the site's tree.
            if f.endswith(".html") and not (root == site and f == "404.html"):
                path = os.path.join(root, f)
                p = Page()
                with open(path, encoding="utf-8") as fh:
                    p.feed(fh.read())
                pages[path] = p
    if not pages:
        sys.exit(f"check_site_links: no HTML files in {site}")
    broken, checked = [], 0
    for path, p in sorted(pages.items()):
        rel = os.path.relpath(path, site)
        for v in p.remote:
            broken.append(f"{rel}: loads {v} from the network (the site must work offline)")
        for tag, v in p.links:
            u = urllib.parse.urlsplit(v)
            if u.scheme in ("mailto", "javascript", "data") or u.scheme:
                continue
            checked += 1
            target = path if not u.path else os.path.realpath(
                os.path.join(os.path.dirname(path), urllib.parse.unquote(u.path)))
            if os.path.isdir(target):
                target = os.path.join(target, "index.html")
            if not (target == site or target.startswith(site + os.sep)):
                broken.append(f"{rel}: <{tag}> {v} points outside the site")
                continue
            if not os.path.isfile(target):
                broken.append(f"{rel}: <{tag}> {v}: {os.path.relpath(target, site)} does not exist")
                continue
            frag = urllib.parse.unquote(u.fragment)
            if frag and target.endswith(".html") and frag not in pages[target].ids:
                broken.append(f"{rel}: <{tag}> {v}: no id '{frag}' in {os.path.relpath(target, site)}")
    for b in broken:
        print("check_site_links: " + b)
    if broken:
        sys.exit(1)
    print(f"check_site_links: {checked} internal links in {len(pages)} pages resolve")


if __name__ == "__main__":
    main()
