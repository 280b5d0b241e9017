#!/usr/bin/env bash
# Installs every Debian 12 package ddafit needs to build, test and benchmark.
# The one list of dependencies: the README's commands and CI both call this.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  cmake make g++                 # toolchain
  libeigen3-dev                  # small dense algebra (6x6 blocks)
  libsuitesparse-dev             # CHOLMOD sparse Cholesky
  libopenblas0-pthread           # BLAS for CHOLMOD's supernodal factorisation (3.7x the reference BLAS)
  libcgal-dev libgmp-dev libmpfr-dev   # exact 2D arrangements for the block generator
  libyaml-cpp-dev                # scene files
  libcli11-dev libfmt-dev nlohmann-json3-dev   # command line, formatting, summary.json
  libgtest-dev libgmock-dev      # tests
  libnlopt-dev libceres-dev      # optimisers for ddafit invert
  libsqlite3-dev                 # the inversion's evaluation cache
  libbenchmark-dev               # bench/
  gnuplot-nox                    # PNG charts (ddafit mesh, simulate --plots)
  clang libfuzzer-14-dev         # scripts/fuzz.sh: libFuzzer targets of the input readers
  openmpi-bin libopenmpi-dev     # scans under mpirun (a manager rank and worker ranks)
  slurm-wlm munge                # scan --slurm, tested against a real one-node cluster
  graphviz                       # docs/architecture.md: the library graph (scripts/architecture_graph.py)
  pybind11-dev python3-dev        # the Python module (import ddafit; docs/python.md)
  python3-numpy python3-pytest python3-matplotlib   # its arrays, its tests, the worked example's chart
  chromium                       # the test that opens report.html as a browser draws it
)
if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${packages[@]}" > /dev/null
