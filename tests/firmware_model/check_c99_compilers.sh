#!/usr/bin/env bash
# The firmware (firmware_model/target/*.c) compiles as strict C99 under both host compilers with
# no diagnostic at all: gcc and clang, -std=c99 -pedantic -Wall -Wextra -Werror and the firmware's
# own warnings (ADAHRS_FIRMWARE_C_WARNINGS in firmware_model/CMakeLists.txt, passed as arguments).
# The build itself uses one compiler (gcc); this check adds the other, as the dsPIC's XC16 is a
# third. Usage: check_c99_compilers.sh <project root> <warning flags...>
set -uo pipefail
root=$1
shift
status=0
count=0
for cc in gcc clang; do
  if ! command -v "$cc" >/dev/null; then
    echo "check_c99_compilers: $cc not installed (scripts/setup)"
    exit 1
  fi
  for source in "$root"/firmware_model/target/*.c; do
    output=$("$cc" -std=c99 -Wall -Wextra -Werror "$@" -fsyntax-only "$source" 2>&1)
    if [ $? -ne 0 ] || [ -n "$output" ]; then
      echo "check_c99_compilers: $cc ${source#"$root"/}:"
      echo "$output"
      status=1
    fi
    count=$((count + 1))
  done
done
echo "check_c99_compilers: $count compilations (gcc and clang, C99 strict), $([ $status -eq 0 ] && echo 'no diagnostic' || echo 'diagnostics above')"
exit $status
