"""Every test method of the end-to-end tests runs in ctest.

    checkTestRegistration.py TESTS_DIR REGISTERED_FILE

tests/tutorials/CMakeLists.txt registers each Python test method by name
(one ctest test each, so that a failure names the behaviour) and writes
what it registered, a 'script:Class.method' a line, to REGISTERED_FILE.
This loads every TESTS_DIR/test*.py as unittest would (generated methods
too) and fails, naming them, on the methods defined there that are not
registered, and on registered names that no longer exist.
"""

import importlib
import os
import sys
import unittest


def defined_tests(tests_dir):
    """{'script:Class.method'} of the test methods each script defines
    (not those of classes it imports from another script)"""
    sys.path.insert(0, tests_dir)
    found = set()
    for name in sorted(os.listdir(tests_dir)):
        if not (name.startswith("test") and name.endswith(".py")):
            continue
        module = importlib.import_module(name[:-3])
        suite = unittest.TestLoader().loadTestsFromModule(module)
        stack = [suite]
        while stack:
            item = stack.pop()
            if isinstance(item, unittest.TestSuite):
                stack.extend(item)
            elif type(item).__module__ == module.__name__:
                found.add("%s:%s.%s" % (name, type(item).__name__, item._testMethodName))
    return found


def main(tests_dir, registered_file):
    with open(registered_file) as f:
        registered = {line.strip() for line in f if line.strip()}
    defined = defined_tests(tests_dir)
    unregistered = sorted(defined - registered)
    vanished = sorted(registered - defined)
    for name in unregistered:
        print("not registered in tests/tutorials/CMakeLists.txt (never runs): " + name)
    for name in vanished:
        print("registered but not defined: " + name)
    print("%d test methods, %d registered" % (len(defined), len(registered)))
    return 1 if unregistered or vanished else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
