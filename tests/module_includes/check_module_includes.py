#!/usr/bin/env python3
"""Fails when a source file includes a header of a module its own module does not depend on.

Usage: check_module_includes.py MODULES_TXT SOURCE_ROOT [--pretend FILE=MODULE ...]

MODULES_TXT is written by CMakeLists.txt (lfcam_module): one line per module, bottom first,
"name: dependencies | public headers". A file in src/<module>/ belongs to that module, and so
does a public header include/lfcam/<module>/<name>.hpp the module names. Tests, benches, fuzz targets and
tools sit above every module and are not checked. --pretend checks one more file as if it
belonged to MODULE (the suite uses it to show that a leak is caught).
"""
import pathlib
import re
import sys

UMBRELLA = "lfcam/lfcam.hpp"  # every public header, for users: above every module, not checked
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def read_modules(path):
    modules, header_module, problems = {}, {}, []
    for line in pathlib.Path(path).read_text().splitlines():
        if not line.strip():
            continue
        name, rest = line.split(":", 1)
        dependencies, headers = rest.split("|")
        dependencies = dependencies.split()
        for dependency in dependencies:
            if dependency not in modules:
                problems.append(f"module {name} depends on {dependency}, which is not below it")
        modules[name] = set(dependencies)
        for header in headers.split():
            header_module[f"lfcam/{name}/{header}.hpp"] = name
    return modules, header_module, problems


def module_of_include(include, modules, header_module):
    if include in header_module:
        return header_module[include]
    if include == UMBRELLA:
        return None
    first = include.split("/", 1)[0]
    return first if first in modules and "/" in include else None


def check_file(path, module, modules, header_module, root):
    problems = []
    for include in INCLUDE.findall(path.read_text(errors="replace")):
        owner = module_of_include(include, modules, header_module)
        if owner is None and include.startswith("lfcam/") and include != UMBRELLA:
            problems.append(f"{path.relative_to(root)}: includes {include}, which no module names")
        elif owner is not None and owner != module and owner not in modules[module]:
            allowed = " ".join(sorted(modules[module])) or "nothing"
            problems.append(f"{path.relative_to(root)}: includes {include} of module {owner}, "
                            f"but {module} depends only on: {allowed}")
    return problems


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    modules, header_module, problems = read_modules(argv[1])
    root = pathlib.Path(argv[2]).resolve()
    files = []
    for module in modules:
        files += [(p, module) for p in sorted((root / "src" / module).glob("*.[ch]pp"))]
    public = root / "include" / "lfcam"
    for header in sorted(public.rglob("*.hpp")):
        key = "lfcam/" + header.relative_to(public).as_posix()
        if key in header_module:
            files.append((header, header_module[key]))
        elif key != UMBRELLA:
            problems.append(f"include/{key}: a public header that no module names (CMakeLists.txt)")
    for pretend in argv[3:]:
        if pretend == "--pretend":
            continue
        path, module = pretend.rsplit("=", 1)
        files.append((pathlib.Path(path).resolve(), module))
    for path, module in files:
        problems += check_file(path, module, modules, header_module, root if root in path.parents else path.parent)
    for problem in problems:
        print(problem)
    print(f"{len(files)} files of {len(modules)} modules checked: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
