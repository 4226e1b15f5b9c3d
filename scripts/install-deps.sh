#!/usr/bin/env bash
# Installs the Debian packages ssrcl builds and tests with; does nothing when all are present.
set -euo pipefail
packages=(build-essential cmake ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd
          libopenexr-dev libglm-dev libcli11-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev clinfo
          slurmctld slurmd slurm-client munge
          clang libclang-rt-dev  # clang and its libFuzzer runtime: scripts/test-sanitizers.sh
          python3-dev python3-numpy python3-pybind11 pybind11-dev)  # the Python module (python/)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "Installing: ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
