#!/usr/bin/env bash
# Frame time of the real window while a value is dragged or the optimiser runs, under Xvfb at
# 1400×900, on an idle machine or beside a CPU hog.
#
#   scripts/frame-time.sh [--hog N] BINARY slot|pocket|corner|optimise
#
# slot: drags the Plots tab's Step s slider; pocket: drags the Pocket tab's step-over a_e box;
# corner: drags the Corner tab's corner angle slider; optimise: starts the Machine & optimise
# tab's optimiser on the Table 1 job and waits for its result. --hog N runs N busy processes
# (one per core: as many as `nproc`) beside the window from before it starts until the end;
# they are killed on exit.
#
# The app runs with TROCHOPLAN_FRAME_LOG=1 (one line per frame on stderr: the window's time,
# frame and UI times, whether a value is dragged, whether the slot, Pocket and Corner tabs
# wait for a plan, the optimiser's progress) and an empty HOME, so no stored window state is
# restored. Printed: the frames while dragging (or while the optimiser runs), their median,
# p90 and max frame time and UI-code time; the replan latency, from the last frame of the drag
# to the first frame that shows the new plan; for optimise the time to the result and how
# long the bar stood at 99 % or more before it.
# Needs Xvfb and xdotool (apt-get install -y xvfb xdotool). Tabs are reached by their
# shortcuts (Ctrl+1 … in the tab bar's order, read from src/app/tabs.rs); the positions inside
# the tabs belong to the layout at 1400×900 (as in scripts/screenshots.sh).
set -euo pipefail
usage() { sed -n 5p "$0" | sed 's/^# */usage: /' >&2; exit 2; }
HOG=0
if [[ ${1:-} == --hog ]]; then
    [[ ${2:-} =~ ^[0-9]+$ ]] || usage
    HOG=$2
    shift 2
fi
[[ $# == 2 && $2 =~ ^(slot|pocket|corner|optimise)$ ]] || usage
BIN=$1
MODE=$2
ROOT=$(cd "$(dirname "$0")/.." && pwd)
mapfile -t TAB_LABELS < <(grep -o 'label: "[^"]*"' "$ROOT/src/app/tabs.rs" | sed 's/label: "\(.*\)"/\1/')
tab_key() { # label → the digit of its shortcut
    local i
    for i in "${!TAB_LABELS[@]}"; do
        [[ ${TAB_LABELS[$i]} == "$1" ]] && { echo $(((i + 1) % 10)); return; }
    done
    echo "frame-time: no tab labelled $1 in src/app/tabs.rs" >&2
    exit 1
}
DISPLAY_NO=71
while [[ -e /tmp/.X11-unix/X$DISPLAY_NO || -e /tmp/.X$DISPLAY_NO-lock ]]; do DISPLAY_NO=$((DISPLAY_NO + 1)); done
WORK=$(mktemp -d)
HOGS=()
APP=
XV=
cleanup() {
    [[ -n $APP ]] && kill "$APP" 2>/dev/null || true
    [[ -n $XV ]] && kill "$XV" 2>/dev/null || true
    local p
    for p in "${HOGS[@]}"; do kill "$p" 2>/dev/null || true; done
    rm -rf -- "$WORK"
}
trap cleanup EXIT
for _ in $(seq "$HOG"); do
    bash -c 'while :; do :; done' &
    HOGS+=($!)
done
Xvfb ":$DISPLAY_NO" -screen 0 1400x900x24 -nolisten tcp >/dev/null 2>&1 &
XV=$!
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

drag() { # x y: drag sideways from (x, y), twice across 140 px and back, then 70 px (the last
    # value differs from the first: it needs a new plan)
    local x0=$1 y=$2 x
    xdotool mousemove "$x0" "$y"
    sleep .3
    xdotool mousedown 1
    sleep .3
    for x in $(seq 0 3 140) $(seq 140 -3 0) $(seq 0 3 140) $(seq 140 -3 0) $(seq 0 3 70); do
        xdotool mousemove $((x0 + x)) "$y"
        sleep 0.03
    done
    sleep .3
    xdotool mouseup 1
}
# the value of KEY in each line of the frame log, as "t value" (t: the window's time, s)
field() { sed -n "s/^t=\([0-9.]*\) .*$1=\([^ ]*\).*/\1 \2/p" "$WORK/frames.log"; }
q() { sort -g | awk -v p="$1" '{a[NR]=$1} END {print a[int((NR-1)*p)+1]}'; }
stats() { # file of "frame_ms ui_ms" lines
    printf 'frame median %s ms, p90 %s ms, max %s ms; UI code median %s ms, p90 %s ms' \
        "$(cut -d' ' -f1 "$1" | q 0.5)" "$(cut -d' ' -f1 "$1" | q 0.9)" "$(cut -d' ' -f1 "$1" | q 1)" \
        "$(cut -d' ' -f2 "$1" | q 0.5)" "$(cut -d' ' -f2 "$1" | q 0.9)"
}
# replan latency: from the last frame of the drag to the first later frame where KEY is false
latency() {
    local last
    last=$(grep 'dragging=true' "$WORK/frames.log" | tail -1 | sed 's/^t=\([0-9.]*\) .*/\1/')
    field "$1" | awk -v t0="$last" '$1 > t0 && $2 == "false" {printf "%.2f", $1 - t0; found = 1; exit}
        END {if (!found) printf "none shown"}'
}

case $MODE in
slot) drag 158 498 ;; # the Step s slider's handle
pocket)
    xdotool key "ctrl+$(tab_key Pocket)"
    sleep 3
    drag 129 89 ;; # the step-over box: dragging it sideways changes a_e
corner)
    xdotool key "ctrl+$(tab_key Corner)"
    sleep 3
    drag 155 65 ;; # the corner angle slider's handle
optimise)
    xdotool key "ctrl+$(tab_key 'Machine & optimise')"
    sleep 2
    xdotool mousemove 517 360 click 1 # Optimise
    for _ in $(seq 240); do
        grep -q 'optimise=done' "$WORK/frames.log" && break
        sleep .5
    done ;;
esac
sleep 3 # the last replan shown
hog="idle"
((HOG == 0)) || hog="beside $HOG busy processes"
if [[ $MODE == optimise ]]; then
    grep -q 'optimise=done' "$WORK/frames.log" || { echo "frame-time: no optimiser result in 2 min" >&2; exit 1; }
    grep -E 'optimise=[0-9.]+' "$WORK/frames.log" | sed 's/.*frame_ms=\([0-9.]*\) ui_ms=\([0-9.]*\).*/\1 \2/' >"$WORK/run"
    read -r t_start t_top t_done < <(field optimise | awk '
        $2 ~ /^[0-9.]+$/ && !s {s = $1} $2 ~ /^[0-9.]+$/ && $2 >= 0.99 && !top {top = $1}
        $2 == "done" {if (!top) top = $1; print s, top, $1; exit}')
    printf 'optimise (%s): %d frames while running: %s; result after %s s, bar at 99 %% or more for the last %s s\n' \
        "$hog" "$(wc -l <"$WORK/run")" "$(stats "$WORK/run")" \
        "$(awk -v a="$t_done" -v b="$t_start" 'BEGIN {printf "%.1f", a - b}')" \
        "$(awk -v a="$t_done" -v b="$t_top" 'BEGIN {printf "%.2f", a - b}')"
    exit 0
fi
grep 'dragging=true' "$WORK/frames.log" | sed 's/.*frame_ms=\([0-9.]*\) ui_ms=\([0-9.]*\).*/\1 \2/' >"$WORK/drag"
n=$(wc -l <"$WORK/drag")
((n > 0)) || { echo "frame-time: no frame logged while dragging" >&2; exit 1; }
extra=
case $MODE in
slot) extra="; $(grep 'dragging=true' "$WORK/frames.log" | grep -c 'replanned=true' || true) slot replans; new slot shown $(latency slot_pending) s after the last edit" ;;
pocket) extra="; new pocket shown $(latency pocket_pending) s after the last edit" ;;
corner) extra="; new corner shown $(latency corner_pending) s after the last edit" ;;
esac
printf '%s (%s): %d frames while dragging: %s%s\n' "$MODE" "$hog" "$n" "$(stats "$WORK/drag")" "$extra"
