#!/usr/bin/env bash
# Installs the Debian 12 packages the build and tests need (as root), only
# those that are missing, so a machine that has them needs no network.
# The package lists live in scripts/deps/*.list (one name a line, # comments);
# a list may name a foreign architecture package such as libgpiod-dev:arm64,
# which adds that architecture first.
set -euo pipefail
cd "$(dirname "$0")"

mapfile -t packages < <(cat deps/*.list | sed -e 's/#.*//' -e 's/[[:space:]]//g' | grep -v '^$' | sort -u)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]})) || exit 0

echo "deps: installing ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "deps: need root to install packages (run as root or with sudo)" >&2
  exit 1
fi
for p in "${missing[@]}"; do
  if [[ $p == *:* ]]; then
    arch=${p##*:}
    dpkg --print-foreign-architectures | grep -qx "$arch" || dpkg --add-architecture "$arch"
  fi
done
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
