#!/usr/bin/python3
"""roslaunch with an exit status that says whether the nodes did their job.

roslaunch exits 0 when a node failed: a required node that died with exit code 1 (agraph_node on
a building it cannot load), a node that logged FATAL, a node that could not be started. This
runs roslaunch, keeps its whole output (--log), reads it as it comes and exits non-zero naming
the node. The scripts that run a launch (make demo, make screenshot) run it through this.

  scripts/roslaunch_checked.py [--log FILE] [--tee] [--keep-going] [--max-restarts N] \\
      -- ROSLAUNCH_ARGUMENTS...
  e.g. scripts/roslaunch_checked.py --log run.log -- -p 11411 is_graphs localize.launch \\
      bim:=$PWD/bim/rotated.ifc bag:=$PWD/bags/D5_rotated.bag

  --log FILE      roslaunch's output (stdout and stderr) into FILE, and this script's verdict
                  after it; without --log the output goes to stdout
  --tee           with --log: to stdout as well
  --keep-going    do not stop the launch at the first FATAL (default: stop it, SIGINT, since a
                  node that logs FATAL and respawns would fail again every second)
  --max-restarts N  stop the launch and fail when one node has restarted more than N times
                  (default: no limit; a restart is a warning)

The roslaunch run is the one on PATH (put /usr/bin first for Debian's ROS). The verdict goes to
stderr, one line each, prefixed "roslaunch_checked:". Exit status:
  0    every node that ended did so cleanly: a required node (the bag player) that exited 0 ends
       the launch normally; a node that died and was restarted (respawn) is a warning naming it
       and how often, not a failure
  1    a node failed, named on stderr: a required node died with a non-zero exit code (or none),
       a node died with a non-zero exit code and did not come back, a node logged FATAL, a node
       could not be launched, or a node restarted more than --max-restarts times
  2    usage error
  3    roslaunch itself failed (a launch file it cannot read, a missing argument, no master)
       with no node to name: its exit code and last lines on stderr
  130, 143  interrupted (SIGINT, SIGTERM: passed on to roslaunch, which stops its nodes) with
       no failure seen before
"""
import argparse
import collections
import os
import re
import signal
import subprocess
import sys
import threading

PREFIX = "roslaunch_checked"
ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]|\x1b\][^\x07]*\x07")  # colours, terminal titles
# roslaunch's own lines (roslaunch/pmon.py, nodeprocess.py, launch.py), searched anywhere in a
# line: a node's output without its newline may come first. Process names are the node's name
# with a counter: "agraph_node-3", in a namespace "robot/agraph_node-3".
DIED = re.compile(r"\[(?P<proc>[^\]\s]+)\] process has (?:died|finished cleanly)")
DIED_CODE = re.compile(r"process has died \[pid \d+, exit code (?P<code>-?\d+)")
RESTART = re.compile(r"\[(?P<proc>[^\]\s]+)\] restarting process")
REQUIRED = re.compile(r"REQUIRED process \[(?P<proc>[^\]]+)\] has died!")
CANNOT_LAUNCH = re.compile(r"ERROR: cannot launch node of type \[(?P<type>[^\]]+)\]: ?(?P<why>.*)")
LAUNCH_FAILED = re.compile(r"^(?:local )?launch of (?P<type>\S+) .*failed")
# A ROS log line at FATAL: "[FATAL] [1700000000.5] [/agraph_node]: ..." with the format this
# script sets, "[FATAL] [1700000000.5]: ..." with roscpp's default.
FATAL = re.compile(r"\[\s*FATAL\s*\]\s*(?:\[[^\]]*\]\s*)?"
                   r"(?:\[(?P<node>/[^\]]*)\])?:?\s*(?P<msg>.*)")
# The node's name in every log line, so that a FATAL names its node.
ROSCONSOLE_FORMAT = "[${severity}] [${time}] [${node}]: ${message}"
GRACE = 2.0     # s between a FATAL and stopping the launch: roslaunch reports the death first


def node_name(proc):
    """'agraph_node-3' -> 'agraph_node'; 'robot/agraph_node-12' -> 'robot/agraph_node'."""
    return re.sub(r"-\d+$", "", proc).strip("/")


def exit_description(text):
    """The exit code in roslaunch's description of a death: an int, or None when it has none."""
    if "finished cleanly" in text:
        return 0
    m = DIED_CODE.search(text)
    return int(m.group("code")) if m else None


class Verdict:
    """Reads roslaunch's output line by line and keeps what failed and what restarted."""

    def __init__(self):
        self.failures = []                          # (node, message), in order
        self.restarts = collections.Counter()       # node -> restarts
        self.exit_codes = collections.defaultdict(list)  # node -> exit codes of its deaths
        self.pending = {}                           # node -> exit code of a death not yet restarted
        self.required_pending = None                # a REQUIRED line waiting for its description
        self.fatals = []                            # (node or None, message)
        self.unnamed_fatal = None                   # a FATAL waiting for the next death to name it
        self.tail = collections.deque(maxlen=15)
        self.stop_reason = None                     # set when the launch should be stopped now

    def fail(self, node, message):
        self.failures.append((node, message))

    def fail_death(self, node, message):
        """A death: it takes the place of the node's FATAL, whose message it repeats."""
        fatal = self._fatal_of(node)
        if fatal:
            self.failures = [(n, m) for n, m in self.failures
                             if not (n == node and m.startswith(f"{node} logged FATAL"))]
        self.fail(node, message + fatal)

    def line(self, raw, max_restarts=None):
        text = ANSI.sub("", raw).rstrip("\r\n")
        if text.strip():
            self.tail.append(text)
        if self.required_pending is not None:
            node = self.required_pending
            if "process has" in text:
                self.required_pending = None
                code = exit_description(text)
                self.pending.pop(node, None)
                if code != 0:
                    self.fail_death(node, f"{node} (required) died with "
                                    + (f"exit code {code}" if code is not None else "no exit code"))
                return
        m = REQUIRED.search(text)
        if m:
            self.required_pending = node_name(m.group("proc"))
            return
        m = DIED.search(text)
        if m:
            node = node_name(m.group("proc"))
            code = exit_description(text)
            self.pending[node] = code
            self.exit_codes[node].append(code)
            if self.unnamed_fatal is not None:
                self.fatals.append((node, self.unnamed_fatal))
                self.fail(node, f"{node} logged FATAL: {self.unnamed_fatal}")
                self.unnamed_fatal = None
            return
        m = RESTART.search(text)
        if m:
            node = node_name(m.group("proc"))
            self.pending.pop(node, None)
            self.restarts[node] += 1
            if max_restarts is not None and self.restarts[node] > max_restarts:
                self.fail(node, f"{node} restarted {self.restarts[node]} times "
                          f"(more than --max-restarts {max_restarts}); exit codes "
                          + ", ".join(str(c) for c in self.exit_codes[node]))
                self.stop_reason = self.stop_reason or f"{node} restarts too often"
            return
        m = CANNOT_LAUNCH.search(text) or LAUNCH_FAILED.search(text)
        if m:
            node = m.group("type")
            why = m.groupdict().get("why") or ""
            self.fail(node, f"cannot launch {node}" + (f": {why}" if why else ""))
            return
        m = FATAL.search(text)
        if m:
            node = (m.group("node") or "").strip("/") or None
            msg = m.group("msg").strip()
            if node is None:
                # roscpp's default format names no node: ours start their messages "<node>: "
                head = re.match(r"^([A-Za-z_][\w/]*):\s", msg)
                node = head.group(1) if head else None
            if node is None:
                self.unnamed_fatal = msg      # named by the next death, else "a node"
            else:
                self.fatals.append((node, msg))
                self.fail(node, f"{node} logged FATAL: {msg}")
            self.stop_reason = self.stop_reason or "a node logged FATAL"

    def _fatal_of(self, node):
        for name, msg in reversed(self.fatals):
            if name == node:
                return f" after FATAL: {msg}"
        return ""

    def finish(self):
        """Deaths never followed by a restart: a non-zero exit is a failure."""
        if self.unnamed_fatal is not None:
            self.fail("a node", f"a node logged FATAL: {self.unnamed_fatal}")
            self.unnamed_fatal = None
        for node, code in self.pending.items():
            if code == 0:
                continue
            known = [m for n, m in self.failures if n == node]
            if known and (self.restarts[node] or
                          any(not m.startswith(f"{node} logged FATAL") for m in known)):
                continue        # a respawning node's FATAL, or already told
            self.fail_death(node, f"{node} died with "
                            + (f"exit code {code}" if code is not None else "no exit code")
                            + " and was not restarted")
        self.pending = {}


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="roslaunch_checked.py", description=__doc__.split("\n\n")[0],
        usage="%(prog)s [--log FILE] [--tee] [--keep-going] [--max-restarts N] "
              "-- ROSLAUNCH_ARGS...")
    parser.add_argument("--log")
    parser.add_argument("--tee", action="store_true")
    parser.add_argument("--keep-going", action="store_true")
    parser.add_argument("--max-restarts", type=int)
    parser.add_argument("roslaunch_args", nargs=argparse.REMAINDER)
    args = parser.parse_args(argv)
    launch_args = args.roslaunch_args
    if launch_args and launch_args[0] == "--":
        launch_args = launch_args[1:]
    if not launch_args:
        parser.print_usage(sys.stderr)
        print(f"{PREFIX}: error: no roslaunch arguments (after --)", file=sys.stderr)
        return 2
    if args.tee and not args.log:
        print(f"{PREFIX}: error: --tee needs --log", file=sys.stderr)
        return 2

    try:
        log = open(args.log, "w", encoding="utf-8") if args.log else None
    except OSError as e:
        print(f"{PREFIX}: error: cannot write the log: {e}", file=sys.stderr)
        return 2
    echo = sys.stdout if (log is None or args.tee) else None

    lock = threading.Lock()

    def out(text):
        with lock:
            _out(text)

    def _out(text):
        if log is not None:
            log.write(text)
            log.flush()
        if echo is not None:
            echo.write(text)
            echo.flush()

    env = dict(os.environ)
    env.setdefault("ROSCONSOLE_FORMAT", ROSCONSOLE_FORMAT)
    env.setdefault("PYTHONUNBUFFERED", "1")
    try:
        launch = subprocess.Popen(["roslaunch"] + launch_args, stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=env)
    except OSError as e:
        print(f"{PREFIX}: error: cannot run roslaunch: {e}", file=sys.stderr)
        return 3

    interrupted = []
    stopping = threading.Event()

    def on_signal(signum, _frame):
        # roslaunch may have had the same signal (a terminal's Ctrl-C, kill of the group); a
        # second one is harmless (it ignores signals once shutting down).
        interrupted.append(signum)
        if launch.poll() is None:
            try:
                launch.send_signal(signum)
            except OSError:
                pass

    for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(s, on_signal)

    def stop_launch(reason):
        """SIGINT to roslaunch GRACE s from now (so that the node's death is in the log)."""
        if stopping.is_set():
            return
        stopping.set()

        def stop():
            if launch.poll() is not None:
                return
            out(f"{PREFIX}: stopping the launch: {reason}\n")
            launch.send_signal(signal.SIGINT)
            # roslaunch escalates to SIGTERM/SIGKILL on its nodes itself; this is for roslaunch.
            kill = threading.Timer(60.0, lambda: launch.poll() is None and launch.kill())
            kill.daemon = True
            kill.start()

        timer = threading.Timer(GRACE, stop)
        timer.daemon = True
        timer.start()

    verdict = Verdict()
    for raw in iter(launch.stdout.readline, b""):
        line = raw.decode("utf-8", errors="replace")
        out(line)
        verdict.line(line, args.max_restarts)
        if verdict.stop_reason and not (args.keep_going and verdict.stop_reason ==
                                        "a node logged FATAL"):
            stop_launch(verdict.stop_reason)
    rc = launch.wait()
    verdict.finish()

    messages = []
    for node, times in sorted(verdict.restarts.items()):
        codes = ", ".join(str(c) for c in verdict.exit_codes[node][:times])
        if not any(n == node for n, _ in verdict.failures):
            messages.append(f"warning: {node} died and was restarted {times} time"
                            f"{'s' if times != 1 else ''} (exit codes {codes})")
    status = 0
    if verdict.failures:
        seen = set()
        for node, message in verdict.failures:
            if message not in seen:
                seen.add(message)
                messages.append(f"error: {message}")
        nodes = list(dict.fromkeys(n for n, _ in verdict.failures))
        messages.append(f"error: failed: {', '.join(nodes)}"
                        + (f" (log: {args.log})" if args.log else ""))
        status = 1
    elif interrupted:
        messages.append(f"interrupted (signal {interrupted[0]})")
        status = 128 + interrupted[0]
    elif rc != 0:
        messages.append(f"error: roslaunch exited {rc}; its last lines:")
        messages.extend("  " + t for t in verdict.tail)
        status = 3
    for m in messages:
        if log is not None:
            log.write(f"{PREFIX}: {m}\n")
        print(f"{PREFIX}: {m}", file=sys.stderr, flush=True)
    if log is not None:
        log.close()
    return status


if __name__ == "__main__":
    sys.exit(main())
