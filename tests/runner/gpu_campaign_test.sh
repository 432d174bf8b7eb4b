#!/usr/bin/env bash
# ctest GpuCampaign: experiments/gpu_campaign.sh as a GPU machine runs it, on lavapipe at a tiny
# size and on one scene of one config (the whole campaign takes minutes here: experiments/README.md
# "The GPU campaign"). Its bundle as a folder holds the program, the five configs, their models
# and the script; from there, in another folder, `run` writes the result set, its table with the
# device under it and its report, drops the images beyond --max-mib after the report, and removes
# its cache; a deadline stops a config while it runs and keeps a result set of what finished; bad
# arguments exit 2 naming them.
#
#   gpu_campaign_test.sh HYBRIDLAB_BINARY SOURCE_DIR
set -uo pipefail
hybridlab=$(realpath "$1")
source_dir=$(realpath "$2")
unset HYBRIDLAB_ASSETS HYBRIDLAB_SCENES HYBRIDLAB_CACHE
work=$(mktemp -d /tmp/hybridlab-gpu-campaign.XXXXXX) || { echo "FAILED: no temporary folder"; exit 1; }
trap 'rm -rf "$work"' EXIT

fail() {
  echo "FAILED: $*"
  for f in "$work"/out*/campaign.log "$work"/out*/logs/*.log; do
    [ -f "$f" ] && { echo "--- $f (last 30 lines)"; tail -n 30 "$f"; }
  done
  exit 1
}
expect_in() {  # FILE TEXT
  grep -qF -- "$2" "$1" || fail "$1 lacks '$2'"
}

# Bad arguments: exit 2 and the reason, nothing written.
script=$source_dir/experiments/gpu_campaign.sh
for args in "run" "run $work/bad --scale 2" "run $work/bad --only nothing" "run $work/bad --deadline-s 0" "run $work/bad --frobnicate" \
            "run $work/bad --bench-s soon" "run $work/bad --repeat nothing:1" "run $work/bad --repeat macedo2019"; do
  HYBRIDLAB=$hybridlab "$script" $args >"$work/bad.txt" 2>&1
  status=$?
  [ "$status" -eq 2 ] || fail "gpu_campaign.sh $args: exit status $status, expected 2: $(cat "$work/bad.txt")"
  grep -q '^gpu_campaign: ' "$work/bad.txt" || fail "gpu_campaign.sh $args: no message: $(cat "$work/bad.txt")"
  [ ! -e "$work/bad" ] || fail "gpu_campaign.sh $args wrote $work/bad"
done

# The bundle, as a folder (a .tar.xz of it is what travels; xz alone takes a minute here).
HYBRIDLAB=$hybridlab "$script" bundle "$work/bundle" >"$work/bundle.txt" 2>&1 || fail "bundle: $(cat "$work/bundle.txt")"
for f in hybridlab gpu_campaign.sh configs/walewski2019.toml configs/sabino2012.toml configs/macedo2019.toml configs/hakura2001.toml \
         configs/gbuffer_rays_gpu.toml scenes/assets/sponza scenes/assets/armadillo scenes/assets/dining_room scenes/assets/bunny \
         scenes/assets/teapot; do
  [ -e "$work/bundle/$f" ] || fail "the bundle lacks $f"
done

# From the bundle, in another folder, with the checkout named for the tables and the report: the
# device traces per ray (bench), one scene of macedo2019 (three frames of its orbit) at 80x45, and
# that config once more for the verdict's repeatability.
skip=bunnies-falling-10,bunnies-falling-15,bunnies-falling-20,bunnies-falling-25,bunnies-falling-30
skip=$skip,teapots-deforming-5,teapots-deforming-10,teapots-deforming-15,teapots-deforming-20,teapots-deforming-25,teapots-deforming-30
mkdir -p "$work/elsewhere"
(cd "$work/elsewhere" && HYBRIDLAB_CHECKOUT=$source_dir "$work/bundle/gpu_campaign.sh" run "$work/out" --only macedo2019 \
   --skip-scenes "$skip" --scale 0.0625 --max-mib 1 --repeat macedo2019:1) >"$work/run.txt" 2>&1 || fail "run: $(tail -n 30 "$work/run.txt")"
set_dir=$work/out/macedo2019
[ "$(ls "$set_dir/runs" | grep -c '\.json$')" -eq 3 ] || fail "expected 3 runs in $set_dir/runs"
[ -f "$set_dir/results.json" ] || fail "no results.json"
expect_in "$set_dir/tables.md" "Table I"
expect_in "$set_dir/tables.md" "Measured on: "
[ -f "$set_dir/report/index.html" ] || fail "no report"
expect_in "$work/out/campaign.log" "dropped the images of macedo2019 to stay under 1 MiB"
[ ! -e "$set_dir/images" ] || fail "the images were kept over --max-mib"
expect_in "$work/out/campaign.log" "macedo2019: "
expect_in "$work/out/campaign.log" " s, 3 runs"
expect_in "$work/out/device.json" '"vulkan_device"'
[ ! -e "$work/out/cache" ] || fail "the campaign's cache was left in its folder"
grep -q "bunnies-falling-10" "$work/out/configs/macedo2019.toml" && fail "--skip-scenes left bunnies-falling-10 in"
expect_in "$work/out/bench.txt" "device traces per ray"
expect_in "$work/out/bench.txt" "heuristic_rt, gbuffer raster, compact"
expect_in "$work/out/campaign.log" "repeats: macedo2019 run 2, "
[ "$(ls "$work/out/repeats/run-2/runs" | grep -c '\.json$')" -eq 3 ] || fail "expected 3 runs in the repeated set"
[ ! -e "$work/out/repeats/run-2/images" ] || fail "the repeated set kept its images"
expect_in "$work/out/repeats/verdicts.txt" "verdict rows identical in all 2 runs"
expect_in "$work/out/campaign.log" "verdict rows identical in all 2 runs"

# `finish` on that folder: the table again, and no report without the images.
"$script" finish "$work/out" >"$work/finish.txt" 2>&1 || fail "finish: $(cat "$work/finish.txt")"
expect_in "$work/finish.txt" "report: none, the images were dropped"

# A deadline that falls while the config runs: the whole config (twelve scenes, 36 runs; on the
# fastest CPU seen, 2 s a run) against 25 s, so that no machine finishes it first; stopped, what
# finished kept as a result set.
HYBRIDLAB=$hybridlab "$script" run "$work/out2" --only macedo2019 --scale 0.0625 --deadline-s 25 --bench-s 0 --repeat none \
  >"$work/run2.txt" 2>&1 || fail "run with a deadline: $(tail -n 30 "$work/run2.txt")"
expect_in "$work/out2/campaign.log" "macedo2019: stopped at the deadline after "
[ -f "$work/out2/macedo2019/results.json" ] || fail "no results.json after the deadline"
echo "GpuCampaign: passed"
