#!/bin/sh
# The C++ sources in the repository's clang-format style (.clang-format). `format.sh` rewrites them
# in place (make format); `format.sh --check` lists the files that differ and fails (a CTest test).
set -eu
cd "$(dirname "$0")/.."
files=$(find apps bench examples lib plugin tests -name '*.cpp' -o -name '*.hpp' -o -name '*.h' | grep -v node_modules | sort)
if [ "${1:-}" = "--check" ]; then
    bad=0
    for f in $files; do
        if ! clang-format --dry-run --Werror "$f" > /dev/null 2>&1; then
            echo "not in clang-format style: $f (make format)"
            bad=1
        fi
    done
    exit $bad
fi
clang-format -i $files
