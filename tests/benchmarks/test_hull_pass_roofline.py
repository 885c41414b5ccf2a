"""The hull pass's roofline counters (benchmarks/perf/hull_pass_roofline.py).

- The byte counter on a tiny synthetic pass whose bytes are worked by hand below.
- The PTX counter on a hand-written PTX entry (3 fma and 1 add in a loop behind a branch) and on the PTX that
  Warp's NVRTC emits for a kernel doing exactly 3 multiply-adds and 1 add (skipped where NVRTC is missing).
"""

import numpy as np
import pytest

from benchmarks.perf import hull_pass_roofline as roof


def test_bytes_of_a_tiny_pass_worked_by_hand():
    shape = roof.HullPassShape(vertices=4, triangles=2, boats=2, block_dim=2, wave_points=1, inversion_steps=1.0,
                               origin_inversion_steps=2.0, depth_bands=(0.25, 0.25, 0.0, 0.0), footprint_nodes=9.0,
                               fields_read=3)
    # A vertex: 12 (position) + 32 (one displacement lookup) + 64 (height and velocity) + 0.25 x 16 + 0.25 x 32.
    assert roof.vertex_request_bytes(shape) == pytest.approx(12 + 32 + 64 + 4 + 8)
    # Each of 2 threads: state 4 + 12 + 16 + 24, type table 24, origin (2 + 4) x 32 + 64 = 292 -> 336;
    # one wave point 8 + 96 + 32 + 64 = 200; seakeeping read 24; stores 12 + 24 + 48.
    assert roof.boat_request_bytes(shape) == pytest.approx(2 * 336 + 200 + 24 + 84)
    counted = roof.hull_pass_bytes(shape)
    # Shared: 2 triangles x 3 corners x 16 + 4 vertices x 16.
    assert counted["per_boat"]["shared"] == 160
    assert counted["per_triangle"]["shared"] == 80
    # L1: 2 triangles x (12 + 36) + 4 x 120 + 980.
    assert counted["per_boat"]["l1_requests"] == pytest.approx(96 + 480 + 980)
    # DRAM: state 56 + 24 + 36 + 48, ocean 9 x 3 x 8, the mesh (48 + 24 + 104) over 2 boats.
    assert counted["mesh_bytes"] == 176
    assert counted["per_boat"]["dram"] == pytest.approx(164 + 216 + 88)
    assert counted["per_triangle"]["dram"] == pytest.approx(234)


def test_footprint_of_a_square_plan():
    # A 2 m square, axis-aligned (one heading): a/cell + 2 nodes a side, (2 + 2)^2 on a 1 m grid, (4 + 2)^2 on
    # a 0.5 m one; turned 45 deg its box is 2 sqrt(2) a side: (2 sqrt(2) + 2)^2.
    square = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]
    assert roof.footprint_nodes(np.array(square), 1.0, headings=1) == pytest.approx(16.0)
    assert roof.footprint_nodes(np.array(square), 0.5, headings=1) == pytest.approx(36.0)
    # headings=4 averages 0, 45, 90 and 135 deg.
    assert roof.footprint_nodes(np.array(square), 1.0, headings=4) == pytest.approx(
        (2 * 16.0 + 2 * (2 * np.sqrt(2) + 2) ** 2) / 4)


HAND_PTX = """
.version 8.0
.target sm_90
.visible .entry tiny(
    .param .u64 tiny_param_0
)
{
    .reg .pred %p<3>;
    .reg .f32 %f<9>;
    .reg .b32 %r<4>;
    ld.param.u64 %rd1, [tiny_param_0];
    ld.global.f32 %f1, [%rd1];
    setp.gt.f32 %p1, %f1, 0f00000000;
    @%p1 bra $L__skip;
$L__loop:
    fma.rn.f32 %f2, %f1, %f1, 0f3F800000;
    fma.rn.f32 %f3, %f2, %f1, 0f40000000;
    fma.rn.f32 %f4, %f3, %f1, 0f40400000;
    add.f32 %f5, %f4, %f1;
    setp.lt.s32 %p2, %r1, 4;
    @%p2 bra $L__loop;
$L__skip:
    sqrt.approx.f32 %f6, %f1;
    st.global.v2.f32 [%rd1], {%f5, %f6};
    ret;
}
"""


def test_ptx_counter_on_a_hand_written_entry():
    blocks = roof.parse_blocks(HAND_PTX)
    assert roof.instruction_counts("fma.rn.ftz.f32 %f1, %f2, %f3, %f4;")["flops"] == 2
    assert roof.instruction_counts("ld.global.v4.f32 {%f1, %f2, %f3, %f4}, [%rd1];")["global_load_bytes"] == 16
    loop = next(i for i, b in enumerate(blocks) if b.label == "$L__loop")
    assert roof.back_edges(blocks) == [(loop, loop)]
    body = roof.block_counts(blocks[loop])
    assert (body["flops"], body["fp32_instructions"], body["sfu"]) == (7, 4, 0)
    end = len(blocks) - 1
    longest = roof.extreme_path(blocks, 0, end, longest=True, include_stop=True)
    shortest = roof.extreme_path(blocks, 0, end, longest=False, include_stop=True)
    # Through the loop once: 3 fma (6) + 1 add + the sqrt; around it: the sqrt alone.
    assert (longest["flops"], longest["sfu"]) == (8, 1)
    assert (shortest["flops"], shortest["sfu"]) == (1, 1)
    assert longest["global_load_bytes"] == 4 and longest["global_store_bytes"] == 8
    assert sorted(p["flops"] for p in roof.all_paths(blocks, 0, end)) == [1, 8]


def test_ptx_counter_on_a_warp_kernel():
    wp = pytest.importorskip("warp")
    import tempfile
    from pathlib import Path

    @wp.kernel(module="unique", enable_backward=False)
    def three_fma_one_add(a: wp.array(dtype=float), b: wp.array(dtype=float)):
        i = wp.tid()
        x = a[i]
        y = x * x + 1.0
        y = y * x + 2.0
        y = y * x + 3.0
        b[i] = y + x

    with tempfile.TemporaryDirectory() as folder:
        try:
            paths = wp.compile_aot_module(three_fma_one_add.module, arch=90, use_ptx=True, module_dir=folder)
        except Exception as error:  # no NVRTC in this Warp build
            pytest.skip(f"no PTX for sm_90 here: {error}")
        ptx = Path(paths[0]).read_text(errors="replace")
    blocks = roof.parse_blocks(ptx)
    # Warp's launch loop holds the body once on each of its two ways; each way does 3 fma and 1 add.
    bodies = [roof.block_counts(b) for b in blocks if roof.block_counts(b)["flops"]]
    assert bodies and all((c["flops"], c["fp32_instructions"]) == (7, 4) for c in bodies)
    assert all(sum(ins.startswith("fma.rn") for ins in b.instructions) == 3 for b in blocks
               if roof.block_counts(b)["flops"])
