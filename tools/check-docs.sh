#!/bin/sh
# check-docs.sh -- the documentation names only what the repository has.
#
# usage: sh tools/check-docs.sh [--make CMD] [--no-make] [FILE.md ...]
#
# Reads README.md and docs/*.md (or the FILEs given, relative to the
# repository root) and checks that:
#   - every relative link [text](target) and image ![alt](target) points to
#     a file or directory that exists (relative to the document, anchors
#     ignored; http:, https: and mailto: links are not followed);
#   - every repository path named in inline code or in a shell or text code
#     block (a word starting with src/, include/, tools/, tests/, docs/, mk/,
#     examples/ or .ci/, or the top-level Makefile, README.md, carom.pc.in)
#     exists; paths under build/ are build products and are not checked;
#   - every file named alone in inline code (a code span of one word such as
#     `world.c`, `test_events.c`, `default.scene`: a name ending in .c .h
#     .cpp .md .sh .mk .py .scene .in .svg .png) exists somewhere in the
#     repository (outside build/);
#   - every `make TARGET` named in inline code or a shell code block is a
#     target that `make help` lists, and README.md's targets table (its rows
#     starting with `make TARGET`) lists every target `make help` lists;
#   - nothing points outside the repository: the design note and its errata
#     files, or "issue N" (a user has only the repository;
#     docs/design-note.md restates the note).
# Words with placeholders (FILE, DIR, NAME.svg, *, $, <, =, ...) are skipped.
#
#   --make CMD   the make to ask for `make help` (default: make)
#   --no-make    skip the make target checks
#   -h, --help   this text
#
# Prints one line per problem on stderr, FILE:LINE: what is missing, and a
# summary on stdout. Exit status: 0 all present, 1 something is missing,
# 2 bad usage or a document that cannot be read.
set -eu

make_cmd="make"
use_make=1

usage() {
    awk 'NR == 1 { next } !/^#/ { exit } { sub(/^# ?/, ""); print }' "$0"
}
die() {
    echo "check-docs: $*" >&2
    exit 2
}

while [ $# -gt 0 ]; do
    case $1 in
        --make)
            [ $# -ge 2 ] || die "--make needs a command"
            make_cmd=$2
            shift 2 ;;
        --make=*) make_cmd=${1#--make=}; shift ;;
        --no-make) use_make=0; shift ;;
        -h|--help) usage; exit 0 ;;
        --) shift; break ;;
        -*) die "unknown option '$1' (try --help)" ;;
        *) break ;;
    esac
done

root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

if [ $# -eq 0 ]; then
    set -- README.md
    for f in docs/*.md; do
        [ -e "$f" ] && set -- "$@" "$f"
    done
fi
for f in "$@"; do
    if [ ! -f "$f" ] || [ ! -r "$f" ]; then
        die "cannot read '$f'"
    fi
done

tmp=$(mktemp -d "${TMPDIR:-/tmp}/check-docs.XXXXXX") || die "mktemp failed"
trap 'rm -rf "$tmp"' EXIT
trap 'exit 2' HUP INT TERM

# Every file of the repository by its name alone (for bare file names).
find . \( -path ./build -o -path ./.git \) -prune -o -type f -print |
    sed 's|.*/||' | sort -u > "$tmp/names"

# The references, one per line: KIND TAB FILE TAB LINE TAB TOKEN, KIND one
# of link (relative to the document), path (relative to the root), file (a
# bare name), make (a target), outside (a reference out of the repository).
awk '
function trim(w) {
    while (w ~ /^[(\["'"'"'<]/) w = substr(w, 2)
    while (w ~ /[)\]"'"'"'>,.:;!?]$/) w = substr(w, 1, length(w) - 1)
    sub(/:[0-9]+(-[0-9]+)?$/, "", w)          # FILE:LINE
    return w
}
function placeholder(w) {
    return w ~ /[*?$<>{}|=\\]/ || w ~ /\.\.\./ || w ~ /^[-\/~]/ || w ~ /^[a-z]+:/
}
function emit(kind, tok) {
    printf "%s\t%s\t%d\t%s\n", kind, FILENAME, FNR, tok
}
# One word of code: a repository path or a bare file name.
function word(w, bare_files) {
    w = trim(w)
    if (w == "" || placeholder(w))
        return
    if (w ~ /^(\.\/)?(src|include|tools|tests|docs|mk|examples|\.ci)\// ||
        w == "Makefile" || w == "README.md" || w == "carom.pc.in") {
        emit("path", w)
        return
    }
    if (bare_files && w !~ /\// &&
        w ~ /^[A-Za-z0-9_+-][A-Za-z0-9_.+-]*\.(c|h|cpp|md|sh|mk|py|scene|in|svg|png)$/)
        emit("file", w)
}
# make commands among the words w[1..n] (a shell line or a code span).
function makes(w, n,    i, j) {
    for (i = 1; i <= n; ++i) {
        if (w[i] != "make" || (i > 1 && w[i - 1] !~ /^(&&|;|\|\||\$|sudo|then|do)$/))
            continue
        for (j = i + 1; j <= n; ++j) {
            if (w[j] == "#" || w[j] ~ /^(&&|;|\|\||\||>|2>)$/)
                break
            if (w[j] ~ /^-[fCjIo]$/) { ++j; continue }
            if (w[j] ~ /^-/ || w[j] ~ /=/)
                continue
            if (w[j] ~ /^[A-Za-z0-9][A-Za-z0-9_.-]*$/)
                emit("make", w[j])
            break
        }
    }
}
# A code span: a command (several words: paths only, as in a shell block)
# or one word (a path, or a bare file name).
function code_span(s,    w, n, k) {
    n = split(s, w, /[ \t]+/)
    if (w[1] == "") { for (k = 1; k < n; ++k) w[k] = w[k + 1]; --n }
    if (n > 0 && w[n] == "") --n
    makes(w, n)
    for (k = 1; k <= n; ++k)
        word(w[k], n == 1)
}
FNR == 1 { fence = 0; incode = 0; span = "" }
{
    line = $0
    m = line
    while (match(m, /ERRATA[^ ]*|[Ii]ssue #?[0-9]+|shared\/seed[^ )`]*|collision-thoughts[^ )`]*/)) {
        hit = substr(m, RSTART, RLENGTH)
        before = RSTART > 1 ? substr(m, RSTART - 1, 1) : ""
        m = substr(m, RSTART + RLENGTH)
        if (hit ~ /^[Ii]ssue/ && before ~ /[A-Za-z]/)
            continue                          # "tissue 5"
        emit("outside", hit)
    }
    if (line ~ /^[ \t]*(```|~~~)/) {
        if (!fence) {
            fence = 1
            lang = line
            sub(/^[ \t]*(```|~~~)[ \t]*/, "", lang)
            sub(/[ \t].*/, "", lang)
            scan = lang == "" || lang == "sh" || lang == "shell" || lang == "console" ||
                   lang == "text"
        } else {
            fence = 0
        }
        incode = 0; span = ""
        next
    }
    if (fence) {
        if (scan) {
            s = line
            sub(/^[ \t]*\$[ \t]+/, "", s)     # a prompt
            n = split(s, w, /[ \t]+/)
            if (w[1] == "") { for (k = 1; k < n; ++k) w[k] = w[k + 1]; --n }
            makes(w, n)
            for (k = 1; k <= n; ++k) {
                if (w[k] == "#") break
                word(w[k], 0)
            }
        }
        next
    }
    if (line ~ /^[ \t]*$/) { incode = 0; span = ""; next }
    # links and images: ](target)
    s = line
    while (match(s, /\]\([^)]*\)/)) {
        t = substr(s, RSTART + 2, RLENGTH - 3)
        s = substr(s, RSTART + RLENGTH)
        sub(/[ \t]+".*$/, "", t)
        gsub(/^<|>$/, "", t)
        if (t == "" || t ~ /^#/ || t ~ /^[a-z][a-z0-9+.-]*:/)
            continue
        sub(/#.*$/, "", t)
        emit("link", t)
    }
    # inline code, which may run over several lines of a paragraph
    n = split(line, part, /`/)
    for (k = 1; k <= n; ++k) {
        if (incode) span = span " " part[k]
        if (k < n) {
            if (incode) { code_span(span); span = "" }
            incode = !incode
        }
    }
}
' "$@" > "$tmp/refs" || die "awk failed"

# Targets `make help` lists.
: > "$tmp/targets"
if [ "$use_make" = 1 ]; then
    if ! $make_cmd -s --no-print-directory help > "$tmp/help" 2> "$tmp/help.err"; then
        cat "$tmp/help.err" >&2
        die "'$make_cmd help' failed (use --no-make to skip the target checks)"
    fi
    awk '$1 == "make" && $2 ~ /^[A-Za-z0-9]/ { print $2 }' "$tmp/help" | sort -u > "$tmp/targets"
    [ -s "$tmp/targets" ] || die "'$make_cmd help' lists no target"
fi

# "dir/./a/../b" -> "dir/b"
normalize() {
    printf '%s\n' "$1" | awk -F/ '{
        n = 0
        lead = substr($0, 1, 1) == "/" ? "/" : ""
        for (i = 1; i <= NF; ++i) {
            if ($i == "" || $i == ".") continue
            if ($i == ".." && n > 0 && p[n] != "..") { --n; continue }
            p[++n] = $i
        }
        s = lead
        for (i = 1; i <= n; ++i) s = s (i > 1 ? "/" : "") p[i]
        print s
    }'
}

problems=0
checked=0
problem() {
    echo "$1" >&2
    problems=$((problems + 1))
}
tab=$(printf '\t')
while IFS="$tab" read -r kind file line tok; do
    checked=$((checked + 1))
    case $kind in
        link)
            dir=$(dirname "$file")
            target=$(normalize "$dir/$tok")
            [ -e "$target" ] || problem "$file:$line: link to '$tok': no such file ($target)" ;;
        path)
            p=${tok#./}
            case $p in
                build/*) continue ;;
            esac
            if [ ! -e "$p" ]; then
                # a placeholder component (FAMILY, NAME): not a real path
                if printf '%s\n' "$p" | awk -F'[/.-]' '{
                        for (i = 1; i <= NF; ++i)
                            if ($i ~ /^[A-Z][A-Z0-9_]*$/ && $i != "README") exit 0
                        exit 1 }'; then
                    continue
                fi
                problem "$file:$line: no such path '$tok'"
            fi ;;
        file)
            case $tok in
                [A-Z][A-Z0-9_]*.*)
                    stem=${tok%%.*}
                    case $stem in *[!A-Z0-9_]*) ;; *) [ "$stem" = README ] || continue ;; esac ;;
            esac
            grep -q -x -F -e "$tok" "$tmp/names" ||
                problem "$file:$line: no file named '$tok' in the repository" ;;
        make)
            [ "$use_make" = 1 ] || continue
            grep -q -x -F -e "$tok" "$tmp/targets" ||
                problem "$file:$line: 'make $tok': not a target that 'make help' lists" ;;
        outside)
            problem "$file:$line: points outside the repository: '$tok' (restate it, e.g. in docs/design-note.md)" ;;
    esac
done < "$tmp/refs"

# README.md's targets table lists every target of make help.
if [ "$use_make" = 1 ]; then
    for f in "$@"; do
        [ "$f" = README.md ] || continue
        awk '/^\|[ \t]*`make [A-Za-z0-9][A-Za-z0-9_.-]*`[ \t]*\|/ {
                 s = $0; sub(/^\|[ \t]*`make /, "", s); sub(/`.*/, "", s); print s }' \
            README.md | sort -u > "$tmp/table"
        [ -s "$tmp/table" ] || continue
        while IFS= read -r t; do
            checked=$((checked + 1))
            grep -q -x -F -e "$t" "$tmp/table" ||
                problem "README.md: the targets table lacks 'make $t' ('make help' lists it)"
        done < "$tmp/targets"
    done
fi

if [ "$problems" -gt 0 ]; then
    echo "check-docs: $problems problem(s) in $# document(s) ($checked references checked)"
    exit 1
fi
echo "check-docs: $# documents, $checked references: every path, file and target exists"
