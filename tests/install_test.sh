#!/bin/sh
# install_test.sh -- check an installed carom (make install-test, mk/install.mk).
#
# usage: sh tests/install_test.sh DESTDIR PKGCONFIGDIR LIBDIR BINDIR VERSION WORKDIR
#
# `make install DESTDIR=...` has run. Build a small program the way a user
# would, with `pkg-config --cflags --libs carom` (pkgconf's sysroot
# pointing into DESTDIR), link it against the shared library, run it with
# LD_LIBRARY_PATH; check the soname, the exported symbols, the static
# archive and the installed bin/carom.

set -eu

if [ $# -ne 6 ]; then
    echo "usage: sh tests/install_test.sh DESTDIR PKGCONFIGDIR LIBDIR BINDIR VERSION WORKDIR" >&2
    exit 2
fi
root=$1 pcdir=$2 libdir=$3 bindir=$4 version=$5 work=$6
major=${version%%.*}
cc=${CC:-cc}
mkdir -p "$work"

fail() {
    echo "install-test: FAIL: $*" >&2
    exit 1
}

cat > "$work/prog.c" <<'EOC'
/* A user's program: a ball dropped in an empty world falls. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <carom.h>

#define STR2(x) #x
#define STR(x) STR2(x)

int main(void)
{
    const char *want = STR(CAROM_VERSION_MAJOR) "." STR(CAROM_VERSION_MINOR)
                       "." STR(CAROM_VERSION_PATCH);
    carom_world_def wd = carom_default_world_def();
    carom_body_def ball = carom_default_body_def();
    carom_body_state s;
    carom_world *w;
    void *mem;
    int id, i;
    if (strcmp(carom_version(), want) != 0) {
        fprintf(stderr, "library %s, header %s\n", carom_version(), want);
        return 1;
    }
    wd.max_bodies = 2;
    mem = malloc(carom_world_buffer_size(&wd));
    if (!mem || carom_world_init(&w, &wd, mem, carom_world_buffer_size(&wd)) != CAROM_OK)
        return 1;
    ball.position.y = 10.0f;
    if (carom_world_add_body(w, &ball, &id) != CAROM_OK)
        return 1;
    for (i = 0; i < 60; ++i)
        if (carom_world_step(w) != CAROM_OK)
            return 1;
    carom_body_get_state(w, id, &s);
    printf("carom %s: ball at %.3f after %.3f s\n", carom_version(),
           (double)s.position.y, (double)carom_world_time(w));
    free(mem);
    return s.position.y < 6.0f && s.position.y > 4.0f ? 0 : 1;
}
EOC

# pkg-config sees only the installed carom.pc; the sysroot maps its
# /usr/local/... paths into DESTDIR.
pc() {
    PKG_CONFIG_PATH="" PKG_CONFIG_LIBDIR="$root$pcdir" PKG_CONFIG_SYSROOT_DIR="$root" \
        pkg-config "$@"
}
pc --exists carom || fail "pkg-config does not find carom.pc in $root$pcdir"
got=$(pc --modversion carom)
[ "$got" = "$version" ] || fail "carom.pc has version '$got', carom.h says $version"
flags=$(pc --cflags --libs carom)
echo "pkg-config --cflags --libs carom: $flags"
case " $flags " in
    *" -lcarom "*) ;;
    *) fail "Libs lack -lcarom: $flags" ;;
esac
case " $flags " in
    *" -lm "*) ;;
    *) fail "Libs lack -lm: $flags" ;;
esac

# the same paths with --define-prefix (prefix from where carom.pc lies),
# when carom.pc is PREFIX/lib/pkgconfig/carom.pc
if [ "$pcdir" = "${pcdir%/lib/pkgconfig}/lib/pkgconfig" ]; then
    dp=$(PKG_CONFIG_PATH="" PKG_CONFIG_LIBDIR="$root$pcdir" pkg-config --define-prefix --cflags --libs carom)
    [ "$dp" = "$flags" ] ||
        fail "pkg-config --define-prefix gives '$dp', the sysroot gives '$flags'"
fi

# shared: the program needs libcarom.so.MAJOR and runs against it
# shellcheck disable=SC2086 # flags are words
"$cc" -std=c99 -Wall -Wextra -Werror "$work/prog.c" $flags -o "$work/prog-shared"
readelf -d "$work/prog-shared" | grep -q "NEEDED.*\[libcarom\.so\.$major\]" ||
    fail "prog-shared does not need libcarom.so.$major"
readelf -d "$root$libdir/libcarom.so.$version" | grep -q "SONAME.*\[libcarom\.so\.$major\]" ||
    fail "libcarom.so.$version has no soname libcarom.so.$major"
[ "$(readlink "$root$libdir/libcarom.so.$major")" = "libcarom.so.$version" ] ||
    fail "libcarom.so.$major does not point to libcarom.so.$version"
[ "$(readlink "$root$libdir/libcarom.so")" = "libcarom.so.$major" ] ||
    fail "libcarom.so does not point to libcarom.so.$major"
LD_LIBRARY_PATH="$root$libdir" "$work/prog-shared" || fail "prog-shared failed"
ldd_out=$(LD_LIBRARY_PATH="$root$libdir" ldd "$work/prog-shared")
echo "$ldd_out" | grep -q "libcarom\.so\.$major => $root$libdir/" ||
    fail "prog-shared did not load the installed library: $ldd_out"

# only carom_* is exported
extra=$(nm -D --defined-only "$root$libdir/libcarom.so.$version" |
        awk '$2 ~ /^[TDBR]$/ && $3 !~ /^carom_/ { print $3 }')
[ -z "$extra" ] || fail "libcarom.so exports non-carom symbols: $extra"

# static: the same program from libcarom.a
cflags=$(pc --cflags carom)
# shellcheck disable=SC2086
"$cc" -std=c99 -Wall -Wextra -Werror "$work/prog.c" $cflags \
    "$root$libdir/libcarom.a" -lm -o "$work/prog-static"
"$work/prog-static" || fail "prog-static failed"
if readelf -d "$work/prog-static" | grep -q "NEEDED.*libcarom"; then
    fail "prog-static needs libcarom.so"
fi

# the CLI
"$root$bindir/carom" --version | grep -qx "carom $version" ||
    fail "bin/carom --version does not print 'carom $version'"

echo "install-test: ok (carom $version: pkg-config, shared and static link, bin/carom)"
