# SPDX-License-Identifier: Apache-2.0
"""cmake/git_commit.cmake (the build-time commit behind summary.json's git_commit) in scratch
repositories: "unknown" outside a checkout and in a directory below another repository's top;
the HEAD commit of a clean tree; "-dirty" for a modified tracked file and for an untracked one,
not for an ignored one; a new commit shows up on the next run (no re-configure needed); an
unchanged result leaves the header file untouched (nothing recompiles).

Usage: test_git_commit_script.py CMAKE_EXE SCRIPT
"""
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

CMAKE, SCRIPT = sys.argv[1], sys.argv[2]
TMP = scratch_dir("uvms-git-commit-")  # removed at exit (tests/support/scratch.py)
HEADER = os.path.join(TMP, "out", "uvms_git_commit.h")


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def git(repo, *args):
    return subprocess.run(["git", "-C", repo, "-c", "user.name=t", "-c", "user.email=t@example.org",
                           "-c", "commit.gpgsign=false", *args],
                          capture_output=True, text=True, check=True).stdout.strip()


def commit_of(source_dir):
    subprocess.run([CMAKE, f"-DSOURCE_DIR={source_dir}", f"-DOUTPUT={HEADER}",
                    "-DGIT_EXECUTABLE=git", "-P", SCRIPT], check=True)
    with open(HEADER) as f:
        m = re.search(r'#define UVMS_GIT_COMMIT "([^"]*)"', f.read())
    if not m:
        fail(f"{HEADER} has no UVMS_GIT_COMMIT")
    return m.group(1)


def expect(source_dir, want, what):
    got = commit_of(source_dir)
    print(f"{what}: {got}")
    if got != want:
        fail(f"{what}: got {got!r}, expected {want!r}")


plain = os.path.join(TMP, "plain")
os.makedirs(plain)
expect(plain, "unknown", "not a checkout")

repo = os.path.join(TMP, "repo")
os.makedirs(os.path.join(repo, "sub"))
git(repo, "init", "-q")
with open(os.path.join(repo, "a.txt"), "w") as f:
    f.write("one\n")
with open(os.path.join(repo, ".gitignore"), "w") as f:
    f.write("/build/\n")
git(repo, "add", "a.txt", ".gitignore")
git(repo, "commit", "-q", "-m", "first")
first = git(repo, "rev-parse", "HEAD")
expect(repo, first, "clean checkout")
stamp = os.stat(HEADER).st_mtime_ns
os.utime(HEADER, ns=(stamp - 10**9, stamp - 10**9))  # one second back: a rewrite would show
expect(repo, first, "clean checkout again")
if os.stat(HEADER).st_mtime_ns != stamp - 10**9:
    fail("an unchanged commit rewrote the header (everything including it would recompile)")

expect(os.path.join(repo, "sub"), "unknown", "a directory below another repository's top")

os.makedirs(os.path.join(repo, "build"))
with open(os.path.join(repo, "build", "x.o"), "w") as f:
    f.write("ignored\n")
expect(repo, first, "ignored file only")
with open(os.path.join(repo, "new.txt"), "w") as f:
    f.write("untracked\n")
expect(repo, first + "-dirty", "untracked file")
os.remove(os.path.join(repo, "new.txt"))
with open(os.path.join(repo, "a.txt"), "w") as f:
    f.write("two\n")
expect(repo, first + "-dirty", "modified tracked file")

git(repo, "commit", "-q", "-am", "second")
second = git(repo, "rev-parse", "HEAD")
if second == first:
    fail("the scratch commit did not change HEAD")
expect(repo, second, "after a new commit, without re-configuring")
print("PASS")
