#!/usr/bin/env python3
"""Checks the relative links of the documentation: README.md and docs/*.md.

Every relative link target (Markdown `[text](target)`, `![alt](target)`, reference definitions
`[id]: target`, and HTML `href="..."` / `src="..."`) must name a file or folder that exists,
relative to the page that links it. A `#anchor` (alone, or after a .md target) must be a heading
of that page, spelled as GitHub spells heading anchors. Links with a scheme (https:, mailto:)
are not followed. Text in fenced code blocks and inline code is not read.

usage: check_doc_links.py [--root DIR] [PAGE.md ...]    exit 0: all resolve, 1: broken links
       check_doc_links.py --self-test                    checks that a broken link is caught
"""
import argparse
import os
import re
import sys
import tempfile

INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEFINITION = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
HTML_LINK = re.compile(r"""\b(?:href|src)\s*=\s*["']([^"']+)["']""")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")
INLINE_CODE = re.compile(r"(`+)(?:(?!\1).)+?\1")
HTML_COMMENT = re.compile(r"<!--.*?-->", re.S)
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")


def prose_lines(text):
    """(line number, line) outside fenced code blocks, inline code spans and HTML comments
    (which are not rendered) blanked."""
    text = HTML_COMMENT.sub(lambda m: "\n" * m.group(0).count("\n"), text)
    fence = None
    for number, line in enumerate(text.splitlines(), 1):
        opening = FENCE.match(line)
        if fence:
            if opening and opening.group(1) == fence:
                fence = None
            continue
        if opening:
            fence = opening.group(1)
            continue
        yield number, INLINE_CODE.sub(lambda m: " " * len(m.group(0)), line)


def slug(heading):
    """The anchor GitHub gives a heading: markup dropped, lower case, punctuation removed
    (letters, digits, '_', '-' and spaces kept), spaces turned into hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links: their text
    text = re.sub(r"<[^>]+>", "", text)  # HTML tags
    text = text.replace("`", "").lower()
    text = "".join(c for c in text if c.isalnum() or c in "_- ")
    return text.replace(" ", "-")


ANCHOR_CACHE = {}


def anchors(path):
    """Every heading anchor of a Markdown page (repeated headings get -1, -2, ...)."""
    cache = ANCHOR_CACHE
    if path not in cache:
        seen = {}
        found = set()
        with open(path, encoding="utf-8") as page:
            text = page.read()
        fence = None
        for line in text.splitlines():
            opening = FENCE.match(line)
            if fence:
                fence = None if opening and opening.group(1) == fence else fence
                continue
            if opening:
                fence = opening.group(1)
                continue
            heading = HEADING.match(line)
            if not heading:
                continue
            base = slug(heading.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
        cache[path] = found
    return cache[path]


def link_targets(text):
    """(line number, target) of every link on a page."""
    for number, line in prose_lines(text):
        for pattern in (INLINE_LINK, HTML_LINK):
            for match in pattern.finditer(line):
                yield number, match.group(1)
        definition = REFERENCE_DEFINITION.match(line)
        if definition:
            yield number, definition.group(1)


def check_page(page):
    """Messages for the broken links of one page."""
    problems = []
    with open(page, encoding="utf-8") as source:
        text = source.read()
    for number, target in link_targets(text):
        if SCHEME.match(target) or target.startswith("//"):
            continue  # https:, mailto: and the like: not checked here
        path_part, _, anchor = target.partition("#")
        path_part = path_part.split("?", 1)[0]
        resolved = os.path.normpath(os.path.join(os.path.dirname(page), path_part)) \
            if path_part else page
        where = f"{page}:{number}: {target}"
        if not os.path.exists(resolved):
            problems.append(f"{where}: no such file {resolved}")
            continue
        if anchor and resolved.endswith(".md") and os.path.isfile(resolved):
            if anchor.lower() not in anchors(resolved):
                problems.append(f"{where}: no heading #{anchor} in {resolved}")
    return problems


def default_pages(root):
    pages = [os.path.join(root, "README.md")]
    docs = os.path.join(root, "docs")
    if os.path.isdir(docs):
        pages += sorted(os.path.join(docs, name) for name in os.listdir(docs)
                        if name.endswith(".md"))
    return [page for page in pages if os.path.isfile(page)]


def check(pages):
    problems = []
    for page in pages:
        problems += check_page(page)
    for problem in problems:
        print(problem, file=sys.stderr)
    print(f"{len(pages)} pages, {len(problems)} broken links")
    return 1 if problems else 0


def self_test():
    """A page with good links passes; the same page with one broken link or anchor fails."""
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "docs"))
        with open(os.path.join(root, "docs", "guide.md"), "w", encoding="utf-8") as page:
            page.write("# The guide\n\n## Run it: `drvslam run`\n\n```\n[x](missing.md)\n```\n")
        good = ("# Title\n\nSee [the guide](docs/guide.md#run-it-drvslam-run), "
                "[top](#title), `[not a link](nowhere.md)` and [web](https://example.org/x).\n"
                "<!-- not rendered:\n![later](docs/images/later.png) -->\n")
        cases = [(good, 0),
                 (good + "\n![picture](docs/images/missing.png)\n", 1),
                 (good + "\n[anchor](docs/guide.md#no-such-heading)\n", 1),
                 (good + "\n[ref]: docs/absent.md\n", 1)]
        for text, expected in cases:
            with open(os.path.join(root, "README.md"), "w", encoding="utf-8") as readme:
                readme.write(text)
            ANCHOR_CACHE.clear()
            status = check(default_pages(root))
            if status != expected:
                print(f"self-test: expected exit {expected}, got {status} for:\n{text}",
                      file=sys.stderr)
                return 1
    print("self-test: broken links are caught")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pages", nargs="*", help="pages to check (default: README.md, docs/*.md)")
    parser.add_argument("--root", default=os.path.join(os.path.dirname(__file__), ".."),
                        help="the checkout (default: this script's parent folder)")
    parser.add_argument("--self-test", action="store_true",
                        help="check that broken links and anchors are reported")
    args = parser.parse_args()
    if args.self_test:
        return self_test()
    return check(args.pages or default_pages(os.path.normpath(args.root)))


if __name__ == "__main__":
    sys.exit(main())
