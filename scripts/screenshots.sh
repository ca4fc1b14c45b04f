#!/usr/bin/env bash
# Retake the pictures in screenshots/ from the real window. Every picture, every size (about
# 8 minutes on a loaded 2-core machine, unattended, from a clean checkout after
# `cargo build --release`):
#
#   bash scripts/screenshots.sh --all-sizes target/release/trochoplan
#
# Usage: scripts/screenshots.sh [--size WxH]... [--all-sizes] BINARY [NAME...]
#
# BINARY is a built `trochoplan`. --size picks the window size (repeatable; default 1400x900,
# the window's own size); --all-sizes is --size 1400x900 --size 1366x768 --size 1920x1080.
# Pictures at 1400x900 go to screenshots/NAME.png, at any other size to
# screenshots/WxH/NAME.png. NAMEs pick pictures: the tab pictures, one per tab of the tab bar
# (main = Plots, compare, sweep, forces, export, corner, pocket, machine = Machine & optimise,
# program, operations = the example part examples/part.toml opened; a tab added later is
# pictured as the first word of its label in lower case), and
# the extra ones (invalid-value teaching corner-table pocket-adaptive program-compare).
# Default: at 1400x900 all of them, at other sizes the tab pictures.
#
# Each picture starts the window afresh with an empty HOME / XDG_DATA_HOME / XDG_CONFIG_HOME,
# so no saved job or layout is restored, resizes it to the size asked for, reaches its tab by
# the tab's keyboard shortcut (Ctrl+1 … in the tab bar's order, read from src/app/tabs.rs)
# and drives the rest with xdotool. The Program tab's pictures open their programs at start
# through the TROCHOPLAN_PROGRAM_* variables (docs/verify.md).
#
# Needs Xvfb, xdotool, ImageMagick (`import`) and x11-utils installed
# (apt-get install -y xvfb xdotool imagemagick x11-utils). The click positions below (the
# controls inside a tab) belong to the layout: the side panels keep their width and the tab's
# contents start at its top left, so most of them hold at every size; after a layout change,
# take one picture, check where the controls are and adjust them. Look at every picture
# before committing it. SCREENSHOT_LOG=FILE keeps the window's own output (default: discarded).
set -euo pipefail

usage() { grep -m1 '^# Usage: ' "$0" | sed 's/^# Usage: */usage: /' >&2; exit 2; }
SIZES=()
while [ $# -gt 0 ]; do
	case $1 in
	--size)
		[[ ${2:-} =~ ^[0-9]+x[0-9]+$ ]] || usage
		SIZES+=("$2")
		shift 2 ;;
	--all-sizes)
		SIZES+=(1400x900 1366x768 1920x1080)
		shift ;;
	-*) usage ;;
	*) break ;;
	esac
done
[ $# -ge 1 ] || usage
BIN=$(realpath "$1")
shift
ROOT=$(cd "$(dirname "$0")/.." && pwd)
NAMES=("$@")
[ ${#SIZES[@]} -gt 0 ] || SIZES=(1400x900)

# The tab bar's labels in order, as src/app/tabs.rs lists them; a tab's shortcut is Ctrl with
# its place (1 … 9, then 0).
mapfile -t TAB_LABELS < <(grep -o 'label: "[^"]*"' "$ROOT/src/app/tabs.rs" | sed 's/label: "\(.*\)"/\1/')
[ ${#TAB_LABELS[@]} -gt 0 ] || { echo "no tab labels found in src/app/tabs.rs" >&2; exit 1; }
tab_picture() { # label → the name of its picture
	case $1 in
	Plots) echo main ;;
	"Export NC") echo export ;;
	"Machine & optimise") echo machine ;;
	*) echo "$1" | awk '{print tolower($1)}' ;;
	esac
}
TAB_PICTURES=()
for label in "${TAB_LABELS[@]}"; do TAB_PICTURES+=("$(tab_picture "$label")"); done
EXTRA_PICTURES=(invalid-value teaching corner-table pocket-adaptive program-compare)

# A display of our own, as large as the largest size: the first free number from 57 on
# (SCREENSHOT_DISPLAY picks another start).
SCREEN_W=0 SCREEN_H=0
for s in "${SIZES[@]}"; do
	w=${s%x*} h=${s#*x}
	((w > SCREEN_W)) && SCREEN_W=$w
	((h > SCREEN_H)) && SCREEN_H=$h
done
N=${SCREENSHOT_DISPLAY:-57}
while [ -e "/tmp/.X11-unix/X$N" ] || [ -e "/tmp/.X$N-lock" ]; do N=$((N + 1)); done
Xvfb ":$N" -screen 0 "${SCREEN_W}x${SCREEN_H}x24" -nolisten tcp >/dev/null 2>&1 &
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

W= H= OUT=
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
	for _ in $(seq 100); do # mapped: it can take the keyboard
		xwininfo -id "$WID" 2>/dev/null | grep -q IsViewable && break
		sleep .1
	done
	xdotool windowmove "$WID" 0 0
	xdotool windowsize "$WID" "$W" "$H" # no window manager: the window takes the size asked
	xdotool windowfocus "$WID"          # and the keyboard
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
tab() { # label: show that tab by its shortcut
	local i
	for i in "${!TAB_LABELS[@]}"; do
		if [ "${TAB_LABELS[$i]}" = "$1" ]; then
			((i < 10)) || { echo "tab $1 has no shortcut" >&2; exit 1; }
			xdotool key "ctrl+$(((i + 1) % 10))"
			sleep 1
			return
		fi
	done
	echo "no tab labelled $1 in src/app/tabs.rs" >&2
	exit 1
}
shot() { # name [seconds to wait first]
	xdotool mousemove $((W - 8)) $((H - 8)) # park the pointer: no hover crosshair in the plots
	sleep "${2:-1.5}"
	import -window "$WID" "$OUT/$1.png"
	echo "${OUT#"$ROOT"/}/$1.png"
}

# Positions of controls inside the tabs (x y in the window; the same at every size unless
# set per size in `positions`).
positions() {
	TOOL_DIAMETER="418 210"                   # parameters: tool diameter number box
	MACHINE_PICKER="97 694" HOBBY_ROUTER="61 744" # parameters: the machine preset
	PIN_PAPER_SET="650 43"                    # Compare tab
	RUN_SWEEP="570 66"                        # Sweep tab
	OPTIMISE="517 360"                        # Machine & optimise tab
	ACCEPTANCE_TABLE="154 43"                 # Corner tab
	POCKET_MEDIAL_AXIS="633 65" POCKET_STEP_OVER="129 89" # Pocket tab
	POCKET_MACHINE="927 112" POCKET_VMC="890 186"
	FIRST_PROBLEM="870 447" SIDE_BY_SIDE="232 89" # Program tab
	case ${W}x$H in
	1366x768)
		RUN_SWEEP="615 63"    # the sweep's row wraps before "values"
		HOBBY_ROUTER="61 621" ;; # the machine list opens upwards
	1920x1080)
		RUN_SWEEP="1201 43"  # the sweep's settings fit in one row
		OPTIMISE="1379 294"      # so do the optimiser's limits
		FIRST_PROBLEM="1240 447" ;;
	esac
}
FREECAD=$ROOT/tests/data/freecad

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

take() { # name: the window is open on its defaults
	case $1 in
	main) shot main ;;
	invalid-value)
		type_into $TOOL_DIAMETER 25 # wider than half the 20 mm slot: invalid
		shot invalid-value ;;
	compare)
		tab Compare
		click $PIN_PAPER_SET
		shot compare 3 ;;
	sweep)
		tab Sweep
		click $RUN_SWEEP
		shot sweep 8 ;;
	forces)
		tab Forces
		shot forces ;;
	teaching)
		xdotool key ctrl+t
		shot teaching ;;
	export)
		tab "Export NC"
		shot export 3 ;;
	machine)
		click $MACHINE_PICKER
		click $HOBBY_ROUTER
		tab "Machine & optimise"
		click $OPTIMISE
		shot machine 25 ;;
	corner)
		tab Corner # opens on one 90° corner with variable circles
		shot corner 3 ;;
	corner-table)
		tab Corner
		click $ACCEPTANCE_TABLE
		shot corner-table 40 ;;
	pocket)
		tab Pocket
		sleep 4 # the first plan shown: no "still being made" line moves the rows
		type_into $POCKET_STEP_OVER 1.527
		sleep 4
		click $POCKET_MEDIAL_AXIS
		shot pocket 15 ;;
	pocket-adaptive)
		tab Pocket # adaptive clearing is chosen by default
		sleep 4
		type_into $POCKET_STEP_OVER 1.527
		sleep 4
		click $POCKET_MACHINE
		click $POCKET_VMC # the real time of the program on the vmc preset
		shot pocket-adaptive 10 ;;
	operations)
		xdotool key ctrl+shift+p # Open part…: no portal here, so the window's own path field
		sleep 1.5
		xdotool key ctrl+a # the field starts with the working folder
		xdotool type --delay 20 "$ROOT/examples/part.toml"
		xdotool key Return
		tab Operations
		shot operations 25 ;; # every operation planned on the vmc preset
	*)
		local i
		for i in "${!TAB_PICTURES[@]}"; do
			if [ "${TAB_PICTURES[$i]}" = "$1" ]; then # a tab pictured as it opens
				tab "${TAB_LABELS[$i]}"
				shot "$1" 3
				return
			fi
		done
		echo "unknown picture $1" >&2
		exit 2 ;;
	esac
}

for size in "${SIZES[@]}"; do
	W=${size%x*} H=${size#*x}
	OUT=$ROOT/screenshots
	[ "$size" = 1400x900 ] || OUT=$ROOT/screenshots/$size
	mkdir -p "$OUT"
	positions
	names=("${NAMES[@]}")
	if [ ${#names[@]} -eq 0 ]; then
		names=("${TAB_PICTURES[@]}")
		[ "$size" != 1400x900 ] || names+=("${EXTRA_PICTURES[@]}")
	fi
	for name in "${names[@]}"; do
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
done
