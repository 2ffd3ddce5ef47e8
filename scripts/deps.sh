#!/usr/bin/env bash
# Installs the Debian 12 packages a job needs (as root), only those that are
# missing, so a machine that has them needs no network:
#   deps.sh main   building and running the mrd program (scripts/main.sh):
#                  the lists core, discrepancy, idle, risk and python
#   deps.sh all    every list (scripts/test.sh; the default): also the test
#                  suite's (test), the boards' (board) and the firmware's (firmware)
# The package lists live in scripts/deps/*.list (one name a line, # comments);
# a list may name a foreign architecture package such as libgpiod-dev:arm64,
# which adds that architecture first.
set -euo pipefail
cd "$(dirname "$0")"

main_lists=(deps/core.list deps/discrepancy.list deps/idle.list deps/risk.list deps/python.list)
case ${1:-all} in
  main) lists=("${main_lists[@]}") ;;
  all) lists=(deps/*.list) ;;
  *)
    echo "deps: expected main or all, got '$1'" >&2
    exit 2
    ;;
esac

mapfile -t packages < <(cat "${lists[@]}" | sed -e 's/#.*//' -e 's/[[:space:]]//g' | grep -v '^$' | sort -u)

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
