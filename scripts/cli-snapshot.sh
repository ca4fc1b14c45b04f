#!/usr/bin/env bash
# Snapshot of every CLI command's output, to prove that a refactor leaves it byte-identical.
#
#   scripts/cli-snapshot.sh BINARY OUTDIR          run the fixed invocations of BINARY into OUTDIR
#   scripts/cli-snapshot.sh --compare BIN_A BIN_B  snapshot both into temporary folders and diff
#
# Per invocation k: OUTDIR/NNN-name.stdout, .stderr, .exit (the exit code), and every file it
# writes (NC programs, CSV series) as OUTDIR/NNN-name.EXT. The inputs (the repository's
# assets/*.toml, the pocket polygons and engagement CSVs written here) are copied into OUTDIR
# first, and the binary runs inside OUTDIR with relative file names, so the snapshot does not
# depend on where OUTDIR is. Each run gets an empty environment, stdin from /dev/null and
# argv[0] = "trochoplan" (clap prints argv[0]'s file name in usage and error text), so neither
# the caller's environment, a terminal nor the binary's file name can change the output.
# OUTDIR must be empty or not exist. --compare exits 1 and prints the diff on any difference,
# else prints "N invocations identical". CLI_SNAPSHOT_TIMES=1 prints each invocation's time.
set -euo pipefail

usage() {
    sed -n '4,5p' "$0" | sed 's/^# */usage: /' >&2
    exit "${1:-2}"
}

die() {
    echo "cli-snapshot: $*" >&2
    exit 2
}

SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO_DIR=$(dirname "$SCRIPT_DIR")

# Absolute path of an executable given as a path or a command name.
resolve_bin() {
    local b=$1
    if [[ $b != */* ]]; then
        b=$(command -v -- "$b") || die "no such command: $1"
    fi
    [[ -f $b && -x $b ]] || die "not an executable file: $1"
    echo "$(cd "$(dirname "$b")" && pwd)/$(basename "$b")"
}

# Wall clock in microseconds, and a duration in microseconds as seconds with two decimals.
now_us() { local t=${EPOCHREALTIME/[.,]/}; echo "$((10#$t))"; }
secs() { printf '%d.%02d' "$(($1 / 1000000))" "$(($1 % 1000000 / 10000))"; }

# ---------------------------------------------------------------------------------------------
# Inputs (written into OUTDIR before any invocation).
write_inputs() {
    mkdir assets inputs
    local jobs=("$REPO_DIR"/assets/*.toml)
    ((${#jobs[@]} > 0)) || die "no job files in $REPO_DIR/assets"
    cp -- "${jobs[@]}" assets/
    # 60 × 40 mm rectangle (README), with a comment line.
    printf '# rectangle 60 x 40 mm\n0,0\n60,0\n60,40\n0,40\n' >inputs/rect.txt
    # L-shaped pocket, 60 × 60 with arms 25 mm wide (README), one reflex vertex at (25, 25).
    printf '# L shape 60 x 60, arms 25\n0,0\n60,0\n60,25\n25,25\n25,60\n0,60\n' >inputs/l-shape.txt
    # Self-intersecting "bow tie": invalid polygon.
    printf '0,0\n10,10\n10,0\n0,10\n' >inputs/bowtie.txt
    # Engagement: a straight cut with a_e = 2.5 mm along +x (60° once moving, D = 10) ...
    printf 'x,y\n-20,0\n20,0\n' >inputs/straight-path.csv
    printf -- '-50,2.5\n50,2.5\n50,40\n-50,40\n' >inputs/stock-band.txt
    # ... and a polyline along the rectangle's bottom wall, turning up into the stock.
    printf 'x,y\n-10,3\n30,3\n30,25\n45,25\n' >inputs/turn-path.csv
}

# ---------------------------------------------------------------------------------------------
# One invocation: run NAME [--expect CODE] ARGS...; "@P" in an argument becomes NNN-name.
K=0
UNEXPECTED=0
run() {
    local name=$1
    shift
    local expect=0
    if [[ ${1-} == --expect ]]; then
        expect=$2
        shift 2
    fi
    K=$((K + 1))
    local p a
    printf -v p '%03d-%s' "$K" "$name"
    local args=()
    for a in "$@"; do args+=("${a//@P/$p}"); done
    local rc=0 t0
    t0=$(now_us)
    (exec -c -a trochoplan "$BIN" "${args[@]}") </dev/null >"$p.stdout" 2>"$p.stderr" || rc=$?
    echo "$rc" >"$p.exit"
    if [[ ${CLI_SNAPSHOT_TIMES-} == 1 ]]; then
        printf '%7s s  %s\n' "$(secs $(($(now_us) - t0)))" "$p" >&2
    fi
    # A crash between create and rename would leave a PID-named temporary file: give it a fixed
    # name so that the snapshot stays deterministic (and the crash shows in the diff).
    local f
    for f in .*.tmp[0-9]*; do
        [[ -e $f ]] && mv -- "$f" "${f%.tmp*}.tmp-LEFTOVER"
    done
    if [[ $rc != "$expect" ]]; then
        echo "cli-snapshot: warning: $p exited $rc (expected $expect)" >&2
        UNEXPECTED=$((UNEXPECTED + 1))
    fi
}

ext_of() {
    case $1 in
        linuxcnc) echo ngc ;;
        fanuc) echo nc ;;
        grbl) echo gcode ;;
        sinumerik) echo mpf ;;
    esac
}

# ---------------------------------------------------------------------------------------------
invocations() {
    local d j

    # --- help and version (argv[0] is fixed, no terminal: fixed width)
    run help --help
    run version --version
    for c in analyze sweep export corner pocket engagement optimize; do
        run "help-$c" "$c" --help
    done

    # --- analyze: default job, every path type, series CSV, job files, invalid values
    run analyze-default analyze
    run analyze-circular analyze --path circular
    run analyze-circular-type analyze --path circular-type
    run analyze-circular-type-step0.795 analyze --path circular-type --step 0.795
    run analyze-elliptical-0.8 analyze --path elliptical --aspect-ratio 0.8
    run analyze-elliptical-0.5 analyze --path elliptical --aspect-ratio 0.5
    run analyze-elliptical-1.2 analyze --path elliptical --aspect-ratio 1.2
    run analyze-linear-elliptical-d1 analyze --path linear-elliptical --aspect-ratio 0.8 --linear-distance 1
    run analyze-linear-elliptical-d0.5 analyze --path linear-elliptical --aspect-ratio 0.6 --linear-distance 0.5
    run analyze-custom-job analyze --slot-width 24 --slot-length 30 --depth 4 --tool-diameter 12 \
        --teeth 3 --feed 900 --rpm 3000 --step 0.7
    run analyze-engagement-limit30 analyze --path circular-type --engagement-limit 30
    run analyze-series-circular analyze --series @P.csv
    run analyze-series-elliptical-0.8 analyze --path elliptical --aspect-ratio 0.8 --series @P.csv
    run analyze-series-linear-elliptical analyze --path linear-elliptical --aspect-ratio 0.8 \
        --linear-distance 1 --series @P.csv
    for j in assets/*.toml; do
        run "analyze-job-$(basename "$j" .toml)" analyze --job "$j"
    done
    run analyze-job-override-feed800 analyze --job assets/linear-elliptical-d1.toml --feed 800
    run analyze-invalid-tool-diameter --expect 2 analyze --tool-diameter 25
    run analyze-invalid-aspect-ratio --expect 2 analyze --path elliptical --aspect-ratio -1
    run analyze-invalid-path-value --expect 2 analyze --path bogus
    run analyze-missing-job-file --expect 2 analyze --job assets/missing.toml

    # --- sweep
    run sweep-aspect-ratio-table2 sweep --param aspect-ratio --from 0.5 --to 1.2 --steps 8
    run sweep-linear-distance sweep --param linear-distance --from 0 --to 1.25 --steps 6 --aspect-ratio 0.8
    run sweep-step-circular sweep --param step --from 0.5 --to 1.5 --steps 5
    run sweep-step-circular-type sweep --param step --path circular-type --from 0.6 --to 1.0 --steps 5
    run sweep-aspect-ratio-on-circular-type --expect 2 sweep --param aspect-ratio --path circular-type \
        --from 0.5 --to 1 --steps 2
    run sweep-zero-steps --expect 2 sweep --param step --from 0.5 --to 1 --steps 0

    # --- export: the four dialects for four path types
    for d in linuxcnc fanuc grbl sinumerik; do
        run "export-$d-circular" export --dialect "$d" -o "@P.$(ext_of "$d")"
        run "export-$d-circular-type" export --path circular-type --step 0.795 --dialect "$d" \
            -o "@P.$(ext_of "$d")"
        run "export-$d-elliptical-0.8" export --path elliptical --aspect-ratio 0.8 --dialect "$d" \
            -o "@P.$(ext_of "$d")"
        run "export-$d-linear-elliptical" export --job assets/linear-elliptical-d1.toml --dialect "$d" \
            -o "@P.$(ext_of "$d")"
    done
    # ... and the variants
    run export-linuxcnc-elliptical-L100 export --path elliptical --aspect-ratio 0.8 --slot-length 100 \
        --dialect linuxcnc -o @P.ngc
    run export-linuxcnc-compact-circular-type export --job assets/circular-type-46deg.toml --compact \
        --dialect linuxcnc -o @P.ngc
    run export-sinumerik-compact-circular-type export --path circular-type --step 0.795 --compact \
        --dialect sinumerik -o @P.mpf
    run export-linuxcnc-compact-elliptical export --path elliptical --aspect-ratio 0.8 --compact \
        --dialect linuxcnc -o @P.ngc
    run export-sinumerik-compact-linear-elliptical export --job assets/linear-elliptical-d1.toml --compact \
        --dialect sinumerik -o @P.mpf
    run export-linuxcnc-linear-segments-elliptical export --path elliptical --aspect-ratio 0.8 \
        --linear-segments --dialect linuxcnc -o @P.ngc
    run export-fanuc-linear-segments-circular-type export --path circular-type --step 0.795 \
        --linear-segments --dialect fanuc -o @P.nc
    run export-linuxcnc-return-feed-circular export --return-feed 1200 --dialect linuxcnc -o @P.ngc
    run export-grbl-return-feed-elliptical export --path elliptical --aspect-ratio 0.8 --return-feed 900 \
        --dialect grbl -o @P.gcode
    run export-fanuc-coolant-elliptical export --path elliptical --aspect-ratio 0.8 --coolant \
        --dialect fanuc -o @P.nc
    run export-sinumerik-coolant-circular export --coolant --dialect sinumerik -o @P.mpf
    run export-linuxcnc-title export --title 'Slot (A); test' --dialect linuxcnc -o @P.ngc
    run export-sinumerik-title export --path circular-type --title 'Slot (A); test' --dialect sinumerik \
        -o @P.mpf
    run export-fanuc-tolerance0.02 export --path elliptical --aspect-ratio 0.8 --tolerance 0.02 \
        --dialect fanuc -o @P.nc
    run export-grbl-all-options export --path linear-elliptical --aspect-ratio 0.8 --linear-distance 1 \
        --linear-segments --coolant --return-feed 900 --title 'all options' --dialect grbl -o @P.gcode
    run export-invalid-tolerance --expect 2 export --tolerance 0 --dialect fanuc -o @P.nc

    # --- corner: each method at a couple of angles, the acceptance table of one method, export
    run corner-plain-90 corner --angle 90 --method plain
    run corner-plain-60 corner --angle 60 --method plain
    run corner-variable-90 corner --angle 90 --method variable
    run corner-variable-60 corner --angle 60 --method variable
    run corner-variable-120 corner --angle 120 --method variable
    run corner-variable-75-step-over2.5 corner --angle 75 --method variable --step-over 2.5
    run corner-isometric-90 corner --angle 90 --method isometric
    run corner-isometric-60 corner --angle 60 --method isometric
    run corner-medial-axis-90 corner --angle 90 --method medial-axis
    run corner-medial-axis-120 corner --angle 120 --method medial-axis
    for d in plain variable isometric medial-axis; do
        run "corner-table-$d" corner --method "$d" --table
    done
    run corner-export-variable-90-linuxcnc corner --angle 90 --method variable --spacing 1 \
        --export @P.ngc --dialect linuxcnc
    run corner-export-variable-90-sinumerik corner --angle 90 --method variable --spacing 1 \
        --export @P.mpf --dialect sinumerik
    run corner-export-isometric-60-fanuc-options corner --angle 60 --method isometric --spacing 1 \
        --export @P.nc --dialect fanuc --linear-segments --coolant --depth 3 --rpm 3000 --title 'corner 60'
    run corner-export-medial-axis-90-grbl corner --angle 90 --method medial-axis --spacing 1 \
        --export @P.gcode --dialect grbl --nc-tolerance 0.01
    run corner-invalid-angle180 --expect 2 corner --angle 180
    run corner-table-with-export --expect 2 corner --table --export @P.ngc

    # --- pocket: rectangle and L, adaptive / plain / variable / isometric / medial axis, exports
    for j in rect l-shape; do
        for d in adaptive plain variable isometric medial-axis; do
            run "pocket-$j-$d" pocket --polygon "inputs/$j.txt" --method "$d"
        done
    done
    run pocket-rect-plain-ae1.527 pocket --polygon inputs/rect.txt --step-over 1.527
    run pocket-export-rect-plain-linuxcnc pocket --polygon inputs/rect.txt --export @P.ngc --dialect linuxcnc
    run pocket-export-rect-plain-fanuc pocket --polygon inputs/rect.txt --export @P.nc --dialect fanuc
    run pocket-export-rect-variable-sinumerik pocket --polygon inputs/rect.txt --method variable \
        --export @P.mpf --dialect sinumerik
    run pocket-export-l-shape-variable-grbl-options pocket --polygon inputs/l-shape.txt --method variable \
        --export @P.gcode --dialect grbl --linear-segments --coolant --depth 4 --rpm 2500 --title 'L pocket'
    run pocket-export-rect-medial-axis-linuxcnc pocket --polygon inputs/rect.txt --method medial-axis \
        --export @P.ngc --dialect linuxcnc
    run pocket-export-l-shape-medial-axis-fanuc pocket --polygon inputs/l-shape.txt --method medial-axis \
        --export @P.nc --dialect fanuc --nc-tolerance 0.01
    for d in adaptive plain variable isometric medial-axis; do
        run "pocket-export-rect-$d-linuxcnc" pocket --polygon inputs/rect.txt --method "$d" \
            --step-over 1.527 --export @P.ngc --dialect linuxcnc
    done
    run pocket-export-l-shape-adaptive-sinumerik pocket --polygon inputs/l-shape.txt --method adaptive \
        --export @P.mpf --dialect sinumerik
    run pocket-export-l-shape-adaptive-fanuc-options pocket --polygon inputs/l-shape.txt --depth 4 \
        --rpm 2500 --coolant --linear-segments --export @P.nc --dialect fanuc --title 'L adaptive'
    run pocket-rect-adaptive-open-edge0 pocket --polygon inputs/rect.txt --step-over 1.527 --open-edges 0
    run pocket-export-rect-adaptive-open-edges02-grbl pocket --polygon inputs/rect.txt --step-over 1.527 \
        --open-edges 0,2 --export @P.gcode --dialect grbl
    run pocket-l-shape-adaptive-conventional pocket --polygon inputs/l-shape.txt --direction conventional
    run pocket-invalid-bowtie --expect 2 pocket --polygon inputs/bowtie.txt

    # --- optimize: the limits alone, a job file, a machine preset
    run optimize-hmax0.1-eng60 optimize --max-hmax 0.1 --max-engagement 60
    run optimize-job-vmc optimize --job assets/linear-elliptical-d1.toml --machine vmc --max-hmax 0.08 \
        --max-engagement 50 --max-waviness 0.02
    run optimize-invalid-hmax --expect 2 optimize --max-hmax -1 --max-engagement 60

    # --- engagement
    run engagement-straight engagement --path-csv inputs/straight-path.csv \
        --stock-polygon inputs/stock-band.txt --spacing 1
    run engagement-turn-D8 engagement --path-csv inputs/turn-path.csv --stock-polygon inputs/rect.txt \
        --tool-diameter 8 --spacing 0.5
    run engagement-invalid-bowtie --expect 2 engagement --path-csv inputs/straight-path.csv \
        --stock-polygon inputs/bowtie.txt
}

# Snapshot BINARY into OUTDIR (in a subshell: it changes directory and sets an EXIT trap).
snapshot() {
    local src out=$2
    src=$(resolve_bin "$1")
    mkdir -p -- "$out"
    [[ -z $(ls -A -- "$out") ]] || die "$out is not empty"
    # Run a private copy: a build into a shared target folder must not swap the binary mid-run.
    local bin_dir
    bin_dir=$(mktemp -d "${TMPDIR:-/tmp}/cli-snapshot-bin.XXXXXX")
    # shellcheck disable=SC2064 # expand $bin_dir now
    trap "rm -rf -- '$bin_dir'" EXIT
    cp -- "$src" "$bin_dir/trochoplan"
    BIN=$bin_dir/trochoplan
    cd -- "$out"
    shopt -s nullglob
    write_inputs
    local t0
    t0=$(now_us)
    invocations
    echo "cli-snapshot: $K invocations of $src into $out in $(secs $(($(now_us) - t0))) s" >&2
    if ((UNEXPECTED > 0)); then
        echo "cli-snapshot: warning: $UNEXPECTED invocation(s) exited with an unexpected code" >&2
    fi
}

compare() {
    local a b
    a=$(resolve_bin "$1")
    b=$(resolve_bin "$2")
    local tmp
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-snapshot.XXXXXX")
    # shellcheck disable=SC2064 # expand $tmp now
    trap "rm -rf -- '$tmp'" EXIT
    (snapshot "$a" "$tmp/a")
    (snapshot "$b" "$tmp/b")
    local n rc=0
    n=$(find "$tmp/a" -maxdepth 1 -name '*.exit' | wc -l)
    (cd "$tmp" && diff -rq a b) >"$tmp/summary" || rc=$?
    if ((rc == 0)); then
        echo "$n invocations identical"
        return 0
    fi
    ((rc == 1)) || die "diff failed"
    echo "cli-snapshot: outputs differ (a: $a, b: $b):"
    cat "$tmp/summary"
    echo
    (cd "$tmp" && diff -ru a b) || true
    exit 1
}

case ${1-} in
    --compare)
        [[ $# == 3 ]] || usage
        compare "$2" "$3"
        ;;
    -h | --help) usage 0 ;;
    "") usage ;;
    -*) usage ;;
    *)
        [[ $# == 2 ]] || usage
        (snapshot "$1" "$2")
        ;;
esac
