#!/bin/sh
# The seeds' experiments, rerun with this project's own tools (oitgen,
# oitprep, oitbench), and set beside the papers' published figures:
#
#   Wang & Xie Table 1  management schemes on the Dragon: parts,
#                                  triangles, file size, preprocessing
#                                  seconds, stream ms per frame
#            Table 2               per model: triangles, averaged max
#                                  layers, parts, preprocessing seconds, and
#                                  ms per frame of every exact method,
#                                  transparent and translucent
#            (and the dragon's part file with every threshold method at four
#            thresholds: early termination as speed against error)
#            Table 3               GPU memory at 20, 60 and 100 layers
#                                  (oitgen quads), at the paper's 1024x1024
#   Maule et al. Table I  the bunny at 500, 800 and 1100 square
#            Fig. 5                synthetic quads: 1, 5, 10 layers at two
#                                  coverages
#            Fig. 7                1, 5 and 10 instances of the dragon
#
# then `oitbench plot` over the runs of one image size, and OUT_DIR/report.md
# with the machine, the command line, every table and the charts. Each run's
# own folder (results.csv, report.md, charts) stays under OUT_DIR/runs.
#
# Usage: data_scripts/paper_suite.sh BIN_DIR OUT_DIR [SIZE]
#   SIZE (default 256x256) is the image size of everything but Table 3 and
#   Table I, which use the papers' sizes. Environment: PAPER_ORBIT (views per
#   run, default 2), PAPER_FRAMES (timed frames, default 2), PAPER_MEMORY_SIZE
#   (Table 3, default 1024x1024), PAPER_NOTE (a line for the report, e.g. that
#   another job shared the machine), OIT_MESH_CACHE (default
#   data_scripts/cache; models missing there are skipped and say so).
# Takes about 10 minutes on 2 cores with llvmpipe at 256x256. Not part of
# ctest. Exit 1 when a run failed outright (its row says so).
set -u
usage() { sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
case "${1:-}" in -h | --help) usage; exit 0 ;; esac
[ $# -ge 2 ] || { usage >&2; exit 2; }
BIN=$1 OUT=$2 SIZE=${3:-256x256}
ORBIT=${PAPER_ORBIT:-2} FRAMES=${PAPER_FRAMES:-2} MEMSIZE=${PAPER_MEMORY_SIZE:-1024x1024}
CACHE=${OIT_MESH_CACHE:-$(dirname "$0")/cache}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
for t in oitgen oitprep oitbench; do
    [ -x "$BIN/$t" ] || { echo "paper_suite: $BIN/$t: not found (build first)" >&2; exit 2; }
done
# scenes and part files are big and made again in seconds: they stay in a
# scratch folder; oitprep's figures go to OUT_DIR/prep
RUNS="$OUT/runs" PREP="$OUT/prep" MD="$OUT/report.md" CMDS="$OUT/commands.txt"
SCENES=$(mktemp -d) && trap 'rm -rf "$SCENES"' EXIT
mkdir -p "$RUNS" "$PREP" || exit 1
: >"$CMDS"
FAILED=0
START=$(date +%s)

say() { echo "paper_suite: $*" >&2; }
log() { echo "$*" >>"$CMDS"; }

# ---- running -------------------------------------------------------------

# bench NAME MODEL OITBENCH_ARGS...: one oitbench run into runs/NAME
bench() {
    name=$1 model=$2
    shift 2
    log "$BIN/oitbench $model $* --out $RUNS/$name"
    say "run $name"
    if ! "$BIN/oitbench" "$model" "$@" --out "$RUNS/$name" 2>"$RUNS/$name.log"; then
        say "run $name failed: $(tail -n 1 "$RUNS/$name.log")"
        FAILED=$((FAILED + 1))
    fi
}

# prep NAME INPUT [OITPREP_ARGS...]: NAME.oitp in the scratch folder, its
# --stats in prep/NAME.json
prep() {
    name=$1 input=$2
    shift 2
    log "$BIN/oitprep $input -o $SCENES/$name.oitp $* --stats $PREP/$name.json"
    if ! "$BIN/oitprep" "$input" -o "$SCENES/$name.oitp" "$@" --stats "$PREP/$name.json" \
        >"$PREP/$name.log" 2>&1; then
        say "oitprep $name failed: $(tail -n 1 "$PREP/$name.log")"
        FAILED=$((FAILED + 1))
        return 1
    fi
    wc -c <"$SCENES/$name.oitp" >"$PREP/$name.bytes"
}

gen() {
    log "$BIN/oitgen $*"
    "$BIN/oitgen" "$@" >/dev/null || { say "oitgen $* failed"; FAILED=$((FAILED + 1)); }
}

# ---- reading results -----------------------------------------------------

# col RUN METHOD COLUMN: a summary figure of results.csv ("" when absent).
# Columns 1-12 hold no commas; reason (13) may, so the columns after it
# count from the end (the header's own count, whatever columns it has).
col() {
    f="$RUNS/$1/results.csv"
    [ -s "$f" ] || return 0
    awk -F, -v m="$2" -v name="$3" '
        NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; h = NF; next }
        $1 == "summary" && $2 == m {
            if (!(name in c)) exit
            print (c[name] > 13 ? $(NF - (h - c[name])) : $c[name])
            exit
        }' "$f"
}

# avg_layers RUN: mean over the views of their depth (the reference's).
avg_layers() {
    f="$RUNS/$1/results.csv"
    [ -s "$f" ] || return 0
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "view_max_layers") k = NF - i; next }
             $1 == "view" && !($3 in d) { d[$3] = $(NF - k); s += $(NF - k); n++ }
             END { if (n) printf "%.1f", s / n }' "$f"
}

# ms RUN METHOD: median ms, or "-" with why
ms() {
    v=$(col "$1" "$2" ms_median)
    st=$(col "$1" "$2" status)
    if [ "$st" = ok ] && [ -n "$v" ]; then printf '%.1f' "$v"; else printf 'not run'; fi
}

fps() {
    v=$(col "$1" "$2" ms_median)
    st=$(col "$1" "$2" status)
    if [ "$st" = ok ] && [ -n "$v" ]; then awk -v m="$v" 'BEGIN { printf "%.1f", 1000 / m }'
    else printf 'not run'; fi
}

mib() {
    v=$(col "$1" "$2" gpu_bytes_peak)
    if [ -n "$v" ]; then awk -v b="$v" 'BEGIN { printf "%.1f", b / 1048576 }'; else printf -- '-'; fi
}

# ratio RUN METHOD: the paper's speed-up of stream over METHOD, (old-new)/new
ratio() {
    a=$(col "$1" stream ms_median) b=$(col "$1" "$2" ms_median)
    if [ -n "$a" ] && [ -n "$b" ] && [ "$(col "$1" "$2" status)" = ok ]; then
        awk -v n="$a" -v o="$b" 'BEGIN { printf "(%.2f)", (o - n) / n }'
    fi
}

json() { sed -n "s/.*\"$1\": *\([-0-9.eE]*\).*/\1/p" "$2" | head -n 1; }

# why RUN METHOD: the reason a method did not run, short
why() {
    f="$RUNS/$1/results.csv"
    [ -s "$f" ] && grep "^summary,$2,,not_runnable," "$f" | sed 's/^[^"]*"//; s/",[0-9][^"]*$//' |
        cut -c1-110
}

renderer() {
    for j in "$RUNS"/*/results.json; do
        [ -s "$j" ] && sed -n 's/.*"renderer": "\([^"]*\)".*/\1/p' "$j" && return
    done
}

COMMON="--orbit $ORBIT --frames $FRAMES --warmup 1 --size $SIZE"
EXACT=stream,dfb,pll,b3d,dp,ddp
DFBPAPER=b3d,dfb,ppll4,pll

# ---- Wang & Xie, Table 1: management schemes --------------------------------

DRAGON="$CACHE/ChineseDragon-10kv.off"
table1() {
    [ -f "$DRAGON" ] || { say "Table 1 skipped: $DRAGON missing"; return; }
    prep t1_default "$DRAGON"
    prep t1_grid16 "$DRAGON" --grid 16
    prep t1_kd "$DRAGON" --manage kd-parts
    prep t1_facets "$DRAGON" --manage kd-facets
    for v in default grid16 kd facets; do
        [ -s "$SCENES/t1_$v.oitp" ] && bench "t1_$v" "$SCENES/t1_$v.oitp" --methods stream $COMMON
    done
}

table1_md() {
    echo "## Wang & Xie, Table 1: managing parts (the Dragon)"
    echo
    echo "Paper (Dragon, 871K triangles; Xeon E5620 2.4 GHz 8 cores, 8 GB, GeForce GTX 680"
    echo "2 GB; 1024x1024; storage excludes the vertex data):"
    echo
    echo "| scheme | parts | storage MB | preprocessing s | ms per frame |"
    echo "|---|---|---|---|---|"
    echo "| kd-tree (facets) | 216K | 10.5 | 7 | 103.09 |"
    echo "| kd-tree (parts) | 52 | 3.9 | 17 | 4.88 |"
    echo "| ours (grid + subgrids) | 36 | 3.7 | 15 | 3.98 |"
    echo
    echo "Here: ChineseDragon-10kv.off ($(json triangles_in "$PREP/t1_default.json" 2>/dev/null)"
    echo "triangles, a 44th of the paper's Dragon), $SIZE, stream only, oitprep on"
    echo "$(json threads "$PREP/t1_default.json" 2>/dev/null) threads. --manage grid (the default) kd-subdivides"
    echo "the cells of a top grid until a cell's parts can be ordered; --manage kd-parts"
    echo "builds one kd-tree over the model's convex pieces, one part a leaf; --manage"
    echo "kd-facets one over single facets, leaves of at most K = 8 (the paper's facet"
    echo "tree). --grid 16 adds a finer top grid. The file holds everything (vertices"
    echo "included), and the kd clipping splits triangles, so \"triangles out\" exceeds"
    echo "the input."
    echo
    echo "| oitprep options | parts | triangles out | file MB | preprocessing s | stream ms per frame |"
    echo "|---|---|---|---|---|---|"
    for v in "default:--manage grid" "grid16:--grid 16" "kd:--manage kd-parts" "facets:--manage kd-facets"; do
        k=${v%%:*} opts=${v#*:}
        j="$PREP/t1_$k.json"
        if [ ! -s "$j" ]; then echo "| $opts | not run | | | | |"; continue; fi
        printf '| %s | %s | %s | %.1f | %s | %s |\n' "$opts" "$(json parts "$j")" \
            "$(json triangles_out "$j")" \
            "$(awk '{ print $1 / 1e6 }' "$PREP/t1_$k.bytes")" \
            "$(json total "$j")" "$(ms "t1_$k" stream)"
    done
    echo
}

# ---- Wang & Xie, Table 2: models, transparent and translucent --------------

# name:input pairs; the plant stands in for the Powerplant at a size
# llvmpipe renders in seconds
T2_MODELS="elephant:$CACHE/refined_elephant.off dragon:$CACHE/ChineseDragon-10kv.off bunny:$CACHE/bunny00.off plant20k:$SCENES/plant20k.ply"

table2() {
    gen plant --triangles 20000 -o "$SCENES/plant20k.ply"
    for pair in $T2_MODELS; do
        n=${pair%%:*} in=${pair#*:}
        [ -f "$in" ] || { say "Table 2: $in missing, skipped"; continue; }
        prep "t2_$n" "$in" || continue
        for sh in transparent translucent; do
            bench "t2_${n}_$sh" "$SCENES/t2_$n.oitp" --methods $EXACT --shading $sh $COMMON
        done
    done
}

table2_md() {
    echo "## Wang & Xie, Table 2: models, transparent and translucent"
    echo
    echo "Paper (ms per frame, 1024x1024, averaged over many views; in brackets the"
    echo "speed-up of ours, (old - new) / new; same machine as Table 1):"
    echo
    echo "| | Horse | Dragon | Buddha | Powerplant | Lucy | Xyzrgb_dragon |"
    echo "|---|---|---|---|---|---|---|"
    echo "| triangles | 97K | 871K | 1,087K | 12,748K | 28,055K | 43,313K |"
    echo "| averaged max layers | 11 | 13 | 16 | 152 | 26 | 29 |"
    echo "| decomposed parts | 14 | 36 | 48 | 2968 | 1131 | 2115 |"
    echo "| preprocessing s | 2 | 15 | 19 | 286 | 143 | 206 |"
    echo "| transparent: ours | 2.05 | 3.98 | 4.24 | 64.18 | 79.55 | 114.03 |"
    echo "| ABS (A-buffer) | 2.6 (0.27) | 5.54 (0.39) | 6.05 (0.43) | 96.9 (0.51) | 123.15 (0.55) | 190.11 (0.67) |"
    echo "| DDP | 3.09 (0.51) | 5.37 (0.35) | 7.17 (0.7) | 4761.9 (73.2) | 4166.67 (51.38) | 6250 (53.81) |"
    echo "| DP | 4.32 (1.11) | 10.83 (1.72) | 13.63 (2.21) | 10000 (154.81) | 8333.33 (103.76) | 12500 (108.62) |"
    echo "| translucent: ours | 2.15 | 4.56 | 4.7 | 82.24 | 106.16 | 149.03 |"
    echo "| ABS (A-buffer) | 2.89 (0.34) | 6.87 (0.51) | 7.22 (0.54) | 124.84 (0.52) | 160.51 (0.51) | 252.53 (0.69) |"
    echo "| DDP | 3.49 (0.62) | 6.13 (0.34) | 8.24 (0.75) | 6666.67 (80.06) | 5555.56 (51.33) | 8333.33 (54.92) |"
    echo "| DP | 5.17 (1.4) | 12.31 (1.7) | 16.32 (2.47) | 14285.71 (172.71) | 11111.11 (103.66) | 16666.67 (110.83) |"
    echo
    echo "Models here: elephant (refined_elephant.off, near the Horse's size), dragon"
    echo "(ChineseDragon-10kv.off), bunny (bunny00.off) and plant20k (oitgen plant"
    echo "--triangles 20000, a procedural plant standing in for the Powerplant at a"
    echo "size llvmpipe renders in seconds)."
    echo
    echo "(The paper also lists MDTS, BDP, BDP2 and ADP, which this project does not"
    echo "implement.) Here: $SIZE, views: $ORBIT, median of $FRAMES timed frames a view;"
    echo "\"ours\" is stream, ABS is matched by b3d (a fixed per-pixel array), and dfb"
    echo "and pll are added. Every method renders the part file's triangles (oitprep's"
    echo "kd clipping multiplies them; \"triangles\" gives in / out), side by side in"
    echo "one oitbench run. In brackets the same speed-up of stream over the method:"
    echo "negative where the method is faster than stream here."
    echo
    printf '| |'
    for pair in $T2_MODELS; do printf ' %s |' "${pair%%:*}"; done
    printf '\n|---|'
    for pair in $T2_MODELS; do printf -- '---|'; done
    printf '\n'
    row() { # LABEL FUNCTION...: one table row over the models
        label=$1
        shift
        printf '| %s |' "$label"
        for pair in $T2_MODELS; do printf ' %s |' "$("$@" "${pair%%:*}")"; done
        printf '\n'
    }
    t2_tri() {
        j="$PREP/t2_$1.json"
        [ -s "$j" ] && printf '%s / %s' "$(json triangles_in "$j")" "$(json triangles_out "$j")"
    }
    t2_layers() { avg_layers "t2_$1_transparent"; }
    t2_parts() { [ -s "$PREP/t2_$1.json" ] && json parts "$PREP/t2_$1.json"; }
    t2_secs() { [ -s "$PREP/t2_$1.json" ] && json total "$PREP/t2_$1.json"; }
    t2_cell() { # SHADING METHOD MODEL
        printf '%s' "$(ms "t2_$3_$1" "$2")"
        r=$(ratio "t2_$3_$1" "$2")
        [ "$2" = stream ] || [ -z "$r" ] || printf ' %s' "$r"
    }
    row "triangles in / out" t2_tri
    row "averaged max layers" t2_layers
    row "parts" t2_parts
    row "preprocessing s" t2_secs
    for sh in transparent translucent; do
        for m in stream b3d ddp dp dfb pll; do
            label=$m
            [ $m = stream ] && label="$sh: stream"
            row "$label" t2_cell $sh $m
        done
    done
    echo
    for pair in $T2_MODELS; do
        r=$(why "t2_${pair%%:*}_translucent" ddp)
        [ -n "$r" ] && { echo "ddp, translucent: not run: $r"; echo; break; }
    done
}

# ---- early termination: the thresholds as points of speed against error ----

sweep() {
    [ -s "$SCENES/t2_dragon.oitp" ] || { say "threshold sweep skipped: no dragon part file"; return; }
    bench eps_dragon "$SCENES/t2_dragon.oitp" --methods stream,f2b,guarded,dfb \
        --epsilon 0,0.01,0.05,0.2 $COMMON
}

sweep_md() {
    echo "## Early termination: speed against error (DESIGN.md; seeds 001, 004)"
    echo
    echo "The dragon's part file with every threshold method at 0, 0.01, 0.05 and 0.2"
    echo "(stream: transmittance; f2b: alpha threshold; guarded: contribution), dfb"
    echo "beside them, $SIZE, views: $ORBIT. Mean RMSE against the reference; the"
    echo "exact methods' floor is where rasterization and the reference's rays"
    echo "disagree on silhouette pixels."
    echo
    echo "| entry | ms per frame | mean rmse | worst % pixels off by > 1/255 |"
    echo "|---|---|---|---|"
    for m in dfb stream@0 stream@0.01 stream@0.05 stream@0.2 f2b@0 f2b@0.01 f2b@0.05 f2b@0.2 \
             guarded@0 guarded@0.01 guarded@0.05 guarded@0.2; do
        printf '| %s | %s | %s | %s |\n' $m "$(ms eps_dragon $m)" "$(col eps_dragon $m rmse)" \
            "$(col eps_dragon $m pct_over_1_255)"
    done
    echo
    echo "![speed against error, the dragon](runs/eps_dragon/speed_vs_error.png)"
    echo
}

# ---- Wang & Xie, Table 3: memory against layers ------------------------------

table3() {
    for n in 20 60 100; do
        gen quads --count $n -o "$SCENES/quads$n.ply"
        prep "t3_quads$n" "$SCENES/quads$n.ply" || continue
        bench "t3_quads$n" "$SCENES/t3_quads$n.oitp" --methods $EXACT --orbit 1 --frames 1 \
            --warmup 0 --size "$MEMSIZE"
    done
}

table3_md() {
    echo "## Wang & Xie, Table 3: GPU memory against depth layers"
    echo
    echo "Paper (MB, 1024x1024):"
    echo
    echo "| depth layers | ours | MDTS | ABS | BDP | BDP2 | ADP | DDP | DP |"
    echo "|---|---|---|---|---|---|---|---|---|"
    echo "| 20 | 36 | 80 | 81 | 128 | 256 | 208 | 16 | 8 |"
    echo "| 60 | 36 | 240 | 244 | 128 | 256 | 208 | 16 | 8 |"
    echo "| 100 | 36 | 400 | 404 | 128 | 256 | 208 | 16 | 8 |"
    echo
    echo "Here: oitgen quads --count 20 / 60 / 100 (coverage 0.5), converted, one view"
    echo "(azimuth 0, elevation 20) at $MEMSIZE: GPU buffers and textures each method"
    echo "allocated at its peak, in MiB (the model's own vertex buffer included;"
    echo "stream's figure is its upload ring, slot budget and screen buffers, all"
    echo "bounded whatever the depth). \"depth\" is the most surfaces the reference ray"
    echo "met at one pixel."
    echo
    echo "| quads | depth | stream | b3d | dfb | pll | ddp | dp |"
    echo "|---|---|---|---|---|---|---|---|"
    for n in 20 60 100; do
        r="t3_quads$n"
        printf '| %s | %s |' "$n" "$(col $r dfb view_max_layers)"
        for m in stream b3d dfb pll ddp dp; do
            if [ "$(col $r $m status)" = ok ]; then printf ' %s |' "$(mib $r $m)"
            else printf ' not run |'; fi
        done
        printf '\n'
    done
    echo
    for n in 20 60 100; do
        for m in stream b3d dfb pll ddp dp; do
            r=$(why "t3_quads$n" $m)
            [ -n "$r" ] && echo "- $m at $n quads not run: $r"
        done
    done
    echo
    echo "![memory against depth, $MEMSIZE](plots-memory/memory_vs_depth.png)"
    echo
}

# ---- Maule et al.: Table I, Fig. 5, Fig. 7 --------------------------------------

BUNNY="$CACHE/bunny00.off"
seed000() {
    if [ -f "$BUNNY" ]; then
        for s in 500 800 1100; do
            bench "t0_bunny$s" "$BUNNY" --methods $DFBPAPER --orbit 1 --frames $FRAMES \
                --warmup 1 --size "${s}x$s"
        done
    else
        say "Table I skipped: $BUNNY missing"
    fi
    for cov in 0.25 1; do
        for n in 1 5 10; do
            gen quads --count $n --coverage $cov -o "$SCENES/f5_q${n}_c$cov.ply"
            bench "f5_q${n}_c$cov" "$SCENES/f5_q${n}_c$cov.ply" --methods $DFBPAPER $COMMON
        done
    done
    [ -f "$DRAGON" ] || { say "Fig. 7 skipped: $DRAGON missing"; return; }
    for n in 1 5 10; do
        gen instances --input "$DRAGON" --count $n -o "$SCENES/f7_dragon$n.ply"
        bench "f7_dragon$n" "$SCENES/f7_dragon$n.ply" --methods $DFBPAPER $COMMON
    done
}

seed000_md() {
    echo "## Maule et al. (Dynamic Fragment Buffer)"
    echo
    echo "Paper: Intel i7 980, GeForce GTX 580 (1.5 GB), Windows 7; frames per second."
    echo
    echo "### Table I: the bunny (paper: decimated, 69K triangles; here bunny00.off, 75K)"
    echo
    echo "| size | B3D | DFB | PLL4 (ppll4) | PLL1 (pll) |"
    echo "|---|---|---|---|---|"
    echo "| paper 500x500 | 1250 | 500 | 500 | 333 |"
    echo "| paper 800x800 | 625 | 294 | 213 | 141 |"
    echo "| paper 1100x1100 | 345 | 170 | 114 | 74 |"
    for s in 500 800 1100; do
        printf '| here %sx%s |' $s $s
        for m in b3d dfb ppll4 pll; do printf ' %s |' "$(fps "t0_bunny$s" $m)"; done
        printf '\n'
    done
    echo
    echo "(DxDFB, the paper's fifth column, is not implemented.) Here: one view, median"
    echo "of $FRAMES timed frames."
    echo
    echo "### Fig. 5: synthetic quads (paper: a chart, FPS of 1, 5, 10 quads at several"
    echo "coverages and resolutions; B3D fastest, DFB second above 25% coverage)"
    echo
    echo "Here: oitgen quads --count N --coverage C, $SIZE, views: $ORBIT; frames per"
    echo "second, and GPU MiB at peak in brackets."
    echo
    echo "| quads | coverage | depth | b3d | dfb | ppll4 | pll |"
    echo "|---|---|---|---|---|---|---|"
    for cov in 0.25 1; do
        for n in 1 5 10; do
            r="f5_q${n}_c$cov"
            printf '| %s | %s | %s |' $n $cov "$(col $r dfb view_max_layers)"
            for m in b3d dfb ppll4 pll; do printf ' %s (%s) |' "$(fps $r $m)" "$(mib $r $m)"; done
            printf '\n'
        done
    done
    echo
    echo "### Fig. 7: instances of the dragon (paper: 871,414 triangles each; up to 20,"
    echo "28 and 46 layers for 1, 5, 10 instances; B3D fastest but out of memory in 4 of"
    echo "9 tests, DFB fastest of the rest in 8 of 9 with the least memory)"
    echo
    echo "Here: oitgen instances --input ChineseDragon-10kv.off --count N (19,994"
    echo "triangles each), $SIZE, views: $ORBIT; frames per second, GPU MiB in brackets."
    echo
    echo "| instances | triangles | depth | b3d | dfb | ppll4 | pll |"
    echo "|---|---|---|---|---|---|---|"
    for n in 1 5 10; do
        r="f7_dragon$n"
        printf '| %s | %s | %s |' $n "$(col $r dfb triangles)" "$(col $r dfb view_max_layers)"
        for m in b3d dfb ppll4 pll; do printf ' %s (%s) |' "$(fps $r $m)" "$(mib $r $m)"; done
        printf '\n'
    done
    echo
}

# ---- the whole ------------------------------------------------------------

table1
table2
sweep
table3
seed000

# charts across the runs of one image size (Table 3 and Table I differ)
SAME=""
for d in "$RUNS"/t2_*_transparent "$RUNS"/f5_* "$RUNS"/f7_*; do
    [ -s "$d/results.csv" ] && SAME="$SAME $d"
done
MEM=""
for d in "$RUNS"/t3_*; do [ -s "$d/results.csv" ] && MEM="$MEM $d"; done
log "$BIN/oitbench plot $OUT/plots$SAME"
"$BIN/oitbench" plot "$OUT/plots" $SAME 2>>"$CMDS.log" || { say "oitbench plot failed"; FAILED=$((FAILED + 1)); }
log "$BIN/oitbench plot $OUT/plots-memory$MEM"
"$BIN/oitbench" plot "$OUT/plots-memory" $MEM 2>>"$CMDS.log" || { say "oitbench plot (memory) failed"; FAILED=$((FAILED + 1)); }
END=$(date +%s)

{
    echo "# The papers' experiments with this project's tools"
    echo
    echo "Written by \`data_scripts/paper_suite.sh\`; every command it ran is in"
    echo "[commands.txt](commands.txt), every run's own report, results.csv and charts"
    echo "under [runs/](runs/)."
    echo
    echo "- command: \`$0 $BIN $OUT $SIZE\` (PAPER_ORBIT=$ORBIT PAPER_FRAMES=$FRAMES PAPER_MEMORY_SIZE=$MEMSIZE)"
    echo "- machine: $(nproc) CPU cores ($(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1)), $(awk '/^MemTotal/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo) memory, $(uname -sm)"
    echo "- GL renderer: $(renderer)"
    echo "- source: $(git -C "$(dirname "$0")" rev-parse --short HEAD 2>/dev/null || echo unknown), $(date -u '+%Y-%m-%d %H:%M UTC'); the suite took $((END - START)) s"
    [ -n "${PAPER_NOTE:-}" ] && echo "- note: $PAPER_NOTE"
    echo
    echo "The papers measured GPUs at 1024x1024; a software renderer measures CPU work."
    echo "Only ratios between methods of one run (measured side by side, interleaved)"
    echo "carry over, and even those favour what is cheap on a CPU. Memory figures do"
    echo "not depend on the machine."
    echo
    table1_md
    table2_md
    sweep_md
    table3_md
    seed000_md
    echo "## Charts across the runs at $SIZE"
    echo
    echo "\`oitbench plot\` over Table 2 (transparent), Fig. 5 and Fig. 7:"
    echo
    echo "![time against triangles](plots/time_vs_triangles.png)"
    echo
    echo "![memory against depth](plots/memory_vs_depth.png)"
    echo
    echo "Each run's own speed-against-error and memory charts are in its folder under"
    echo "runs/."
    echo
    if [ "$FAILED" -ne 0 ]; then echo "**$FAILED step(s) failed; see runs/*.log.**"; echo; fi
} >"$MD"
say "wrote $MD ($((END - START)) s, $FAILED failure(s))"
[ "$FAILED" -eq 0 ]
