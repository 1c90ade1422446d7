#!/usr/bin/env bash
# Fails, naming the files, when a C++ file of the project differs from what clang-format makes
# of it (.clang-format at the root). Run by the test command; fix with: scripts/check_format.sh -fix
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
format="$(command -v clang-format-14 || command -v clang-format || true)"
if [ -z "$format" ]; then
  echo "[check_format] clang-format not found (scripts/install_deps.sh installs it)" >&2
  exit 1
fi
if [ -d .git ] || [ -f .git ]; then
  mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.hpp')
else
  mapfile -t files < <(find benchmarks examples fuzz include src test tools -name '*.cpp' -o -name '*.h' -o -name '*.hpp' 2>/dev/null)
fi
if [ "${1:-}" = "-fix" ]; then
  "$format" -i "${files[@]}"
  exit 0
fi
# One clang-format process for all files (one per file took minutes): it names each file that
# would change in its "file:line:col: error:" lines.
if "$format" --dry-run --Werror "${files[@]}" >/dev/null 2>"${TMPDIR:-/tmp}/check_format.$$"; then
  rm -f "${TMPDIR:-/tmp}/check_format.$$"
  echo "[check_format] ${#files[@]} files formatted"
  exit 0
fi
bad="$(grep -o '^[^:]*:[0-9]*:[0-9]*: error' "${TMPDIR:-/tmp}/check_format.$$" | cut -d: -f1 | sort -u | tr '\n' ' ')"
rm -f "${TMPDIR:-/tmp}/check_format.$$"
echo "[check_format] not formatted (scripts/check_format.sh -fix): ${bad:-clang-format failed}" >&2
exit 1
