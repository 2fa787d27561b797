#!/bin/sh
# Benchmark of hhneck-animate (not a test): the animation of a 0.3 s run
# (the NBDL 15 g deck run to 0.3 s; the default 20x slow motion at 25
# frames/s, 151 frames of 960 x 560 pixels) written as a GIF, and as an MP4
# when ffmpeg is installed. Prints the wall time and the CPU time of each
# (the CPU time is the one to compare on a shared machine). Release build.
#   sh dev/bench_animate.sh [PYTHON_PACKAGE_DIR]   (default: this tree's python/)
set -eu
cd "$(dirname "$0")/.."
pkg=${1:-$(pwd)/python}
fpm build --profile release > /dev/null 2>&1
hh=$(pwd)/$(fpm run --profile release --runner echo 2>/dev/null | tail -n 1)
tmp=$(mktemp -d)
sed -e 's/^CONTROL   0.25 /CONTROL   0.3  /' -e '/^H5FILE/d' input/nbdl15g.inp > "$tmp/run03.inp"
"$hh" -I "$(pwd)" --h5 "$tmp/run03.h5" "$tmp/run03.inp" > /dev/null 2>&1
formats=gif
command -v ffmpeg > /dev/null 2>&1 && formats="gif mp4"
echo "hhneck-animate of a 0.3 s run (input/nbdl15g.inp to 0.3 s), package $pkg, $(nproc) cores"
for ext in $formats; do
    PYTHONPATH=$pkg python3 - "$tmp/run03.h5" "$tmp/anim.$ext" <<'PY'
import resource, sys, time
from hhneck.tools import animate
t0, c0 = time.perf_counter(), time.process_time()
animate.main([sys.argv[1], sys.argv[2], "--quiet"])
wall, cpu = time.perf_counter() - t0, time.process_time() - c0
ext = sys.argv[2].rsplit(".", 1)[1]
kids = resource.getrusage(resource.RUSAGE_CHILDREN)       # ffmpeg, for an MP4
print("  %-4s %6.1f s wall, %6.1f s CPU%s" % (ext, wall, cpu, "" if ext == "gif" else
                                              " (+ %.1f s in ffmpeg)" % (kids.ru_utime + kids.ru_stime)))
PY
done
[ "$formats" = gif ] && echo "  mp4  not measured: ffmpeg is not installed"
rm -rf "$tmp"
