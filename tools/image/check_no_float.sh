#!/usr/bin/env sh
# check_no_float.sh NM FILE...
# Fails when any FILE (archive or object) defines or references a soft-float
# runtime routine (__aeabi_f*, __aeabi_d*: float/double arithmetic and
# conversions; also the int-to-float __aeabi_[u][il]2[fd] and the generic
# libgcc names __addsf3, __floatsisf, __fixdfsi ...), or when nm shows no symbols at all (a wrong or empty file
# must not pass as "clean").
set -eu
nm_tool=$1
shift
symbols=$("$nm_tool" "$@")
if [ -z "$(printf '%s\n' "$symbols" | grep -E ' [TtUuDdBbRr] ' || true)" ]; then
    echo "check_no_float: no symbols in $* - is this the right file?" >&2
    exit 2
fi
bad=$(printf '%s\n' "$symbols" |
    grep -E '__aeabi_([fd]|u?[il]2[fd])|__[a-z]+[sd]f[0-9]?$|__float|__fix' || true)
if [ -n "$bad" ]; then
    echo "check_no_float: float runtime symbols found in $*:" >&2
    printf '%s\n' "$bad" >&2
    exit 1
fi
echo "check_no_float: $* - no __aeabi_f*/__aeabi_d* symbols ($(printf '%s\n' "$symbols" | grep -c ' T ') functions defined)"
