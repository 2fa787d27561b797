#!/bin/sh
# The scene decks (docs/scenes.md): each runs, closes its energy balance
# and its listing shows the criteria of its loading direction; a scene
# with the head supported (the restraint, the side support, the rear
# 24 km/h seat) keeps every joint within its physiological range, the
# unsupported ones (16 km/h rear without the restraint, frontal) may only
# warn of a joint past it; the 16 km/h rear scene with the head restraint
# against the same run without it: head extension relative to T1 at most
# half of it without; the restraint's starting gap is the 20 mm backset
# the deck's geometry gives by hand; the backset sweep runs, its summary
# has the rear-impact outputs, the head extends less and touches the
# restraint earlier the smaller the backset at every height (two members
# whose head never reaches it agree), the smallest backset always touched,
# its member at
# the base deck's values repeats the single run's criteria and its
# first-contact time the one computed here from the single run's
# penetration channel (NIC is not compared: its peak comes before the
# head reaches the restraint). Run from
# the project root; the executable in $HHNECK.
# builds: release
. test/scripts/lib/checks.sh

# row VALUE-FIELD LABEL LISTING: the number after a criteria row's label
row() {
    awk -v lab="   $2 " -v f="$1" 'index($0, lab) == 1 {split(substr($0, length(lab) + 1), a, " "); print a[f]; exit}' "$3"
}

for deck in scene_rear16:REAR scene_rear16_nohr:REAR scene_rear24:REAR scene_lateral7g:LATERAL \
    scene_frontal:FRONTAL; do
    d=${deck%%:*}
    dir=${deck#*:}
    "$HHNECK" --h5 "$tmp/$d.h5" < "input/$d.inp" > "$tmp/$d.lis" 2> "$tmp/$d.err"
    rc=$?
    check "$d runs (exit 0, got $rc)" [ "$rc" -eq 0 ]
    case $d in
        scene_rear16_nohr|scene_frontal)
            check "$d: no warning in the listing or on stderr but a joint past its range" \
                sh -c '! grep -i "warning" "$1" "$2" | grep -qv "past its physiological range"' sh "$tmp/$d.lis" \
                "$tmp/$d.err" ;;
        *)
            check "$d: no warning in the listing or on stderr" \
                sh -c '! grep -qi "warning" "$1" "$2"' sh "$tmp/$d.lis" "$tmp/$d.err" ;;
    esac
    check "$d: loading direction $dir" grep -q "^   LOADING DIRECTION      $dir  \[5\]$" "$tmp/$d.lis"
    case $dir in
        REAR) rows='NIC (M2/S2);NDC EXTENSION (DEG);NDC RETRACTION (MM);T1 X ACCELERATION (G)' ;;
        LATERAL) rows='LAT. MOMENT |MX| (N M);LAT. SHEAR |FY| (N);HEAD LAT. BENDING (DEG)' ;;
        FRONTAL) rows='NIJ NTE;NIJ NCF;SHEAR |FX| (N);FLEXION MOMENT (N M)' ;;
    esac
    check "$d: the $dir criteria rows ($rows)" \
        sh -c 'IFS=";"; for r in $2; do grep -qF "   $r " "$1" || exit 1; done' \
        sh "$tmp/$d.lis" "$rows"
done

# the restraint against no restraint (16 km/h)
ext_hr=$(row 1 'NDC EXTENSION (DEG)' "$tmp/scene_rear16.lis")
ext_no=$(row 1 'NDC EXTENSION (DEG)' "$tmp/scene_rear16_nohr.lis")
nic_hr=$(row 1 'NIC (M2/S2)' "$tmp/scene_rear16.lis")
check "head extension relative to T1 with the restraint ($ext_hr deg) at most half of it without ($ext_no deg)" \
    awk -v a="$ext_hr" -v b="$ext_no" 'BEGIN {exit !(a != "" && b + 0 < -10 && a + 0 <= 0 && a + 0 > 0.5 * b)}'

# the backset sweep
"$HHNECK" --sweep --h5 "$tmp/bs.h5" < input/sweep_backset.inp > "$tmp/bs.lis" 2> "$tmp/bs.err"
rc=$?
check "the backset sweep runs, all 9 members complete (exit 0, got $rc)" [ "$rc" -eq 0 ]
check "its listing has the rear-impact member table" \
    grep -q '^   RUN ST      HT1_EXT    HT1_EXT_T          NIC       OC_EXT   OC_FX_PEAK    CONTACT_T$' "$tmp/bs.lis"
check "... and their sensitivities" grep -q '^ SENSITIVITIES, REAR-IMPACT OUTPUTS' "$tmp/bs.lis"
cat > "$tmp/sweep.py" <<'PY'
import sys
import h5py
import numpy as np
import hhneck.results as hr

tmp, ext_hr, nic_hr = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
ok = True


def check(what, cond):
    global ok
    print(("PASS  " if cond else "FAIL  ") + what)
    ok = ok and cond


with h5py.File(f"{tmp}/bs.h5") as f:
    names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["runs/output_names"][()]]
    y = f["runs/outputs"][()]
check("the sweep file has the outputs HT1_EXT, HT1_EXT_T, NIC, CONTACT_T",
      all(n in names for n in ("HT1_EXT", "HT1_EXT_T", "NIC", "CONTACT_T")))
k = {n: names.index(n) for n in names}
if y.shape[0] != 9 and y.shape[1] == 9:
    y = y.T
base = y[8]   # backset 20 mm, cushion centre at the head's height: the base deck
check(f"member 9 (the base deck's values) repeats the single run's extension {ext_hr} deg "
      f"(got {base[k['HT1_EXT']]:.2f})", abs(base[k["HT1_EXT"]] - ext_hr) < 0.06)
check(f"... and its NIC {nic_hr} (got {base[k['NIC']]:.3f})", abs(base[k["NIC"]] - nic_hr) < 0.006)
# first contact from the single run's penetration channel, interpolated here
d = hr.read_channels(f"{tmp}/scene_rear16.h5", ["HEADREST_D"])
t, x = d.index.to_numpy(), d["HEADREST_D"].to_numpy()
check(f"the restraint starts 20 mm behind the head (the backset; penetration at the start {x[0]:.3f} mm)",
      abs(x[0] + 20.0) < 0.1)
i = int(np.argmax(x > 0))
t_touch = 1000 * (t[i - 1] + (t[i] - t[i - 1]) * (-x[i - 1]) / (x[i] - x[i - 1]))
check(f"member 9's first contact {base[k['CONTACT_T']]:.3f} ms is the single run's {t_touch:.3f} ms",
      abs(base[k["CONTACT_T"]] - t_touch) < 0.01)
ext = -y[:, k["HT1_EXT"]]
ct = y[:, k["CONTACT_T"]]
# CONTACT_T -1: the head never reached the restraint, the latest of all
late = np.where(ct < 0, np.inf, ct)
# two members of one height, the larger backset first: both untouched, the
# restraint is not in the run and they agree; else the smaller backset's
# head extends less and touches earlier
pairs = [(3 * h + i, 3 * h + i + 1) for h in range(3) for i in range(2)]
untouched = [np.isinf(late[a]) and np.isinf(late[b]) for a, b in pairs]
check(f"the head extends less relative to T1 the smaller the backset, at every height, where the restraint is "
      f"touched (deg: {np.round(ext, 1)})",
      all(abs(ext[a] - ext[b]) < 1e-6 if u else ext[a] > ext[b] > 0 for (a, b), u in zip(pairs, untouched)))
check(f"the restraint is touched later the larger the backset, at every height, and at the smallest "
      f"backset always (ms, -1 never: {np.round(ct, 1)})",
      all(u or late[a] > late[b] for (a, b), u in zip(pairs, untouched))
      and all(np.isfinite(late[3 * h + 2]) for h in range(3)))
sys.exit(0 if ok else 1)
PY
py_checks "$tmp/sweep.py" "$tmp" "$ext_hr" "$nic_hr"
finish
