#!/usr/bin/env bash
# GPU session: the CUDA half of the test suite, then the benchmarks, logs and JSON into $OUT (or ./out/gpu).
# Usage on a CUDA machine with the project installed:  bash benchmarks/run_gpu.sh [stage ...]
# Stages: tests, ocean, sweep, passes, ocean_cpu, hull, hull_flat, hull_blocks, eboat, breakdown, polar, envs, mission (default: all).
set -uo pipefail
out=${OUT:-out/gpu}
mkdir -p "$out"
stages=${*:-tests ocean sweep passes ocean_cpu hull hull_flat hull_blocks eboat breakdown polar envs mission}
export PYTHONUNBUFFERED=1
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee "$out/gpu.txt"
for stage in $stages; do
  start=$(date +%s)
  case $stage in
    tests) timeout 400 python -m pytest -q --device cuda tests 2>&1 | tail -n 30 | tee "$out/tests.txt" ;;
    ocean) timeout 240 python -m benchmarks.perf.bench_ocean --device cuda:0 --sizes 256 512 1024 --json "$out/ocean.json" 2>&1 | tee "$out/ocean.txt" ;;
    sweep) timeout 300 python -m benchmarks.perf.bench_ocean --device cuda:0 --sizes 512 --sweep 256 512 1024 --json "$out/sweep.json" 2>&1 | tee "$out/sweep.txt" ;;
    ocean_cpu) timeout 200 python -m benchmarks.perf.bench_ocean --device cpu --sizes 256 512 --json "$out/ocean_cpu.json" 2>&1 | tee "$out/ocean_cpu.txt" ;;
    passes) timeout 200 python -m benchmarks.perf.ocean_passes --sizes 256 512 1024 2>&1 | tee "$out/passes.txt" ;;
    hull) timeout 420 python -m benchmarks.perf.bench_hull --device cuda:0 --json "$out/hull.json" 2>&1 | tee "$out/hull.txt" ;;
    hull_flat) timeout 200 python -m benchmarks.perf.bench_hull --device cuda:0 --boats 4096 16384 --triangles 2000 --choppiness 0 --json "$out/hull_flat.json" 2>&1 | tee "$out/hull_flat.txt" ;;
    hull_blocks) timeout 200 python -m benchmarks.perf.bench_hull --device cuda:0 --boats 4096 --triangles 500 2000 8000 --block-dim 32 64 128 256 2>&1 | tee "$out/hull_blocks.txt" ;;
    eboat) timeout 400 python -m benchmarks.perf.bench_eboat --device cuda:0 --json "$out/eboat.json" 2>&1 | tee "$out/eboat.txt"
           timeout 300 python -m benchmarks.perf.bench_eboat --device cuda:0 --choppiness 0 --json "$out/eboat_flat.json" 2>&1 | tee "$out/eboat_flat.txt" ;;
    breakdown) timeout 300 python -m benchmarks.perf.eboat_breakdown --device cuda:0 --choppiness 0 2>&1 | tee "$out/breakdown.txt"
               timeout 300 python -m benchmarks.perf.eboat_breakdown --device cuda:0 --choppiness 0.5 2>&1 | tee -a "$out/breakdown.txt" ;;
    polar) timeout 300 python -m ocean_warp.examples.polar_chart --device cuda:0 --angle-step 10 --sheet-step 10 --out "$out/polar" 2>&1 | tee "$out/polar.txt" ;;
    envs) timeout 420 python -m benchmarks.perf.bench_envs --device cuda:0 --envs 1024 4096 16384 65536 --json "$out/envs.json" 2>&1 | tee "$out/envs.txt"
          timeout 240 python -m benchmarks.perf.bench_envs --device cuda:0 --envs 4096 16384 --dt 0.1 --interfaces core rsl_rl --json "$out/envs_dt01.json" 2>&1 | tee "$out/envs_dt01.txt" ;;
    mission) timeout 400 python -m benchmarks.studies.autopilot_mission --device cuda:0 --runs 20 2>&1 | tee "$out/mission.txt" ;;
    *) echo "unknown stage $stage" ;;
  esac
  echo "stage $stage took $(( $(date +%s) - start )) s"
done
