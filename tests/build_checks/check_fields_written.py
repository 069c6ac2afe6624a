"""Every field of the scene descriptions is written by the writer that keys renders by them
(io/scene_state_text.cpp: the scene's state; core/params/parameter_set.cpp: a parameter's
canonical text), or two scenes differing only in a new field would share a render key. Read from
the declarations' source, so it holds on every ABI and cannot miss a field added into padding
(the size checks it replaces could). Source locations (loc, ...Loc) are not part of a state.

Usage: check_fields_written.py SOURCE_DIR"""

import re
import sys
from pathlib import Path

# (header, struct, writer): each struct's fields must be named in its writer as ".field".
CHECKS = [
    ("io/scene_desc.h", s, "io/scene_state_text.cpp")
    for s in ("SettingsDesc", "CameraDesc", "LightDesc", "ObjectDesc", "MediumDesc",
              "NamedSpectrumDesc", "NamedMaterialDesc", "MaterialDesc")
] + [
    ("core/params/scene_values.h", s, "core/params/parameter_set.cpp")
    for s in ("SpectrumDesc", "IorDesc", "FluorescenceDesc", "EemDesc", "CoatingDesc")
] + [("core/params/eem_layout.h", "EemLayout", "core/params/parameter_set.cpp")]


def struct_body(text, name):
    m = re.search(r"\bstruct\s+" + name + r"\b[^;{]*\{", text)
    if not m:
        return None
    depth, i = 1, m.end()
    while depth:
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    return text[m.end():i - 1]


def fields(body):
    """Names of the data members declared at the body's top level."""
    body = re.sub(r"//[^\n]*", "", body)
    # drop nested braces (function bodies, default member initialisers' braces kept as {})
    flat, depth = [], 0
    for c in body:
        if c == "{":
            depth += 1
            flat.append("{" if depth == 1 else "")
        elif c == "}":
            depth -= 1
            flat.append("}" if depth == 0 else "")
        elif depth == 0:
            flat.append(c)
    names = []
    for stmt in "".join(flat).split(";"):
        stmt = " ".join(stmt.split())
        if not stmt or "(" in stmt.split("=")[0] or stmt.startswith(("using ", "static ", "friend ", "enum ", "struct ", "class ")):
            continue
        if re.match(r"^(public|private|protected):", stmt):
            stmt = stmt.split(":", 1)[1].strip()
        stmt = re.sub(r"\{\}$", "", stmt)
        decl = stmt.split("=")[0].strip()
        decl = re.sub(r"<[^<>]*(<[^<>]*>[^<>]*)*>", "<>", decl)  # templates' commas
        for part in decl.split(","):
            words = re.findall(r"[A-Za-z_]\w*", re.sub(r"\{.*", "", part))
            if words:
                names.append(words[-1])
    return names


def main(root, edit=lambda header, text: text):
    root = Path(root)
    failures = counted = 0
    for header, name, writer in CHECKS:
        body = struct_body(edit(header, (root / header).read_text()), name)
        if body is None:
            print(f"FAIL: no struct {name} in {header}")
            failures += 1
            continue
        written = (root / writer).read_text()
        for f in fields(body):
            counted += 1
            if f == "loc" or f.endswith("Loc"):
                continue
            if not re.search(r"\." + f + r"\b", written):
                print(f"FAIL: {name}::{f} ({header}) is not written by {writer}")
                failures += 1
    if failures:
        return 1
    print(f"every field of {len(CHECKS)} descriptions ({counted} fields) is written")
    return 0


def self_test(root):
    """A field added to CameraDesc (after its last one, where padding may hold it) fails."""
    def add(header, text):
        return text.replace("SourceLocation loc, distortionLoc;",
                            "SourceLocation loc, distortionLoc;\n  bool addedField = false;")
    if main(root, add) != 1:
        print("FAIL: an added field went unnoticed")
        return 1
    print("an added field is reported")
    return 0


if __name__ == "__main__":
    if sys.argv[1] == "--self-test":
        sys.exit(self_test(sys.argv[2]))
    sys.exit(main(sys.argv[1]))
