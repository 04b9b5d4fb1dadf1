#!/usr/bin/env bash
# Installs what is missing, builds libsss with tests, and runs the whole suite under ctest.
# Usage: scripts/test.sh            (build dir: build/, executables in build/bin/)
# Environment: SSS_BUILD_TYPE (default Release), SSS_CMAKE_ARGS (extra configure arguments),
#              SSS_JOBS (parallel jobs, default: number of cores), SSS_BUILD_DIR (default build).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh --viewer
jobs=${SSS_JOBS:-$(nproc)}
build=${SSS_BUILD_DIR:-build}
# shellcheck disable=SC2086  # SSS_CMAKE_ARGS is a list of arguments on purpose
# The Python module is built for, and tested with, the Debian interpreter that install-deps.sh
# gives NumPy and pytest (not whatever python3 comes first on PATH, e.g. a pyenv shim).
python=()
if [[ -x /usr/bin/python3 ]]; then python=(-DPython_EXECUTABLE=/usr/bin/python3); fi
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE="${SSS_BUILD_TYPE:-Release}" -DSSS_BUILD_TESTS=ON \
      -DSSS_BUILD_EXAMPLES=ON -DSSS_BUILD_BENCH=ON -DSSS_WITH_GLFW=ON "${python[@]}" ${SSS_CMAKE_ARGS:-}
cmake --build "$build" -j "$jobs"
# Tests need no GPU: headless EGL on Mesa llvmpipe. No DISPLAY is needed (or used). Mesa is
# installed above, so a GL test without a context is a failure here, not a skip.
export SSS_REQUIRE_GL="${SSS_REQUIRE_GL:-1}"
ctest --test-dir "$build" --output-on-failure -j "$jobs"
