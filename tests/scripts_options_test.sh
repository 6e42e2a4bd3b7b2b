#!/usr/bin/env bash
# The README's two commands share build/: each script must set every CMake option itself (a
# cache left by the other must not decide what is built), and every ctest run must fail when
# it finds no test. Usage: scripts_options_test.sh SOURCE_DIR
set -euo pipefail
source_dir="$1"
options=$(sed -n 's/^option(\(NOCDYN_[A-Z_]*\).*/\1/p' "$source_dir/CMakeLists.txt")
status=0
for script in scripts/test.sh scripts/test-extended.sh scripts/reproduce.sh; do
  # one command per line: join the backslash continuations
  commands=$(grep -v '^[[:space:]]*#' "$source_dir/$script" | sed -e ':a' -e '/\\$/N; s/\\\n//; ta')
  while IFS= read -r line; do
    for option in $options; do
      if [[ "$line" != *"-D$option="* ]]; then
        echo "$script: '$line' does not set $option"
        status=1
      fi
    done
  done < <(grep -E '^\s*cmake -S' <<<"$commands")
  while IFS= read -r line; do
    if [[ "$line" != *"--no-tests=error"* ]]; then
      echo "$script: '$line' passes when it finds no test (needs --no-tests=error)"
      status=1
    fi
  done < <(grep -E '(^|\s)ctest ' <<<"$commands" || true)
done
[[ -n "$options" ]] || { echo "no option() found in CMakeLists.txt"; exit 1; }
exit $status
