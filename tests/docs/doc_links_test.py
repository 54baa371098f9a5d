#!/usr/bin/env python3
"""Every relative link in README.md and docs/**/*.md names a file or folder of the tree.

Usage: doc_links_test.py SOURCE_DIR. Exit 1 listing each broken link (file:line: target).
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1]).resolve()
pages = [root / "README.md", root / "BENCHMARKS.md", *sorted((root / "docs").rglob("*.md"))]
link = re.compile(r"\]\(([^)\s]+)\)")
broken = []
for page in pages:
    in_code = False
    for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
        if line.startswith("```"):
            in_code = not in_code
        if in_code:
            continue
        for target in link.findall(line):
            if re.match(r"^[a-z]+://", target) or target.startswith("mailto:"):
                continue
            path = target.split("#", 1)[0]
            if not path:
                broken.append(f"{page.relative_to(root)}:{number}: {target} (a link within the page; "
                              "pages are short, link the page)")
                continue
            if not (page.parent / path).exists():
                broken.append(f"{page.relative_to(root)}:{number}: {target}")
if broken:
    print("broken links:\n  " + "\n  ".join(broken))
    sys.exit(1)
print(f"{len(pages)} pages, every relative link resolves")
