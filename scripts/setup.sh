#!/usr/bin/env bash
# Installs, from Debian's packages, whatever vdec needs that this machine lacks.
# Idempotent and quiet when everything is already there.
set -euo pipefail
packages=(
  cmake g++ make git
  libeigen3-dev libcgal-dev libboost-dev libgtest-dev libbenchmark-dev
  libtomlplusplus-dev nlohmann-json3-dev libcli11-dev libssl-dev
  python3-numpy python3-scipy python3-matplotlib python3-pytest
  python3-reportlab poppler-utils  # report.pdf is typeset with ReportLab; the tests read it with pdftotext
  clang libclang-rt-dev libomp-dev  # scripts/fuzz.sh: clang, its libFuzzer and sanitizer runtimes, OpenMP
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
