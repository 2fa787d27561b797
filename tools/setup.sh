#!/bin/sh
# Installs what hhneck needs when it is missing, and nothing when it is all
# there: gfortran, LAPACK/BLAS, the Fortran HDF5 library, pkg-config (Debian
# packages), Open MPI for parameter sweeps on many cores (openmpi-bin,
# libopenmpi-dev), cmake and make (to build pFUnit for the tests, once, in
# tools/pfunit.sh), fpm (from PyPI) and numpy, h5py, matplotlib, pandas
# for the report and export tools, objective-rating-metrics (the ISO/TS
# 18571 rating of hhneck-iso18571) and pytest for their tests, and the
# project's Python package python/hhneck itself (pip install -e python:
# editable, its console commands hhneck-animate, hhneck-export, ... on
# PATH) when `import hhneck` fails or finds another copy. Run as root on
# Debian or Ubuntu. Safe to run again.
set -eu

missing=""
for p in gfortran liblapack-dev libblas-dev libhdf5-dev pkg-config openmpi-bin libopenmpi-dev cmake make; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
command -v python3 >/dev/null 2>&1 || missing="$missing python3"
if command -v python3 >/dev/null 2>&1 && ! python3 -m pip --version >/dev/null 2>&1; then
    missing="$missing python3-pip"
elif ! command -v python3 >/dev/null 2>&1; then
    missing="$missing python3-pip"
fi
if [ -n "$missing" ]; then
    echo "setup: installing Debian packages:$missing" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >&2
    apt-get install -y -qq --no-install-recommends $missing >&2
fi

pip_install() {
    # Debian's own Python refuses system-wide pip installs unless told (PEP 668)
    python3 -m pip install -q "$@" >&2 2>/dev/null || python3 -m pip install -q --break-system-packages "$@" >&2
}
command -v fpm >/dev/null 2>&1 || { echo "setup: installing fpm from PyPI" >&2; pip_install fpm; }
python3 -c "import numpy, h5py, matplotlib, pandas, pytest" >/dev/null 2>&1 || {
    echo "setup: installing numpy h5py matplotlib pandas pytest from PyPI" >&2
    pip_install numpy h5py matplotlib pandas pytest
}
python3 -c "import objective_rating_metrics.rating" >/dev/null 2>&1 || {
    echo "setup: installing objective-rating-metrics (ISO/TS 18571) from PyPI" >&2
    pip_install objective-rating-metrics
}
command -v fpm >/dev/null 2>&1 || { echo "setup: fpm is not on PATH after installing it" >&2; exit 1; }

# the project's Python package, editable (python/ of this checkout), when
# `import hhneck` fails or imports another checkout's copy
root=$(cd "$(dirname "$0")/.." && pwd -P)
here=$root/python
found=$(cd / && python3 -c 'import hhneck, os; print(os.path.dirname(os.path.dirname(os.path.realpath(hhneck.__file__))))' 2>/dev/null || true)
if [ "$found" != "$here" ] || [ -z "$found" ]; then
    echo "setup: installing the Python package python/hhneck (pip install -e)" >&2
    pip_install -e "$root/python"
    # pyenv's shims learn new console commands only on a rehash
    if command -v pyenv >/dev/null 2>&1; then pyenv rehash >&2 2>/dev/null || true; fi
fi
scripts=$(python3 -c 'import sysconfig; print(sysconfig.get_paths()["scripts"])')
command -v hhneck-animate >/dev/null 2>&1 ||
    echo "setup: the console commands (hhneck-animate, ...) are in $scripts, which is not on PATH" >&2

# the release executable, built here so that its build progress goes to
# stderr and the first run's standard output is the listing alone
fpm build --profile release >&2
