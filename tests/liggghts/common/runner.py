"""Runs LIGGGHTS decks for the regression drivers and gives them one command line.

Runner runs a deck (1 rank directly, NP ranks under mpiexec) in a work directory with -var
settings and returns its log; driver_main is the command line every driver shares
(`DRIVER TEST --exe ... --workdir ...`).  A deck named without a folder is the calling driver's
own; every run gets `-var commondir <this folder>` for the shared deck pieces (walls_*.in,
in.settle).  Pure Python (no numpy).
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import time

COMMON = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(COMMON)))
GEN = os.path.join(ROOT, "scripts", "gen_pack.py")


class Fail(Exception):
    pass


def read_text(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


class Runner:
    def __init__(self, args, deckdir):
        self.deckdir = deckdir
        self.exe = args.exe
        self.mpiexec = args.mpiexec
        self.mpiflags = [f for f in re.split(r"[;\s]+", args.mpiexec_flags or "") if f]
        self.python = args.python or sys.executable
        self.work = os.path.abspath(args.workdir)
        self.timeout = args.timeout
        if os.path.isdir(self.work) and not args.keep:
            shutil.rmtree(self.work)
        os.makedirs(self.work, exist_ok=True)
        if not (os.path.isfile(self.exe) and os.access(self.exe, os.X_OK)):
            raise Fail("LIGGGHTS executable not found: %s" % self.exe)

    def gen(self, name, gen_args):
        out = os.path.join(self.work, name)
        cmd = [self.python, GEN] + gen_args + ["--out", out]
        r = subprocess.run(cmd, cwd=self.work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           universal_newlines=True)
        if r.returncode != 0:
            raise Fail("generator failed: %s\n%s" % (" ".join(cmd), r.stdout))
        print("  gen: " + r.stdout.strip())
        return out

    def run(self, deck, tag, np, variables, expect_ok=True):
        """Runs deck in the work dir; returns (rc, log text, tag)."""
        log = os.path.join(self.work, tag + ".log")
        cmd = []
        if np != 1:  # one rank: run the executable directly (mpirun start-up costs ~2 s)
            if not self.mpiexec:
                raise Fail("no mpiexec given, cannot run on %d ranks" % np)
            cmd += [self.mpiexec] + self.mpiflags + ["-np", str(np)]
        # Screen output goes to our pipe, line-buffered (stdbuf): errors raised on one rank
        # (error->one, e.g. "Neighbor list overflow") reach only the screen, then MPI_Abort
        # discards whatever stdio still buffers, the log file included.
        if shutil.which("stdbuf"):
            cmd += ["stdbuf", "-oL", "-eL"]
        cmd += [self.exe, "-in", os.path.join(self.deckdir, deck), "-log", log, "-echo", "none"]
        variables = dict(variables)
        variables.setdefault("commondir", COMMON)
        variables.setdefault("out", tag)
        for k, v in variables.items():
            cmd += ["-var", k, str(v)]
        env = dict(os.environ)
        # Open MPI: allow root, allow more ranks than cores (harmless for other MPIs)
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
        env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
        t0 = time.time()
        try:
            r = subprocess.run(cmd, cwd=self.work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               universal_newlines=True, errors="replace", env=env, timeout=self.timeout)
            rc, out = r.returncode, r.stdout
        except subprocess.TimeoutExpired as e:
            rc, out = 124, (e.stdout or "") if isinstance(e.stdout, str) else ""
        dt = time.time() - t0
        text = read_text(log) if os.path.exists(log) else ""
        print("  run: %-34s np=%d rc=%d %.1fs" % (tag, np, rc, dt))
        if expect_ok and rc != 0:
            err = [l for l in (text + "\n" + out).splitlines() if "ERROR" in l]
            raise Fail("%s failed (rc=%d): %s\n  command: %s\n  log: %s"
                       % (tag, rc, "; ".join(err[:3]) or out[-2000:], " ".join(cmd), log))
        return rc, text + "\n" + out


def driver_main(doc, dispatch, list_tests=None, workdir_prefix=""):
    """The command line every regression driver shares (check_neighbor_spacetree.py,
    check_ranks.py, check_adaptive_grid.py, check_restart_tree.py): `TEST [--exe ...]`;
    dispatch(R, parts) runs the test named by the ':'-separated parts and returns False for an
    unknown name; decks named without a folder are the driver's own (its directory). Exit status
    0 = pass, 1 = fail, 2 = unknown test."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("test", help="test name" + (", or 'list'" if list_tests else ""))
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "liggghts-spacetree"))
    ap.add_argument("--mpiexec", default=shutil.which("mpirun") or shutil.which("mpiexec"))
    ap.add_argument("--mpiexec-flags", default="",
                    help="flags before -np (';' or blank separated), e.g. --allow-run-as-root;--oversubscribe")
    ap.add_argument("--python", default=None, help="interpreter for gen_pack.py (default: this one)")
    ap.add_argument("--workdir", default=None)
    ap.add_argument("--keep", action="store_true", help="do not wipe the work directory first")
    ap.add_argument("--timeout", type=float, default=300.0, help="per LIGGGHTS run (s)")
    a = ap.parse_args()
    if list_tests and a.test == "list":
        print("\n".join(list_tests()))
        return 0
    if a.workdir is None:
        a.workdir = os.path.join(ROOT, "build", "tests-liggghts", workdir_prefix + a.test.replace(":", "_"))
    print("test %s (exe %s)" % (a.test, a.exe))
    t0 = time.time()
    try:
        deckdir = os.path.dirname(os.path.abspath(sys.argv[0]))
        if not dispatch(Runner(a, deckdir), a.test.split(":")):
            known = ("; known:\n  " + "\n  ".join(list_tests())) if list_tests else ""
            print("unknown test '%s'%s" % (a.test, known))
            return 2
    except Fail as e:
        print("FAIL %s (%.1fs)\n%s" % (a.test, time.time() - t0, e))
        return 1
    print("ok %s (%.1fs)" % (a.test, time.time() - t0))
    return 0
