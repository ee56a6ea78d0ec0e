#!/usr/bin/python3
"""Every equation label cited in the code's comments (E1–E21, G1–G7,
A1–A10, and ranges such as E16–E18) is defined in docs/model.md, as
**LABEL** (or, for a section, ## §N). Exit status 1 lists the missing ones."""
import os
import re
import sys

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
model = open(os.path.join(root, "docs", "model.md")).read()
defined = set(re.findall(r"\*\*([EGA]\d+[a-c]?)\*\*", model))
defined |= set(re.findall(r"^## (§\d)", model, re.M))
# A label is a letter and a number at a word boundary, in a comment
label = re.compile(r"(?<![\w.])([EGA])(\d{1,2})([a-c]?)(?:\s*[–-]\s*\1?(\d{1,2}))?(?![\w.])")
section = re.compile(r"docs/model\.md\s*((?:§\d(?:,\s*)?)+)")
comment = {".cpp": "//", ".h": "//", ".py": "#", ".txt": "#", ".sh": "#"}
missing = {}
for folder in ("src", "forms", "demos", "tests"):
    for dirpath, _, files in os.walk(os.path.join(root, folder)):
        for name in files:
            ext = os.path.splitext(name)[1]
            if ext not in comment:
                continue
            path = os.path.join(dirpath, name)
            for n, line in enumerate(open(path, encoding="utf-8"), 1):
                i = line.find(comment[ext])
                if i < 0:
                    continue
                text = line[i:]
                cited = []
                for m in label.finditer(text):
                    kind, a, suffix, b = m.groups()
                    if kind == "E" or "docs/model.md" in text or kind + a in defined:
                        last = int(b) if b else int(a)
                        if kind != "E" and not (1 <= int(a) <= 9):
                            continue
                        cited += [f"{kind}{k}" for k in range(int(a), last + 1)]
                        if suffix:
                            cited[-1] += suffix
                for m in section.finditer(text):
                    cited += re.findall(r"§\d", m.group(1))
                for c in cited:
                    if c not in defined and c.rstrip("abc") not in defined:
                        missing.setdefault(c, []).append(f"{os.path.relpath(path, root)}:{n}")
for c, where in sorted(missing.items()):
    print(f"{c}: not defined in docs/model.md (cited in {', '.join(where[:3])})")
print(f"{len(defined)} labels defined, {len(missing)} cited but undefined")
sys.exit(1 if missing else 0)
