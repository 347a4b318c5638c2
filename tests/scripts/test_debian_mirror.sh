#!/usr/bin/env bash
# LABEL scripts: scripts/debian-mirror.sh finds the mirror of a suite's main component in sample apt sources,
# one-line and deb822, with the traps real files have (options in brackets, deb-src, disabled stanzas,
# security and backports suites, comments, several URIs and suites, a trailing slash). No network, no host
# machine files: every case writes its own ROOT/etc/apt.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/../../scripts/debian-mirror.sh"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0

# expect NAME SUITE EXPECTED_URI_OR_EMPTY; reads ROOT from $root
expect() {
  local name=$1 suite=$2 want=$3 got status=0
  got=$(debian_mirror_uri "$suite" "$root" 2>"$scratch/err") || status=$?
  if [ -z "$want" ]; then
    if [ $status -ne 1 ] || [ -n "$got" ] || ! grep -q "no apt source" "$scratch/err"; then
      echo "FAIL $name: expected no mirror for $suite (status 1 and a message), got '$got' status $status"
      failures=$((failures + 1))
    else
      echo "ok   $name"
    fi
  elif [ $status -ne 0 ] || [ "$got" != "$want" ]; then
    echo "FAIL $name: for $suite expected '$want', got '$got' (status $status: $(cat "$scratch/err"))"
    failures=$((failures + 1))
  else
    echo "ok   $name"
  fi
}

new_root() { root="$scratch/$1"; mkdir -p "$root/etc/apt/sources.list.d"; }

# ---- one-line format --------------------------------------------------------------------------------------
new_root one-line
cat > "$root/etc/apt/sources.list" <<'SRC'
# deb http://commented.example/debian bookworm main
deb-src http://source-only.example/debian bookworm main
deb http://security.example/debian-security bookworm-security main
deb [arch=amd64 signed-by=/usr/share/keyrings/a b.gpg] http://mirror.example:3142/debian/ bookworm main contrib  # proxy
deb http://second.example/debian bookworm main
deb http://contrib-only.example/debian trixie contrib non-free
SRC
expect "one-line: options with spaces, trailing slash, first match wins" bookworm "http://mirror.example:3142/debian"
expect "one-line: the security suite is its own suite" bookworm-security "http://security.example/debian-security"
expect "one-line: a suite without main is not a match" trixie ""
expect "one-line: an absent suite" bullseye ""

new_root list-d
cat > "$root/etc/apt/sources.list.d/local.list" <<'SRC'
deb file:/srv/local-mirror/debian bookworm main
SRC
expect "one-line in sources.list.d, no sources.list" bookworm "file:/srv/local-mirror/debian"

# ---- deb822 format ----------------------------------------------------------------------------------------
new_root deb822
cat > "$root/etc/apt/sources.list.d/debian.sources" <<'SRC'
Types: deb-src
URIs: http://source-only.example/debian
Suites: bookworm
Components: main

# a disabled stanza is skipped
Types: deb
URIs: http://disabled.example/debian
Suites: bookworm
Components: main
Enabled: no

Types: deb deb-src
# http://snapshot.example/archive/debian/20250520T000000Z
URIs: http://proxy.example/debian/ http://other.example/debian
Suites: bookworm-updates bookworm
Components: contrib main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb
URIs: http://proxy.example/debian-security
Suites: bookworm-security
Components: main
SRC
expect "deb822: deb-src and disabled stanzas skipped, several suites and URIs" bookworm "http://proxy.example/debian"
expect "deb822: bookworm-updates from the same stanza" bookworm-updates "http://proxy.example/debian"
expect "deb822: the security stanza" bookworm-security "http://proxy.example/debian-security"

new_root deb822-continuation
cat > "$root/etc/apt/sources.list.d/debian.sources" <<'SRC'
types: deb
uris: http://lower.example/debian
suites:
 bookworm
components: main
SRC
expect "deb822: lower-case keys and a continuation line" bookworm "http://lower.example/debian"

# both formats at once: the one-line files are read first
new_root both
echo "deb http://one-line.example/debian bookworm main" > "$root/etc/apt/sources.list"
printf 'Types: deb\nURIs: http://deb822.example/debian\nSuites: bookworm\nComponents: main\n' \
  > "$root/etc/apt/sources.list.d/debian.sources"
expect "both formats: one-line first" bookworm "http://one-line.example/debian"
rm "$root/etc/apt/sources.list"
expect "both formats: deb822 alone" bookworm "http://deb822.example/debian"

new_root empty
expect "no sources at all" bookworm ""

# the command-line form: usage errors exit 2
status=0
bash "$here/../../scripts/debian-mirror.sh" >/dev/null 2>&1 || status=$?
if [ $status -eq 2 ]; then echo "ok   usage error exits 2"; else echo "FAIL usage error exited $status"; failures=$((failures + 1)); fi

# no host name in the repository's set-up scripts: they take the mirror from apt
if grep -nE "deb\.debian\.org|https?://[a-z0-9.-]+\.(org|com|net)" "$here/../../scripts/install-deps.sh" \
     "$here/../../scripts/check-fresh-debian.sh"; then
  echo "FAIL a set-up script names a mirror host"
  failures=$((failures + 1))
else
  echo "ok   set-up scripts name no mirror host"
fi

[ $failures -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
echo "all cases passed"
