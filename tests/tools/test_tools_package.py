# SPDX-License-Identifier: Apache-2.0
"""The Python tools as a package (tools/pyproject.toml): what it declares is what tools/ holds,
its entry points resolve, the console scripts that tools/bootstrap installs into the venv run,
and a wheel built from it installs and imports outside the checkout.

Usage: test_tools_package.py SOURCE_DIR
Run with the venv's interpreter (tools/bootstrap installed the package into it, editable).
Building the wheel (from a copy of tools/ in a scratch directory) fetches the pinned build
backend (setuptools) from PyPI or pip's cache.
"""
import ast
import glob
import os
import shutil
import subprocess
import sys
import tempfile
import tomllib
import zipfile

SRC = sys.argv[1]
TOOLS = os.path.join(SRC, "tools")
with open(os.path.join(TOOLS, "pyproject.toml"), "rb") as fh:
    PROJECT = tomllib.load(fh)
SETUP = PROJECT["tool"]["setuptools"]
SCRIPTS = PROJECT["project"]["scripts"]
TMP = tempfile.mkdtemp(prefix="uvms-tools-package-")
results = []


def check(ok, what):
    results.append((bool(ok), what))
    print(("ok   " if ok else "FAIL ") + what, flush=True)


def defines_functions(path):
    """A module of the package defines functions; a thin script wrapper (tools/report.py) only
    imports one."""
    with open(path, encoding="utf-8") as fh:
        tree = ast.parse(fh.read())
    return any(isinstance(n, (ast.FunctionDef, ast.ClassDef)) for n in tree.body)


def check_declarations():
    modules = sorted(os.path.basename(p)[:-3] for p in glob.glob(os.path.join(TOOLS, "*.py"))
                     if defines_functions(p))
    check(sorted(SETUP["py-modules"]) == modules,
          f"py-modules {sorted(SETUP['py-modules'])} are tools/*.py with code {modules}")
    packages = sorted(os.path.relpath(os.path.dirname(p), TOOLS).replace(os.sep, ".")
                      for p in glob.glob(os.path.join(TOOLS, "**", "__init__.py"), recursive=True)
                      if "egg-info" not in p and "/build/" not in p)
    check(sorted(SETUP["packages"]) == packages,
          f"packages {sorted(SETUP['packages'])} are the directories with __init__.py {packages}")


def check_entry_points():
    import importlib
    sys.path.insert(0, TOOLS)
    for name, target in sorted(SCRIPTS.items()):
        module, func = target.split(":")
        obj = getattr(importlib.import_module(module), func, None)
        check(callable(obj), f"entry point {name} = {target} resolves to a callable")


def check_console_scripts():
    bindir = os.path.dirname(sys.executable)
    for name in sorted(SCRIPTS):
        exe = os.path.join(bindir, name)
        if not os.path.exists(exe):
            check(False, f"{name} is on the venv's PATH ({exe} missing: run tools/bootstrap)")
            continue
        p = subprocess.run([exe, "--help"], capture_output=True, text=True, timeout=60, cwd=TMP)
        check(p.returncode == 0 and "usage" in p.stdout.lower() and not p.stderr,
              f"{name} --help from outside the checkout: exit {p.returncode}, usage printed")


def source_copy():
    """tools/ and the top-level CMakeLists.txt (the version's source) copied into TMP: building
    writes build/ and *.egg-info beside the sources, which stay out of the checkout this way."""
    root = os.path.join(TMP, "src")
    shutil.copytree(TOOLS, os.path.join(root, "tools"), ignore=shutil.ignore_patterns(
        "build", "*.egg-info", "__pycache__"))
    shutil.copy(os.path.join(SRC, "CMakeLists.txt"), root)
    return os.path.join(root, "tools")


def build_wheel():
    p = subprocess.run([sys.executable, "-m", "pip", "wheel", "--disable-pip-version-check",
                        "--no-deps", "-q", "-w", os.path.join(TMP, "dist"), source_copy()],
                       capture_output=True, text=True, timeout=300)
    wheels = glob.glob(os.path.join(TMP, "dist", "uvms_tools-*.whl"))
    check(p.returncode == 0 and len(wheels) == 1,
          f"pip wheel tools/ builds one wheel (exit {p.returncode}) {p.stderr.strip()[-300:]}")
    return wheels[0] if wheels else None


def check_wheel(wheel):
    with zipfile.ZipFile(wheel) as z:
        names = set(z.namelist())
        eps = next((z.read(n).decode() for n in names if n.endswith("entry_points.txt")), "")
    for m in SETUP["py-modules"]:
        check(f"{m}.py" in names, f"the wheel holds module {m}")
    for pkg in SETUP["packages"]:
        check(pkg.replace(".", "/") + "/__init__.py" in names, f"the wheel holds package {pkg}")
    for name, target in SCRIPTS.items():
        check(f"{name} = {target}" in eps, f"the wheel's entry_points.txt names {name}")
    target = os.path.join(TMP, "site")
    p = subprocess.run([sys.executable, "-m", "pip", "install", "--disable-pip-version-check",
                        "--no-deps", "-q", "--target", target, wheel],
                       capture_output=True, text=True, timeout=300)
    check(p.returncode == 0, f"the wheel installs into a directory (exit {p.returncode})")
    code = ("import toolenv, uvmslog, uvms_report.cli, uvms_viz.kinematics, campaign_dask.cli; "
            "print(toolenv.VERSION, uvmslog.__file__)")
    env = dict(os.environ, PYTHONPATH=target)
    p = subprocess.run([sys.executable, "-c", code], capture_output=True,
                       text=True, timeout=60, cwd=TMP, env=env)
    check(p.returncode == 0 and p.stdout.split()[:1] == [SETUP_VERSION()] and target in p.stdout,
          f"installed outside the checkout it imports, with the project's version: "
          f"{(p.stdout + p.stderr).strip()[-300:]}")


def SETUP_VERSION():
    sys.path.insert(0, TOOLS)
    import toolenv
    return toolenv.VERSION


def main():
    try:
        check_declarations()
        check_entry_points()
        check_console_scripts()
        wheel = build_wheel()
        if wheel:
            check_wheel(wheel)
    finally:
        shutil.rmtree(TMP, ignore_errors=True)
    failed = sum(1 for ok, _ in results if not ok)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
