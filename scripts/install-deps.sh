#!/usr/bin/env bash
# Installs the Debian 12 packages this project needs to build, test and fetch
# its sample data. Idempotent: only missing packages are installed.
# Usage: scripts/install-deps.sh        (as root, or with sudo available)
set -euo pipefail

packages=(
  # build
  build-essential cmake ninja-build pkg-config clang-format
  # the compiler cache every tree goes through (scripts/lib/ccache.sh)
  ccache
  # fuzzing (scripts/fuzz.sh): clang and its libFuzzer runtime
  clang libclang-rt-14-dev
  # libraries (docs/install.md lists what the programs link)
  libgdal-dev libgeos-dev libproj-dev libtiff-dev libzstd-dev libsqlite3-dev libpng-dev zlib1g-dev
  # globe-serve: HTTP from GNU libmicrohttpd (docs/serve.md "HTTP")
  libmicrohttpd-dev
  # globe-view as a web client: HTTP(S) from libcurl (lib/net, docs/viewer.md "Remote sources")
  libcurl4-openssl-dev
  # viewer image tile decoding without GDAL
  libjpeg62-turbo-dev libwebp-dev
  # lib/text: FreeType, HarfBuzz, FriBiDi, protozero, the fonts it falls back on, and
  # hb-shape (tests/text_test.cpp checks the shaping against it)
  libfreetype-dev libharfbuzz-dev libfribidi-dev libprotozero-dev fonts-noto-core fonts-dejavu-core
  libharfbuzz-bin
  googletest libgtest-dev
  # viewer: GLM, GLFW window, OSMesa and EGL (Mesa llvmpipe) headless contexts
  libglm-dev libglfw3-dev libosmesa6-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  # command-line tools used by samples/fetch.sh, tests and benchmarks
  gdal-bin sqlite3 unzip ca-certificates curl time bc xz-utils
  # tests/http_conformance/: the clients globe-serve is checked through
  wget
  # tests/data/hostile/make_hostile.sh, samples/fetch.sh's conversions
  python3
  # gdal2tiles.py (imagery benchmark peer)
  python3-gdal
  # tests/flow_test.cpp: GRASS r.watershed, the flow accumulation peer
  grass-core
  # tests/cluster_test.cpp: a single-node Slurm cluster (scripts/slurm/local-cluster.sh)
  slurm-wlm munge
  # tests/robustness_test.cpp: holds a build at one syscall (strace -e inject)
  strace
  # window tests under a virtual X server, keys sent with xdotool
  xvfb xauth xdotool
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present" >&2
else
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "install-deps: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

# The web tests' browser and client libraries (chromium, npm packages in a
# cache folder): tests/web/README.md.
"$(dirname "$0")/web-deps.sh" >/dev/null
