#!/bin/sh
# Fails if an object compiled for one instruction set (solver/CMakeLists.txt,
# SPLAT_ISA_SOURCES) defines a function other files could link to, besides its
# entry points in namespace isa_<set>. Such a function (an inline function
# left out of line, a template instance) is a weak definition the linker may
# pick for the whole program: an AVX-512 copy of it would crash on an older
# CPU. Data (constant tables) is the same on every set and is not checked.
# Arguments: the object files (an argument may list several, separated by ;).
set -eu
status=0
count=0
objects=$(printf '%s;' "$@" | tr ';' '\n' | grep -v '^$')
for obj in $objects; do
  count=$((count + 1))
  # Defined functions that are global, weak or unique (uppercase class
  # letters and u; lowercase ones are local to the object).
  found=$(nm -C --defined-only --format=sysv "$obj" |
    awk -F'|' '$3 ~ /^ *(u|[A-Z]) *$/ && $4 ~ /FUNC/ { print $1 }' |
    grep -v -E '^splat::(fe_block::)?isa_(baseline|v3|v4)::[a-z_]+\(' || true)
  if [ -n "$found" ]; then
    echo "$obj defines symbols outside its entry points:"
    echo "$found" | cut -c1-300
    status=1
  fi
done
[ $count -gt 0 ] || { echo "no objects given"; exit 1; }
[ $status -eq 0 ] && echo "the $count instruction-set objects define only their entry points"
exit $status
