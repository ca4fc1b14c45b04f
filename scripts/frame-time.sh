#!/usr/bin/env bash
# Frame time of the real window while a value is dragged, under Xvfb at 1400×900.
#
#   scripts/frame-time.sh BINARY slot|pocket
#
# slot: drags the Plots tab's Step s slider; pocket: drags the Pocket tab's step-over a_e box.
# The app runs with TROCHOPLAN_FRAME_LOG=1 (one line per frame on stderr) and an empty HOME, so
# no stored window state is restored; the statistics are over the frames logged while dragging.
# Needs Xvfb and xdotool (apt-get install -y xvfb xdotool). The positions belong to the layout
# at 1400×900 (as in scripts/screenshots.sh).
set -euo pipefail
[[ $# == 2 && ( $2 == slot || $2 == pocket ) ]] || { sed -n 4p "$0" | sed 's/^# */usage: /' >&2; exit 2; }
BIN=$1
MODE=$2
DISPLAY_NO=71
while [[ -e /tmp/.X11-unix/X$DISPLAY_NO ]]; do DISPLAY_NO=$((DISPLAY_NO + 1)); done
WORK=$(mktemp -d)
Xvfb ":$DISPLAY_NO" -screen 0 1400x900x24 -nolisten tcp >/dev/null 2>&1 &
XV=$!
APP=
cleanup() {
    [[ -n $APP ]] && kill "$APP" 2>/dev/null || true
    kill "$XV" 2>/dev/null || true
    rm -rf -- "$WORK"
}
trap cleanup EXIT
sleep 2
export DISPLAY=:$DISPLAY_NO
unset WAYLAND_DISPLAY
HOME=$WORK XDG_DATA_HOME=$WORK XDG_CONFIG_HOME=$WORK TROCHOPLAN_FRAME_LOG=1 "$BIN" 2>"$WORK/frames.log" &
APP=$!
WID=
for _ in $(seq 60); do
    WID=$(xdotool search --pid "$APP" --name TrochoPlan 2>/dev/null | head -1 || true)
    [[ -n $WID ]] && break
    sleep 1
done
[[ -n $WID ]] || { echo "frame-time: no window" >&2; exit 1; }
sleep 4
xdotool windowfocus "$WID"
if [[ $MODE == pocket ]]; then
    xdotool mousemove 480 12 click 1 # the Pocket tab
    sleep 3
    X0=1032 Y=43 # the step-over box: dragging it sideways changes a_e
else
    X0=153 Y=402 # the Step s slider's handle
fi
xdotool mousemove "$X0" "$Y"
sleep .3
xdotool mousedown 1
sleep .3
for _ in 1 2; do
    for x in $(seq 0 3 140) $(seq 140 -3 0); do
        xdotool mousemove $((X0 + x)) "$Y"
        sleep 0.03
    done
done
sleep .3
xdotool mouseup 1
sleep 1
grep 'dragging=true' "$WORK/frames.log" | sed 's/frame_ms=\([0-9.]*\) ui_ms=\([0-9.]*\).*replanned=\([a-z]*\)/\1 \2 \3/' >"$WORK/drag"
n=$(wc -l <"$WORK/drag")
((n > 0)) || { echo "frame-time: no frame logged while dragging" >&2; exit 1; }
q() { sort -g | awk -v p="$1" '{a[NR]=$1} END {print a[int((NR-1)*p)+1]}'; }
printf '%s: %d frames while dragging (%d with a slot replan): frame median %s ms, p90 %s ms, max %s ms; UI code median %s ms, p90 %s ms\n' \
    "$MODE" "$n" "$(grep -c ' true$' "$WORK/drag" || true)" \
    "$(cut -d' ' -f1 "$WORK/drag" | q 0.5)" "$(cut -d' ' -f1 "$WORK/drag" | q 0.9)" "$(cut -d' ' -f1 "$WORK/drag" | q 1)" \
    "$(cut -d' ' -f2 "$WORK/drag" | q 0.5)" "$(cut -d' ' -f2 "$WORK/drag" | q 0.9)"
