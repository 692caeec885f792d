#!/usr/bin/env python3
"""Fetches the sources the browser build compiles that Debian ships only as source packages
(Dear ImGui, Qhull, meshoptimizer: their binary packages hold libraries built for this machine,
not for WebAssembly), from the same Debian archive and release the machine installs from.

    python3 web/fetch_sources.py DEST

apt does the fetching, through a private configuration: a sources list in DEST with one
`deb-src` line made from the machine's own `deb` entry for its release (read from
/etc/apt/sources.list and /etc/apt/sources.list.d/ now, never written), and package lists and
caches in DEST. apt checks each file against the archive's signed index. The machine's apt
configuration and state are not touched, and no root is needed. The upstream tarballs are then
unpacked into DEST (imgui-1.86/, qhull-2020.2/, meshoptimizer-0.18/). Run again, it does nothing.
"""
import glob
import os
import shutil
import subprocess
import sys
import tarfile

PACKAGES = {  # source package: the folder its upstream tarball unpacks to (web/CMakeLists.txt)
    "imgui": "imgui-1.86",
    "qhull": "qhull-2020.2",
    "meshoptimizer": "meshoptimizer-0.18",
}


def fail(message):
    print(f"fetch_sources.py: {message}", file=sys.stderr)
    sys.exit(1)


def release_codename():
    with open("/etc/os-release") as f:
        for line in f:
            if line.startswith("VERSION_CODENAME="):
                return line.split("=", 1)[1].strip().strip('"')
    fail("/etc/os-release names no VERSION_CODENAME: not a Debian release?")


def deb_entries():
    """(uris, suites, components, signed_by) of every enabled `deb` entry of the machine."""
    entries = []
    one_line = ["/etc/apt/sources.list"] + sorted(glob.glob("/etc/apt/sources.list.d/*.list"))
    for path in one_line:
        if not os.path.exists(path):
            continue
        with open(path) as f:
            for line in f:
                words = line.split("#", 1)[0].split()
                if not words or words[0] != "deb":
                    continue
                words = words[1:]
                signed_by = None
                if words and words[0].startswith("["):  # [key=value ...]
                    options = []
                    while words:
                        word = words.pop(0)
                        options.append(word.strip("[]"))
                        if word.endswith("]"):
                            break
                    for option in options:
                        if option.startswith("signed-by="):
                            signed_by = option.split("=", 1)[1]
                if len(words) >= 3:
                    entries.append(([words[0]], [words[1]], words[2:], signed_by))
    for path in sorted(glob.glob("/etc/apt/sources.list.d/*.sources")):
        with open(path) as f:
            stanzas = f.read().split("\n\n")
        for stanza in stanzas:
            fields, key = {}, None
            for line in stanza.splitlines():
                if line.startswith("#") or not line.strip():
                    continue
                if line[0] in " \t" and key:  # a continued field
                    fields[key] += " " + line.strip()
                    continue
                key, _, value = line.partition(":")
                key = key.strip().lower()
                fields[key] = value.strip()
            if "deb" not in fields.get("types", "").split() or fields.get("enabled", "yes").lower() == "no":
                continue
            entries.append((fields.get("uris", "").split(), fields.get("suites", "").split(),
                            fields.get("components", "").split(), fields.get("signed-by")))
    return entries


def source_line():
    codename = release_codename()
    for uris, suites, components, signed_by in deb_entries():
        if codename in suites and "main" in components and uris:
            options = f"[signed-by={signed_by}] " if signed_by and not signed_by.startswith("-----") else ""
            return f"deb-src {options}{uris[0]} {codename} main\n"
    fail(f"no 'deb' entry for {codename} main in /etc/apt/sources.list or /etc/apt/sources.list.d/")


def main():
    if len(sys.argv) != 2:
        fail("usage: fetch_sources.py DEST")
    dest = os.path.abspath(sys.argv[1])
    if all(os.path.isdir(os.path.join(dest, folder)) for folder in PACKAGES.values()):
        return 0
    if not shutil.which("apt-get"):
        fail("apt-get is needed (a Debian machine)")
    apt_dir = os.path.join(dest, "apt")
    downloads = os.path.join(dest, "downloads")
    for folder in (os.path.join(apt_dir, "lists", "partial"), os.path.join(apt_dir, "cache", "archives", "partial"), downloads):
        os.makedirs(folder, exist_ok=True)
    sources_list = os.path.join(apt_dir, "sources.list")
    with open(sources_list, "w") as f:
        f.write(source_line())
    options = ["-o", f"Dir::Etc::SourceList={sources_list}", "-o", "Dir::Etc::SourceParts=/dev/null",
               "-o", f"Dir::State::Lists={os.path.join(apt_dir, 'lists')}",
               "-o", f"Dir::Cache={os.path.join(apt_dir, 'cache')}"]
    if os.geteuid() == 0:
        options += ["-o", "APT::Sandbox::User=root"]  # the folders are root's, not apt's own user's
    print(f"fetch_sources.py: {open(sources_list).read().strip()}", flush=True)
    for command in (["update"], ["source", "--download-only", *PACKAGES]):
        result = subprocess.run(["apt-get", "-q", *options, *command], cwd=downloads)
        if result.returncode != 0:
            fail(f"apt-get {command[0]} failed (exit {result.returncode}); is Debian's archive reachable?")
    for package, folder in PACKAGES.items():
        tarballs = glob.glob(os.path.join(downloads, f"{package}_*.orig.tar.*"))
        if len(tarballs) != 1:
            fail(f"expected one upstream tarball of {package} in {downloads}, found {len(tarballs)}")
        with tarfile.open(tarballs[0]) as tar:
            if hasattr(tarfile, "data_filter"):
                tar.extractall(dest, filter="data")  # nothing outside dest, no devices or odd modes
            else:
                tar.extractall(dest)
        if not os.path.isdir(os.path.join(dest, folder)):
            fail(f"{os.path.basename(tarballs[0])} did not unpack to {folder} (another version? see web/CMakeLists.txt)")
        print(f"fetch_sources.py: {os.path.basename(tarballs[0])} -> {os.path.join(dest, folder)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
