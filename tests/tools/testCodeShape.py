"""tools/codeShape on small trees: it must fail on each kind of offender
and pass on a tree without any."""

import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.environ.get("PMSH_PROJECT_DIR",
                                   os.path.join(os.path.dirname(__file__), "..", "..")),
                    "tools", "codeShape")


def function(name, bodyLines):
    return (f"int {name}()\n{{\n"
            + "".join(f"    int a{i} = {i};\n" for i in range(bodyLines))
            + "    return 0;\n}\n")


class codeShape(unittest.TestCase):

    def tree(self, files):
        root = tempfile.mkdtemp()
        for path, text in files.items():
            full = os.path.join(root, path)
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w") as f:
                f.write(text)
        return root

    def run_tool(self, files):
        result = subprocess.run([sys.executable, TOOL, self.tree(files)],
                                capture_output=True, text=True)
        return result.returncode, result.stdout

    def test_passesWithoutOffenders(self):
        code, out = self.run_tool({
            "src/core/a.H": '#include "b.H"\n',
            "src/core/b.H": "namespace pmsh\n{\n" + function("f", 100) + "}\n",
            "src/other/c.C": '#include "a.H"\n',
        })
        self.assertEqual(code, 0, out)

    def test_longFileIsAnError(self):
        code, out = self.run_tool({"src/core/long.C": "// line\n" * 801})
        self.assertEqual(code, 1, out)
        self.assertIn("src/core/long.C: 801 lines (limit 800)", out)

    def test_longFunctionIsAnErrorEvenFirstInANamespace(self):
        code, out = self.run_tool({
            "src/core/f.C": "namespace pmsh\n{\n" + function("longOne", 149) + "}\n"})
        self.assertEqual(code, 1, out)
        self.assertIn("function longOne: 153 lines (limit 150)", out)

    def test_folderCycleIsAnError(self):
        code, out = self.run_tool({
            "src/core/a.H": '#include "b.H"\n',
            "src/other/b.H": "",
            "src/other/b.C": '#include "b.H"\n#include "a.H"\n',
        })
        self.assertEqual(code, 1, out)
        self.assertIn("include cycle between folders src/core, src/other", out)

    def test_fileCycleIsAnError(self):
        # x.C and x.H are one node: a.C including b.H while b.C includes
        # a.H is a cycle, though no header includes the other
        code, out = self.run_tool({
            "src/core/a.H": "",
            "src/core/a.C": '#include "a.H"\n#include "b.H"\n',
            "src/core/b.H": "",
            "src/core/b.C": '#include "b.H"\n#include "a.H"\n',
        })
        self.assertEqual(code, 1, out)
        self.assertIn("error: include cycle between files src/core/a, src/core/b", out)

    def test_lambdaAtNamespaceScopeIsMeasured(self):
        body = "".join(f"    int a{i} = {i};\n" for i in range(149))
        code, out = self.run_tool({
            "src/core/f.C": "namespace pmsh\n{\nauto longOne = [](int x)\n{\n"
                            + body + "    return x;\n};\n}\n"})
        self.assertEqual(code, 1, out)
        self.assertIn("function lambda longOne: 152 lines (limit 150)", out)

    def test_memberFunctionsInAClassBodyAreMeasured(self):
        # A constructor with brace member initialisers, and an operator
        # whose "<" is no template bracket, both defined in a header
        body = "".join(f"        int a{i} = {i};\n" for i in range(149))
        code, out = self.run_tool({
            "src/core/c.H": "namespace pmsh\n{\nclass c\n{\n    int b_, c_;\n"
                            "public:\n    c(int x)\n    :\n        b_{x},\n"
                            "        c_{x}\n    {\n" + body + "    }\n"
                            "    bool operator<(const c& o) const\n    {\n"
                            + body + "        return false;\n    }\n};\n}\n"})
        self.assertEqual(code, 1, out)
        self.assertIn("function c: 155 lines (limit 150)", out)
        self.assertIn("function operator<: 153 lines (limit 150)", out)

    def test_aFunctionIsCountedFromItsSignature(self):
        # OpenFOAM's style: a parameter a line. 146 lines of body fit
        # between the braces; with the 6 lines of signature they do not
        signature = "pmsh::label pmsh::f\n(\n    int a,\n    int b,\n    int c\n)\n"
        body = "".join(f"    int a{i} = {i};\n" for i in range(146))
        code, out = self.run_tool({
            "src/core/f.C": signature + "{\n" + body + "}\n"})
        self.assertEqual(code, 1, out)
        self.assertIn("src/core/f.C:1: function pmsh::f: 154 lines (limit 150)", out)

    def test_testsAndBenchScriptsAreChecked(self):
        # A test file may be longer than a source file, not without end;
        # a Python function of bench/ keeps the function limit
        long_test = "// line\n" * 1201
        script = "def long_one():\n" + "    x = 1\n" * 150
        code, out = self.run_tool({
            "tests/unit/testLong.C": long_test,
            "tests/unit/testFine.C": "// line\n" * 1000,
            "bench/script.py": script,
        })
        self.assertEqual(code, 1, out)
        self.assertIn("tests/unit/testLong.C: 1201 lines (limit 1200)", out)
        self.assertNotIn("testFine.C", out)
        self.assertIn("bench/script.py:1: function long_one: 151 lines (limit 150)", out)

if __name__ == "__main__":
    unittest.main()
