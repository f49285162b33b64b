#!/usr/bin/env bash
# Every relative link and picture in README.md and docs/**/*.md must resolve to a file or folder
# of the repository: inline links and images [text](target), reference definitions [id]: target
# and <img src="target">. Fenced code blocks and `inline code` are skipped; web and mail links and
# pure #anchors are not checked (no network); a target's own #anchor is dropped before the check.
#   bash tests/docs/links.sh [REPO_ROOT]     (ctest runs it as `docs_links`)
set -euo pipefail
root="$(cd "${1:-$(dirname "$0")/../..}" && pwd)"
cd "$root"

files=(README.md)
while IFS= read -r -d '' f; do files+=("$f"); done < <(find docs -name '*.md' -print0 | sort -z)

bad=0
checked=0
for file in "${files[@]}"; do
  dir="$(dirname "$file")"
  # One target per output line, as "LINE<TAB>TARGET": code fences and inline code removed first.
  targets="$(awk '
    /^[[:space:]]*(```|~~~)/ { fence = !fence; next }
    fence { next }
    {
      line = $0
      gsub(/`[^`]*`/, "", line)
      while (match(line, /\]\([^)]*\)/)) {
        t = substr(line, RSTART + 2, RLENGTH - 3)
        sub(/^[[:space:]]*</, "", t); sub(/>[[:space:]]*$/, "", t)
        sub(/[[:space:]]+"[^"]*"[[:space:]]*$/, "", t)
        print NR "\t" t
        line = substr(line, RSTART + RLENGTH)
      }
      if (match(line, /^[[:space:]]*\[[^]]+\]:[[:space:]]*[^[:space:]]+/)) {
        t = line; sub(/^[[:space:]]*\[[^]]+\]:[[:space:]]*/, "", t); sub(/[[:space:]].*$/, "", t)
        print NR "\t" t
      }
      while (match(line, /<img[^>]*src="[^"]*"/)) {
        t = substr(line, RSTART, RLENGTH); sub(/.*src="/, "", t); sub(/"$/, "", t)
        print NR "\t" t
        line = substr(line, RSTART + RLENGTH)
      }
    }' "$file")"
  [ -n "$targets" ] || continue
  while IFS=$'\t' read -r line target; do
    case "$target" in
      http://*|https://*|mailto:*|'#'*|'') continue ;;
    esac
    path="${target%%#*}"
    path="${path%%\?*}"
    checked=$((checked + 1))
    if [[ "$path" = /* ]]; then
      echo "$file:$line: absolute link \"$target\" (use a path relative to $file)" >&2
      bad=$((bad + 1))
    elif [[ "$(realpath -m "$dir/$path")/" != "$root/"* ]]; then
      echo "$file:$line: \"$target\" leaves the repository" >&2
      bad=$((bad + 1))
    elif [ ! -e "$dir/$path" ]; then
      echo "$file:$line: \"$target\" does not resolve ($dir/$path is missing)" >&2
      bad=$((bad + 1))
    fi
  done <<< "$targets"
done

if [ "$bad" -gt 0 ]; then
  echo "$bad of $checked links in ${#files[@]} pages do not resolve" >&2
  exit 1
fi
echo "all $checked links in ${#files[@]} pages resolve"
