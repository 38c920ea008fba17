#!/usr/bin/env python3
"""check_vsix.py VSIX SOURCE_DIR: what the packaged VS Code extension holds.

Prints the manifest's identity and the files a working extension needs, and
fails (one line per problem, exit 1) if one is missing, if a packaged file
differs from its source in editors/vscode, if development files (tests,
vsce, the grammar test runner) were packaged, or if a package that
vscode-languageclient requires at run time is not inside."""
import json
import pathlib
import re
import sys
import zipfile

vsix, source = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
problems = []
with zipfile.ZipFile(vsix) as z:
    names = set(z.namelist())
    manifest = json.loads(z.read("extension/package.json"))
    print("manifest: %s.%s %s, main %s" % (manifest["publisher"], manifest["name"],
                                           manifest["version"], manifest["main"]))
    for f in ["extension.vsixmanifest", "extension/package.json",
              "extension/extension.js", "extension/language-configuration.json",
              "extension/syntaxes/bscript.tmLanguage.json", "extension/README.md",
              "extension/node_modules/vscode-languageclient/package.json",
              "extension/node_modules/vscode-languageclient/node.js"]:
        if f in names:
            print("has " + f)
        else:
            problems.append("missing " + f)
    for f in ["package.json", "extension.js", "language-configuration.json",
              "syntaxes/bscript.tmLanguage.json"]:
        packaged = "extension/" + f
        if packaged in names and f != "package.json" and \
                z.read(packaged) != (source / f).read_bytes():
            problems.append(packaged + " differs from the source's " + f)
    # vsce rewrites package.json; its contents must still be the source's.
    if json.loads((source / "package.json").read_text())["contributes"] != manifest["contributes"]:
        problems.append("extension/package.json: contributes differs from the source's")
    client = json.loads(z.read("extension/node_modules/vscode-languageclient/package.json"))
    print("vscode-languageclient " + client["version"])
    if not client["version"].startswith("9."):
        problems.append("vscode-languageclient is %s, not 9.x" % client["version"])

    # Every package a packaged package depends on is packaged, as Node's
    # require would find it: in a node_modules of the package or above.
    packages = set()
    for n in names:
        m = re.fullmatch(r"(.*/node_modules/(?:@[^/]+/)?[^/]+)/package\.json", n)
        if m:
            packages.add(m.group(1))
    for package in sorted(packages | {"extension"}):
        deps = json.loads(z.read(package + "/package.json")).get("dependencies", {})
        for dep in deps:
            where, found = package, False
            while True:
                if (where + "/node_modules/" + dep + "/package.json") in names:
                    found = True
                    break
                if "/node_modules/" not in where:
                    break
                where = where.rsplit("/node_modules/", 1)[0]
            if not found:
                problems.append("%s needs %s, which is not packaged" % (package, dep))
    print("%d packages inside" % len(packages))
    for name in sorted(names):
        if name.startswith("extension/test/") or "/node_modules/@vscode/vsce/" in name \
                or "/node_modules/vscode-tmgrammar-test/" in name or name.endswith(".vsix"):
            problems.append("packaged, but not for users: " + name)
print("%d files, %d bytes" % (len(names), vsix.stat().st_size))
for p in problems:
    print(p)
sys.exit(1 if problems else 0)
