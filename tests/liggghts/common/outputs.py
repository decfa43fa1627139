"""Parsers of what a LIGGGHTS run writes: dump local pair lists, dump custom atoms, the thermo
block of a log and the neighbour statistics at its end.  Pure Python (no numpy)."""

import collections
import re

from .runner import Fail


def parse_local_dump(path):
    """dump local file -> OrderedDict step -> Counter of (min tag, max tag)."""
    steps = collections.OrderedDict()
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    n = len(lines)
    while i < n:
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            i += 2
            continue
        if lines[i].startswith("ITEM: NUMBER OF ENTRIES"):
            count = int(lines[i + 1])
            i += 2
            continue
        if lines[i].startswith("ITEM: ENTRIES"):
            c = collections.Counter()
            for k in range(i + 1, i + 1 + count):
                a, b = lines[k].split()[:2]
                a, b = int(float(a)), int(float(b))
                c[(a, b) if a < b else (b, a)] += 1
            steps[step] = c
            i += 1 + count
            continue
        i += 1
    return steps


def parse_atoms_dump(path):
    """dump custom (id radius x y z) -> dict step -> dict id -> (r, x, y, z), and box per step."""
    steps, boxes = {}, {}
    with open(path) as f:
        lines = f.read().split("\n")
    i, n = 0, len(lines)
    while i < n:
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            i += 2
        elif lines[i].startswith("ITEM: NUMBER OF ATOMS"):
            count = int(lines[i + 1])
            i += 2
        elif lines[i].startswith("ITEM: BOX BOUNDS"):
            boxes[step] = [tuple(float(v) for v in lines[i + 1 + k].split()[:2]) for k in range(3)]
            i += 4
        elif lines[i].startswith("ITEM: ATOMS"):
            d = {}
            for k in range(i + 1, i + 1 + count):
                v = lines[k].split()
                d[int(v[0])] = tuple(float(x) for x in v[1:5])
            steps[step] = d
            i += 1 + count
        else:
            i += 1
    return steps, boxes


def parse_thermo(text):
    """-> (column names, list of rows (floats)) of the last thermo block in a log.
    Column names as LIGGGHTS prints them: c_/f_/v_ prefixes stripped (c_rke -> rke)."""
    lines = text.splitlines()
    blocks = []
    i = 0
    while i < len(lines):
        t = lines[i].split()
        if t and t[0] == "Step":
            cols = [re.sub(r"^[cfv]_", "", c) for c in t]
            rows = []
            i += 1
            while i < len(lines) and not lines[i].startswith("Loop time"):
                v = lines[i].split()
                if len(v) == len(cols):
                    try:
                        rows.append([float(x) for x in v])
                    except ValueError:
                        pass
                i += 1
            blocks.append((cols, rows))
        i += 1
    if not blocks:
        raise Fail("no thermo output found in log")
    return blocks[-1]


def parse_stats(text):
    s = {}
    m = re.search(r"Total # of neighbors = (\S+)", text)
    if m:
        s["neighbors"] = float(m.group(1))
    m = re.search(r"Neighbor list builds = (\d+)", text)
    if m:
        s["builds"] = int(m.group(1))
    m = re.search(r"Dangerous builds = (\d+)", text)
    if m:
        s["dangerous"] = int(m.group(1))
    return s
