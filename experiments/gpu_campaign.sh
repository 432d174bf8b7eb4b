#!/usr/bin/env bash
# The GPU campaign: the papers' tables that are about a GPU's speed, in one command for a GPU
# machine lent for minutes (experiments/README.md "The GPU campaign").
#
#   gpu_campaign.sh bundle [FILE.tar.xz|DIR]  (here, in the checkout) the portable bundle with the
#                                          campaign's configs, their models and this script
#                                          (default out/hybridlab-gpu-campaign.tar.xz)
#   gpu_campaign.sh run OUT [--scale S] [--limit-s N] [--deadline-s N] [--pack DIR] [--max-mib M]
#                           [--only A,B] [--cache DIR] [--skip-scenes A,B] [--bench-s N]
#                           [--repeat NAME:K|none] [--launch compact|full]
#                                          the device traces per ray (`hybridlab bench`, OUT/bench.txt,
#                                          at most --bench-s, default 60; 0: none), every config of
#                                          configs/gpu_campaign/ into OUT/NAME, then NAME K more times
#                                          (default gbuffer_rays_gpu:1) into OUT/repeats/run-2.. for the
#                                          verdict's repeatability, then each one's table and report
#                                          where the Python packages are; all of it, OUT packed into
#                                          DIR/OUT.tar.xz.aa.. (--pack) included, within --limit-s
#   gpu_campaign.sh finish OUT             the tables and reports of a campaign folder, on a machine
#                                          set up by setup.sh (after a GPU machine that lacks them)
#
# `run` works from the checkout (build/hybridlab, experiments/configs/gpu_campaign/) or from the
# bundle (its hybridlab and configs/; the tables and reports then read the checkout in the working
# folder or $HYBRIDLAB_CHECKOUT). It ends, packed, within --limit-s (default 480): every program it
# starts is stopped at the limit, so that a hung driver cannot cost the results. It stops starting
# configs at --deadline-s (default: the limit less 30 s, for packing) and stops a config still
# running then, keeping its finished runs; then it keeps OUT under --max-mib (default 60) by
# dropping whole result sets' images, largest set first. Exit status: 0 the campaign ran (configs
# stopped at the deadline included), 2 bad arguments, 3 a folder could not be written, 4 the bench
# failed (the campaign stopped there: its log is printed; `--launch full` is the fallback that
# launches the hybrids' rays one invocation a texel), 5 this machine has an NVIDIA GPU that Vulkan
# does not find (the loader's own account in OUT/logs/vulkan_loader.log).
set -uo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
PYTHON=/usr/bin/python3

# name, config file, table script, estimated seconds on an H100/H200 at full size: per group a
# second of warm-up a setting and 1-2 s of rounds, per run about 1.5 s of scoring and files at
# 1280x720 on 16 cores, per reference about 1 s of Embree (references are rendered there: at
# 11 MB each at 1280x720 they do not fit in the transfer beside the bundle). The cheap ones first,
# so that a late deadline costs the largest.
CAMPAIGN=(
  "sabino2012 sabino2012.toml sabino_table3.py 30"
  "gbuffer_rays_gpu gbuffer_rays_gpu.toml gbuffer_rays_table.py 40"
  "hakura2001 hakura2001.toml hakura_tables.py 50"
  "walewski2019 walewski2019.toml walewski_tables.py 140"
  "macedo2019 macedo2019.toml macedo_tables.py 120"
)

die() { echo "gpu_campaign: $*" >&2; exit 2; }
usage() { sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; }

# Where the program and the configs are: a bundle has both beside this script.
if [ -x "$here/hybridlab" ] && [ -d "$here/configs" ]; then
  HYBRIDLAB=${HYBRIDLAB:-$here/hybridlab}
  CONFIGS=$here/configs
  CHECKOUT=${HYBRIDLAB_CHECKOUT:-$PWD}
else
  CHECKOUT=$(cd "$here/.." && pwd -P)
  HYBRIDLAB=${HYBRIDLAB:-$CHECKOUT/build/hybridlab}
  CONFIGS=$CHECKOUT/experiments/configs/gpu_campaign
fi

# Whether this machine can write the tables and reports: the checkout's scripts and the Debian
# Python packages setup.sh installs. Prints why not.
python_missing() {
  if [ ! -f "$CHECKOUT/paper_figures/walewski_tables.py" ]; then
    echo "no checkout at $CHECKOUT (set HYBRIDLAB_CHECKOUT)"
  elif [ ! -x "$PYTHON" ]; then
    echo "no $PYTHON"
  else
    "$PYTHON" -c 'import jsonschema, matplotlib, OpenImageIO' 2>&1 | tail -1 | grep . || true
  fi
}

mib() { du -sm "$1" | cut -f1; }
config_names() { for entry in "${CAMPAIGN[@]}"; do set -- $entry; printf '%s ' "$1"; done | sed 's/ $//'; }
# A size times the scale as the runner scales it: rounded, even, at least 16.
scaled_size() { awk -v x="$1" -v s="$2" 'BEGIN { v = int(x * s + 0.5); if (v % 2) v++; if (v < 16) v = 16; print v }'; }
records() { find "$1/runs" -maxdepth 1 -name '[!.]*.json' 2>/dev/null | wc -l; }

# A config without the [[scenes]] entries (with their views) of the scenes in the list "a,b".
without_scenes() {
  awk -v skip=",$2," '
    function flush() { if (!drop) printf "%s", block; block = ""; drop = 0 }
    /^\[\[scenes\]\]/ { flush(); inblock = 1 }
    /^\[/ && !/^\[\[scenes/ { flush(); inblock = 0 }
    inblock {
      block = block $0 "\n"
      if ($0 ~ /^scene *= *"/) { s = $0; sub(/^scene *= *"/, "", s); sub(/".*/, "", s); if (index(skip, "," s ",")) drop = 1 }
      next
    }
    { print }
    END { flush() }' "$1"
}

# The Python scripts, stopped at $PYTHON_UNTIL (seconds since the epoch) where it is set.
py() {
  if [ -n "${PYTHON_UNTIL:-}" ]; then
    timeout --signal=TERM --kill-after=5 $((PYTHON_UNTIL - $(date +%s) > 1 ? PYTHON_UNTIL - $(date +%s) : 1)) "$PYTHON" "$@"
  else
    "$PYTHON" "$@"
  fi
}

# The table and the report of one result set, each beside it, with the device record under the
# table (the table scripts print it). report.py is what `hybridlab report` runs, called directly
# because a bundle's program names the build machine's checkout.
tables_and_report() {
  local dir=$1 table=$2
  py "$CHECKOUT/paper_figures/$table" "$dir" --out "$dir/tables.md" >/dev/null &&
    echo "  table:  $dir/tables.md" || echo "  table:  $table failed (above)"
  if [ ! -d "$dir/images" ]; then
    echo "  report: none, the images were dropped to fit the size limit"
  elif py "$CHECKOUT/report/report.py" "$dir" --out "$dir/report" >/dev/null; then
    echo "  report: $dir/report/index.html"
  else
    echo "  report: report.py failed (above)"
  fi
}

# The bundle: `hybridlab bundle` with every config of the campaign, and this script beside its
# launcher. FILE.tar.xz: the folder packed (xz takes a 2-core machine under 2 minutes); any other
# name: the folder itself.
cmd_bundle() {
  local target=${1:-$CHECKOUT/out/hybridlab-gpu-campaign.tar.xz}
  [ -x "$HYBRIDLAB" ] || die "no program at $HYBRIDLAB: build it first (./setup.sh)"
  [ ! -e "$target" ] || die "$target: exists; choose another name or remove it"
  local folder=$target work="" args=()
  if [[ $target == *.tar.xz ]]; then
    work=$(mktemp -d) || exit 3
    # shellcheck disable=SC2064  # expanded now: $work is local to this function
    trap "rm -rf '$work'" EXIT
    folder=$work/$(basename "$target" .tar.xz)
  fi
  for entry in "${CAMPAIGN[@]}"; do
    set -- $entry
    args+=(--config "$CONFIGS/$2")
  done
  "$HYBRIDLAB" bundle --out "$folder" "${args[@]}" 2>&1 | grep -v '^warning:'
  [ "${PIPESTATUS[0]}" -eq 0 ] || exit "${PIPESTATUS[0]}"
  cp "$0" "$folder/gpu_campaign.sh" || exit 3
  if [ -n "$work" ]; then
    mkdir -p "$(dirname "$target")" &&
      tar -C "$work" -cf - "$(basename "$folder")" | xz -T0 -6 >"$target.tmp" && mv "$target.tmp" "$target" || exit 3
    echo "gpu_campaign: $target, $(du -m "$target" | cut -f1) MiB"
  fi
  echo "run: $(basename "$folder")/gpu_campaign.sh run OUT   (from the folder that holds it)"
}

# A config whose hybrids on the device (heuristic_rt and ssr_fallback with rays = "vulkan") launch
# their rays one invocation a texel (launch = "full") instead of over the classified texels.
with_full_launch() {
  awk '
    /^\[\[techniques\]\]/ { hybrid = 0; intech = 1 }
    /^\[/ && !/^\[\[techniques\]\]/ { intech = 0 }
    intech && /^name *= *"(heuristic_rt|ssr_fallback)"/ { hybrid = 1 }
    intech && hybrid && /^params *= *\{/ && /rays *= *"vulkan"/ && !/launch *=/ { sub(/\{ */, "{ launch = \"full\", ") }
    { print }' "$1"
}

at_most() { echo $(($1 < $2 ? $1 : $2)); }

# Runs "$@" for at most $1 seconds (TERM, then KILL 5 s later); exit status 124 without running it
# when no time is left.
bounded() {
  local seconds=$1
  shift
  [ "$seconds" -ge 1 ] || return 124
  timeout --signal=TERM --kill-after=5 "$seconds" "$@"
}

cmd_run() {
  local out=${1:-}
  [ -n "$out" ] && [ "${out#-}" = "$out" ] || die "run: expected an output folder first (gpu_campaign.sh run OUT ...)"
  shift
  local scale=1 limit=480 deadline="" maxmib=60 only="" cache="" skip="" bench_s=60 repeat=gbuffer_rays_gpu:1 pack="" launch=compact
  while [ $# -gt 0 ]; do
    case $1 in
      --scale) scale=${2:-}; shift 2 || die "--scale needs a value" ;;
      --limit-s) limit=${2:-}; shift 2 || die "--limit-s needs a value" ;;
      --deadline-s) deadline=${2:-}; shift 2 || die "--deadline-s needs a value" ;;
      --pack) pack=${2:-}; shift 2 || die "--pack needs a value" ;;
      --max-mib) maxmib=${2:-}; shift 2 || die "--max-mib needs a value" ;;
      --only) only=${2:-}; shift 2 || die "--only needs a value" ;;
      --cache) cache=${2:-}; shift 2 || die "--cache needs a value" ;;
      --skip-scenes) skip=${2:-}; shift 2 || die "--skip-scenes needs a value" ;;
      --bench-s) bench_s=${2:-}; shift 2 || die "--bench-s needs a value" ;;
      --repeat) repeat=${2:-}; shift 2 || die "--repeat needs a value" ;;
      --launch) launch=${2:-}; shift 2 || die "--launch needs a value" ;;
      *) die "run: unknown argument '$1' (expected --scale, --limit-s, --deadline-s, --pack, --max-mib, --only, --cache, --skip-scenes, --bench-s, --repeat, --launch)" ;;
    esac
  done
  # The packing's share of the limit (xz -1 of 60 MiB takes seconds on 16 cores, 10 s on 2).
  local pack_s=30
  [[ $limit =~ ^[0-9]+$ ]] && [ "$limit" -gt "$pack_s" ] || die "--limit-s $limit: expected a whole number of seconds above $pack_s"
  [ -n "$deadline" ] || deadline=$((limit - pack_s))
  [[ $deadline =~ ^[0-9]+$ ]] && [ "$deadline" -gt 0 ] || die "--deadline-s $deadline: expected a whole number of seconds above 0"
  [ "$deadline" -le $((limit - pack_s)) ] || die "--deadline-s $deadline: past --limit-s $limit less the $pack_s s its packing takes"
  [[ $maxmib =~ ^[0-9]+$ ]] && [ "$maxmib" -gt 0 ] || die "--max-mib $maxmib: expected a whole number of MiB above 0"
  [[ $scale =~ ^(0?\.[0-9]+|1(\.0*)?)$ ]] && [ "$scale" != "0" ] || die "--scale $scale: expected a number in (0, 1]"
  [[ $bench_s =~ ^[0-9]+$ ]] || die "--bench-s $bench_s: expected a whole number of seconds (0: no bench)"
  [[ $launch =~ ^(compact|full)$ ]] || die "--launch $launch: expected compact (the hybrids' default) or full"
  local repeat_name="" repeat_runs=0
  if [ "$repeat" != none ]; then
    [[ $repeat =~ ^([a-z0-9_]+):([1-9])$ ]] || die "--repeat $repeat: expected NAME:K (K from 1 to 9 more runs of config NAME) or none"
    repeat_name=${BASH_REMATCH[1]} repeat_runs=${BASH_REMATCH[2]}
    [[ " $(config_names) " == *" $repeat_name "* ]] || die "--repeat $repeat: $repeat_name is none of the campaign's configs ($(config_names))"
  fi
  [ -x "$HYBRIDLAB" ] || die "no program at $HYBRIDLAB: build it (./setup.sh), or run the bundle's gpu_campaign.sh"
  local selected=()
  for entry in "${CAMPAIGN[@]}"; do
    set -- $entry
    if [ -z "$only" ] || [[ ,$only, == *,$1,* ]]; then selected+=("$entry"); fi
  done
  [ ${#selected[@]} -gt 0 ] || die "--only $only: names none of the campaign's configs ($(config_names))"
  if [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then die "$out: exists and is not empty; choose another folder"; fi
  mkdir -p "$out/logs" || exit 3
  out=$(cd "$out" && pwd -P)
  if [ -n "$pack" ]; then
    mkdir -p "$pack" || exit 3
    pack=$(cd "$pack" && pwd -P)
  fi
  # References and layered-EM bakes are made on the campaign's machine (they are Embree's work,
  # on its CPUs), in a cache of the campaign's own, removed at the end, unless --cache names one
  # ($HYBRIDLAB_CACHE's layout: references/, layered-em/).
  local own_cache=0
  [ -n "$cache" ] || { cache=$out/cache; own_cache=1; }
  export HYBRIDLAB_CACHE=$cache

  local start=$SECONDS estimate=0 spent_est=0 spent=0 status summary=()
  # Seconds left to the deadline, and to the start of the packing.
  to_deadline() { echo $((deadline - (SECONDS - start))); }
  to_packing() { echo $((limit - pack_s - (SECONDS - start))); }
  # ... and to the last seconds of the limit, which the packing keeps in any case.
  to_last() { echo $((limit - 15 - (SECONDS - start))); }
  # The end of the campaign, early or not: the own cache removed, the summary, OUT packed; exit $1.
  conclude() {
    [ "$own_cache" -eq 0 ] || rm -rf "$cache"
    {
      echo
      echo "campaign: $((SECONDS - start)) s, $(mib "$out") MiB in $out"
      for line in "${summary[@]}"; do echo "  $line"; done
    } | tee -a "$out/campaign.log"
    if [ -n "$pack" ]; then
      local name parent
      name=$(basename "$out") parent=$(dirname "$out")
      rm -f "$pack/$name.tar.xz."*
      # At least 10 s, past the limit if it must: an unpacked campaign does not come back.
      # shellcheck disable=SC2016  # the inner script's own arguments
      if bounded $((limit - (SECONDS - start) > 10 ? limit - (SECONDS - start) : 10)) \
           bash -c 'set -o pipefail; tar -C "$1" -cf - "$2" | xz -T0 -1 | split -b 15M - "$3/$2.tar.xz."' _ "$parent" "$name" "$pack"; then
        echo "packed: $(cd "$pack" && echo "$name".tar.xz.*) ($(du -cm "$pack/$name".tar.xz.* | tail -1 | cut -f1) MiB in $pack," \
             "$((SECONDS - start)) s in all)"
      else
        echo "packing $out into $pack failed or was stopped"
        [ "$1" -ne 0 ] || set -- 3
      fi
    fi
    exit "$1"
  }

  for entry in "${selected[@]}"; do set -- $entry; estimate=$((estimate + $4)); done
  {
    echo "gpu_campaign: ${#selected[@]} configs into $out, scale $scale, deadline ${deadline} s, limit ${limit} s," \
         "at most $maxmib MiB$([ "$launch" = compact ] || echo ", the hybrids' rays launched full")"
    echo "program: $HYBRIDLAB"
    bounded "$(at_most 60 "$(to_packing)")" "$HYBRIDLAB" --version
  } | tee "$out/campaign.log"
  # The results on disk: a memory file system may be small, and is lost with the machine anyway.
  case $(stat -f -c %T "$out" 2>/dev/null) in
    tmpfs|ramfs) echo "warning: $out is on a memory file system; a folder on disk keeps what does not fit there" | tee -a "$out/campaign.log" ;;
  esac
  # An NVIDIA driver mounted into a container registers its Vulkan driver outside the loader's
  # search path; without its Vulkan device the campaign would measure nothing, so it stops here.
  local icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  if [ -z "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}" ] && [ -f "$icd" ] &&
     ! ls /usr/share/vulkan/icd.d/nvidia* /etc/vulkan/icd.d/nvidia* >/dev/null 2>&1; then
    export VK_DRIVER_FILES=$icd
  fi
  bounded "$(at_most 60 "$(to_packing)")" "$HYBRIDLAB" --version --json >"$out/device.json" 2>"$out/logs/device.log"
  if command -v nvidia-smi >/dev/null && ! grep -q '"vulkan_device_type": "[a-z]*_gpu"' "$out/device.json"; then
    # The loader's own account of the drivers it found and refused, kept for the next try.
    VK_LOADER_DEBUG=all bounded "$(at_most 60 "$(to_packing)")" "$HYBRIDLAB" --version --json >/dev/null 2>"$out/logs/vulkan_loader.log"
    echo "gpu_campaign: this machine has an NVIDIA GPU, but Vulkan found $(grep '"vulkan_device"' "$out/device.json" | cut -d'"' -f4):" \
         "its driver needs glvnd's libraries (libglvnd0 libgl1 libglx0 libegl1 libopengl0 libgles2; experiments/README.md)." \
         "The loader's account: $out/logs/vulkan_loader.log; its drivers and errors:" | tee -a "$out/campaign.log"
    grep -E 'ICD manifest|ICD drivers named|ERROR|WARNING|[Ff]ail|Using "' "$out/logs/vulkan_loader.log" | awk '!seen[$0]++' |
      tail -n 25 | cut -c1-300 | tee -a "$out/campaign.log"
    summary+=("stopped: no NVIDIA Vulkan device (logs/vulkan_loader.log)")
    conclude 5
  fi
  echo "estimate: about $estimate s on an H100/H200 at full size (updated as configs finish)" | tee -a "$out/campaign.log"

  # The device traces per ray by kind, each hybrid beside rt_only (`hybridlab bench`), first: it is
  # short, what the campaign's tables cannot show, and the first compacted launch on the device,
  # so a failure here stops the campaign before it spends minutes on configs that would fail alike.
  if [ "$bench_s" -gt 0 ]; then
    local bw bh t0=$SECONDS bench_limit
    bw=$(scaled_size 1280 "$scale") bh=$(scaled_size 720 "$scale")
    bench_limit=$(at_most "$bench_s" "$(to_deadline)")
    echo "bench: the device traces per ray, sponza-spheres at ${bw}x${bh}, at most ${bench_limit} s" | tee -a "$out/campaign.log"
    bounded "$bench_limit" "$HYBRIDLAB" bench --scene sponza-spheres --width "$bw" --height "$bh" \
      --repeats 5 --device-traces-only --launch "$([ "$launch" = full ] && echo full || echo both)" >"$out/bench.txt" 2>"$out/logs/bench.log"
    status=$?
    if [ "$status" -eq 0 ] && grep -q "^device traces per ray" "$out/bench.txt" && ! grep -q "not measured" "$out/bench.txt"; then
      summary+=("bench: $((SECONDS - t0)) s, $out/bench.txt")
      echo "  ${summary[-1]}" | tee -a "$out/campaign.log"
    else
      local what="failed (exit status $status)"
      [ "$status" -ne 0 ] || what="measured no traces"
      [ "$status" -ne 124 ] && [ "$status" -ne 137 ] || what="stopped at its ${bench_limit} s"
      summary+=("bench: $what after $((SECONDS - t0)) s: the campaign stopped there")
      {
        echo "  ${summary[-1]}; its output and log (logs/bench.log):"
        tail -n 15 "$out/bench.txt" | sed 's/^/  | /'
        grep -v '^warning:' "$out/logs/bench.log" | tail -n 25 | cut -c1-300 | sed 's/^/  | /'
        [ "$launch" = full ] ||
          echo "  the fallback, every hybrid's rays launched one invocation a texel: gpu_campaign.sh run OUT2 --launch full (same options)"
      } | tee -a "$out/campaign.log"
      conclude 4
    fi
  fi

  local k=0
  declare -A ran_config ran_seconds
  for entry in "${selected[@]}"; do
    set -- $entry
    local name=$1 config=$CONFIGS/$2 est=$4
    k=$((k + 1))
    # The copies run (OUT/configs/): without the skipped scenes, with the full launch.
    if [ -n "$skip" ] || [ "$launch" = full ]; then
      mkdir -p "$out/configs"
      if [ -n "$skip" ]; then without_scenes "$config" "$skip"; else cat "$config"; fi >"$out/configs/$2.tmp"
      if [ "$launch" = full ]; then with_full_launch "$out/configs/$2.tmp"; else cat "$out/configs/$2.tmp"; fi >"$out/configs/$2"
      rm -f "$out/configs/$2.tmp"
      config=$out/configs/$2
      if ! grep -q '^\[\[scenes\]\]' "$config"; then
        summary+=("$name: skipped, every scene of it is in --skip-scenes")
        continue
      fi
    fi
    local elapsed=$((SECONDS - start)) left
    left=$(to_deadline)
    # The estimate scaled by how the finished configs went against theirs (a CPU, a smaller scale).
    local scaled=$est
    [ "$spent_est" -gt 0 ] && scaled=$((est * spent / spent_est))
    if [ "$left" -lt 15 ]; then
      summary+=("$name: skipped, the deadline (${deadline} s) was reached")
      echo "[$k/${#selected[@]}] $name: skipped, ${elapsed} s of the ${deadline} s deadline spent" | tee -a "$out/campaign.log"
      continue
    fi
    echo "[$k/${#selected[@]}] $name: $(basename "$config"), about ${scaled} s; ${elapsed} s elapsed, ${left} s to the deadline" |
      tee -a "$out/campaign.log"
    local t0=$SECONDS
    # The runner's progress lines (a group at a time) shown as they come, and kept in logs/.
    bounded "$left" "$HYBRIDLAB" run "$config" --out "$out/$name" --scale "$scale" 2>&1 |
      tee "$out/logs/$name.log" | grep --line-buffered -v '^warning:' | sed -u 's/^/  /'
    status=${PIPESTATUS[0]}
    local took=$((SECONDS - t0))
    spent=$((spent + took))
    spent_est=$((spent_est + est))
    local runs
    runs=$(records "$out/$name")
    # Stopped (the deadline) or failed: the finished runs stay, and results.json is written from
    # them as the runner does when it stops (no rendering).
    if [ "$status" -ne 0 ] && [ "$runs" -gt 0 ] && [ ! -f "$out/$name/results.json" ]; then
      bounded "$(at_most 60 "$(to_last)")" "$HYBRIDLAB" run "$config" --out "$out/$name" --scale "$scale" --quiet --resume --max-runs 0 \
        >>"$out/logs/$name.log" 2>&1
    fi
    if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
      summary+=("$name: stopped at the deadline after ${took} s, $runs runs kept")
    elif [ "$status" -ne 0 ]; then
      summary+=("$name: failed (exit status $status) after ${took} s, $runs runs kept: $out/logs/$name.log")
    else
      summary+=("$name: ${took} s, $runs runs")
      ran_config[$name]=$config ran_seconds[$name]=$took
    fi
    echo "  ${summary[-1]}" | tee -a "$out/campaign.log" >/dev/null
    echo "  done in ${took} s ($((SECONDS - start)) s in all)"
  done

  # The repeatability of one config's verdict: the same config again (references from the cache),
  # where it finished and the deadline leaves the time it took. Only the records are kept.
  if [ -n "$repeat_name" ]; then
    if [ -z "${ran_config[$repeat_name]:-}" ]; then
      summary+=("repeats: none, $repeat_name did not run to its end")
    else
      mkdir -p "$out/repeats" && ln -sfn "../$repeat_name" "$out/repeats/run-1"
      local i
      for ((i = 2; i <= repeat_runs + 1; ++i)); do
        local left t0=$SECONDS
        left=$(to_deadline)
        if [ "$left" -lt $((ran_seconds[$repeat_name] + 15)) ]; then
          summary+=("repeats: $repeat_name run $i skipped, ${left} s to the deadline")
          break
        fi
        echo "repeat: $repeat_name run $i; ${left} s to the deadline" | tee -a "$out/campaign.log"
        bounded "$left" "$HYBRIDLAB" run "${ran_config[$repeat_name]}" --out "$out/repeats/run-$i" \
          --scale "$scale" --quiet >"$out/logs/$repeat_name-run-$i.log" 2>&1
        status=$?
        rm -rf "$out/repeats/run-$i/images" "$out/repeats/run-$i/references"
        if [ "$status" -ne 0 ]; then
          rm -rf "$out/repeats/run-$i"
          summary+=("repeats: $repeat_name run $i stopped or failed (exit status $status): $out/logs/$repeat_name-run-$i.log")
          break
        fi
        summary+=("repeats: $repeat_name run $i, $((SECONDS - t0)) s")
      done
    fi
  fi
  [ "$own_cache" -eq 0 ] || rm -rf "$cache"

  # The tables and reports, before any image is dropped, where this machine can and the limit
  # leaves the time (else `finish` writes them from what comes back).
  local missing
  missing=$(python_missing)
  if [ -n "$missing" ]; then
    echo "tables and reports: not here ($missing); on a machine set up by setup.sh: gpu_campaign.sh finish OUT" |
      tee -a "$out/campaign.log"
  elif [ "$(to_packing)" -lt 10 ]; then
    echo "tables and reports: no time left before the limit (${limit} s); gpu_campaign.sh finish OUT writes them" |
      tee -a "$out/campaign.log"
  else
    PYTHON_UNTIL=$(($(date +%s) + $(to_packing))) finish_sets "$out"
  fi

  # Under the size limit: whole result sets' images dropped, the largest set first.
  local set
  while [ "$(mib "$out")" -gt "$maxmib" ]; do
    set=$(for d in "$out"/*/; do [ -d "$d/images" ] && echo "$(du -sm "$d/images" "$d/references" 2>/dev/null | awk '{s += $1} END {print s}') $d"; done |
            sort -rn | head -1 | cut -d' ' -f2-)
    [ -n "$set" ] || break
    rm -rf "${set}images" "${set}references"
    echo "dropped the images of $(basename "$set") to stay under $maxmib MiB" | tee -a "$out/campaign.log"
  done
  conclude 0
}

finish_sets() {
  local out=$1
  for entry in "${CAMPAIGN[@]}"; do
    set -- $entry
    [ -d "$out/$1" ] || continue
    echo "$1:"
    if [ "$(records "$out/$1")" -eq 0 ]; then
      echo "  no runs recorded: no table or report"
    else
      tables_and_report "$out/$1" "$3"
    fi
  done 2>&1 | tee -a "$out/campaign.log"
  repeatability "$out" 2>&1 | tee -a "$out/campaign.log"
}

# The verdict rows of a config's repeated runs side by side (verdict_repeatability.py), with its
# speed-ups over rt_only against the first run's intervals.
repeatability() {
  local dir=$1/repeats runs=0 d
  [ -d "$dir" ] || return 0
  for d in "$dir"/run-*; do [ -f "$d/results.json" ] && runs=$((runs + 1)); done
  if [ "$runs" -lt 2 ]; then
    echo "repeats: $runs run(s) of $(readlink "$dir/run-1"): nothing to compare"
    return 0
  fi
  py "$CHECKOUT/experiments/verdict_repeatability.py" --reuse --out "$dir" --runs "$runs" --speedups rt_only \
    >"$dir/verdicts.txt" 2>&1 &&
    echo "repeats: $(grep -E 'verdict rows identical' "$dir/verdicts.txt") ($dir/verdicts.txt)" ||
    echo "repeats: verdict_repeatability.py failed: $dir/verdicts.txt"
}

cmd_finish() {
  local out=${1:-}
  [ -n "$out" ] && [ -f "$out/campaign.log" ] || die "finish: ${out:-(none)}: not a campaign folder (expected OUT of gpu_campaign.sh run)"
  local missing
  missing=$(python_missing)
  [ -z "$missing" ] || die "finish: cannot write the tables here: $missing"
  finish_sets "$out"
}

case ${1:-} in
  bundle) shift; cmd_bundle "$@" ;;
  run) shift; cmd_run "$@" ;;
  finish) shift; cmd_finish "$@" ;;
  -h|--help|help) usage ;;
  *) usage >&2; exit 2 ;;
esac
