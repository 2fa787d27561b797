#!/bin/sh
# Animations and the ParaView sidecar (docs/animation.md): runs case 6-2 to
# a temporary result file, checks the element tables in /model/elements
# against the deck's cards, makes a small GIF and a key-frame strip, checks
# the MP4 path (made when ffmpeg is installed; one clear line when it is
# not), checks the drawn geometry against body position + rotation .
# attachment point computed here from the deck, and checks that the XDMF
# file is well formed and every dataset it references exists.
# Run from the project root: sh test/scripts/animate.sh
HHNECK=${HHNECK:-$(fpm run --runner echo 2>/dev/null | tail -n 1)}
PYTHONPATH=$(pwd)/python${PYTHONPATH:+:$PYTHONPATH}   # the project's own package
export PYTHONPATH
PY=$(python3 -c 'import sys; print(sys.executable)')   # the interpreter itself, not a shim
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
pass=0
fail=0

# Print a check's result and count it.
check() {  # check WHAT STATUS
    if [ "$2" -eq 0 ]; then
        echo "PASS  $1"; pass=$((pass + 1))
    else
        echo "FAIL  $1"; fail=$((fail + 1))
    fi
}

# Run python checks that print PASS/FAIL lines; count them.
pycheck() {  # pycheck FILE ARGS... (script on stdin)
    "$PY" - "$@" > "$tmp/py.out" 2>&1
    cat "$tmp/py.out"
    p=$(grep -c '^PASS' "$tmp/py.out")
    f=$(grep -c '^FAIL' "$tmp/py.out")
    pass=$((pass + p))
    fail=$((fail + f))
    if [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then
        echo "FAIL  python check ran no checks"; fail=$((fail + 1))
    fi
}

"$HHNECK" --h5 "$tmp/c62.h5" < input/case6-2.inp > "$tmp/listing.txt" 2> "$tmp/run.err"
check "case 6-2 runs to $tmp/c62.h5 (exit $?)" $?

# --- the element tables against the deck's LIGAMENT, MUSCLE and DISC cards
pycheck "$tmp/c62.h5" input/head_neck_54dof.inp <<'EOF'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
cards = [l.rstrip("\n") for l in open(sys.argv[2]) if not l.startswith("*")]
bodies = [l.split()[1] for l in cards if l.startswith("BODY ")]
want = {"LIGAMENT": {}, "MUSCLE": {}, "DISC": {}}
for n, l in enumerate(cards):
    key = {"HILL": "MUSCLE"}.get(l[:10].strip(), l[:10].strip())   # Hill-type muscles are muscles too
    if key in want:
        w = l.split()
        pts = [float(v) for v in cards[n + 1].split()[:6]]
        want[key][w[1]] = ([bodies.index(w[2]) + 1, bodies.index(w[3]) + 1], pts)
ok = True
for key, group in (("LIGAMENT", "ligaments"), ("MUSCLE", "muscles"), ("DISC", "discs")):
    g = f["model/elements/" + group]
    names = [n.decode().strip() for n in g["name"][:]]
    ok &= sorted(names) == sorted(want[key]) and len(names) == len(want[key])
    for e, n in enumerate(names):
        b, p = want[key][n]
        ok &= list(g["body"][e]) == b and np.array_equal(g["point"][e].ravel(), p)
counts = [len(want[k]) for k in want]
print(("PASS" if ok and min(counts) > 0 else "FAIL") +
      "  /model/elements: %d ligaments, %d muscles, %d discs with the deck's names, bodies and points" % tuple(counts))
units = []
f["model/elements"].visititems(lambda n, o: units.append((n, o.attrs.get("units")))
                               if isinstance(o, h5py.Dataset) and o.dtype.kind in "fiu" else None)
missing = [n for n, u in units if u is None]
print(("PASS" if units and not missing else "FAIL") +
      "  every numeric dataset of /model/elements has a units attribute (%d datasets; missing: %s)" % (len(units), missing))
EOF

# --- a small GIF (6 frames: 0 to 100 ms every 20 ms) and a key-frame strip
"$PY" -m hhneck.tools.animate "$tmp/c62.h5" "$tmp/small.gif" --slow 1 --fps 50 --dpi 30 --quiet \
    --strip "$tmp/strip.png" > "$tmp/anim.out" 2> "$tmp/anim.err"
check "animate.py writes a GIF and a strip (exit $?)" $?
pycheck "$tmp" <<'EOF'
import sys
from PIL import Image
t = sys.argv[1]
im = Image.open(t + "/small.gif")
print(("PASS" if im.format == "GIF" and im.n_frames == 6 and im.size == (360, 210) else "FAIL") +
      "  small.gif: %s, %d frames (expected 6: 0-100 ms every 20 ms), %dx%d pixels (expected 360x210)"
      % (im.format, im.n_frames, *im.size))
out = open(t + "/anim.out").read()
st = Image.open(t + "/strip.png")
print(("PASS" if st.format == "PNG" and "(6 key frames)" in out else "FAIL") +
      "  strip.png: %s, %dx%d pixels, 6 key frames (0-100 ms every 20 ms)" % (st.format, *st.size))
EOF

# --- MP4: one clear line when ffmpeg is missing; an H.264 file when present
PATH=/nonexistent "$PY" -m hhneck.tools.animate "$tmp/c62.h5" "$tmp/no.mp4" > "$tmp/mp4.out" 2> "$tmp/mp4.err"
rc=$?
lines=$(wc -l < "$tmp/mp4.err")
grep -q "apt-get install ffmpeg" "$tmp/mp4.err" && grep -q "gif" "$tmp/mp4.err" \
    && [ "$rc" -eq 2 ] && [ "$lines" -eq 1 ] && [ ! -e "$tmp/no.mp4" ]
check "MP4 without ffmpeg: exit $rc, $lines line naming apt-get install ffmpeg and .gif, no file" $?
if command -v ffmpeg > /dev/null 2>&1; then
    "$PY" -m hhneck.tools.animate "$tmp/c62.h5" "$tmp/small.mp4" --slow 1 --fps 50 --dpi 30 --quiet > /dev/null 2>&1
    rc=$?
    frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
             -of csv=p=0 "$tmp/small.mp4" 2> /dev/null)
    [ "$rc" -eq 0 ] && [ "$frames" = "6" ]
    check "MP4 with ffmpeg: exit $rc, $frames frames (expected 6)" $?
else
    echo "(ffmpeg not installed: MP4 encoding not tried)"
fi
# the frames handed to ffmpeg: a stand-in ffmpeg that keeps its standard
# input (the raw RGBA frames) as the output file: 6 frames of 360 x 210 x 4 bytes
mkdir -p "$tmp/fakebin"
cat > "$tmp/fakebin/ffmpeg" <<'SH'
#!/bin/sh
for a in "$@"; do out=$a; done
cat > "$out"
SH
chmod +x "$tmp/fakebin/ffmpeg"
PATH="$tmp/fakebin:$PATH" "$PY" -m hhneck.tools.animate "$tmp/c62.h5" "$tmp/raw" --slow 1 --fps 50 --dpi 30 --quiet \
    > /dev/null 2>&1
rc=$?
size=$(wc -c < "$tmp/raw.mp4" 2> /dev/null || echo 0)
[ "$rc" -eq 0 ] && [ "$size" -eq $((6 * 360 * 210 * 4)) ]
check "OUT without a suffix and ffmpeg on PATH: OUT.mp4, ffmpeg given 6 raw frames of 360x210 RGBA ($size bytes)" $?
PATH=/nonexistent "$PY" -m hhneck.tools.animate "$tmp/c62.h5" "$tmp/plain" --slow 1 --fps 50 --dpi 30 --quiet > /dev/null 2>&1
rc=$?
[ "$rc" -eq 0 ] && [ "$(head -c 6 "$tmp/plain.gif" 2> /dev/null)" = "GIF89a" ] && [ ! -e "$tmp/plain.mp4" ]
check "OUT without a suffix and no ffmpeg: OUT.gif (exit $rc)" $?

# --- the drawn geometry against independent truth
pycheck "$tmp/c62.h5" input/head_neck_54dof.inp <<'EOF'
import sys
sys.path.insert(0, "python")
import h5py, numpy as np
from hhneck.tools import animate
f = h5py.File(sys.argv[1], "r")
cards = [l for l in open(sys.argv[2]) if not l.startswith("*")]
bodies = [l.split()[1] for l in cards if l.startswith("BODY ")]
def card(name):
    """bodies (1-based) and points of a LIGAMENT or MUSCLE card of the deck"""
    n = [k for k, l in enumerate(cards) if l[10:20].strip() == name][0]
    w, p = cards[n].split(), [float(v) for v in cards[n + 1].split()[:6]]
    return [bodies.index(w[2]) + 1, bodies.index(w[3]) + 1], [p[:3], p[3:]]
def truth(i, k, c):
    """r_k + S c with S_ij = /bodies/rotation[i, k, j, i] (docs/output-format.md)"""
    r, s = f["bodies/position"][i, k - 1], f["bodies/rotation"][i, k - 1]
    return np.array([r[a] + sum(s[j, a] * c[j] for j in range(3)) for a in range(3)])
res = animate.Result(sys.argv[1])
i = len(res.time) - 1                          # 100 ms: head extended by some 40 deg
fig, scene = animate.build_figure(res, np.array([0, i]), 30, views=("side", "front", "iso"))
scene.update(i)
head = bodies.index("HEAD") + 1
side, front, d3 = (scene.artists[v] for v in ("side", "front", "iso"))
r = f["bodies/position"][i, head - 1]
k = head - 1                                   # the mass-centre markers: one line, a point per body
x, z = (np.asarray(a)[k] for a in side["cm"].get_data())
y, z2 = (np.asarray(a)[k] for a in front["cm"].get_data())
p3 = np.array([np.asarray(a)[k] for a in d3["cm"].get_data_3d()])
err = max(abs(x - r[0]), abs(z - r[2]), abs(y - r[1]), abs(z2 - r[2]), *abs(p3 - r))
print(("PASS" if err < 1e-12 else "FAIL") +
      "  head mass centre drawn at /bodies/position (side, front, 3-D views, t = %.0f ms): error %.1e m"
      % (1000 * f["time"][i], err))
for name in ("SCML", "ALLC2C1", "TRAPR"):
    b, c = card(name)
    want = np.array([truth(i, b[e], c[e]) for e in range(2)])
    fam, e = scene.index[name]                 # one line collection per family and view
    xs, zs = side["lines"][fam].get_segments()[e].T
    ys, zf = front["lines"][fam].get_segments()[e].T
    err = max(abs(ys - want[:, 1]).max(), abs(xs - want[:, 0]).max(), abs(zs - want[:, 2]).max(),
              abs(zf - want[:, 2]).max())
    print(("PASS" if err < 1e-12 else "FAIL") +
          "  %s (%s to %s) drawn from r + S c of its deck card (side and front views): error %.1e m, "
          "ends (%.4f %.4f %.4f) (%.4f %.4f %.4f)"
          % (name, bodies[b[0] - 1], bodies[b[1] - 1], err, *want[0], *want[1]))
label = scene.label_text.get_text()
shown = float(label.split("head flexion")[1].split()[0])
chan = f["channels/HEAD_THETY"][i]
print(("PASS" if abs(shown - chan) <= 0.051 and abs(chan) > 30 else "FAIL") +
      "  head rotation on the frame %.1f deg = channel HEAD_THETY %.3f deg" % (shown, chan))
EOF

# --- the element-table fallback: a file without /model/elements still animates
"$PY" - "$tmp/c62.h5" "$tmp/old.h5" <<'EOF'
import sys, shutil, h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "a") as f:
    del f["model/elements"]
EOF
"$PY" -m hhneck.tools.animate "$tmp/old.h5" "$tmp/old.gif" --slow 1 --fps 20 --dpi 20 --quiet > /dev/null 2> "$tmp/old.err"
rc=$?
[ "$rc" -eq 0 ] && [ -s "$tmp/old.gif" ] && grep -q "no /model/elements" "$tmp/old.err"
check "a file without /model/elements: GIF of the bodies and one warning (exit $rc)" $?

# --- XDMF: well formed, every referenced dataset exists with the declared shape
"$PY" -m hhneck.tools.xdmf "$tmp/c62.h5" > "$tmp/xdmf.out" 2>&1
check "write_xdmf.py writes c62.xmf and c62.elements.h5 (exit $?)" $?
pycheck "$tmp/c62.xmf" "$tmp/c62.h5" input/head_neck_54dof.inp <<'EOF'
import sys, os
import xml.etree.ElementTree as ET
import h5py, numpy as np
xmf, h5 = sys.argv[1], sys.argv[2]
try:
    root = ET.parse(xmf).getroot()
    print("PASS  %s is well-formed XML (root <%s Version=%s>)" % (os.path.basename(xmf), root.tag, root.get("Version")))
except ET.ParseError as e:
    print("FAIL  %s is not well-formed XML: %s" % (xmf, e)); sys.exit()
here = os.path.dirname(xmf)
def dims(item):
    return [int(v) for v in item.get("Dimensions").split()]
bad, nref, values = [], 0, {}
def value(item):
    """the array a DataItem stands for (HDF, XML or HyperSlab)"""
    if item.get("ItemType") == "HyperSlab":
        sel, src = list(item)
        s = np.array(sel.text.split(), dtype=int).reshape(3, -1)
        data = value(src)
        if np.any(s[0] + s[1] * (s[2] - 1) >= data.shape) or np.prod(s[2]) != np.prod(dims(item)):
            bad.append("hyperslab %s of %s" % (sel.text, src.text))
            return np.zeros(dims(item))
        return data[tuple(slice(a, a + b * c, b) for a, b, c in zip(*s))].reshape(dims(item))
    if item.get("Format") == "HDF":
        global nref
        nref += 1
        fname, path = item.text.strip().split(":")
        full = os.path.join(here, fname)
        if not os.path.exists(full):
            bad.append("file " + fname); return np.zeros(dims(item))
        if (full, path) not in values:
            with h5py.File(full, "r") as f:
                values[(full, path)] = f[path][()] if path in f else None
        data = values[(full, path)]
        if data is None or list(data.shape) != dims(item):
            bad.append("%s:%s %s" % (fname, path, "missing" if data is None else "shape %s" % (data.shape,)))
            return np.zeros(dims(item))
        return data
    v = np.array(item.text.split(), dtype=float)
    if v.size != np.prod(dims(item)):
        bad.append("inline item of %d values for Dimensions %s" % (v.size, item.get("Dimensions")))
    return v
steps = root.find("Domain/Grid").findall("Grid")
times = [float(g.find("Time").get("Value")) for g in steps]
arrays = [{grid.get("Name"): {(c.get("Name") or c.tag): value(c.find("DataItem")) for c in grid}
           for grid in g.findall("Grid")} for g in steps]
print(("PASS" if not bad and nref > 0 else "FAIL") +
      "  every one of %d HDF5 references exists with its declared shape, hyperslabs in bounds%s"
      % (nref, "" if not bad else ": " + "; ".join(sorted(set(bad))[:5])))
f = h5py.File(h5, "r")
t = f["time"][:]
print(("PASS" if len(times) == 101 and np.allclose(times, np.arange(101) * 1e-3, atol=1e-9) else "FAIL") +
      "  temporal collection: %d steps, 0 to %.0f ms every 1 ms (expected 101)" % (len(times), 1000 * times[-1]))
# at 100 ms: body points = /bodies/position; head z axis gives HEAD_THETY; LCAPL ends = r + S c
i, s = len(t) - 1, len(steps) - 1
bod, el = arrays[s]["bodies"], arrays[s]["elements"]
head = 8
err_p = abs(bod["Geometry"].reshape(-1, 3) - f["bodies/position"][i]).max()
z = bod["z_axis"].reshape(-1, 3)[head]
theta = np.degrees(np.arctan2(z[0], z[2]))
print(("PASS" if err_p < 1e-15 and abs(theta - f["channels/HEAD_THETY"][i]) < 1e-9 else "FAIL") +
      "  bodies grid at 100 ms: points = /bodies/position (error %.1e m); head z_axis gives %.4f deg = HEAD_THETY %.4f deg"
      % (err_p, theta, f["channels/HEAD_THETY"][i]))
cards = [l for l in open(sys.argv[3]) if not l.startswith("*")]
bodies = [l.split()[1] for l in cards if l.startswith("BODY ")]
n = [k for k, l in enumerate(cards) if l[10:20].strip() == "LCAPL"][0]
w, c = cards[n].split(), np.array(cards[n + 1].split()[:6], dtype=float).reshape(2, 3)
def world(body, point):
    k = bodies.index(body)
    return f["bodies/position"][i, k] + f["bodies/rotation"][i, k].T @ np.asarray(point, dtype=float)
via = [l.split() for l in cards if l.startswith("VIA ") and l.split()[1] == "LCAPL"]
want = [world(w[2], c[0])] + [world(v[2], v[3:6]) for v in via] + [world(w[3], c[1])]
side = h5py.File(os.path.join(os.path.dirname(xmf), "c62.elements.h5"), "r")
segs = [k for k, m in enumerate(side["name"][:]) if m.decode().strip() == "LCAPL"]
geo = el["Geometry"].reshape(-1, 3)
path = [geo[2 * segs[0]]] + [geo[2 * k + 1] for k in segs]
joined = all(np.array_equal(geo[2 * a + 1], geo[2 * b]) for a, b in zip(segs, segs[1:]))
force = el["force"].ravel()[segs]
err = abs(np.array(path) - np.array(want)).max() if len(path) == len(want) else np.inf
print(("PASS" if len(via) > 0 and joined and err < 1e-12 and np.all(force == f["channels/LCAPL"][i]) and force[0] > 1
       else "FAIL") +
      "  elements grid at 100 ms: LCAPL (C5 to HEAD) drawn as %d joined segments through its %d VIA points, "
      "points = r + S c of its deck cards (error %.1e m), force %.2f N = channel LCAPL on each"
      % (len(segs), len(via), err, force[0]))
EOF

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
