#!/bin/sh
# ensure-deps.sh WHAT... -- make sure the packages a make target needs are
# installed. Installs them with apt-get when it can (root, or passwordless
# sudo); otherwise prints the exact command and fails.
#   check  -> Check unit-test framework (pkg-config check)
#   box2d  -> libbox2d-dev 2.4.1 (pkg-config box2d) and a C++ compiler
#   plot   -> gnuplot
#   gcovr  -> gcovr (make coverage)
#   valgrind -> valgrind (make memcheck)
set -u
pkgs=""
for what in "$@"; do
    case "$what" in
    check) pkg-config --exists check 2>/dev/null || pkgs="$pkgs check pkg-config" ;;
    box2d) { pkg-config --exists box2d 2>/dev/null && command -v c++ >/dev/null; } ||
               pkgs="$pkgs libbox2d-dev pkg-config g++" ;;
    plot) command -v gnuplot >/dev/null 2>&1 || pkgs="$pkgs gnuplot-nox" ;;
    gcovr) command -v gcovr >/dev/null 2>&1 || pkgs="$pkgs gcovr" ;;
    valgrind) command -v valgrind >/dev/null 2>&1 || pkgs="$pkgs valgrind" ;;
    *) echo "ensure-deps: unknown dependency '$what'" >&2; exit 2 ;;
    esac
done
[ -z "$pkgs" ] && exit 0

if [ "$(id -u)" = 0 ]; then
    sudo=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    sudo="sudo -n"
else
    echo "missing packages:$pkgs" >&2
    echo "install them with:  sudo apt-get update && sudo apt-get install -y$pkgs" >&2
    exit 1
fi
if ! command -v apt-get >/dev/null 2>&1; then
    echo "missing packages:$pkgs (no apt-get here: install them by hand)" >&2
    exit 1
fi
echo "installing:$pkgs" >&2
# shellcheck disable=SC2086 # $pkgs is a list of package names
for attempt in 1 2; do
    if $sudo apt-get update -qq && \
       DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq $pkgs >/dev/null; then
        exit 0
    fi
    echo "apt-get failed (attempt $attempt)" >&2
    sleep 5
done
echo "could not install:$pkgs" >&2
exit 1
