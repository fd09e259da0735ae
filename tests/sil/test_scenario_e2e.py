#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""End-to-end checks of `uvms scenario check` (the real binary): exit codes, the one-line
summary of a good file, and one error line naming FILE:LINE and the key for a bad one.

usage: test_scenario_e2e.py UVMS_BINARY PAPER_SCENARIO_DIR CASE   (CASE: a key of CASES)
Exit status 0 when the case passes; a message on stderr otherwise.
"""
import os
import subprocess
import sys
import tempfile

PREFIX = "uvms scenario: error: "


class Failure(Exception):
    pass


def expect(cond, message):
    if not cond:
        raise Failure(message)


def run(uvms, args):
    p = subprocess.run([uvms, "scenario"] + args, capture_output=True, text=True, timeout=60)
    return p.returncode, p.stdout, p.stderr


def write_temp(text):
    fd, path = tempfile.mkstemp(suffix=".toml", prefix="scenario_e2e_")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    return path


def expect_error(code, out, err, want_code, *fragments):
    expect(code == want_code, f"exit code {code}, expected {want_code}; stderr: {err!r}")
    expect(out == "", f"stdout not empty: {out!r}")
    lines = err.splitlines()
    expect(len(lines) >= 1 and lines[0].startswith(PREFIX), f"bad error output: {err!r}")
    for f in fragments:
        expect(f in lines[0], f"{f!r} not in {lines[0]!r}")


def case_good(uvms, paper):
    path = os.path.join(paper, "case_VII_unsteady.toml")
    code, out, err = run(uvms, ["check", path])
    expect(code == 0, f"exit code {code}; stderr: {err!r}")
    expect(err == "", f"stderr not empty: {err!r}")
    lines = out.splitlines()
    expect(len(lines) == 1, f"expected one summary line, got {out!r}")
    for f in ["case_VII_unsteady", "case VII", "payload 10 kg", "2000 ticks",
              "flow unsteady", "density error on"]:
        expect(f in lines[0], f"{f!r} not in {lines[0]!r}")


def case_bad_key(uvms, paper):
    path = write_temp('[control]\ncase = "IV"\n\n[run]\nduraton_s = 30\n')  # typo on line 5
    try:
        code, out, err = run(uvms, ["check", path])
        expect_error(code, out, err, 1, f"{path}:5:", 'key "run.duraton_s"', "unknown key")
    finally:
        os.unlink(path)


def case_bad_value(uvms, paper):
    path = write_temp('[control]\ncase = "VII"\nposition_feedback = false\n')
    try:
        code, out, err = run(uvms, ["check", path])
        expect_error(code, out, err, 1, f"{path}:3:", 'key "control.position_feedback"',
                     "contradicts")
    finally:
        os.unlink(path)


def case_set_override(uvms, paper):
    path = os.path.join(paper, "case_IV_stagnant.toml")
    code, out, err = run(uvms, ["check", path, "--set", "run.duration_s=6"])
    expect(code == 0 and "200 ticks" in out, f"override not applied: {code} {out!r} {err!r}")
    code, out, err = run(uvms, ["check", path, "--set", "run.duraton_s=6"])
    expect_error(code, out, err, 1, "--set", 'key "run.duraton_s"')


def case_usage(uvms, paper):
    for args in [[], ["check"], ["verify", "x.toml"], ["check", "--frobnicate", "x.toml"],
                 ["check", "a.toml", "b.toml"], ["check", "a.toml", "--set"]]:
        code, out, err = run(uvms, args)
        expect(code == 2, f"{args}: exit code {code}, expected 2; stderr {err!r}")
        expect(err.startswith(PREFIX) and "usage: uvms scenario" in err, f"{args}: {err!r}")
    code, out, err = run(uvms, ["check", "/nonexistent/x.toml"])
    expect_error(code, out, err, 1, "/nonexistent/x.toml", "cannot read")


def case_help(uvms, paper):
    for args in [["--help"], ["check", "--help"]]:
        code, out, err = run(uvms, args)
        expect(code == 0 and "usage: uvms scenario check FILE" in out and "--set" in out,
               f"{args}: {code} {out!r} {err!r}")


CASES = {name[len("case_"):]: fn for name, fn in globals().items() if name.startswith("case_")}


def main():
    if len(sys.argv) != 4 or sys.argv[3] not in CASES:
        sys.stderr.write(__doc__)
        return 2
    try:
        CASES[sys.argv[3]](sys.argv[1], sys.argv[2])
    except Failure as e:
        sys.stderr.write(f"FAIL {sys.argv[3]}: {e}\n")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
