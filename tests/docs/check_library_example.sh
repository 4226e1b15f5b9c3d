#!/usr/bin/env bash
# docs/library.md's C++ example must be, to the letter, the one tests/consumer/main.cpp compiles
# and runs against the installed package (between its "docs/library.md's example" markers), so
# the page cannot show code that no longer builds or does something else.
#   check_library_example.sh LIBRARY_MD CONSUMER_MAIN_CPP
set -euo pipefail
doc=$1 main=$2
[[ -r $doc && -r $main ]] || { echo "cannot read $doc or $main"; exit 1; }
# The first cpp block of the page, without its #include (the consumer has its own includes).
shown=$(awk '/^```cpp$/ && !seen {inside = 1; seen = 1; next} inside && /^```$/ {exit} inside' "$doc" |
        grep -v '^#include')
compiled=$(awk '/docs\/library.md.s example: end/ {exit} inside; /docs\/library.md.s example.*: begin/ {inside = 1}' "$main")
[[ -n $compiled ]] || { echo "$main has no docs/library.md example between its markers"; exit 1; }
if [[ $(printf '%s\n' "$shown" | sed '/./,$!d') != $(printf '%s\n' "$compiled" | sed '/./,$!d') ]]; then
  echo "docs/library.md's example differs from the one tests/consumer/main.cpp compiles:"
  diff <(printf '%s\n' "$shown" | sed '/./,$!d') <(printf '%s\n' "$compiled" | sed '/./,$!d') || true
  exit 1
fi
