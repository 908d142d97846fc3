#!/usr/bin/env bash
# Checks that the runtime library stands apart from the tools: no runtime archive defines or
# references a symbol that a tools archive (synth, eval, truth, ...) defines.
#
# usage: check_runtime_symbols.sh --runtime A.a [A.a ...] --tools T.a [T.a ...]
# Exit 0 when the runtime archives are clean, 1 (listing the offending symbols) when not, 2 on
# bad arguments. CTest runs it over the build's archives (tests/CMakeLists.txt).
set -euo pipefail

runtime=()
tools=()
list=""
for arg in "$@"; do
  case "$arg" in
    --runtime) list=runtime ;;
    --tools) list=tools ;;
    *)
      if [[ ! -f "$arg" ]]; then
        echo "error: archive $arg does not exist" >&2
        exit 2
      fi
      case "$list" in
        runtime) runtime+=("$arg") ;;
        tools) tools+=("$arg") ;;
        *) echo "error: $arg comes before --runtime or --tools" >&2; exit 2 ;;
      esac
      ;;
  esac
done
if [[ ${#runtime[@]} -eq 0 || ${#tools[@]} -eq 0 ]]; then
  echo "usage: $0 --runtime A.a [A.a ...] --tools T.a [T.a ...]" >&2
  exit 2
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# What the tools define for good: strong code and data symbols (weak ones are inline functions
# and template instances any library may hold a copy of).
nm --defined-only "${tools[@]}" 2>/dev/null |
  awk 'NF == 3 && $2 ~ /^[TDBR]$/ {print $3}' | sort -u >"$work/tools_defined"
if [[ ! -s "$work/tools_defined" ]]; then
  echo "error: the tools archives define no symbols: wrong archives?" >&2
  exit 2
fi

status=0
for archive in "${runtime[@]}"; do
  # Every symbol the archive defines or needs, mangled (the exact name the linker matches).
  nm "$archive" 2>/dev/null | awk 'NF >= 2 {print $NF}' | sort -u >"$work/runtime_symbols"
  comm -12 "$work/runtime_symbols" "$work/tools_defined" >"$work/shared"
  if [[ -s "$work/shared" ]]; then
    count=$(wc -l <"$work/shared")
    echo "FAIL $(basename "$archive"): $count symbol(s) of the tools libraries:"
    c++filt <"$work/shared" | head -20 | sed 's/^/  /'
    status=1
  else
    echo "ok   $(basename "$archive")"
  fi
done
exit $status
