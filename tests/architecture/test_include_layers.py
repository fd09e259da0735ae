#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The C/C++ include graph follows the layers of docs/ARCHITECTURE.md.

Every quoted #include of every C/C++ file under firmware/, plant/ and sil/ is resolved to the
folder it names, and checked against the table below:
  - firmware/ includes only firmware/ (its own headers, "uvms/..." and the generated
    "uvms/config.h"); its CMake files add no include directory outside firmware/;
  - plant/ includes only plant/ ("uvms_plant/...");
  - each sil/ folder includes only the folders its row allows (sil/ depends on the firmware, the
    plant and the generated LCM types; nothing below includes sil/).
A file or folder missing from the table fails too, so a new folder gets a row on purpose.
The checker first proves itself on a scratch tree with one arrow of each kind added back
(a test that cannot fail is a defect). Usage: test_include_layers.py SOURCE_DIR
"""
import os
import re
import sys
import tempfile

# Who may include whom. Keys and values are folders relative to the repository root; the
# longest key that prefixes a file's folder is its row. "lcm" stands for the generated LCM C
# and C++ types (uvms_*_t.h, uvms/*_t.hpp), "generated" the build's git-commit header, and
# <lcm/...> is a system include, not checked.
LAYERS = {
    "firmware": {"firmware"},
    "plant": {"plant"},
    "sil/msg": {"sil/msg", "firmware", "lcm", "generated"},
    "sil/link": {"sil/link", "sil/msg", "firmware", "lcm"},
    "sil/scenario": {"sil/scenario", "sil/msg", "firmware", "plant", "lcm"},
    "sil/run": {"sil/run", "sil/link", "sil/scenario", "sil/msg", "firmware", "plant", "lcm",
                "generated"},
    "sil/campaign": {"sil/campaign", "sil/run", "sil/scenario", "sil/msg", "firmware", "plant",
                     "lcm"},
    "sil/pil": {"sil/pil", "sil/link", "sil/msg", "firmware", "lcm"},
    "sil/pil/target": {"sil/pil", "sil/msg", "firmware"},
    "sil/cli": {"sil/cli", "sil/campaign", "sil/run", "sil/scenario", "sil/link", "sil/msg",
                "sil/pil", "firmware", "plant", "lcm"},
}
ROOTS = ("firmware", "plant", "sil")
SOURCE_EXT = (".c", ".h", ".cpp", ".hpp", ".inc")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
SIL_FOLDERS = ("msg", "link", "scenario", "run", "campaign", "pil", "cli")


def row_of(folder):
    """The table row of a folder: the longest key that is the folder or one of its parents."""
    best = None
    for key in LAYERS:
        if folder == key or folder.startswith(key + "/"):
            if best is None or len(key) > len(best):
                best = key
    return best


def target_of(src, file_dir, name):
    """The folder an include names: a sibling file, a folder-qualified sil/ header, a firmware
    or plant header, a generated LCM type; None when it names nothing known."""
    if os.path.isfile(os.path.join(src, file_dir, name)):
        return os.path.normpath(os.path.join(file_dir, os.path.dirname(name)))
    first = name.split("/")[0]
    if first in SIL_FOLDERS and os.path.isfile(os.path.join(src, "sil", name)):
        return os.path.normpath(os.path.join("sil", os.path.dirname(name)))
    if first == "uvms" and (os.path.isfile(os.path.join(src, "firmware", "include", name))
                            or name == "uvms/config.h"):
        return "firmware"
    if first == "uvms_m4f" and os.path.isfile(os.path.join(src, "firmware", "target", "include",
                                                          name)):
        return "firmware"  # the Cortex-M4F images' headers (uvms_add_m4f_image)
    if first == "uvms_plant" and os.path.isfile(os.path.join(src, "plant", "include", name)):
        return "plant"
    if re.fullmatch(r"uvms_\w+_t\.h|uvms/\w+_t\.hpp", name):
        return "lcm"
    if name == "uvms_git_commit.h":  # written at build time by sil/CMakeLists.txt
        return "generated"
    return None


def sources(src):
    for root in ROOTS:
        for dirpath, _, files in os.walk(os.path.join(src, root)):
            for f in sorted(files):
                if f.endswith(SOURCE_EXT):
                    yield os.path.relpath(os.path.join(dirpath, f), src)


def check_includes(src):
    """One message per include that breaks the table (or names nothing known)."""
    errors = []
    for rel in sources(src):
        folder = os.path.dirname(rel)
        row = row_of(folder)
        if row is None:
            errors.append(f"{rel}: folder {folder} has no row in the layer table")
            continue
        text = open(os.path.join(src, rel), encoding="utf-8").read()
        for m in INCLUDE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            target = target_of(src, folder, m.group(1))
            if target is None:
                errors.append(f'{rel}:{line}: #include "{m.group(1)}" names no file of the tree')
            elif row_of(target) not in LAYERS[row] and target not in LAYERS[row]:
                errors.append(f'{rel}:{line}: #include "{m.group(1)}": {row} may not include '
                              f"{row_of(target) or target}")
    return errors


def check_firmware_cmake(src):
    """firmware/'s CMake files add no include directory outside firmware/."""
    errors = []
    for dirpath, _, files in os.walk(os.path.join(src, "firmware")):
        for f in files:
            if f != "CMakeLists.txt" and not f.endswith(".cmake"):
                continue
            rel = os.path.relpath(os.path.join(dirpath, f), src)
            text = open(os.path.join(src, rel), encoding="utf-8").read()
            for m in re.finditer(r"include_directories\s*\(([^)]*)\)", text):
                for word in m.group(1).split():
                    if re.search(r"PROJECT_SOURCE_DIR\}/(?!firmware)|\.\./", word):
                        errors.append(f"{rel}: include directory {word} is outside firmware/")
    return errors


def write(root, rel, text):
    path = os.path.join(root, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def self_test():
    """The checker finds each kind of wrong arrow in a scratch tree, and passes a clean one."""
    with tempfile.TemporaryDirectory() as tmp:
        write(tmp, "firmware/include/uvms/controller.h", "")
        write(tmp, "firmware/src/controller.c", '#include "uvms/controller.h"\n')
        write(tmp, "firmware/CMakeLists.txt", "target_include_directories(x PUBLIC include)\n")
        write(tmp, "plant/include/uvms_plant/plant.hpp", "")
        write(tmp, "sil/msg/codec.h", '#include "uvms/controller.h"\n#include "uvms_sensors_t.h"\n')
        write(tmp, "sil/run/plant_node.hpp", '#include "msg/codec.h"\n#include "uvms_plant/plant.hpp"\n')
        write(tmp, "sil/cli/run_cmd.cpp", '#include "run/plant_node.hpp"\n')
        clean = check_includes(tmp) + check_firmware_cmake(tmp)
        if clean:
            return ["self-test: a clean tree was refused: " + "; ".join(clean)]
        arrows = {
            "firmware/src/pil.c": '#include "pil/pil_protocol.h"\n',   # firmware -> sil
            "sil/msg/bad.c": '#include "run/plant_node.hpp"\n',        # msg -> run (upward)
            "plant/src/bad.cpp": '#include "uvms/controller.h"\n',     # plant -> firmware
            "sil/newfolder/x.c": "",                                   # a folder with no row
        }
        write(tmp, "sil/pil/pil_protocol.h", "")
        misses = []
        for rel, text in arrows.items():
            write(tmp, rel, text)
            if not any(e.startswith(rel) for e in check_includes(tmp)):
                misses.append(rel)
            os.remove(os.path.join(tmp, rel))
        write(tmp, "firmware/target/CMakeLists.txt",
              "target_include_directories(x PRIVATE ${PROJECT_SOURCE_DIR}/sil)\n")
        if not check_firmware_cmake(tmp):
            misses.append("firmware/target/CMakeLists.txt (include dir into sil/)")
        return [f"self-test: the arrow added in {m} was not found" for m in misses]


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    src = argv[1]
    errors = self_test() + check_includes(src) + check_firmware_cmake(src)
    for e in errors:
        print("FAIL:", e)
    n = sum(1 for _ in sources(src))
    print(f"{n} files checked against {len(LAYERS)} layer rows: {len(errors)} problem(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
