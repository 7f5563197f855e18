#!/usr/bin/env python3
"""Does `pip install ./python` (maturin: the crate impact-python alone) reuse the workspace's
release build? It does when every library unit it needs has the same features in both
resolutions; a dependency with one more feature on one side gets its own build, and with it
every crate above it (the solver, the verification crate: about 3 minutes on 2 cores).

Compares cargo's unit graphs (`--unit-graph`, read with RUSTC_BOOTSTRAP=1; nothing is built)
of `cargo test --workspace --release`, `cargo build --workspace --all-targets --release` and
`cargo build -p impact-python --lib --release`. Prints each differing crate with its features
on both sides and the pin to add to python/Cargo.toml; exits 1 if any differs.
"""
import json
import os
import subprocess
import sys

BUILDS = {
    "cargo test --workspace --release": ["test", "--workspace", "--release", "--no-run"],
    "cargo build --workspace --all-targets --release": ["build", "--workspace", "--all-targets", "--release"],
}
PYTHON_ALONE = ["build", "-p", "impact-python", "--lib", "--release"]


def library_features(args):
    """{package id: set of feature tuples} of the library units `cargo ARGS` would build."""
    env = dict(os.environ, RUSTC_BOOTSTRAP="1")
    out = subprocess.run(["cargo", *args, "--unit-graph", "-Z", "unstable-options"],
                         env=env, check=True, capture_output=True, text=True).stdout
    units = {}
    for unit in json.loads(out)["units"]:
        kinds = unit["target"]["kind"]
        if unit["mode"] != "build" or kinds in (["bin"], ["custom-build"]):
            continue
        units.setdefault(unit["pkg_id"], set()).add(tuple(unit["features"]))
    return units


def main():
    alone = library_features(PYTHON_ALONE)
    differing = 0
    for name, args in BUILDS.items():
        workspace = library_features(args)
        for pkg, features in sorted(alone.items()):
            if workspace.get(pkg) != features:
                differing += 1
                crate = pkg.split("#")[-1]
                print(f"{crate}: {name} builds it with {sorted(workspace.get(pkg, []))}, "
                      f"impact-python alone with {sorted(features)}: pin the missing features "
                      "in python/Cargo.toml")
    if differing:
        print(f"one build: {differing} library units differ; maturin will rebuild them and all above")
        return 1
    print(f"one build: impact-python's {len(alone)} library units are those of the workspace build")
    return 0


if __name__ == "__main__":
    sys.exit(main())
