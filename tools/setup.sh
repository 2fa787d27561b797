#!/bin/sh
# Installs what hhneck needs when it is missing, and nothing when it is all
# there. Run as root on Debian or Ubuntu (on another system, install the
# same things by hand: then it only makes the checkout's environment). Safe
# to run again; quiet when there is nothing to do.
#   For the machine, once: gfortran, LAPACK/BLAS, the Fortran HDF5 library,
#   pkg-config, Open MPI for parameter sweeps on many cores (openmpi-bin,
#   libopenmpi-dev), cmake and make (to build pFUnit for the tests, once, in
#   tools/pfunit.sh), python3 with pip and venv (Debian packages); fpm, and
#   numpy, h5py, matplotlib, pandas, objective-rating-metrics (the ISO/TS
#   18571 rating of hhneck-iso18571) for the tools, and pytest and vtk for
#   their tests (PyPI, into the machine's Python: one copy shared by every
#   checkout; Debian's Python refuses such installs unless told, PEP 668).
#   For this checkout: its own Python environment .venv/ (git-ignored; a
#   virtual environment that sees the machine's packages) holding this
#   checkout's package python/hhneck, editable, and its console commands
#   (hhneck-animate, hhneck-export, ...) in .venv/bin. Nothing outside the
#   checkout points at it, and it points at nothing of another checkout:
#   two checkouts on one machine each use their own package. tools/test.sh
#   uses it; in a shell, `. .venv/bin/activate` puts it first on PATH.
#   FORD (PyPI, one version) into .venv, to build the API pages from the
#   !! comments (test/scripts/api_docs.sh); not with --python.
#   Then the release build of the program, so that its build progress goes
#   to stderr and the first run's standard output is the listing alone.
#   tools/setup.sh --python   the Python part alone (no Debian packages, no
#                             FORD, no build): the machine's packages and .venv/
set -eu

python_only=no
case "${1:-}" in
    --python) python_only=yes ;;
    "") ;;
    *) echo "usage: tools/setup.sh [--python]" >&2; exit 1 ;;
esac
root=$(cd "$(dirname "$0")/.." && pwd -P)
venv=$root/.venv

if [ "$python_only" = no ]; then
    missing=""
    for p in gfortran liblapack-dev libblas-dev libhdf5-dev pkg-config openmpi-bin libopenmpi-dev cmake make; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
    done
    if ! command -v python3 >/dev/null 2>&1; then
        missing="$missing python3 python3-pip python3-venv"
    else
        python3 -m pip --version >/dev/null 2>&1 || missing="$missing python3-pip"
        # Debian's python3 makes environments only with python3-venv (ensurepip)
        python3 -c "import ensurepip, venv" >/dev/null 2>&1 || missing="$missing python3-venv"
    fi
    if [ -n "$missing" ]; then
        echo "setup: installing Debian packages:$missing" >&2
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq >&2
        apt-get install -y -qq --no-install-recommends $missing >&2
    fi
fi

# the machine's Python: the third-party packages, one copy for every checkout
export PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_ROOT_USER_ACTION=ignore
pip_install() {
    # Debian's own Python refuses system-wide pip installs unless told (PEP 668)
    python3 -m pip install -q "$@" >&2 2>/dev/null || python3 -m pip install -q --break-system-packages "$@" >&2
}
command -v fpm >/dev/null 2>&1 || { echo "setup: installing fpm from PyPI" >&2; pip_install fpm; }
command -v fpm >/dev/null 2>&1 || { echo "setup: fpm is not on PATH after installing it" >&2; exit 1; }
# (the PyPI names of the missing ones: looked for, not imported, which is
# quick); setuptools and wheel build the checkouts' editable packages
# without a download
wanted=$(python3 -c '
import importlib.util
names = {"numpy": "numpy", "h5py": "h5py", "matplotlib": "matplotlib", "pandas": "pandas",
         "objective_rating_metrics": "objective-rating-metrics", "pytest": "pytest", "vtkmodules": "vtk",
         "setuptools": "setuptools", "wheel": "wheel"}
print(" ".join(p for m, p in names.items() if importlib.util.find_spec(m) is None))')
if [ -n "$wanted" ]; then
    echo "setup: installing from PyPI: $wanted" >&2
    # shellcheck disable=SC2086
    pip_install $wanted
fi

# this checkout's environment: made when missing or when it no longer runs
# (a checkout moved elsewhere: its scripts name the old path)
py=$venv/bin/python
if [ ! -x "$py" ] || ! "$py" -c "" >/dev/null 2>&1 ||
   ! grep -q "^#!$venv/bin/python" "$venv/bin/pip" 2>/dev/null; then
    echo "setup: making this checkout's Python environment .venv (python3 -m venv --system-site-packages)" >&2
    rm -rf "$venv"
    python3 -m venv --system-site-packages "$venv" >&2
fi
# the package: this checkout's python/hhneck, editable, with every console
# command of python/pyproject.toml in .venv/bin; installed again when the
# environment imports another copy or lacks a command (one added since)
found=$(cd / && "$py" -c 'import hhneck, os; print(os.path.dirname(os.path.dirname(os.path.realpath(hhneck.__file__))))' 2>/dev/null || true)
lacking=$(sed -n 's/^\(hhneck-[a-z0-9-]*\) *=.*/\1/p' "$root/python/pyproject.toml" |
          while read -r cmd; do [ -x "$venv/bin/$cmd" ] || echo "$cmd"; done)
if [ "$found" != "$root/python" ] || [ -n "$lacking" ]; then
    echo "setup: installing this checkout's Python package python/hhneck into .venv (pip install -e)" >&2
    # the machine's packages serve as dependencies (--no-deps); built with
    # the environment's setuptools when it can build an editable wheel by
    # itself (64 or later with wheel, or 70.1 or later: no download), else
    # with the ones pip fetches
    if "$py" -c "
import sys, setuptools
v = tuple(int(x) for x in setuptools.__version__.split('.')[:2])
if v < (70, 1):
    import wheel
sys.exit(v < (64, 0))" >/dev/null 2>&1; then
        "$py" -m pip install -q --no-deps --no-build-isolation -e "$root/python" >&2
    else
        "$py" -m pip install -q --no-deps -e "$root/python" >&2
    fi
    found=$(cd / && "$py" -c 'import hhneck, os; print(os.path.dirname(os.path.dirname(os.path.realpath(hhneck.__file__))))' 2>/dev/null || true)
    [ "$found" = "$root/python" ] || {
        echo "setup: .venv imports hhneck from '$found', not from $root/python" >&2
        exit 1
    }
fi

[ "$python_only" = yes ] && exit 0
# FORD, the API documentation generator (test/scripts/api_docs.sh builds
# the pages from the !! comments): into this checkout's environment (its
# dependencies pin versions the machine's packages need not have), one
# version so that its warnings are the same on every machine
ford_version=7.0.13
[ "$("$venv/bin/ford" --version 2>/dev/null)" = "ford version $ford_version" ] || {
    echo "setup: installing FORD $ford_version from PyPI into .venv" >&2
    "$py" -m pip install -q "ford==$ford_version" >&2
}

# a build made before a source file moved to another folder keeps the old
# file's object, and fpm can link a program from stale objects: when
# build/ holds an object of a source that no longer exists, build afresh
if [ -d build ]; then
    expected=$(for f in src/*/*.f90; do echo "src_$(echo "${f#src/}" | tr / _).o"; done)
    for o in build/gfortran_*/hhneck/src_*.f90.o; do
        [ -e "$o" ] || continue
        if ! echo "$expected" | grep -qx "$(basename "$o")"; then
            echo "setup: build/ holds objects of sources that moved ($(basename "$o")); building afresh" >&2
            rm -rf build
            break
        fi
    done
fi

# fpm's progress to stderr as it comes, but for its line when nothing was
# to build (a second run says nothing)
status=$( { { fpm build --profile release 2>&1 && echo 0 >&3 || echo $? >&3; } |
            { grep --line-buffered -v -x 'Project is up to date' >&2 || true; }; } 3>&1 )
exit "$status"
