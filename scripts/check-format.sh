#!/usr/bin/env bash
# Checks that every C and C++ file git tracks is formatted as .clang-format says, with clang-format 14
# (Debian 12's; later versions format a few constructs differently, so one version decides).
#   scripts/check-format.sh            list the files that differ and exit 1 if any does
#   scripts/check-format.sh --fix      reformat them in place
#   scripts/check-format.sh --self-test  show that the check rejects a misformatted file
# scripts/test.sh runs the self-test and the check before it builds anything.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

formatter=""
for candidate in clang-format-14 clang-format; do
  if command -v "$candidate" >/dev/null && "$candidate" --version | grep -q 'version 14\.'; then
    formatter=$candidate
    break
  fi
done
# Exit code 125 (as a skipped test): no clang-format 14 here (Debian 13 and testing have later ones).
[ -n "$formatter" ] || { echo "[format] SKIPPED: clang-format 14 not found (Debian 12: apt-get install clang-format)" >&2; exit 125; }

# $1 = file; prints nothing and succeeds when the file is formatted.
differs() {
  ! "$formatter" --style=file:"$repo/.clang-format" --dry-run --Werror "$1" >/dev/null 2>&1
}

case "${1:-}" in
  --self-test)
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    printf 'int f(int a){if(a){return 1;}return 0;}\n' >"$tmp/bad.cxx"
    "$formatter" --style=file:"$repo/.clang-format" "$tmp/bad.cxx" >"$tmp/good.cxx"
    if ! differs "$tmp/bad.cxx"; then
      echo "[format] FAIL: self-test: a misformatted file passed the check" >&2
      exit 1
    fi
    if differs "$tmp/good.cxx"; then
      echo "[format] FAIL: self-test: clang-format's own output failed the check" >&2
      exit 1
    fi
    echo "[format] self-test: a misformatted file is rejected, its formatted version accepted"
    exit 0
    ;;
  --fix | "") ;;
  *)
    echo "usage: scripts/check-format.sh [--fix | --self-test]" >&2
    exit 2
    ;;
esac

cd "$repo"
# One clang-format process per 100 files (one per file took 10 times longer); with --Werror it
# names each file that differs as "FILE:LINE:COL: error: code should be clang-formatted"
report=$(git ls-files -z '*.h' '*.cxx' '*.c' \
  | xargs -0 -n 100 "$formatter" --style=file:"$repo/.clang-format" --dry-run --Werror 2>&1) && rc=0 || rc=$?
mapfile -t bad < <(printf '%s\n' "$report" \
  | sed -nE 's/^(.+):[0-9]+:[0-9]+: error: code should be clang-formatted.*/\1/p' | sort -u)
if [ "$rc" != 0 ] && [ "${#bad[@]}" = 0 ]; then
  printf '%s\n' "$report" | tail -n 20 >&2
  echo "[format] FAIL: $formatter failed (above) without naming a misformatted file" >&2
  exit 1
fi

if [ "${1:-}" = --fix ]; then
  for file in "${bad[@]}"; do "$formatter" --style=file -i "$file"; done
  echo "[format] reformatted ${#bad[@]} file(s)"
  exit 0
fi
if [ "${#bad[@]}" -gt 0 ]; then
  printf '[format] not formatted: %s\n' "${bad[@]}" >&2
  echo "[format] FAIL: ${#bad[@]} file(s) differ from .clang-format (scripts/check-format.sh --fix)" >&2
  exit 1
fi
echo "[format] $(git ls-files '*.h' '*.cxx' '*.c' | wc -l) files formatted as .clang-format says ($formatter)"
