"""Stage 4's mesher children (src/process/childProcess.H): they die with
their rank however the run is stopped, and the log says what they do
while they work.

- stopping: a run stopped in the middle of stage 4 leaves no pmshFoam
  process (rank or mesher child) behind after a few seconds: mpirun
  stopped by SIGTERM, mpirun killed (SIGKILL: the ranks then die of
  the lost connection, and their children with them only by
  PR_SET_PDEATHSIG), a serial run stopped by SIGTERM. The processes of
  one run are found by a token in their environment, so that other
  pmshFoam runs on the machine do not count.
- progress: with a short PMSH_PROGRESS_INTERVAL a run prints several
  progress lines per rank in stage 4, in the documented format, with the
  elapsed time growing.

Run one test:  python3 testStage4Processes.py stopping.test_mpirunKilledLeavesNoProcess
"""

import os
import re
import signal
import subprocess
import sys
import time
import unittest
import uuid

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, environment, mpi  # noqa: E402

TOKEN = "PMSH_STAGE4_TEST_TOKEN"

# A progress line of README's "The log" (the rank's prefix in parallel)
PROGRESS = re.compile(
    r"^(?:\[(\d+)\] )?    partition (\d+), attempt (\d+) \((\w+)(?:; [^)]*)?\): "
    r"(\d+) s so far, CPU (\d+) s, (\d+) MiB, step: (.+)$", re.M)


def processes_with(token):
    """{pid: (ppid, command name)} of the processes whose environment
    holds TOKEN=token."""
    found = {}
    needle = ("%s=%s" % (TOKEN, token)).encode()
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open("/proc/%s/environ" % entry, "rb") as f:
                if needle not in f.read().split(b"\0"):
                    continue
            with open("/proc/%s/stat" % entry) as f:
                stat = f.read()
        except OSError:
            continue
        name = stat[stat.index("(") + 1:stat.rindex(")")]
        fields = stat[stat.rindex(")") + 2:].split()
        if fields[0] == "Z":
            continue
        found[int(entry)] = (int(fields[1]), name)
    return found


class stopping(CaseTest):

    def start(self, np, token, mesher):
        """Starts pmshFoam on tutorials/sphere with `mesher` (netgen at
        r = 3, hxt at r = 4: a stage 4 of many seconds) and returns
        (process, case, processes) once a mesher child works in stage 4
        (for hxt a fresh process of pmshFoam)."""
        c = self.case("sphere", refinementLevels=3 if mesher == "netgen" else 4,
                      volumeMesher=mesher)
        argv = mpi(np, [c.pmshFoam, "-case", c.dir])
        env = environment()
        env[TOKEN] = token
        log = os.path.join(c.dir, "log.pmshFoam")
        with open(log, "w") as out:
            proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=out,
                                    stderr=subprocess.STDOUT, env=env, cwd=c.dir)
        deadline = time.time() + 600
        while time.time() < deadline:
            with open(log) as f:
                text = f.read()
            running = processes_with(token)
            children = [p for p, (ppid, name) in running.items()
                        if name == "pmshFoam" and ppid in running
                        and running[ppid][1] == "pmshFoam"]
            if "Stage 4" in text and len(children) == np:
                return proc, c, running
            if proc.poll() is not None:
                self.fail("pmshFoam ended before stage 4's meshers were seen:\n"
                          + text[-3000:])
            time.sleep(0.2)
        proc.kill()
        self.fail("no mesher child in stage 4 after 600 s")

    def assert_nothing_left(self, proc, token, before):
        """No process of the run after 10 s; kills what is left before
        failing, so that a failure leaves nothing running."""
        deadline = time.time() + 10
        left = processes_with(token)
        while left and time.time() < deadline:
            time.sleep(0.2)
            left = processes_with(token)
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
        for pid in left:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        self.assertEqual(left, {}, "left running 10 s after the stop, of %s" % before)

    def stop_and_check(self, np, which, sig, mesher="netgen"):
        token = uuid.uuid4().hex
        proc, c, running = self.start(np, token, mesher)
        if which == "launcher":
            os.kill(proc.pid, sig)
        else:
            for pid, (ppid, name) in running.items():
                if ppid == proc.pid:
                    os.kill(pid, sig)
        self.assert_nothing_left(proc, token, running)
        self.assertFalse(c.exists("processor0") or c.exists("constant/polyMesh"),
                         "a stopped run wrote a mesh")

    def test_mpirunStoppedBySigtermLeavesNoProcess(self):
        """Open MPI signals each rank's process group, which holds the
        rank's child: this one fails if the child leaves that group
        without dying with its rank."""
        self.stop_and_check(2, "launcher", signal.SIGTERM)

    def test_mpirunKilledLeavesNoProcess(self):
        """Nobody signals the children: the ranks die when they lose
        mpirun, and their children only die with them by
        PR_SET_PDEATHSIG (without it they mesh on for minutes)."""
        self.stop_and_check(2, "launcher", signal.SIGKILL)

    def test_mpirunKilledLeavesNoFreshHxtProcess(self):
        """HXT runs in an exec'd pmshFoam: PR_SET_PDEATHSIG holds across
        the exec."""
        self.stop_and_check(2, "launcher", signal.SIGKILL, "hxt")

    def test_serialRunStoppedBySigtermLeavesNoProcess(self):
        self.stop_and_check(1, "launcher", signal.SIGTERM)


class progress(CaseTest):

    def test_severalProgressLinesPerRankInStageFour(self):
        c = self.case("sphere", maxCellSize=0.4, refinementLevels=2,
                      volumeMesher="netgen")
        # An interval far below stage 4's time on any machine (about 0.8 s
        # here, 15k cells; 30-40 lines a rank): the lines do not depend on
        # how fast the machine is
        _, text = c.run("pmshFoam", np=2, env={"PMSH_PROGRESS_INTERVAL": "0.02"})
        stage4 = text[text.index("Stage 4"):text.index("Stage 5")]
        lines = PROGRESS.findall(stage4)
        for rank in ("0", "1"):
            mine = [l for l in lines if l[0] == rank]
            self.assertGreaterEqual(len(mine), 2, "rank %s:\n%s" % (rank, stage4))
            for prefix, partition, attempt, mesher, *_ in mine:
                self.assertEqual((partition, attempt, mesher), (rank, "1", "netgen"))
            elapsed = [int(l[4]) for l in mine]
            self.assertEqual(elapsed, sorted(elapsed))
            steps = {l[7] for l in mine}
            self.assertTrue(steps <= {"starting", "checking the surface"}
                            | {s for s in steps if re.match(r"Netgen: ", s)}
                            | {s for s in steps if s.startswith("checking Netgen's")},
                            steps)
        # Every line of stage 4 is either a progress line or one of the
        # stage's own lines: no half lines of ranks cut into each other
        for line in stage4.splitlines()[1:]:
            if line.strip() and not PROGRESS.match(line):
                self.assertRegex(line, r"^    (fine cells|time \(s\))", stage4)

    def test_noProgressLinesWithTheDefaultInterval(self):
        """A short stage 4 (seconds) prints none with the default 30 s."""
        c = self.case("sphere", refinementLevels=1, volumeMesher="netgen")
        _, text = c.run("pmshFoam", np=2)
        self.assertEqual(PROGRESS.findall(text), [])


if __name__ == "__main__":
    unittest.main()
