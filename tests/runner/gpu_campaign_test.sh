#!/usr/bin/env bash
# ctest GpuCampaign: experiments/gpu_campaign.sh as a GPU machine runs it, on lavapipe at a tiny
# size and on one scene of one config (the whole campaign takes minutes here: experiments/README.md
# "The GPU campaign"). Its bundle as a folder holds the program, the five configs, their models
# and the script; from there, in another folder, `run` writes the result set, its table with the
# device under it and its report, drops the images beyond --max-mib after the report, and removes
# its cache, and packs it; a time limit that falls while a config runs stops it, keeps a result set
# of what finished, with the hybrids' rays launched full, and packs it in time; a bench that fails
# or hangs stops the campaign with its log (exit 4), packed; an NVIDIA machine whose GPU Vulkan does
# not find keeps the loader's account (exit 5); bad arguments exit 2 naming them.
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
            "run $work/bad --bench-s soon" "run $work/bad --repeat nothing:1" "run $work/bad --repeat macedo2019" \
            "run $work/bad --limit-s 30" "run $work/bad --deadline-s 451" "run $work/bad --limit-s 100 --deadline-s 80" \
            "run $work/bad --launch half"; do
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
# that config once more for the verdict's repeatability. The bench takes 12 s here at a low load and
# minutes at a load of 20: its bound is the machine's, not the test's.
skip=bunnies-falling-10,bunnies-falling-15,bunnies-falling-20,bunnies-falling-25,bunnies-falling-30
skip=$skip,teapots-deforming-5,teapots-deforming-10,teapots-deforming-15,teapots-deforming-20,teapots-deforming-25,teapots-deforming-30
mkdir -p "$work/elsewhere"
(cd "$work/elsewhere" && HYBRIDLAB_CHECKOUT=$source_dir "$work/bundle/gpu_campaign.sh" run "$work/out" --only macedo2019 \
   --skip-scenes "$skip" --scale 0.0625 --max-mib 1 --repeat macedo2019:1 --limit-s 1800 --bench-s 900 --pack "$work/packed") >"$work/run.txt" 2>&1 ||
  fail "run: $(tail -n 30 "$work/run.txt")"
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

expect_in "$work/run.txt" "packed: out.tar.xz.aa ("
mkdir -p "$work/unpacked" && cat "$work/packed/out.tar.xz."* | tar xJf - -C "$work/unpacked" || fail "the pack does not unpack"
cmp -s "$work/out/campaign.log" "$work/unpacked/out/campaign.log" || fail "the packed campaign.log differs from the campaign's"
[ "$(ls "$work/unpacked/out/macedo2019/runs" | grep -c '\.json$')" -eq 3 ] || fail "expected 3 runs in the packed set"

# `finish` on that folder: the table again, and no report without the images.
"$script" finish "$work/out" >"$work/finish.txt" 2>&1 || fail "finish: $(cat "$work/finish.txt")"
expect_in "$work/finish.txt" "report: none, the images were dropped"

# A time limit that falls while the config runs: the whole config (twelve scenes, 36 runs; on the
# fastest CPU seen, 2 s a run) against 60 s, whose last 30 are the packing's, so that no machine
# finishes it first; stopped at the deadline that leaves, what finished kept as a result set, no
# time taken for the tables, packed, the whole within the limit. With the fallback's full launch:
# the config copy and the records say launch = "full".
t0=$SECONDS
HYBRIDLAB=$hybridlab "$script" run "$work/out2" --only macedo2019 --scale 0.0625 --limit-s 60 --bench-s 0 --repeat none \
  --launch full --pack "$work/packed2" >"$work/run2.txt" 2>&1 || fail "run with a time limit: $(tail -n 30 "$work/run2.txt")"
took=$((SECONDS - t0))
[ "$took" -le 62 ] || fail "run with --limit-s 60 took $took s"
expect_in "$work/out2/campaign.log" "deadline 30 s, limit 60 s"
expect_in "$work/out2/campaign.log" "macedo2019: stopped at the deadline after "
expect_in "$work/out2/campaign.log" "tables and reports: no time left before the limit (60 s)"
[ -f "$work/out2/macedo2019/results.json" ] || fail "no results.json after the deadline"
expect_in "$work/out2/configs/macedo2019.toml" 'params = { launch = "full", importance_cutoff = 0.0, rays = "vulkan" }'
expect_in "$work/out2/macedo2019/results.json" '"launch": "full"'
mkdir -p "$work/unpacked2" && cat "$work/packed2/out2.tar.xz."* | tar xJf - -C "$work/unpacked2" || fail "the time-limited pack does not unpack"
expect_in "$work/unpacked2/out2/campaign.log" "macedo2019: stopped at the deadline after "
echo "time limit: $took s of 60"

# A bench that fails (a stand-in program whose bench exits as a lost device would) stops the
# campaign at once, its log printed and packed, the fallback named; one that hangs is stopped at the
# deadline the limit leaves (70 s, less 30 for the packing) and stops it alike.
mkdir -p "$work/fake"
cat >"$work/fake/hybridlab" <<EOF
#!/usr/bin/env bash
if [ "\$1" = bench ]; then
  [ "\${FAKE_BENCH:-}" = hang ] && exec sleep 600
  echo "device traces per ray (a first line)"
  echo "Vulkan: VK_ERROR_DEVICE_LOST in the compacted launch" >&2
  exit 1
fi
exec "$hybridlab" "\$@"
EOF
chmod +x "$work/fake/hybridlab"
for mode in fail hang; do
  t0=$SECONDS
  FAKE_BENCH=$mode HYBRIDLAB=$work/fake/hybridlab "$script" run "$work/out-$mode" --only macedo2019 --scale 0.0625 --limit-s 70 \
    --pack "$work/packed-$mode" >"$work/run-$mode.txt" 2>&1
  status=$?
  took=$((SECONDS - t0))
  [ "$status" -eq 4 ] || fail "a bench that does $mode: exit status $status, expected 4: $(tail -n 20 "$work/run-$mode.txt")"
  [ "$took" -le 72 ] || fail "a bench that does $mode: the campaign took $took s of its 70 s limit"
  expect_in "$work/out-$mode/campaign.log" "the campaign stopped there"
  expect_in "$work/run-$mode.txt" "gpu_campaign.sh run OUT2 --launch full"
  [ ! -e "$work/out-$mode/macedo2019" ] || fail "a bench that does $mode: the campaign went on to the configs"
  [ -f "$work/packed-$mode/out-$mode.tar.xz.aa" ] || fail "a bench that does $mode: not packed"
  echo "bench that does $mode: stopped after $took s"
done
expect_in "$work/run-fail.txt" "VK_ERROR_DEVICE_LOST in the compacted launch"
expect_in "$work/out-hang/campaign.log" "bench: stopped at its "
expect_in "$work/out-fail/campaign.log" "bench: failed (exit status 1) after "

# A machine with an NVIDIA GPU (a stand-in nvidia-smi) whose Vulkan device is lavapipe: stopped
# before the bench, with the loader's own account of its drivers kept.
printf '#!/bin/sh\necho "NVIDIA H200"\n' >"$work/fake/nvidia-smi" && chmod +x "$work/fake/nvidia-smi"
PATH=$work/fake:$PATH HYBRIDLAB=$hybridlab "$script" run "$work/out-nogpu" --only macedo2019 --pack "$work/packed-nogpu" \
  >"$work/run-nogpu.txt" 2>&1
status=$?
[ "$status" -eq 5 ] || fail "no NVIDIA Vulkan device: exit status $status, expected 5: $(tail -n 20 "$work/run-nogpu.txt")"
expect_in "$work/run-nogpu.txt" "The loader's account: "
grep -qi "loader" "$work/out-nogpu/logs/vulkan_loader.log" || fail "logs/vulkan_loader.log holds no loader messages"
[ ! -e "$work/out-nogpu/bench.txt" ] || fail "no NVIDIA Vulkan device: the bench ran"
[ -f "$work/packed-nogpu/out-nogpu.tar.xz.aa" ] || fail "no NVIDIA Vulkan device: not packed"
echo "GpuCampaign: passed"
