#!/usr/bin/env bash
# Output matrix: run a fixed set of samplab commands and print one SHA-256 per output, so
# that two builds can be compared byte for byte (refactors must leave every line equal):
#
#   scripts/output_matrix.sh path/to/old/samplab > before.txt
#   scripts/output_matrix.sh target/release/samplab > after.txt
#   diff before.txt after.txt
#
# Covers every registered sampler (2D and 3D where it supports them, and warped), every
# metric, spectra (fast and direct), integration studies, renders in each mode, and the
# fast reproduction's claims and tables (its pages carry timings, so they are left out),
# and every pixel sampler.
set -euo pipefail
bin=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

hash() { sha256sum | cut -c1-16; }
row() { printf '%-90s %s\n' "$1" "$2"; }
run() { # run a command printing to stdout; hash its output (or its error and exit code)
  local out rc=0
  out=$("$bin" "$@" 2>&1) || rc=$?
  row "$*" "$(printf '%s\nrc=%s' "$out" "$rc" | hash)"
}

samplers=(random regular regular.rotated jitter jitter.half jitter.box:delta=0.2 jitter.gaussian:sigma=0.3
  jitter.gaussian:sigma=0.3,edge=resample jitter.uniform jitter.uniform:offsets=4 jitter.uniform-gaussian:0.5,0.2
  nrooks poisson poisson:radius=0.05,edge=plain poisson.fast poisson.maximal pmj02 cmj force-matrix:0.5,2
  sobol sobol.xor sobol.owen sobol.shift halton halton.xor halton.owen halton.shift
  hammersley hammersley.xor hammersley.owen hammersley.shift)
for s in "${samplers[@]}"; do
  run generate "$s" -n 64 --seed 11 --sets 2
  run generate "$s" -n 64 -d 3 --seed 12
done
for w in disk.polar disk.concentric disk.reject tent gaussian hemisphere.uniform hemisphere.cosine; do
  run generate jitter -n 64 --seed 13 --warp "$w"
done
for f in npy json csv; do
  "$bin" generate sobol.owen -n 100 --sets 3 --seed 14 -o "p.$f" >/dev/null 2>&1
  row "generate sobol.owen -o p.$f" "$(hash < "p.$f")"
done
# every registered sampler with its defaults, by the registry's own listing (the counts some
# cannot make are recorded as their errors), and random access against the batch
for s in $("$bin" list samplers | awk '/^[a-z]/ {print $1}'); do
  run generate "$s" -n 64 --seed 31
  run generate "$s" -n 55 -d 2 --seed 32
  run generate "$s" -n 27 -d 3 --seed 33
done
for s in kronecker+micro-jitter lattice.cbc.shift+micro-jitter:fraction=0.3 net.owen:matrices=/nonexistent; do
  run generate "$s" -n 64 --seed 34
done
run generate sobol -n 4294967297
run generate nosuch -n 4

metrics=(star extreme l2-star l2-extreme centered wraparound mixture star-bound:iterations=500,seed=3
  projected:angle=30,kind=extreme)
run discrepancy "${metrics[@]}" --sampler jitter -n 64 --sets 4 --seed 15 --json
run discrepancy star l2-star centered --sampler sobol.owen -n 100 -d 3 --sets 2 --seed 16 --json
run discrepancy star --sampler halton -n 64 -d 4 --seed 16

for extra in "" "--direct" "--theory"; do
  # shellcheck disable=SC2086
  "$bin" spectrum --sampler jitter.gaussian:sigma=0.25 -n 64 --sets 8 --res 32 --seed 17 $extra -o "spec$extra" >/dev/null 2>&1
  for f in spec"$extra"/*; do
    [[ $f == *.png || $f == *.svg ]] || row "spectrum $extra $(basename "$f")" "$(hash < "$f")"
  done
done

for i in quad delaunay-constant delaunay-linear zoneplate cosine:u=8 disk halfplane gaussian smooth; do
  run integrate --sampler random --sampler jitter --sampler sobol.owen --integrand "$i" -n 16,64 --sets 4 --instances 3 --seed 18 --json
done
run integrate --sampler jitter --sampler jitter.uniform --integrand step -n 8,32 --sets 4 --instances 3 --seed 19 --json

render() {
  local name=$1; shift
  "$bin" render "$@" --res 24x16 --seed 20 -o "$name.exr" >/dev/null 2>&1 || true
  row "render $*" "$(hash < "$name.exr" 2>/dev/null || echo missing)"
}
render a spheres --sampler jitter -n 4 --reference ref.exr --reference-samples 64
render b sphere-box --sampler sobol.owen -n 8 --mode direct
render c grids --sampler jitter.uniform -n 4 --pixel area --spp 4
render d sphere-box --mode obscurance --range 0.5 --sampler jitter -n 4
render e checker --pixel area --spp 4 --interleave 2x2 --area-sampler jitter
render f defocus --spp 4 -n 4
render g motion --spp 4 -n 4
render h all --pixel area --spp 4 -n 4 --mode direct --pixel-sampler zsobol

# every pixel sampler (the values of two frames)
for p in $("$bin" list pixels 2>/dev/null | grep -E '^[a-z]' | cut -d' ' -f1); do
  "$bin" pixels "$p" --res 9x7 --spp 4 --dims 6 --frames 2 --seed 22 -o "px.npy" >/dev/null 2>&1 || true
  row "pixels $p" "$(hash < px.npy 2>/dev/null || echo missing)"
  rm -f px.npy
done

"$bin" reproduce --seed 21 --out rep >/dev/null 2>&1
for f in rep/claims.json rep/tables/*.csv; do
  row "reproduce $(basename "$f")" "$(hash < "$f")"
done
