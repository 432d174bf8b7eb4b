#!/usr/bin/env bash
# Set up hybridlab on a fresh Debian 12 machine: install the Debian packages the project needs
# (only those missing; through sudo when not root), then configure and build in Release.
#
#   ./setup.sh                 install, configure, build the hybridlab program (into ./build)
#   ./setup.sh --tests         the same, and build the tests and fetch the browser test's npm packages
#   BUILD_DIR=dir ./setup.sh   build elsewhere
#
# Whatever needs a new package adds it to PACKAGES below, and nowhere else (npm is the one
# exception, checked by command: see below).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"

TESTS=0
for arg in "$@"; do
  case "$arg" in
    --tests) TESTS=1 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown argument '$arg' (expected --tests)" >&2; exit 2 ;;
  esac
done

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config git xz-utils
  # scene core and images
  libglm-dev libtomlplusplus-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev
  # image formats: EXR, PNG, JPEG, and stb_image for BMP, TGA, GIF, PSD, PNM and HDR; OpenImageIO for
  # the rest (TIFF, PFM, DDS, WebP, ...), in a plugin the program loads only when it meets such a file
  libopenexr-dev libpng-dev libjpeg-dev libstb-dev libopenimageio-dev
  # the command-line tools that libopenimageio-dev's CMake config names as imported targets (iconvert,
  # oiiotool, ...): without them find_package(OpenImageIO) stops; the image fixtures' scripts use oiiotool
  openimageio-tools
  # metrics (SSIM's filtering)
  libopencv-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # the tests' sanitizer build and fuzz targets (tests/sanitize: AddressSanitizer, UBSan, libFuzzer)
  clang-14 libclang-rt-14-dev
  # ray tracing (Embree 3 on TBB)
  libembree-dev libtbb-dev
  # independent check of the Whitted reference
  povray
  # raster core (headless Vulkan on lavapipe)
  libvulkan-dev mesa-vulkan-drivers glslc
  # the Khronos validation layer (tests: every Vulkan path without a validation message)
  vulkan-validationlayers
  # metrics cross-check (tests)
  python3-skimage python3-numpy
  # reports and paper figures (Debian's /usr/bin/python3): charts, the result set's images, its records'
  # schema; and zlib for the report's viewer (pako, copied beside it: the browser inflates the result
  # set's EXRs with it)
  python3-matplotlib python3-openimageio python3-jsonschema node-pako
  # the viewer's browser test only (tests/report/viewer: headless Chromium driven by playwright-core,
  # and Ajv for the results schema, both from npm); the hybridlab program needs neither
  chromium nodejs
  # layered-EM inference (sparse least squares by conjugate gradient)
  libeigen3-dev
  # the Slurm end-to-end test only (tests/runner/slurm_end_to_end.sh starts its own munged,
  # slurmctld and slurmd in a temporary folder); the hybridlab program needs neither
  slurm-wlm munge
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

# Debian's npm is a package of its own; a nodejs that bundles npm (NodeSource's) conflicts with it.
command -v npm >/dev/null || missing+=(npm)

if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} missing package(s): ${missing[*]}"
  SUDO=()
  if [ "$(id -u)" -ne 0 ]; then SUDO=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${SUDO[@]}" apt-get update -q
  "${SUDO[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "setup: all ${#PACKAGES[@]} packages present"
fi

# Vulkan ray tracing (VK_KHR_acceleration_structure, VK_KHR_ray_tracing_pipeline) on lavapipe needs
# Mesa 25, which Debian 12 has in bookworm-backports (Mesa 22 in bookworm exposes neither). The
# backports suite gets a sources entry of its own on the mirror the machine already uses; apt takes
# from it only what is asked for with -t.
BACKPORTS_SOURCES=/etc/apt/sources.list.d/hybridlab-bookworm-backports.sources
mesa_version=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
if ! dpkg --compare-versions "${mesa_version:-0}" ge 25; then
  SUDO=()
  if [ "$(id -u)" -ne 0 ]; then SUDO=(sudo); fi
  if [ ! -f "$BACKPORTS_SOURCES" ]; then
    # The first Debian archive the machine names (a deb822 URIs: line or a one-line deb entry; not
    # the security archive, and not the addresses comments may hold).
    mirror=$(cat /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null |
               awk '/^(URIs:|deb )/ { for (i = 2; i <= NF; i++) if ($i ~ /^https?:/) print $i }' |
               grep -v security | head -1 || true)
    printf 'Types: deb\nURIs: %s\nSuites: bookworm-backports\nComponents: main\nSigned-By: %s\n' \
      "${mirror:-http://deb.debian.org/debian}" /usr/share/keyrings/debian-archive-keyring.gpg |
      "${SUDO[@]}" tee "$BACKPORTS_SOURCES" >/dev/null
  fi
  echo "setup: installing Mesa 25 (Vulkan ray tracing on lavapipe) from bookworm-backports"
  export DEBIAN_FRONTEND=noninteractive
  "${SUDO[@]}" apt-get update -q
  "${SUDO[@]}" apt-get install -y -q --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
fi

# The browser test's npm packages (playwright-core, ajv), as locked in tests/report/viewer/package-lock.json,
# for the tests only; npm ci deletes and reinstalls them, so only when the lock file is newer than
# what is installed. A failing npm (no network, a broken registry) costs only that one test, which then says why.
if ((TESTS)) && [ ! tests/report/viewer/node_modules/.package-lock.json -nt tests/report/viewer/package-lock.json ]; then
  if ! timeout 600 npm ci --prefix tests/report/viewer --prefer-offline --no-audit --no-fund --loglevel=error; then
    echo "setup: npm ci failed; the viewer's browser test (ViewerInBrowser) will be skipped" >&2
  fi
fi

BUILD_DIR=${BUILD_DIR:-build}
# ccache, where installed, makes rebuilds in a second checkout (a git worktree) cheap; not required.
LAUNCHER=()
if command -v ccache >/dev/null; then LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "${LAUNCHER[@]}"
# The main job needs only the program; the tests are built only with --tests.
TARGETS=(--target hybridlab)
if ((TESTS)); then TARGETS=(); fi
cmake --build "$BUILD_DIR" -j "$(nproc)" "${TARGETS[@]}"
