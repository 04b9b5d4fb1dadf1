#!/bin/sh
# with_xvfb.sh WxHxD COMMAND [ARG...]: runs COMMAND on a private Xvfb server of that screen size
# and exits with COMMAND's status.
#
# Why not xvfb-run: under ctest -j several xvfb-run -a pick display numbers by looking for lock
# files, which races, and its cleanup can fail after the command has finished, replacing the
# command's exit status with 5 (seen in CI on "viewer: --timeout ends an open window"). Here Xvfb
# picks a free display itself (-displayfd) and cleanup never touches the status.
set -u
if [ $# -lt 2 ]; then
    echo "usage: with_xvfb.sh WxHxD COMMAND [ARG...]" >&2
    exit 2
fi
screen=$1
shift
dir=$(mktemp -d "${TMPDIR:-/tmp}/sss-xvfb.XXXXXX") || { echo "with_xvfb.sh: mktemp failed" >&2; exit 3; }
Xvfb -displayfd 3 -screen 0 "$screen" -nolisten tcp 3>"$dir/display" >"$dir/log" 2>&1 &
server=$!
tries=0
while [ ! -s "$dir/display" ]; do
    if ! kill -0 "$server" 2>/dev/null || [ "$tries" -ge 300 ]; then
        echo "with_xvfb.sh: Xvfb did not start; its log:" >&2
        cat "$dir/log" >&2
        kill "$server" 2>/dev/null
        rm -rf "$dir"
        exit 3
    fi
    sleep 0.1
    tries=$((tries + 1))
done
display=$(head -n 1 "$dir/display")
DISPLAY=":$display" XAUTHORITY= "$@"
status=$?
kill "$server" 2>/dev/null
wait "$server" 2>/dev/null
rm -rf "$dir"
exit "$status"
