# SPDX-License-Identifier: Apache-2.0
"""The Python tools as a package (tools/pyproject.toml): one package, tools/uvms_tools, whose
every directory of modules is a declared (sub)package; the command scripts beside it in tools/
are thin (no code of their own) and their targets resolve, as do the entry points; the console
scripts that tools/bootstrap installs into the venv run; and a wheel built from it holds every
module and installs and imports outside the checkout.

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
PACKAGE = "uvms_tools"
FIND = PROJECT["tool"]["setuptools"]["packages"]["find"]
SCRIPTS = PROJECT["project"]["scripts"]
TMP = tempfile.mkdtemp(prefix="uvms-tools-package-")
results = []


def check(ok, what):
    results.append((bool(ok), what))
    print(("ok   " if ok else "FAIL ") + what, flush=True)


def parse(path):
    with open(path, encoding="utf-8") as fh:
        return ast.parse(fh.read())


def defines_functions(tree):
    """A module of the package defines functions; a thin command script (tools/report.py) only
    calls one."""
    return any(isinstance(n, (ast.FunctionDef, ast.ClassDef)) for n in tree.body)


def command_scripts():
    """The Python command scripts of tools/: *.py and the extensionless ones with a python
    shebang (tools/campaign-dask)."""
    out = []
    for p in sorted(glob.glob(os.path.join(TOOLS, "*"))):
        if not os.path.isfile(p) or p.endswith((".toml", ".txt")):
            continue
        with open(p, encoding="utf-8") as fh:
            first = fh.readline()
        if p.endswith(".py") or "python" in first:
            out.append(p)
    return out


def run_tool_target(tree):
    """The "module:function" string a thin script passes to run_tool, or None."""
    for n in ast.walk(tree):
        if (isinstance(n, ast.Call) and getattr(n.func, "id", None) == "run_tool"
                and len(n.args) == 2 and isinstance(n.args[1], ast.Constant)):
            return n.args[1].value
    return None


def module_dirs():
    """Every directory below tools/uvms_tools holding a .py file, as a dotted name."""
    dirs = set()
    for p in glob.glob(os.path.join(TOOLS, PACKAGE, "**", "*.py"), recursive=True):
        dirs.add(os.path.relpath(os.path.dirname(p), TOOLS).replace(os.sep, "."))
    return sorted(dirs)


def check_declarations():
    check(FIND.get("include") == [PACKAGE, PACKAGE + ".*"] and FIND.get("namespaces") is False,
          f"pyproject.toml finds {PACKAGE} and its subpackages, nothing else ({FIND})")
    missing = [d for d in module_dirs()
               if not os.path.exists(os.path.join(TOOLS, *d.split("."), "__init__.py"))]
    check(not missing, f"every directory of modules in tools/{PACKAGE} is a package "
                       f"(__init__.py; else the wheel leaves it out): {missing or 'all'}")


def check_command_scripts():
    import importlib
    sys.path.insert(0, TOOLS)
    for p in command_scripts():
        tree = parse(p)
        name = os.path.relpath(p, SRC)
        target = run_tool_target(tree)
        check(not defines_functions(tree) and target,
              f"{name} is a thin command script: run_tool({target!r}), no code of its own")
        if target:
            module, func = target.split(":")
            obj = getattr(importlib.import_module(module), func, None)
            check(callable(obj), f"{name}'s target {target} resolves to a callable")


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
    modules = sorted(os.path.relpath(p, TOOLS).replace(os.sep, "/") for p in
                     glob.glob(os.path.join(TOOLS, PACKAGE, "**", "*.py"), recursive=True))
    missing = [m for m in modules if m not in names]
    check(modules and not missing,
          f"the wheel holds every module of tools/{PACKAGE} ({len(modules)}): "
          f"missing {missing or 'none'}")
    extra = sorted(n for n in names if n.endswith(".py") and not n.startswith(PACKAGE + "/"))
    check(not extra, f"the wheel holds nothing outside {PACKAGE}/: {extra or 'nothing'}")
    for name, target in SCRIPTS.items():
        check(f"{name} = {target}" in eps, f"the wheel's entry_points.txt names {name}")
    target = os.path.join(TMP, "site")
    p = subprocess.run([sys.executable, "-m", "pip", "install", "--disable-pip-version-check",
                        "--no-deps", "-q", "--target", target, wheel],
                       capture_output=True, text=True, timeout=300)
    check(p.returncode == 0, f"the wheel installs into a directory (exit {p.returncode})")
    code = ("import uvms_tools.env, uvms_tools.log.runlog, uvms_tools.dashboard.page, "
            "uvms_tools.report.cli, uvms_tools.viz.kinematics, uvms_tools.campaign_dask.cli, "
            "uvms_tools.models.thruster_fit; "
            "print(uvms_tools.env.VERSION, uvms_tools.log.runlog.__file__)")
    env = dict(os.environ, PYTHONPATH=target)
    p = subprocess.run([sys.executable, "-c", code], capture_output=True,
                       text=True, timeout=60, cwd=TMP, env=env)
    check(p.returncode == 0 and p.stdout.split()[:1] == [SETUP_VERSION()] and target in p.stdout,
          f"installed outside the checkout it imports, with the project's version: "
          f"{(p.stdout + p.stderr).strip()[-300:]}")


def SETUP_VERSION():
    sys.path.insert(0, TOOLS)
    from uvms_tools import env
    return env.VERSION


def main():
    try:
        check_declarations()
        check_command_scripts()
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
