#!/bin/sh
# --help against behaviour, for every numeric option of every tool.
# For each option below, the range and default are read from the tool's
# --help text (not from this script), then:
#   - both ends of the range are accepted (the run gets past parsing: an
#     output under /proc/oit_none makes it stop with exit 1 before any work),
#     and values just outside are refused with exit 2 and one stderr line
#     naming the option;
#   - the default is inside the range, and running with `--opt DEFAULT`
#     gives the same output, byte for byte, as running without the option
#     (so the printed default is the code's default).
# Ranges are written in --help as LO..HI (integers, suffix K/M/G allowed),
# [LO, HI] / (LO, HI] / [LO, HI) (numbers), ">= N" or "> 0".
set -u
. "${OIT_TEST_LIB:-$(dirname "$0")/../lib.sh}"
need_every_tool
scratch help_ranges
NO=/proc/oit_none

"$G" quads --count 4 -o "$T/m.ply" >/dev/null || die "oitgen quads"
prep_or_die "$T/m.ply" "$T/m.oitp"
"$S" "$T/m.ply" --size 8x8 --quiet --out "$T/a.png" 2>/dev/null &&
    cp "$T/a.png" "$T/b.png" || die "oitstream"

# The command of a tool form; OUT is replaced by the output path.
form() {
    case $1 in
    prep) echo "$P $T/m.ply -o OUT" ;;
    verify) echo "$P verify $T/m.oitp" ;;
    parts) echo "$P parts $T/m.oitp -o OUT" ;;
    stream) echo "$S $T/m.ply --size 8x8 --quiet --out OUT" ;;
    streamfull) echo "$S $T/m.ply --quiet --out OUT" ;;
    streamparts) echo "$S $T/m.oitp --size 8x8 --quiet --out OUT" ;;
    compare) echo "$S --compare $T/a.png $T/b.png --out OUT" ;;
    bench) echo "$BN $T/m.ply --methods dfb --orbit 1 --frames 1 --warmup 0 --size 8x8 --out OUT" ;;
    quads) echo "$G quads -o OUT" ;;
    instances) echo "$G instances --input $T/m.ply -o OUT" ;;
    plant) echo "$G plant -o OUT" ;;
    esac
}
# The help text of a form's tool (the subcommand's for oitprep's), one line.
help_of() {
    case $1 in
    prep | verify | parts) "$P" --help ;;
    stream* | compare) "$S" --help ;;
    bench) "$BN" --help ;;
    *) "$G" --help ;;
    esac 2>&1 | tr '\n' ' ' | tr -s ' '
}
# The help segments about OPT: text after each " OPT " up to the next "--".
segments() { help_of "$1" | awk -v o="$2 " '{ n = split($0, a, "--"); for (i = 2; i <= n; i++)
    if (index(a[i], substr(o, 3)) == 1) print a[i] }'; }
num() { # 64K -> 65536
    case $1 in
    *K) echo $((${1%K} * 1024)) ;; *M) echo $((${1%M} * 1048576)) ;;
    *G) echo $((${1%G} * 1073741824)) ;; *) echo "$1" ;;
    esac
}

# probe WANT FORM OPT VALUE EXTRA: accepted (WANT=ok) or refused (WANT=no)?
probe() {
    want=$1 f=$2 opt=$3 val=$(echo "$6" | sed "s/V/$4/") extra=$5
    ext=oitp
    case $f in stream* | compare) ext=png ;; bench) ext=d ;; parts | quads | instances | plant) ext=ply ;; esac
    cmd=$(form "$f" | sed "s|OUT|$NO/x.$ext|")
    # shellcheck disable=SC2086
    $cmd $extra "$opt" "$val" >"$T/out.txt" 2>"$T/err.txt"
    rc=$?
    if [ "$want" = ok ]; then
        # verify has no output: accepted means it ran (exit 0)
        { [ "$f" = verify ] && [ "$rc" -eq 0 ]; } ||
            { [ "$rc" -eq 1 ] && grep -q "$NO" "$T/err.txt"; } ||
            fail "$f $opt $val: not accepted (exit $rc: $(head -n 1 "$T/err.txt"))"
    else
        [ "$rc" -eq 2 ] && [ "$(wc -l <"$T/err.txt")" -eq 1 ] && grep -q -- "$opt" "$T/err.txt" ||
            fail "$f $opt $val: not refused with one line naming it (exit $rc: $(head -c 200 "$T/err.txt"))"
    fi
}

# same_default FORM OPT DEFAULT EXTRA TEMPLATE: output without the option ==
# output with --opt DEFAULT.
same_default() {
    f=$1 opt=$2 d=$(echo "$5" | sed "s/V/$3/") extra=$4
    ext=oitp
    case $f in stream* | compare) ext=png ;; parts | quads | instances | plant) ext=ply ;; esac
    for k in 1 2; do
        cmd=$(form "$f" | sed "s|OUT|$T/d$k.$ext|")
        if [ $k -eq 1 ]; then
            # shellcheck disable=SC2086
            $cmd $extra >"$T/d$k.txt" 2>"$T/err.txt"
        else
            # shellcheck disable=SC2086
            $cmd $extra "$opt" "$d" >"$T/d$k.txt" 2>"$T/err.txt"
        fi || { fail "$f $opt: run $k failed: $(head -n 1 "$T/err.txt")"; return; }
    done
    if [ "$f" = verify ]; then
        cmp -s "$T/d1.txt" "$T/d2.txt" || fail "$f $opt: default $d differs from no option"
    else
        cmp -s "$T/d1.$ext" "$T/d2.$ext" || fail "$f $opt: default $d differs from no option"
    fi
    rm -f "$T"/d1.* "$T"/d2.*
}

# check FORM OPT [EXTRA [TEMPLATE [FLAGS]]]: TEMPLATE puts the value in (V);
# FLAGS: nohi (the top of the range is too costly to run), even, nodefault.
check() {
    f=$1 opt=$2 extra=${3:-} tpl=${4:-V} flags=${5:-}
    nth=1
    case $flags in *second*) nth=2 ;; esac
    seg=$(segments "$f" "$opt" | grep -E '\.\.|[[(] ?-?[0-9.]+, ?-?[0-9.]+[])]|>= ?[0-9]|> 0' |
        sed -n "${nth}p")
    [ -n "$seg" ] || { fail "$f $opt: --help gives no range"; return; }
    d=$(echo "$seg" | grep -o -E 'default [-0-9.]+[KMG]?' | head -n 1 | cut -d' ' -f2)
    desc=
    if r=$(echo "$seg" | sed -n -E 's/^[^.]*[^0-9.-]([-]?[0-9]+[KMG]?)\.\.([0-9]+[KMG]?).*/\1 \2/p') && [ -n "$r" ]; then
        lo=$(num "${r% *}") hi=$(num "${r#* }")
        desc="$lo..$hi"
        probe ok "$f" "$opt" "$lo" "$extra" "$tpl"
        case $flags in *nohi*) ;; *) probe ok "$f" "$opt" "$hi" "$extra" "$tpl" ;; esac
        probe no "$f" "$opt" $((lo - 1)) "$extra" "$tpl"
        probe no "$f" "$opt" $((hi + 1)) "$extra" "$tpl"
        case $flags in *even*) probe no "$f" "$opt" $((lo + 1)) "$extra" "$tpl" ;; esac
        if [ -n "$d" ] && { [ "$(num "$d")" -lt "$lo" ] || [ "$(num "$d")" -gt "$hi" ]; }; then
            fail "$f $opt: default $d outside $lo..$hi"
        fi
    elif r=$(echo "$seg" | sed -n -E 's/.*([[(]) ?(-?[0-9.]+), ?(-?[0-9.]+)([])]).*/\1 \2 \3 \4/p') && [ -n "$r" ]; then
        set -- $r
        desc="$1$2, $3$4"
        if [ "$1" = "[" ]; then probe ok "$f" "$opt" "$2" "$extra" "$tpl"; else probe no "$f" "$opt" "$2" "$extra" "$tpl"; fi
        if [ "$4" = "]" ]; then probe ok "$f" "$opt" "$3" "$extra" "$tpl"; else probe no "$f" "$opt" "$3" "$extra" "$tpl"; fi
        probe no "$f" "$opt" "$(awk "BEGIN { print $2 - 1 }")" "$extra" "$tpl"
        probe no "$f" "$opt" "$(awk "BEGIN { print $3 + 1 }")" "$extra" "$tpl"
        [ -z "$d" ] || awk "BEGIN { exit !($d >= $2 && $d <= $3) }" || fail "$f $opt: default $d outside $desc"
    elif r=$(echo "$seg" | sed -n -E 's/.*>= ?([0-9]+[KMG]?).*/\1/p') && [ -n "$r" ]; then
        lo=$(num "$r")
        desc=">= $lo"
        probe ok "$f" "$opt" "$lo" "$extra" "$tpl"
        probe no "$f" "$opt" $((lo - 1)) "$extra" "$tpl"
        [ -z "$d" ] || [ "$(num "$d")" -ge "$lo" ] || fail "$f $opt: default $d below $lo"
    else
        desc="> 0"
        probe ok "$f" "$opt" 0.001 "$extra" "$tpl"
        probe no "$f" "$opt" 0 "$extra" "$tpl"
        probe no "$f" "$opt" -1 "$extra" "$tpl"
    fi
    case $flags in *nodefault*) d= ;; esac
    [ -z "$d" ] || same_default "$f" "$opt" "$d" "$extra" "$tpl"
    printf '%-12s %-22s %-16s default %s\n' "$f" "$opt" "$desc" "${d:-(none stated or not numeric)}"
}

printf '%-12s %-22s %-16s %s\n' form option range default
check prep --max-layers "" V even
check prep --memory
check prep --threads
check prep --grid
check prep --max-piece-triangles "--scheme guaranteed"
check prep --part-triangles
check prep --deflection
check verify --directions "" V nohi
check verify --viewpoints "" V nohi
check verify --chunk-triangles "" V nohi
check parts --alpha
check stream --elevation
check stream --orbit "" V nohi
check stream --alpha
check stream --absorption "--shading translucent"
check stream --max-layers "--method array"
check streamparts --upload-budget
check streamparts --cache-budget
check streamparts --upload-threads
check streamparts --slot-budget
check streamparts --store-budget
check streamparts --gpu-budget
check streamparts --epsilon
check streamfull --size "" Vx8 nohi,nodefault
check streamfull --size "" 8xV nohi,nodefault
same_default streamfull --size 1024x1024 "" V
check compare --gain
check bench --orbit "" V nohi,nodefault
check bench --size "" Vx8 nohi,nodefault
check bench --frames "" V nohi,nodefault
check bench --warmup "" V nohi,nodefault
check bench --max-layers "" V nodefault
check bench --part-triangles "--methods stream --scheme fast" V nodefault
check quads --count
check quads --coverage
check instances --count "" V second
check plant --triangles "" V nodefault

finish --clean "help ranges"
