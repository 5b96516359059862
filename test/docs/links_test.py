#!/usr/bin/env python3
"""Every relative link in README.md and docs/*.md reaches a file, and its
#anchor a heading or an id="..." in it (GitHub's heading slugs), so that
moving a section cannot leave a reference dangling.

usage: links_test.py REPO_ROOT   (exit 0: all reach, 1: some do not)
"""
import os
import re
import sys
import tempfile


def heading_slug(heading):
    """GitHub's anchor for a heading: tags dropped, lower case, punctuation
    other than - and _ removed, spaces to -."""
    text = re.sub(r"<[^>]+>", "", heading).strip().lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors_of(text):
    found = set(re.findall(r'id="([^"]+)"', text))
    found.update(heading_slug(m.group(1)) for m in re.finditer(r"^#+ (.*)$", text, re.M))
    return found


def broken_links(root):
    """(file, link) for each relative link that does not reach its target."""
    docs = os.path.join(root, "docs")
    files = [os.path.join(root, "README.md")]
    files += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    texts = {os.path.normpath(f): open(f, encoding="utf-8").read() for f in files}
    broken = []
    for path, text in texts.items():
        text = re.sub(r"```.*?```", "", text, flags=re.S)  # code blocks hold no links
        for link in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", link):
                continue  # http:, mailto: ...
            target, _, anchor = link.partition("#")
            target = os.path.normpath(os.path.join(os.path.dirname(path), target)) if target else path
            if not os.path.exists(target):
                broken.append((path, link))
            elif anchor and target.endswith(".md"):
                if target not in texts:
                    texts[target] = open(target, encoding="utf-8").read()
                if anchor not in anchors_of(texts[target]):
                    broken.append((path, link))
    return broken


def self_check():
    """The checker itself finds a missing file and a missing anchor, and
    accepts a heading's slug and an explicit id."""
    with tempfile.TemporaryDirectory() as root:
        os.mkdir(os.path.join(root, "docs"))
        with open(os.path.join(root, "README.md"), "w") as f:
            f.write("[a](docs/a.md#the-heading-tried-round-2) [b](docs/a.md#kept) [c](docs/gone.md) [d](docs/a.md#nope)\n")
        with open(os.path.join(root, "docs", "a.md"), "w") as f:
            f.write('# A\n\n## The heading: tried, round 2\n\n<a id="kept"></a>text\n')
        found = sorted(link for _, link in broken_links(root))
        assert found == ["docs/a.md#nope", "docs/gone.md"], found


def main():
    self_check()
    broken = broken_links(sys.argv[1])
    for path, link in broken:
        print(f"{path}: link to {link} reaches nothing")
    print(f"{len(broken)} broken links")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
