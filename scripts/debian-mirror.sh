#!/usr/bin/env bash
# Prints the URI of the package mirror that this machine's own apt sources already use for a Debian suite's
# main component, so that the set-up scripts follow a local mirror or proxy and the repository names no host.
# Reads ROOT/etc/apt/sources.list and ROOT/etc/apt/sources.list.d/*.list (one-line format) and
# ROOT/etc/apt/sources.list.d/*.sources (deb822 format); the first "deb" entry (not deb-src, not disabled)
# whose suites include SUITE and whose components include main wins.
# Usage: bash scripts/debian-mirror.sh SUITE [ROOT]    (or source it and call debian_mirror_uri SUITE [ROOT])
# Exit status: 0 with the URI on stdout; 1 with one line on stderr when no source serves SUITE main; 2 on usage.

# One-line entries of the files given: "deb [options] URI SUITE COMPONENT...", printed as "URI SUITE COMPONENTS".
debian_mirror_one_line() {
  awk '
    { sub(/#.*/, "") }
    $1 != "deb" { next }
    {
      line = $0
      sub(/^[ \t]*deb[ \t]+/, "", line)
      if (line ~ /^\[/) sub(/^\[[^]]*\][ \t]*/, "", line)   # [arch=amd64 signed-by=...] may hold spaces
      n = split(line, f, /[ \t]+/)
      if (n < 3) next
      comps = ""
      for (i = 3; i <= n; i++) comps = comps " " f[i]
      print f[1] "\t" f[2] "\t" comps
    }' "$@"
}

# deb822 stanzas of the files given, printed as one "URI SUITE COMPONENTS" line per URI x suite.
debian_mirror_deb822() {
  awk '
    function flush(   nu, ns, u, s, i, j) {
      if (enabled != "no" && (" " tys " ") ~ / deb /) {
        nu = split(uris, u, /[ \t]+/); ns = split(suites, s, /[ \t]+/)
        for (i = 1; i <= nu; i++) for (j = 1; j <= ns; j++) if (u[i] != "" && s[j] != "") print u[i] "\t" s[j] "\t " comps
      }
      tys = uris = suites = comps = enabled = ""; last = ""; split("", val)
    }
    /^[ \t]*#/ { next }
    /^[ \t]*$/ { flush(); next }
    /^[ \t]/ { if (last != "") { v = $0; sub(/^[ \t]+/, "", v); val[last] = val[last] " " v; assign() } next }
    {
      key = tolower($0); sub(/:.*/, "", key)
      v = $0; sub(/^[^:]*:[ \t]*/, "", v); sub(/[ \t]+$/, "", v)
      last = key; val[key] = v; assign()
    }
    function assign() {
      tys = val["types"]; uris = val["uris"]; suites = val["suites"]; comps = val["components"]
      enabled = tolower(val["enabled"])
    }
    END { flush() }
  ' "$@"
}

debian_mirror_uri() {
  local suite=${1:-} root=${2:-}
  if [ -z "$suite" ]; then
    echo "debian-mirror: usage: debian_mirror_uri SUITE [ROOT]" >&2
    return 2
  fi
  local one_line=() deb822=() f
  [ -f "$root/etc/apt/sources.list" ] && one_line+=("$root/etc/apt/sources.list")
  for f in "$root"/etc/apt/sources.list.d/*.list; do [ -f "$f" ] && one_line+=("$f"); done
  for f in "$root"/etc/apt/sources.list.d/*.sources; do [ -f "$f" ] && deb822+=("$f"); done
  local entries=""
  [ ${#one_line[@]} -gt 0 ] && entries+=$(debian_mirror_one_line "${one_line[@]}")$'\n'
  if [ ${#deb822[@]} -gt 0 ]; then
    for f in "${deb822[@]}"; do entries+=$(debian_mirror_deb822 "$f")$'\n'; done
  fi
  local uri
  uri=$(printf '%s' "$entries" | awk -F '\t' -v suite="$suite" '
    $2 == suite && (" " $3 " ") ~ / main / { u = $1; sub(/\/+$/, "", u); print u; exit }')
  if [ -z "$uri" ]; then
    echo "debian-mirror: no apt source in ${root:-}/etc/apt serves '$suite' with component main" >&2
    return 1
  fi
  printf '%s\n' "$uri"
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
  set -euo pipefail
  if [ $# -lt 1 ] || [ $# -gt 2 ]; then
    echo "usage: bash scripts/debian-mirror.sh SUITE [ROOT]" >&2
    exit 2
  fi
  debian_mirror_uri "$@"
fi
