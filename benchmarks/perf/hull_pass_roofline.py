"""The hull pass's limit: flops and bytes per triangle of ``hull_wrenches_kernel`` against an H100 SXM's roofline.

    python -m benchmarks.perf.hull_pass_roofline [--json benchmarks/data/hull_pass_roofline.json]

Runs on the CPU: the flops are counted statically in the PTX that Warp's NVRTC emits for sm_90 (no GPU or driver
needed), the bytes from the arrays the kernel reads and writes. The pass counted is the one the E-Boat benchmark
builds (``bench_eboat``): the physics profile, the real 2 024-triangle hull (1 014 vertices), seakeeping on (the
33 wave points), still water (no current), 128 threads a boat, fast math, at most 128 registers.

Flops (from the PTX, per path through the code; the hand count of the fully wet triangle below checks one):
FP32 add, sub, mul = 1, fma/mad = 2, and one each for div (``div.approx``: a reciprocal on the SFU and a
multiply), sqrt, rsqrt, rcp, sin, cos, ex2, lg2; min, max, abs, neg, compares and selects are not counted. The
SFU instructions (div, sqrt, rsqrt, rcp, sin, cos, ex2, lg2) are also counted apart: they have their own, lower
roof. A path is one way through the branches as one thread takes it; a warp whose lanes take different paths
pays for every path its lanes take (the triangles are ordered by side and height so that most warps do not).

Bytes, three levels:
- shared memory: each triangle reads its three corners' water state (16 B each), each vertex writes its own.
- L1 requests: every global load the threads issue (mesh, ocean fields, per-boat state): what the SMs' load
  path must deliver. The mesh (27 KB) and the ocean's fields (7 x 512 x 512 x 8 B = 14.7 MB) fit the H100's
  50 MB L2, and a boat's vertices sample the few grid nodes under its hull again and again: most of these hit.
- DRAM (compulsory): each boat's state once, the grid nodes under its hull once per field read (boats lie far
  apart, none shared), and the one mesh that all boats share, once per pass. Sectors (32 B) are not rounded up.

Peaks of the H100 SXM5 (80 GB HBM3), from NVIDIA's H100 datasheet and its Hopper architecture whitepaper (2022):
132 SMs at a 1.98 GHz boost clock; 128 FP32 lanes an SM, so 132 x 128 x 2 x 1.98e9 = 66.9 TFLOP/s (the
datasheet's "67 TFLOPS" FP32); HBM3 3.35 TB/s; 50 MB L2; up to 228 KB of shared memory an SM. The CUDA C++
Programming Guide gives, for compute capability 9.0, 16 results a clock an SM for the SFU's reciprocal,
reciprocal square root, log2, exp2, sine and cosine (4.18 T/s over 132 SMs), and 32 banks of 4 bytes for shared
memory: 128 B a clock an SM, 33.4 TB/s over 132 SMs (the L1 shares that data path).

The measured rates come from benchmarks/RESULTS.md and the text of issue 36; each names its device, its date
and which code it timed. None of them timed the pass counted here (choppy sea with seakeeping on, after issue
33's second pass): the fraction of its roof that this pass reaches needs a GPU run (see ``MEASURED``).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import re
import tempfile
from collections import Counter
from pathlib import Path

import numpy as np

from ocean_warp.atomic_files import atomic_output

DEFAULT_JSON = Path(__file__).resolve().parents[1] / "data" / "hull_pass_roofline.json"

# --- the H100 SXM5's peaks ------------------------------------------------------------------------------------
H100_SXM = {
    "name": "NVIDIA H100 SXM5 80GB HBM3",
    "sms": 132,
    "boost_clock_hz": 1.98e9,
    "fp32_lanes_per_sm": 128,
    "sfu_results_per_clock_per_sm": 16,
    "shared_bytes_per_clock_per_sm": 128,
    "hbm_bytes_per_s": 3.35e12,
    "l2_bytes": 50 * 2**20,
}


def peak_rates(gpu: dict) -> dict:
    """FP32 [flop/s], SFU [results/s], shared/L1 [B/s] and HBM [B/s] peaks of ``gpu`` (a dict like H100_SXM)."""
    clocks = gpu["sms"] * gpu["boost_clock_hz"]
    return {"fp32_flops_per_s": 2.0 * gpu["fp32_lanes_per_sm"] * clocks,
            "sfu_per_s": gpu["sfu_results_per_clock_per_sm"] * clocks,
            "shared_bytes_per_s": gpu["shared_bytes_per_clock_per_sm"] * clocks,
            "hbm_bytes_per_s": gpu["hbm_bytes_per_s"]}


# --- PTX: basic blocks and their FP32 work ------------------------------------------------------------------
FLOPS_PER_OP = {"add": 1, "sub": 1, "mul": 1, "fma": 2, "mad": 2, "div": 1, "sqrt": 1, "rsqrt": 1, "rcp": 1,
                "sin": 1, "cos": 1, "ex2": 1, "lg2": 1}
SFU_OPS = {"div", "sqrt", "rsqrt", "rcp", "sin", "cos", "ex2", "lg2"}
LOAD_BYTES = {"f32": 4, "u32": 4, "s32": 4, "b32": 4, "f64": 8, "u64": 8, "s64": 8, "b64": 8, "u8": 1, "u16": 2}

_LABEL = re.compile(r"^(\$?[A-Za-z_][\w$]*):")
_BRANCH = re.compile(r"^(@!?%\w+\s+)?bra(\.uni)?\s+(\$?[\w$]+)\s*;")


@dataclasses.dataclass
class PtxBlock:
    """A basic block of one PTX entry: its label (or None), its instructions and where control goes next."""

    label: str | None
    instructions: list[str]
    targets: list[str] = dataclasses.field(default_factory=list)
    """Labels its branches jump to."""
    falls_through: bool = True
    """Whether control may go on to the next block (not after an unconditional branch or a return)."""


def instruction_counts(instruction: str) -> Counter:
    """What one PTX instruction adds up to: ``flops``, ``sfu``, ``fp32_instructions``, and the bytes of global
    and shared loads and stores (``global_load_bytes``, ...); parameter loads are not memory traffic here."""
    counts = Counter()
    words = instruction.split()
    if not words:
        return counts
    opcode = words[1] if words[0].startswith("@") and len(words) > 1 else words[0]
    parts = opcode.split(".")
    base = parts[0]
    if "f32" in parts and base in FLOPS_PER_OP:
        counts["flops"] += FLOPS_PER_OP[base]
        counts["fp32_instructions"] += 1
        if base in SFU_OPS:
            counts["sfu"] += 1
    if base in ("ld", "st") and len(parts) >= 2 and parts[1] in ("global", "shared"):
        width = 1
        for part in parts[2:]:
            if part.startswith("v") and part[1:].isdigit():
                width = int(part[1:])
        element = next((LOAD_BYTES[p] for p in reversed(parts) if p in LOAD_BYTES), 0)
        kind = "load" if base == "ld" else "store"
        counts[f"{parts[1]}_{kind}_bytes"] += width * element
    return counts


def entry_body(ptx: str, entry: str | None = None) -> list[str]:
    """The instruction lines of PTX entry ``entry`` (default: the first ``.entry``), labels included."""
    lines = ptx.replace("\x00", "").splitlines()
    starts = [i for i, line in enumerate(lines) if ".entry" in line and (entry is None or entry in line)]
    if not starts:
        raise ValueError(f"hull_pass_roofline: no .entry {entry or ''} in the PTX")
    i = starts[0]
    while "{" not in lines[i]:
        i += 1
    depth, body = 0, []
    for line in lines[i:]:
        depth += line.count("{") - line.count("}")
        body.append(line)
        if depth == 0:
            break
    return body


def parse_blocks(ptx: str, entry: str | None = None) -> list[PtxBlock]:
    """Basic blocks of a PTX entry in layout order. A block starts at each label and at each ``bar.sync`` (so
    that the code between two block-wide barriers is a region of its own)."""
    blocks = [PtxBlock(None, [])]
    for raw in entry_body(ptx, entry):
        line = raw.split("//")[0].strip()
        if not line or line.startswith((".reg", ".shared", ".local", ".loc", ".pragma", "{", "}")):
            continue
        label = _LABEL.match(line)
        if label:
            blocks.append(PtxBlock(label.group(1), []))
            continue
        if line.startswith("bar.sync") and blocks[-1].instructions:
            blocks.append(PtxBlock(None, []))
        block = blocks[-1]
        if not block.falls_through:
            block = PtxBlock(None, [])
            blocks.append(block)
        block.instructions.append(line)
        branch = _BRANCH.match(line)
        if branch:
            block.targets.append(branch.group(3))
            if branch.group(1) is None:
                block.falls_through = False
            blocks.append(PtxBlock(None, []))
        elif line.startswith("ret") or line.startswith("exit"):
            block.falls_through = False
            blocks.append(PtxBlock(None, []))
    return [b for b in blocks if b.instructions or b.label is not None]


def block_counts(block: PtxBlock) -> Counter:
    total = Counter()
    for instruction in block.instructions:
        total.update(instruction_counts(instruction))
    return total


def successors(blocks: list[PtxBlock]) -> list[list[int]]:
    """Indices of each block's successors."""
    index = {b.label: i for i, b in enumerate(blocks) if b.label is not None}
    result = []
    for i, block in enumerate(blocks):
        next_ = [index[t] for t in block.targets]
        if block.falls_through and i + 1 < len(blocks):
            next_.append(i + 1)
        result.append(sorted(set(next_)))
    return result


def dominators(blocks: list[PtxBlock]) -> list[set[int]]:
    """For each block, the blocks every path from the entry to it passes through (itself included)."""
    nexts = successors(blocks)
    preds = [[] for _ in blocks]
    for i, js in enumerate(nexts):
        for j in js:
            preds[j].append(i)
    everything = set(range(len(blocks)))
    dom = [{0}] + [set(everything) for _ in blocks[1:]]
    changed = True
    while changed:
        changed = False
        for i in range(1, len(blocks)):
            new = set.intersection(*(dom[p] for p in preds[i])) | {i} if preds[i] else {i}
            if new != dom[i]:
                dom[i], changed = new, True
    return dom


def back_edges(blocks: list[PtxBlock]) -> list[tuple[int, int]]:
    """(latch, header) of every edge to a block that dominates its source: the loops. (Code the compiler laid out
    after a loop that jumps back into it is not one.)"""
    dom = dominators(blocks)
    return [(i, j) for i, nexts in enumerate(successors(blocks)) for j in nexts if j in dom[i]]


def natural_loop(blocks: list[PtxBlock], header: int) -> set[int]:
    """The blocks of the loop(s) closing on ``header``: it and every block that reaches one of its latches
    without passing through it."""
    nexts = successors(blocks)
    preds = [[] for _ in blocks]
    for i, js in enumerate(nexts):
        for j in js:
            preds[j].append(i)
    body = {header}
    stack = [s for s, t in back_edges(blocks) if t == header]
    while stack:
        node = stack.pop()
        if node not in body:
            body.add(node)
            stack.extend(preds[node])
    return body


def _forward(blocks: list[PtxBlock]) -> list[list[int]]:
    """Successors without the loops' back edges: an acyclic graph (PTX from NVRTC is reducible)."""
    back = set(back_edges(blocks))
    return [[j for j in js if (i, j) not in back] for i, js in enumerate(successors(blocks))]


def extreme_path(blocks: list[PtxBlock], start: int, stops, *, longest: bool, exclude=frozenset(),
                 include_stop: bool = False) -> Counter:
    """Counts along the path from block ``start`` to any block of ``stops`` (an index or a set; loops taken once,
    their back edges dropped) with the most (``longest``) or fewest flops, ties broken by SFU instructions; blocks
    in ``exclude`` are never entered. A stop block is counted only with ``include_stop``. Raises ValueError where
    no path exists."""
    stops = {stops} if isinstance(stops, int) else set(stops)
    nexts = _forward(blocks)
    counts = [block_counts(b) for b in blocks]
    memo: dict[int, Counter | None] = {}

    def key(c: Counter):
        return (c["flops"], c["sfu"])

    def best(i: int) -> Counter | None:
        if i in memo:
            return memo[i]
        if i in exclude:
            result = None
        elif i in stops:
            result = counts[i].copy() if include_stop else Counter()
        else:
            options = [c for c in (best(j) for j in nexts[i]) if c is not None]
            result = None if not options else counts[i] + (max(options, key=key) if longest
                                                           else min(options, key=key))
        memo[i] = result
        return result

    found = best(start)
    if found is None:
        raise ValueError(f"hull_pass_roofline: no path from block {start} to blocks {sorted(stops)}")
    return found


def all_paths(blocks: list[PtxBlock], start: int, stop: int, limit: int = 100_000) -> list[Counter]:
    """Counts of every path from ``start`` to ``stop`` (``stop`` counted; loops taken once), at most ``limit``."""
    nexts = _forward(blocks)
    counts = [block_counts(b) for b in blocks]
    paths: list[Counter] = []
    reaches = {stop}
    changed = True
    while changed:
        changed = False
        for i, js in enumerate(nexts):
            if i not in reaches and any(j in reaches for j in js):
                reaches.add(i)
                changed = True

    def walk(i: int, sofar: Counter):
        if len(paths) >= limit:
            raise ValueError(f"hull_pass_roofline: more than {limit} paths from block {start} to block {stop}")
        here = sofar + counts[i]
        if i == stop:
            paths.append(here)
            return
        for j in nexts[i]:
            if j in reaches:
                walk(j, here)

    walk(start, Counter())
    return paths


def _flops(c: Counter) -> dict:
    return {"flops": int(c["flops"]), "sfu": int(c["sfu"]), "fp32_instructions": int(c["fp32_instructions"])}


def hull_pass_paths(ptx: str, block_dim: int, wave_points: int) -> dict:
    """FP32 work of the hull pass per path, from its PTX: per triangle (dry, fully wet, cut by the waterline
    into one or two pieces), per vertex (above the water, submerged above and below the pressure field's second
    depth) and per boat (what every thread does before the vertices, the wave points, the reduction and lane 0's
    last terms).

    Regions are found by structure: a vertex round is the code between two block barriers that ends in a
    shared-memory store; the triangle loop is the innermost loop around the three 16-byte shared loads of the
    corners; the loop nested in it integrates one submerged piece. Branches inside a piece take the longest way
    without ``pow`` (the E-Boat's falloff exponent 0.5 takes ``sqrt``); after the pieces, the shortest (slamming is
    off in the physics profile)."""
    blocks = parse_blocks(ptx)
    loops = back_edges(blocks)
    bars = [i for i, b in enumerate(blocks) if b.instructions and b.instructions[0].startswith("bar.sync")]
    corner_block = next(i for i, b in enumerate(blocks)
                        if sum(ins.startswith("ld.shared.v4.f32") for ins in b.instructions) == 3)
    headers = {t for _, t in loops}
    triangle_header, triangle_loop = min(((h, natural_loop(blocks, h)) for h in headers
                                          if corner_block in natural_loop(blocks, h)), key=lambda e: len(e[1]))
    triangle_latches = {s for s, t in loops if t == triangle_header}
    piece_header, piece_loop = max(((h, natural_loop(blocks, h)) for h in headers
                                    if h != triangle_header and h in triangle_loop), key=lambda e: len(e[1]))
    piece_latches = {s for s, t in loops if t == piece_header}
    nexts = successors(blocks)
    joins = {j for i in piece_loop for j in nexts[i] if j not in piece_loop}
    if len(joins) != 1:
        raise ValueError(f"hull_pass_roofline: the piece loop leaves to {sorted(joins)}, expected one block")
    join = joins.pop()
    outside_pieces = triangle_loop - piece_loop
    with_sfu = frozenset(i for i in outside_pieces if block_counts(blocks[i])["sfu"] > 0)
    pow_blocks = frozenset(i for i in piece_loop
                           if any(ins.startswith(("lg2", "ex2")) for ins in blocks[i].instructions))

    after_pieces = extreme_path(blocks, join, triangle_latches, longest=False, include_stop=True)
    one_piece = extreme_path(blocks, piece_header, piece_latches, longest=True, exclude=pow_blocks,
                             include_stop=True)
    dry = extreme_path(blocks, triangle_header, triangle_latches, longest=False, exclude=frozenset(piece_loop),
                       include_stop=True)
    # Before the pieces, the only SFU work is the clipping's cut fractions: a whole wet triangle has none.
    wet = extreme_path(blocks, triangle_header, piece_header, longest=True, exclude=with_sfu) + one_piece
    cut = extreme_path(blocks, triangle_header, piece_header, longest=True) + one_piece
    triangle = {"dry": _flops(dry), "wet": _flops(wet + after_pieces),
                "cut_one_piece": _flops(cut + after_pieces), "cut_two_pieces": _flops(cut + one_piece + after_pieces),
                "one_piece": _flops(one_piece)}

    # The vertex rounds are unrolled: the first one stands for all.
    rounds = [(a, b) for a, b in zip(bars, bars[1:])
              if any(ins.startswith("st.shared.v4.f32") and len(set(ins.split("{")[1].split(","))) == 4
                     for i in range(a, b) for ins in blocks[i].instructions)]
    first_round, next_barrier = rounds[0]
    vertex_paths = all_paths(blocks, first_round, next_barrier - 1)
    # Paths that sample the sea (the inversion once): above the water they read the surface alone; below it the
    # pressure fields too, the longest of those standing for every depth.
    above = VERTEX_BYTES + BILINEAR_BYTES + SURFACE_BYTES
    vertex = {"above_water": _flops(max((p for p in vertex_paths if p["global_load_bytes"] == above),
                                        key=lambda c: c["flops"])),
              "submerged": _flops(max((p for p in vertex_paths if p["global_load_bytes"] > above),
                                      key=lambda c: c["flops"]))}
    inversion = [(s, t) for s, t in loops if first_round <= t < next_barrier]
    vertex["inversion_step"] = _flops(extreme_path(blocks, inversion[0][1], inversion[0][0], longest=True,
                                                   include_stop=True)) if inversion else None

    # Per boat: what every thread does before the vertices (the origin's inversion and water), the wave points'
    # loop (one trip a point), the warp shuffles of the block's sum in every thread, and lane 0's last terms (the
    # longest way after the triangle loop: the residuary resistance and the wave terms).
    before = [h for h in headers if h < bars[0] and bars[0] not in natural_loop(blocks, h)]
    wave_header = max(before, key=lambda h: len(natural_loop(blocks, h)))
    wave_latches = {s for s, t in loops if t == wave_header}
    per_thread = extreme_path(blocks, 0, bars[0], longest=True)  # a loop's body cannot reach past its exit
    wave_point = extreme_path(blocks, wave_header, wave_latches, longest=True, include_stop=True)
    exits = sorted({j for i in triangle_loop for j in nexts[i] if j not in triangle_loop})
    ends = {i for i, b in enumerate(blocks) if b.instructions and b.instructions[-1].startswith("ret")}
    lane_zero = extreme_path(blocks, exits[0], ends, longest=True, include_stop=True)
    shuffles = Counter()
    for i in range(exits[0], len(blocks)):
        if any(ins.startswith("shfl") for ins in blocks[i].instructions):
            shuffles += block_counts(blocks[i])
    boat = {"per_thread_before_vertices": _flops(per_thread), "wave_point": _flops(wave_point),
            "shuffle_sum_per_thread": _flops(shuffles), "lane_zero_after_triangles": _flops(lane_zero)}
    boat["total"] = {k: int(block_dim * (per_thread[k] + shuffles[k]) + wave_points * wave_point[k] + lane_zero[k]
                            - shuffles[k]) for k in ("flops", "sfu")}
    return {"triangle": triangle, "vertex": vertex, "boat": boat, "blocks": len(blocks)}


# --- bytes ---------------------------------------------------------------------------------------------------
# dtype sizes [B] of what the kernel reads and writes
VEC2, VEC3, VEC3I, VEC4, VEC6, QUAT, SCALAR = 8, 12, 12, 16, 24, 16, 4
FIELD_NODE_BYTES = 8
"""One grid node of one ocean field (a vec2f)."""
BILINEAR_BYTES = 4 * FIELD_NODE_BYTES
"""One bilinear lookup of one field: its four nodes."""
VERTEX_BYTES = VEC3
"""A vertex's body-frame position."""
SURFACE_BYTES = 2 * BILINEAR_BYTES
BAND_BYTES = (16, 32, 32, 16)
"""What the dynamic pressure head reads in each depth band (``pressure_head``): the upper field's first value;
both its values; its second and the lower field's first; the lower field's first: one float at four nodes each."""
"""The surface's height and velocity at a grid position (two fields)."""
BOAT_STATE_READ_BYTES = SCALAR + VEC3 + QUAT + VEC6
"""hull_type, position, orientation, velocity."""
BOAT_STATE_WRITE_BYTES = VEC3 + VEC6
"""The water's velocity at the origin and the wrench."""
SEAKEEPING_READ_BYTES = VEC6
"""The last substep's water motion under the hull."""
SEAKEEPING_WRITE_BYTES = 2 * VEC6
"""Its new value and its rate of change."""
TYPE_TABLE_BYTES = 6 * SCALAR
"""What every thread reads of its hull type's table (first vertex and triangle, their counts, reference length,
the seakeeping flag)."""
WAVE_POINT_BYTES = VEC2 + 4 * VEC6
"""A wave point's position and its four weight rows."""


@dataclasses.dataclass(frozen=True)
class HullPassShape:
    """What the hull pass's bytes depend on. Fractions are of the hull's vertices at the moment counted."""

    vertices: int
    triangles: int
    boats: int
    block_dim: int
    wave_points: int
    inversion_steps: float
    """Fixed-point steps a vertex's or wave point's inversion takes (each one bilinear lookup of the displacement)."""
    origin_inversion_steps: float
    """Steps of the origin's inversion, started from the point itself."""
    depth_bands: tuple
    """Shares of the vertices in each band between the surface and the pressure fields' depths (z1, z2, z3), and
    below the deepest: four shares; the rest are above the water."""
    footprint_nodes: float
    """Grid nodes under one boat's hull that its lookups touch."""
    fields_read: int
    """Distinct ocean fields the pass reads at those nodes."""


def vertex_request_bytes(shape: HullPassShape) -> float:
    """Global bytes one vertex's sampling asks for, averaged over its water states [B]."""
    return (VERTEX_BYTES + shape.inversion_steps * BILINEAR_BYTES + SURFACE_BYTES
            + sum(share * band for share, band in zip(shape.depth_bands, BAND_BYTES)))


def boat_request_bytes(shape: HullPassShape) -> float:
    """Global bytes one boat asks for outside its vertices and triangles [B]: every thread's state, type table
    and origin lookups (inversion, its gradient from four displacement lookups, the surface), the wave points,
    and the stores."""
    origin = (shape.origin_inversion_steps + 4) * BILINEAR_BYTES + SURFACE_BYTES
    per_thread = BOAT_STATE_READ_BYTES + TYPE_TABLE_BYTES + origin
    wave_point = WAVE_POINT_BYTES + shape.inversion_steps * BILINEAR_BYTES + 2 * BILINEAR_BYTES
    return (shape.block_dim * per_thread + shape.wave_points * wave_point + SEAKEEPING_READ_BYTES
            + BOAT_STATE_WRITE_BYTES + SEAKEEPING_WRITE_BYTES)


def hull_pass_bytes(shape: HullPassShape) -> dict:
    """Bytes per boat and per triangle at each level (shared memory, L1 requests, compulsory DRAM) [B]."""
    triangles, vertices = shape.triangles, shape.vertices
    shared_per_boat = triangles * 3 * VEC4 + vertices * VEC4
    triangle_requests = VEC3I + 3 * VERTEX_BYTES
    l1_per_boat = triangles * triangle_requests + vertices * vertex_request_bytes(shape) + boat_request_bytes(shape)
    mesh = vertices * VEC3 + triangles * VEC3I + shape.wave_points * WAVE_POINT_BYTES
    dram_per_boat = (BOAT_STATE_READ_BYTES + SEAKEEPING_READ_BYTES + BOAT_STATE_WRITE_BYTES + SEAKEEPING_WRITE_BYTES
                     + shape.footprint_nodes * shape.fields_read * FIELD_NODE_BYTES + mesh / shape.boats)
    per_boat = {"shared": shared_per_boat, "l1_requests": l1_per_boat, "dram": dram_per_boat}
    return {"per_boat": per_boat, "per_triangle": {k: v / triangles for k, v in per_boat.items()},
            "mesh_bytes": mesh}


def footprint_nodes(plan_xy: np.ndarray, cell: float, headings: int = 360) -> float:
    """Mean count of grid nodes that bilinear lookups over a hull's plan (points ``plan_xy`` [m], body x, y) touch
    on a grid of spacing ``cell`` [m], over headings and positions: a box of sides a, b at a random offset
    spans a/cell + 1 cells along one axis on average, so needs a/cell + 2 nodes."""
    total = 0.0
    for angle in np.linspace(0.0, np.pi, headings, endpoint=False):
        c, s = np.cos(angle), np.sin(angle)
        x = c * plan_xy[:, 0] - s * plan_xy[:, 1]
        y = s * plan_xy[:, 0] + c * plan_xy[:, 1]
        total += (np.ptp(x) / cell + 2.0) * (np.ptp(y) / cell + 2.0)
    return total / headings


# --- measured rates ------------------------------------------------------------------------------------------
MEASURED = [
    {"what": "issue 36's figure: 4 096 boats x 2 024 triangles in 215 us, linear sea", "device": "NVIDIA H200",
     "date": "2026-11-27 (issue 36's text; RESULTS.md has no hull pass of that day on a linear sea)",
     "triangles_per_s": 4096 * 2024 / 215e-6, "same_pass": False,
     "code": "a linear sea (no choppy inversion); the issue does not say whether seakeeping was on, and the "
             "figure matches the pre-issue-33 pass of RESULTS.md's issue 10 breakdown (213.1 us)"},
    {"what": "RESULTS.md, Speed (issue 10): hull pass 213.1 us at 4 096 boats, linear",
     "device": "NVIDIA H100 80GB HBM3",
     "date": "2026-11-23", "triangles_per_s": 4096 * 2024 / 213.1e-6, "same_pass": False,
     "code": "before issue 33: procedural hull, surface pressure only, no seakeeping, no wave points"},
    {"what": "RESULTS.md, Speed (issue 10): hull pass 269.2 us at 4 096 boats, choppy 0.5",
     "device": "NVIDIA H100 80GB HBM3", "date": "2026-11-23", "triangles_per_s": 4096 * 2024 / 269.2e-6,
     "same_pass": False, "code": "before issue 33 (as above), choppy inversion of that time"},
    {"what": "RESULTS.md, issue 33 first pass: hull pass 346.2 us at 4 096 boats, choppy 0.5, seakeeping on",
     "device": "NVIDIA H200", "date": "2026-11-27", "triangles_per_s": 4096 * 2024 / 346.2e-6, "same_pass": False,
     "code": "the real hull with seakeeping, before issue 33's second pass (heading frame, fitted wave-point "
             "weights, vertices ordered by side and height, the inversion started from the origin's estimate)"},
]


# --- the E-Boat's pass ---------------------------------------------------------------------------------------
def compile_hull_pass_ptx(vertex_rounds: int, block_dim: int, arch: int = 90) -> str:
    """PTX of the E-Boat's hull kernel (wave points on, no current) for sm_``arch``, through Warp's NVRTC."""
    import warp as wp

    from ocean_warp.kernels.hull_forces import hull_wrenches_kernel

    kernel = hull_wrenches_kernel(vertex_rounds, block_dim, wave_points=True, currents=False)
    with tempfile.TemporaryDirectory() as folder:
        paths = wp.compile_aot_module(kernel.module, arch=arch, use_ptx=True, module_dir=folder)
        return Path(paths[0]).read_text(errors="replace")


def eboat_shape(boats: int, block_dim: int, cell: float) -> tuple[HullPassShape, dict]:
    """The E-Boat's pass at rest on still water (its hull's vertices and triangles classified by the waterline
    there) and the triangle mix."""
    from ocean_warp.eboat import EBoat, EBoatConfig
    from ocean_warp.eboat.eboat import eboat_hull_mesh
    from ocean_warp.kernels.hull_forces import WAVE_POINTS
    from ocean_warp.ocean_config import OceanConfig

    config = EBoatConfig(seakeeping=True)
    hull = eboat_hull_mesh(config)
    height = EBoat(config).rest_height()
    z = hull.vertices[:, 2] + height
    depths = [0.0] + [-d for d in OceanConfig().pressure_depths] + [-np.inf]
    wet_corners = (z[hull.triangles] < 0.0).sum(axis=1)
    mix = {"dry": float(np.mean(wet_corners == 0)), "wet": float(np.mean(wet_corners == 3)),
           "cut_one_piece": float(np.mean(wet_corners == 1)), "cut_two_pieces": float(np.mean(wet_corners == 2))}
    shape = HullPassShape(
        vertices=hull.vertex_count, triangles=hull.triangle_count, boats=boats, block_dim=block_dim,
        wave_points=int(WAVE_POINTS), inversion_steps=1.0, origin_inversion_steps=2.0,
        depth_bands=tuple(float(np.mean((z < upper) & (z >= lower))) for upper, lower in zip(depths, depths[1:])),
        footprint_nodes=footprint_nodes(hull.vertices[:, :2], cell), fields_read=6)
    return shape, {"mix": mix, "rest_height_m": height}


# Hand count of one fully wet triangle from the source (kernels/hull_forces.py), flops as above; the physics
# profile's branches: cross flow only, falloff 0.5 (sqrt), skin friction on, slamming off.
HAND_COUNT_WET = {
    "area vector 0.5 (r1 - r0) x (r2 - r0)": 6 + 9 + 3,
    "area |A| (3 mul, 2 add, sqrt)": 6,
    "normal A / |A|": 3,
    "pressures rho g d_i, their sum": 1 + 3 + 2,
    "force -(sum / 3) A": 1 + 3,
    "centre-of-pressure moment (A/12)(sum p_i r_i + sum p (r0 + r1 + r2))": 1 + 9 + 6 + 6 + 3 + 3 + 3,
    "moment n x that": 9,
    "centroid (r0 + r1 + r2) / 3 (sum shared with the above)": 3,
    "relative velocity v + w x c - (u0 + u1 + u2) / 3": 9 + 3 + 6 + 3 + 3,
    "speed |relative|": 6,
    "cross-flow speed (2 mul, 1 add, sqrt)": 4,
    "cos t = n . flow / |flow|": 5 + 1,
    "s, pressure (a + b s) s, falloff sqrt": 1 + 3 + 1,
    "drag -(p f A) n": 2 + 3,
    "tangential flow v - (v . n) n": 5 + 3 + 3,
    "friction 0.5 rho (1 + k) C_F A |t| t": 6 + 5 + 3 + 3,
    "force += drag, moment += c x drag": 3 + 9 + 3,
    "piece total and the thread's total (two vec6 sums)": 12,
}


def build_report(boats: int = 4096, block_dim: int = 128, cell: float = 1.0) -> dict:
    """The whole count for ``boats`` E-Boats on a grid of ``cell`` [m] (the benchmark's 512 m over 512 nodes)."""
    shape, rest = eboat_shape(boats, block_dim, cell)
    vertex_rounds = -(-shape.vertices // block_dim)
    paths = hull_pass_paths(compile_hull_pass_ptx(vertex_rounds, block_dim), block_dim, shape.wave_points)
    bytes_ = hull_pass_bytes(shape)
    mix = rest["mix"]
    triangle_flops = sum(mix[k] * paths["triangle"][k]["flops"] for k in mix)
    triangle_sfu = sum(mix[k] * paths["triangle"][k]["sfu"] for k in mix)
    below = sum(shape.depth_bands)
    vertex = paths["vertex"]
    vertex_flops = (1 - below) * vertex["above_water"]["flops"] + below * vertex["submerged"]["flops"]
    vertex_sfu = (1 - below) * vertex["above_water"]["sfu"] + below * vertex["submerged"]["sfu"]
    per_boat_flops = (shape.triangles * triangle_flops + shape.vertices * vertex_flops
                      + paths["boat"]["total"]["flops"])
    per_boat_sfu = shape.triangles * triangle_sfu + shape.vertices * vertex_sfu + paths["boat"]["total"]["sfu"]
    flops_per_triangle = per_boat_flops / shape.triangles
    sfu_per_triangle = per_boat_sfu / shape.triangles
    peaks = peak_rates(H100_SXM)
    per_triangle_bytes = bytes_["per_triangle"]
    bounds = {
        "fp32": peaks["fp32_flops_per_s"] / flops_per_triangle,
        "sfu": peaks["sfu_per_s"] / sfu_per_triangle,
        "shared_and_l1": peaks["shared_bytes_per_s"]
        / (per_triangle_bytes["shared"] + per_triangle_bytes["l1_requests"]),
        "hbm": peaks["hbm_bytes_per_s"] / per_triangle_bytes["dram"],
    }
    roof = min(bounds.values())
    measured = [dict(m, fraction_of_this_passs_roof_if_it_ran_at_that_rate=m["triangles_per_s"] / roof)
                for m in MEASURED]
    hand = sum(HAND_COUNT_WET.values())
    return {
        "pass": "hull_wrenches_kernel: E-Boat physics profile, real hull, seakeeping on (33 wave points), no "
                "current, choppy sea, 128 threads a boat, fast math, 128 registers; PTX for sm_90 from NVRTC",
        "shape": dataclasses.asdict(shape), "rest": rest,
        "flops_ptx": paths,
        "hand_count_wet_triangle": {"terms": HAND_COUNT_WET, "total": hand,
                                    "ptx_wet_triangle": paths["triangle"]["wet"]["flops"]},
        "per_triangle": {"flops": flops_per_triangle, "sfu": sfu_per_triangle,
                         "bytes": per_triangle_bytes,
                         "flops_per_dram_byte": flops_per_triangle / per_triangle_bytes["dram"],
                         "flops_per_shared_and_l1_byte": flops_per_triangle
                         / (per_triangle_bytes["shared"] + per_triangle_bytes["l1_requests"])},
        "bytes_per_boat": bytes_["per_boat"], "mesh_bytes": bytes_["mesh_bytes"],
        "gpu": H100_SXM, "peaks": peaks,
        "bounds_triangles_per_s": bounds, "roof_triangles_per_s": roof,
        "roof_pass_time_s": boats * shape.triangles / roof,
        "measured": measured,
        "note": "No measured rate is of this pass: each fraction applies this pass's counts to another pass's rate "
                "and is an estimate, not a measurement.",
    }


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.perf.hull_pass_roofline", description=__doc__.split(
        "\n\n")[0])
    parser.add_argument("--json", default=str(DEFAULT_JSON), help="where to write the counts")
    parser.add_argument("--boats", type=int, default=4096)
    args = parser.parse_args(argv)
    if args.boats < 1:
        parser.error(f"--boats must be at least 1, got {args.boats}")
    report = build_report(args.boats)
    t = report["flops_ptx"]["triangle"]
    v = report["flops_ptx"]["vertex"]
    per = report["per_triangle"]
    print("flops (sfu) per triangle path: " + ", ".join(f"{k} {t[k]['flops']} ({t[k]['sfu']})" for k in t))
    print("flops (sfu) per vertex: " + ", ".join(f"{k} {v[k]['flops']} ({v[k]['sfu']})" for k in v if v[k]))
    print(f"per boat outside the loops: {report['flops_ptx']['boat']['total']}")
    print(f"hand count, wet triangle: {report['hand_count_wet_triangle']['total']} flops "
          f"(PTX: {t['wet']['flops']})")
    print(f"triangle mix at rest: {report['rest']['mix']}")
    print(f"all-in per triangle: {per['flops']:.1f} flops, {per['sfu']:.1f} SFU, bytes "
          + ", ".join(f"{k} {b:.1f}" for k, b in per["bytes"].items())
          + f"; {per['flops_per_dram_byte']:.0f} flop/DRAM byte, {per['flops_per_shared_and_l1_byte']:.2f} "
            "flop/(shared + L1) byte")
    for name, bound in report["bounds_triangles_per_s"].items():
        print(f"  {name:>14} roof: {bound / 1e9:7.1f} G triangles/s")
    print(f"roof: {report['roof_triangles_per_s'] / 1e9:.1f} G triangles/s, "
          f"{report['roof_pass_time_s'] * 1e6:.1f} us for {args.boats} boats")
    for m in report["measured"]:
        print(f"  {m['what']} ({m['device']}, {m['date']}): {m['triangles_per_s'] / 1e9:.1f} G/s, "
              f"{100 * m['fraction_of_this_passs_roof_if_it_ran_at_that_rate']:.0f} % of this pass's roof "
              "(another pass: an estimate)")
    with atomic_output(args.json) as temporary:
        Path(temporary).write_text(json.dumps(report, indent=1, default=float) + "\n")
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
