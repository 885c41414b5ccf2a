#!/usr/bin/env bash
# GPU session: the CUDA half of the test suite, then the benchmarks, logs and JSON into $OUT (or ./out/gpu).
# Usage on a CUDA machine with the project installed:  bash benchmarks/run_gpu.sh [stage ...]
# Stages: tests, ocean, sweep, passes, ocean_cpu (default: all).
set -uo pipefail
out=${OUT:-out/gpu}
mkdir -p "$out"
stages=${*:-tests ocean sweep passes ocean_cpu}
export PYTHONUNBUFFERED=1
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee "$out/gpu.txt"
for stage in $stages; do
  start=$(date +%s)
  case $stage in
    tests) timeout 300 python -m pytest -q -x --device cuda tests 2>&1 | tail -n 30 | tee "$out/tests.txt" ;;
    ocean) timeout 240 python benchmarks/bench_ocean.py --device cuda:0 --sizes 256 512 1024 --json "$out/ocean.json" 2>&1 | tee "$out/ocean.txt" ;;
    sweep) timeout 300 python benchmarks/bench_ocean.py --device cuda:0 --sizes 512 --sweep 256 512 1024 --json "$out/sweep.json" 2>&1 | tee "$out/sweep.txt" ;;
    ocean_cpu) timeout 200 python benchmarks/bench_ocean.py --device cpu --sizes 256 512 --json "$out/ocean_cpu.json" 2>&1 | tee "$out/ocean_cpu.txt" ;;
    passes) timeout 200 python benchmarks/ocean_passes.py --sizes 256 512 1024 2>&1 | tee "$out/passes.txt" ;;
    *) echo "unknown stage $stage" ;;
  esac
  echo "stage $stage took $(( $(date +%s) - start )) s"
done
