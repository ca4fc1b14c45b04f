#!/usr/bin/env bash
# Retake the pictures in screenshots/ from the real window.
#
#   bash scripts/screenshots.sh BINARY [NAME...]
#
# BINARY is a built `trochoplan` (e.g. target/release/trochoplan); NAMEs pick pictures
# (main invalid-value compare sweep forces teaching export machine corner corner-table
# pocket pocket-adaptive program program-compare; default: all fourteen). Each picture starts
# the window afresh with an
# empty HOME / XDG_DATA_HOME / XDG_CONFIG_HOME, so no saved job or layout is restored, drives it
# with xdotool and writes screenshots/NAME.png at 1400×900. The Program tab's pictures open
# their programs at start through the TROCHOPLAN_PROGRAM_* variables (docs/verify.md).
#
# Needs Xvfb, xdotool, ImageMagick (`import`) and x11-utils installed
# (apt-get install -y xvfb xdotool imagemagick x11-utils). The click positions below belong to
# the window's layout at 1400×900: after a layout change, take one picture, check where the
# controls are and adjust them. Look at every picture before committing it.
# SCREENSHOT_LOG=FILE keeps the window's own output (default: discarded).
set -euo pipefail

BIN=$(realpath "${1:?usage: scripts/screenshots.sh BINARY [NAME...]}")
shift
OUT=$(cd "$(dirname "$0")/.." && pwd)/screenshots
NAMES=("$@")
[ ${#NAMES[@]} -gt 0 ] || NAMES=(main invalid-value compare sweep forces teaching export
	machine corner corner-table pocket pocket-adaptive program program-compare)

# A display of our own: the first free number from 57 on (SCREENSHOT_DISPLAY picks another start).
N=${SCREENSHOT_DISPLAY:-57}
while [ -e "/tmp/.X11-unix/X$N" ] || [ -e "/tmp/.X$N-lock" ]; do N=$((N + 1)); done
Xvfb ":$N" -screen 0 1400x900x24 -nolisten tcp >/dev/null 2>&1 &
XVFB=$!
export DISPLAY=:$N
unset WAYLAND_DISPLAY
APP=
APP_HOME=
APP_TMP=$(mktemp -d) # programs made for the pictures
cleanup() {
	rm -rf "$APP_TMP"
	[ -n "$APP" ] && kill "$APP" 2>/dev/null || true
	[ -n "$APP_HOME" ] && rm -rf "$APP_HOME"
	kill "$XVFB" 2>/dev/null || true
}
trap cleanup EXIT
for _ in $(seq 50); do
	[ -e "/tmp/.X11-unix/X$N" ] && break
	kill -0 "$XVFB" 2>/dev/null || { echo "Xvfb :$N did not start" >&2; exit 1; }
	sleep .1
done
sleep .5

start_app() { # [VAR=value...]: the window's extra environment
	APP_HOME=$(mktemp -d)
	HOME=$APP_HOME XDG_DATA_HOME=$APP_HOME/data XDG_CONFIG_HOME=$APP_HOME/config \
		env "$@" "$BIN" >"${SCREENSHOT_LOG:-/dev/null}" 2>&1 &
	APP=$!
	WID=
	for _ in $(seq 300); do # up to a minute on a busy machine
		WID=$(xdotool search --pid "$APP" --name TrochoPlan 2>/dev/null | head -1 || true)
		[ -n "$WID" ] && break
		sleep .2
	done
	[ -n "$WID" ] || { echo "no TrochoPlan window" >&2; exit 1; }
	xdotool windowfocus "$WID" # no window manager: give it the keyboard
	sleep 3
}
stop_app() {
	kill "$APP"
	wait "$APP" 2>/dev/null || true
	rm -rf "$APP_HOME"
	APP= APP_HOME=
}
click() { # x y
	xdotool mousemove "$1" "$2"
	sleep .3
	xdotool click 1
	sleep .5
}
type_into() { # x y text: click a number box, replace its text, Enter
	click "$1" "$2"
	xdotool key ctrl+a
	sleep .2
	xdotool type --delay 60 "$3"
	sleep .2
	xdotool key Return
	sleep .8
}
shot() { # name [seconds to wait first]
	xdotool mousemove 1390 890 # park the pointer: no hover crosshair in the plots
	sleep "${2:-1.5}"
	import -window "$WID" "$OUT/$1.png"
	echo "screenshots/$1.png"
}

# Positions in the 1400×900 window.
TAB_COMPARE="205 12" TAB_SWEEP="256 12" TAB_FORCES="307 12" TAB_EXPORT="370 12"
TAB_CORNER="429 12" TAB_POCKET="480 12" TAB_MACHINE="569 12" TEACH="669 12"
TOOL_DIAMETER="337 161"                  # slot tab: tool diameter number box
MACHINE_PICKER="97 598" HOBBY_ROUTER="61 648"
PIN_PAPER_SET="594 43"                   # Compare tab
RUN_SWEEP="1084 43"                      # Sweep tab
OPTIMISE="458 354"                       # Machine & optimise tab
ACCEPTANCE_TABLE="154 43"                # Corner tab
POCKET_MEDIAL_AXIS="633 65" POCKET_STEP_OVER="129 89" # Pocket tab
POCKET_MACHINE="927 112" POCKET_VMC="890 186"
FIRST_PROBLEM="870 447" SIDE_BY_SIDE="232 89" # Program tab
FREECAD=$(cd "$(dirname "$0")/.." && pwd)/tests/data/freecad

# The Program tab's window: FreeCAD's program for the L pocket (A; with `ours`, our own
# adaptive clearing of the same outline as A and FreeCAD's as B), the outline as stock and part,
# the vmc machine.
start_program() { # [ours]
	local a=$FREECAD/L.ngc b=
	if [ "${1:-}" = ours ]; then
		b=$a
		a=$APP_TMP/L-ours.ngc
		"$BIN" pocket --polygon "$FREECAD/L.txt" --tool-diameter 10 --step-over 1.526 --depth 6 \
			--feed 600 --rpm 2000 --export "$a" >/dev/null
	fi
	start_app TROCHOPLAN_PROGRAM_A="$a" ${b:+TROCHOPLAN_PROGRAM_B="$b"} \
		TROCHOPLAN_PROGRAM_STOCK="$FREECAD/L.txt" TROCHOPLAN_PROGRAM_PART="$FREECAD/L.txt" \
		TROCHOPLAN_PROGRAM_MACHINE=vmc
}

take() {
	case $1 in
	main) shot main ;;
	invalid-value)
		type_into $TOOL_DIAMETER 25 # wider than half the 20 mm slot: invalid
		shot invalid-value ;;
	compare)
		click $TAB_COMPARE
		click $PIN_PAPER_SET
		shot compare 3 ;;
	sweep)
		click $TAB_SWEEP
		click $RUN_SWEEP
		shot sweep 8 ;;
	forces)
		click $TAB_FORCES
		shot forces ;;
	teaching)
		click $TEACH
		shot teaching ;;
	export)
		click $TAB_EXPORT
		shot export 3 ;;
	machine)
		click $MACHINE_PICKER
		click $HOBBY_ROUTER
		click $TAB_MACHINE
		click $OPTIMISE
		shot machine 40 ;;
	corner)
		click $TAB_CORNER # opens on one 90° corner with variable circles
		shot corner 3 ;;
	corner-table)
		click $TAB_CORNER
		click $ACCEPTANCE_TABLE
		shot corner-table 40 ;;
	pocket)
		click $TAB_POCKET
		click $POCKET_MEDIAL_AXIS
		type_into $POCKET_STEP_OVER 1.527
		shot pocket 15 ;;
	pocket-adaptive)
		click $TAB_POCKET # adaptive clearing is chosen by default
		type_into $POCKET_STEP_OVER 1.527
		click $POCKET_MACHINE
		click $POCKET_VMC # the real time of the program on the vmc preset
		shot pocket-adaptive 10 ;;
	*)
		echo "unknown picture $1" >&2
		exit 2 ;;
	esac
}

for name in "${NAMES[@]}"; do
	case $name in
	program)
		start_program
		sleep 12 # verified in the background
		click $FIRST_PROBLEM
		shot program ;;
	program-compare)
		start_program ours
		sleep 25
		click $SIDE_BY_SIDE
		shot program-compare ;;
	*)
		start_app
		take "$name" ;;
	esac
	stop_app
done
