"""A tutorial case copied to a scratch directory, run through pmshFoam and
the real OpenFOAM binaries, with readers for what they wrote.

Used by the end-to-end tests in this folder; each test builds one or more
cases, runs them and asserts on OpenFOAM's verdict and on the mesh files.
"""

import os
import re
import shutil
import struct
import subprocess
import tempfile

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TUTORIALS = os.path.join(SOURCE_DIR, "tutorials")


def openfoam_environment():
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env.setdefault("OMPI_MCA_btl", "self,vader")
    env["PMSH_PROJECT_DIR"] = SOURCE_DIR
    return env


class TutorialCase:
    """A fresh copy of tutorials/<name> in a temporary directory."""

    def __init__(self, name, **entries):
        self.name = name
        self.root = tempfile.mkdtemp(prefix="pmshFoam-%s-" % name)
        self.dir = os.path.join(self.root, name)
        shutil.copytree(os.path.join(TUTORIALS, name), self.dir,
                        ignore=shutil.ignore_patterns(
                            "processor*", "log.*", "polyMesh", "postProcessing",
                            "decomposeParDict", "[1-9]*", ".*"))
        self.pmshFoam = os.environ.get("PMSH_BINARY") or shutil.which("pmshFoam")
        if not self.pmshFoam:
            raise RuntimeError("pmshFoam binary not found (PMSH_BINARY or PATH)")
        for key, value in entries.items():
            self.set_entry("system/pmshDict", key, value)

    def cleanup(self):
        shutil.rmtree(self.root, ignore_errors=True)

    # -- dictionaries -----------------------------------------------------

    def set_entry(self, dict_file, key, value):
        """Set (or add) a top-level 'key value;' entry of a dictionary."""
        path = os.path.join(self.dir, dict_file)
        with open(path) as f:
            text = f.read()
        entry = "%s %s;" % (key, value)
        pattern = re.compile(r"^%s\s+[^;]*;" % re.escape(key), re.M)
        if pattern.search(text):
            text = pattern.sub(entry, text, count=1)
        else:
            text += "\n" + entry + "\n"
        with open(path, "w") as f:
            f.write(text)

    def write_format(self, fmt):
        self.set_entry("system/controlDict", "writeFormat", fmt)

    # -- running ----------------------------------------------------------

    def run(self, *command, np=1, log=None, check=True, env=None, timeout=1800):
        """Run an OpenFOAM-style application on the case (in parallel when
        np > 1) with its output in log.<app>; returns (exit code, log)."""
        app = command[0]
        argv = [self.pmshFoam if app == "pmshFoam" else app] + list(command[1:])
        argv += ["-case", self.dir]
        if np > 1:
            argv = ["mpirun", "--oversubscribe", "-np", str(np)] + argv + ["-parallel"]
        environment = openfoam_environment()
        environment.update(env or {})
        proc = subprocess.run(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, env=environment,
                              cwd=self.dir, timeout=timeout)
        text = proc.stdout.decode(errors="replace")
        with open(os.path.join(self.dir, log or "log." + app), "w") as f:
            f.write(text)
        if check and proc.returncode != 0:
            raise AssertionError("%s failed with exit code %d:\n%s"
                                 % (" ".join(argv), proc.returncode, text[-4000:]))
        return proc.returncode, text

    def run_allrun(self, *args, timeout=1100):
        """The tutorial's own Allrun (with its arguments), this pmshFoam
        first on the PATH; returns (exit code, output)."""
        env = openfoam_environment()
        env["PATH"] = os.path.dirname(self.pmshFoam) + ":" + env["PATH"]
        proc = subprocess.run([os.path.join(self.dir, "Allrun")] + list(args),
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, env=env, timeout=timeout)
        return proc.returncode, proc.stdout.decode(errors="replace")

    def check_mesh(self, np=1):
        """Run checkMesh; fail unless it says 'Mesh OK'. Returns the log."""
        _, text = self.run("checkMesh", np=np)
        if not re.search(r"^Mesh OK", text, re.M):
            problems = "\n".join(l for l in text.splitlines()
                                 if "***" in l or "FATAL" in l or "Failed" in l)
            raise AssertionError("checkMesh did not say 'Mesh OK' for %s:\n%s"
                                 % (self.dir, problems or text[-3000:]))
        return text

    # -- reading results --------------------------------------------------

    def exists(self, relative):
        return os.path.exists(os.path.join(self.dir, relative))

    def polymesh(self, location="constant/polyMesh"):
        return PolyMeshFiles(os.path.join(self.dir, location))


def cells_in_checkmesh_log(text):
    m = re.search(r"^\s*cells:\s+(\d+)", text, re.M)
    if not m:
        raise AssertionError("no cell count in checkMesh output")
    return int(m.group(1))


class PolyMeshFiles:
    """Reads points, faces, owner and boundary of a polyMesh (ascii or binary)."""

    def __init__(self, directory):
        self.directory = directory

    def _read(self, name):
        with open(os.path.join(self.directory, name), "rb") as f:
            data = f.read()
        header_end = data.index(b"}", data.index(b"FoamFile")) + 1
        header = data[:header_end].decode()
        binary = re.search(r"format\s+binary", header) is not None
        arch = re.search(r"label=(\d+)", header)
        label_bytes = int(arch.group(1)) // 8 if arch else 4
        cls = re.search(r"class\s+(\w+)", header).group(1)
        return data[header_end:], binary, label_bytes, cls

    @staticmethod
    def _strip_comments(body):
        body = re.sub(rb"/\*.*?\*/", b"", body, flags=re.S)
        return re.sub(rb"//[^\n]*", b"", body)

    def _list(self, body, binary, item_bytes, fmt, parse_ascii, offset=0):
        """Read one list at byte offset; returns (items, end offset)."""
        # OpenFOAM's writers put a "// * * *" line between header and data
        m = re.compile(rb"(?:\s*//[^\n]*\n)*\s*(\d+)\s*").match(body, offset)
        n = int(m.group(1))
        pos = m.end()
        if binary:
            if n == 0:
                return [], pos
            assert body[pos:pos + 1] == b"("
            raw = body[pos + 1:pos + 1 + n * item_bytes]
            items = [struct.unpack_from(fmt, raw, i * item_bytes) for i in range(n)]
            return items, pos + 1 + n * item_bytes + 1
        depth, i = 0, pos
        while True:
            c = body[i:i + 1]
            if c == b"(":
                depth += 1
            elif c == b")":
                depth -= 1
                if depth == 0:
                    break
            i += 1
        return parse_ascii(body[pos:i + 1].decode(), n), i + 1

    def points(self):
        body, binary, _, _ = self._read("points")
        if not binary:
            body = self._strip_comments(body)
        def parse(text, n):
            return [tuple(float(x) for x in t.split())
                    for t in re.findall(r"\(([^()]+)\)", text[1:-1])]
        return self._list(body, binary, 24, "<3d", parse)[0]

    def faces(self):
        body, binary, lb, cls = self._read("faces")
        lfmt = "<q" if lb == 8 else "<i"
        if binary and cls == "faceCompactList":
            offsets, end = self._list(body, True, lb, lfmt, None)
            labels, _ = self._list(body, True, lb, lfmt, None, end)
            offsets = [o[0] for o in offsets]
            labels = [l[0] for l in labels]
            return [labels[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]
        body = self._strip_comments(body)
        def parse(text, n):
            return [[int(x) for x in t.split()]
                    for t in re.findall(r"\d+\(([^()]*)\)", text[1:-1])]
        return self._list(body, False, 0, None, parse)[0]

    def labels(self, name):
        """A labelList file (owner, neighbour, *ProcAddressing)."""
        body, binary, lb, _ = self._read(name)
        if not binary:
            body = self._strip_comments(body)
        def parse(text, n):
            return [int(x) for x in text[1:-1].split()]
        items, _ = self._list(body, binary, lb, "<q" if lb == 8 else "<i", parse)
        return [i[0] if isinstance(i, tuple) else i for i in items]

    def boundary(self):
        """[(name, dict of entries)] from the (always ascii) boundary file."""
        body, _, _, _ = self._read("boundary")
        body = self._strip_comments(body).decode()
        patches = []
        for name, content in re.findall(r"(\w+)\s*\{([^}]*)\}", body):
            entries = dict(re.findall(r"(\w+)\s+([^;]+);", content))
            patches.append((name, entries))
        return patches

    def boundary_points(self):
        """Indices of the points used by boundary faces."""
        faces = self.faces()
        used = set()
        for name, entries in self.boundary():
            start, n = int(entries["startFace"]), int(entries["nFaces"])
            for f in faces[start:start + n]:
                used.update(f)
        return used
