# SPDX-License-Identifier: Apache-2.0
"""Every documented status of the public API has a test, and every test names a documented one.

Parses every doc block (/** ... */) of firmware/include/uvms/*.h that precedes a function
declaration, collects its `@retval UVMS_<STATUS>` lines (one status per line, cFE style) keyed by
that function, and compares the (function, status) pairs with the Catch2 test cases of
tests/firmware/test_api_status.cpp named "<function> returns <STATUS>" (optionally followed by
": <detail>", so one pair may have several cases).

Fails (exit 1), printing each offending pair, when
  - a documented pair has no test case (missing),
  - a test case names a pair that is not documented (stale or misspelt),
  - an @retval line does not start with a status enumerator of uvms_status_t (types.h),
  - a status appears twice in one doc block, or
  - a function declared to return uvms_status_t has no @retval line at all.

A pair that no input can reach (a defensive branch) may be declared in the test file with a line
  // API-STATUS-UNTESTABLE: <function> <STATUS>: <reason>
It must still be documented; it is listed on every run, so it never hides silently.

Usage: check_api_retval.py [--include-dir DIR] [--test-file FILE]"""
import argparse
import pathlib
import re
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent

DOC_BLOCK = re.compile(r"/\*\*(.*?)\*/", re.S)
# The declaration right after a doc block: return type, then the function name and "(".
DECL = re.compile(r"\s*(?:const\s+)?[A-Za-z_][A-Za-z0-9_]*\s*\**\s*(uvms_[A-Za-z0-9_]+)\s*\(")
RETVAL = re.compile(r"@retval\s+(\S+)")
STATUS_DECL = re.compile(r"\buvms_status_t\s+(uvms_[A-Za-z0-9_]+)\s*\(")
TEST_NAME = re.compile(r'TEST_CASE\(\s*"(uvms_[A-Za-z0-9_]+) returns (UVMS_[A-Z0-9_]+)(?::[^"]*)?"')
UNTESTABLE = re.compile(r"//\s*API-STATUS-UNTESTABLE:\s*(uvms_[A-Za-z0-9_]+)\s+(UVMS_[A-Z0-9_]+)")


def status_names(types_h):
    """The enumerators of uvms_status_t, read from types.h (the one source)."""
    text = types_h.read_text(encoding="utf-8")
    m = re.search(r"typedef enum \{(.*?)\}\s*uvms_status_t;", text, re.S)
    if not m:
        raise SystemExit(f"{types_h}: uvms_status_t not found")
    return set(re.findall(r"\b(UVMS_(?:OK|ERR_[A-Z_]+))\s*=", m.group(1)))


def documented_pairs(include_dir, statuses, errors):
    """{(function, status): 'header:line'} from every @retval of every header."""
    pairs = {}
    status_functions = set()
    documented_functions = set()
    for header in sorted(include_dir.glob("*.h")):
        text = header.read_text(encoding="utf-8")
        status_functions.update(STATUS_DECL.findall(text))
        for block in DOC_BLOCK.finditer(text):
            decl = DECL.match(text, block.end())
            if not decl:
                continue  # a doc comment of a type, macro or field
            func = decl.group(1)
            seen = set()
            for rv in RETVAL.finditer(block.group(1)):
                line = text.count("\n", 0, block.start(1) + rv.start()) + 1
                where = f"{header.name}:{line}"
                token = rv.group(1).rstrip(",;.:")
                if token not in statuses:
                    errors.append(f"{where}: @retval of {func} does not start with a status "
                                  f"enumerator: '{rv.group(1)}' (one status per @retval line)")
                    continue
                if token in seen:
                    errors.append(f"{where}: {func} documents {token} twice")
                seen.add(token)
                pairs[(func, token)] = where
                documented_functions.add(func)
    for func in sorted(status_functions - documented_functions):
        errors.append(f"{func} returns uvms_status_t but has no @retval line")
    return pairs


def tested_pairs(test_file):
    text = test_file.read_text(encoding="utf-8")
    tested = {}
    for m in TEST_NAME.finditer(text):
        tested.setdefault((m.group(1), m.group(2)), text.count("\n", 0, m.start()) + 1)
    untestable = {}
    for m in UNTESTABLE.finditer(text):
        untestable[(m.group(1), m.group(2))] = text.count("\n", 0, m.start()) + 1
    return tested, untestable


def main():
    ap = argparse.ArgumentParser(
        description="Check that every (function, status) pair documented by an @retval line "
                    "in the public headers has a test case in test_api_status.cpp, and that "
                    "every such test case names a documented pair.")
    ap.add_argument("--include-dir", type=pathlib.Path,
                    default=ROOT / "firmware" / "include" / "uvms",
                    help="directory of the public headers (default: %(default)s)")
    ap.add_argument("--test-file", type=pathlib.Path, default=HERE / "test_api_status.cpp",
                    help="the Catch2 test file (default: %(default)s)")
    args = ap.parse_args()

    errors = []
    statuses = status_names(args.include_dir / "types.h")
    documented = documented_pairs(args.include_dir, statuses, errors)
    tested, untestable = tested_pairs(args.test_file)

    missing = sorted(p for p in documented if p not in tested and p not in untestable)
    stale = sorted(p for p in tested if p not in documented)
    stale_untestable = sorted(p for p in untestable if p not in documented)
    both = sorted(p for p in untestable if p in tested)

    for func, st in missing:
        errors.append(f"MISSING test: {func} returns {st} (documented at "
                      f"{documented[(func, st)]}) has no TEST_CASE \"{func} returns {st}\"")
    for func, st in stale:
        errors.append(f"UNDOCUMENTED: {args.test_file.name}:{tested[(func, st)]} tests "
                      f"{func} returns {st}, which no @retval of {func} documents")
    for func, st in stale_untestable:
        errors.append(f"UNDOCUMENTED: {args.test_file.name}:{untestable[(func, st)]} declares "
                      f"{func} {st} untestable, but it is not documented")
    for func, st in both:
        errors.append(f"{func} {st} is both tested and declared untestable")

    n_funcs = len({f for f, _ in documented})
    print(f"{len(documented)} documented (function, status) pairs in {n_funcs} functions; "
          f"{len(tested)} tested, {len(untestable)} declared untestable")
    for func, st in sorted(untestable):
        if (func, st) in documented:
            print(f"  untestable (declared): {func} {st}")
    if errors:
        for e in errors:
            print(e)
        print(f"FAILED: {len(errors)} problem(s), {len(missing)} missing pair(s)")
        return 1
    print("OK: every documented status has a test case and every test case is documented")
    return 0


if __name__ == "__main__":
    sys.exit(main())
