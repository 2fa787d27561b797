#!/bin/sh
# Cost breakdown by instructions (valgrind's callgrind) of the shipped NBDL
# 15 g run (input/nbdl15g.inp, HDF5 every 0.1 ms) and of one evaluation of
# the shipped 12 g calibration (input/calibrate_controller.inp scored once
# at the controller deck's values: the analyses at rest, the runs of its
# cases, the ratings), per phase: the evaluation (kinematics, element loads, the
# articulated-body a_ij/f_i and solve), Jacobians, factorizations, stage
# solves, step control, the output samples (their evaluation, channels,
# HDF5 writes), start and finish, and the NBDL run's element loads by
# family. Prints the markdown tables of docs/performance.md ("Where the
# time goes").
# Usage: dev/cost_breakdown.sh [KEEP_DIR]   (a few minutes; the callgrind
# files are kept in KEEP_DIR when given). Instructions do not depend on the
# machine's load; the release build's flags are fpm's release profile.
# Needs valgrind (a developer tool, not a dependency of the program; on
# Debian: apt-get install valgrind).
set -e
cd "$(dirname "$0")/.."
command -v valgrind > /dev/null && command -v callgrind_annotate > /dev/null || {
    echo "cost_breakdown.sh: needs valgrind (Debian: apt-get install valgrind)" >&2
    exit 1
}
fpm build --profile release > /dev/null 2>&1 || { echo "cost_breakdown.sh: the release build failed" >&2; exit 1; }
exe=$(fpm run --profile release --runner echo 2> /dev/null | tail -1)
case $exe in /*) ;; *) exe=$PWD/$exe ;; esac
if [ -n "${1:-}" ]; then out=$1; mkdir -p "$out"; else out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
export OMP_NUM_THREADS=1   # one thread: each phase's instructions in one place

valgrind --tool=callgrind --callgrind-out-file="$out/nbdl.cg" "$exe" --h5 "$out/nbdl.h5" --overwrite \
    input/nbdl15g.inp > "$out/nbdl.lst" 2> "$out/nbdl.err"
# the shipped 12 g calibration (input/calibrate_controller.inp) scored once
# (FIT max evals 0) at the controller deck's own values (its VALUES cards
# dropped): the 12 g case and the standing, return and rest cases
sed -e '/^VALUES/d' -e 's/^\(FIT       NELDER    \)[0-9 ]\{10\}/\10         /' input/calibrate_controller.inp \
    > "$out/cal.inp"
valgrind --tool=callgrind --callgrind-out-file="$out/cal.cg" "$exe" --calibrate "$out/cal.inp" \
    > "$out/cal.lst" 2> "$out/cal.err"
for f in nbdl cal; do
    callgrind_annotate --inclusive=yes --tree=calling --threshold=100 "$out/$f.cg" > "$out/$f.tree" 2> /dev/null
done
evals=$(sed -n 's/.* \([0-9]*\) dynamics evaluations.*/\1/p' "$out/nbdl.err" | tail -1)

python3 - "$out/nbdl.tree" "$out/cal.tree" "$evals" << 'EOF'
import re, sys

def parse(path):
    """Inclusive instructions of every function, and of every callee under each caller (with its calls)."""
    total, incl, calls, parent = 0, {}, {}, None
    pat = re.compile(r'^\s*([\d,]+) \([ \d.]+%\)\s+([*>])?\s*(\S+)(?: \(([\d,]+)x\))?')
    for line in open(path):
        if 'PROGRAM TOTALS' in line:
            total = int(line.split()[0].replace(',', ''))
            continue
        m = pat.match(line)
        if not m or not m.group(2):
            continue
        ir, mark, name = int(m.group(1).replace(',', '')), m.group(2), short(m.group(3))
        if mark == '*':
            parent = name
            incl[name] = max(incl.get(name, 0), ir)
        elif parent:
            n = int(m.group(4).replace(',', '')) if m.group(4) else 0
            ir0, n0 = calls.get((parent, name), (0, 0))
            calls[(parent, name)] = (ir0 + ir, n0 + n)
    return total, incl, calls

def short(name):
    """'???:__hn_run_MOD_run_output.constprop.0' -> 'run_output' (OpenMP outlined parts keep their suffix)."""
    name = name.split(':', 1)[-1]
    name = re.sub(r'^__.*_MOD_', '', name)
    return re.sub(r'\.(constprop|isra|part)\.\d+', '', name)

def integrator_rhs(calls):
    """Instructions and number of the integrator's evaluations (ROS34PW2's steps and stages)."""
    pairs = [calls.get((p, 'model_rhs'), (0, 0)) for p in ('rosw_step', 'rosw_stages')]
    return sum(p[0] for p in pairs), sum(p[1] for p in pairs)

def row(label, ir, total, n=None, unit=''):
    per = f'{ir / n / 1e3:,.1f}k per {unit}' if n else ''
    print(f'| {label} | {ir / 1e6:,.1f} | {100 * ir / total:.1f} % | {f"{n:,}" if n else ""} | {per} |')

def head(title):
    print(f'\n{title}\n')
    print('| phase | instructions (1e6) | share | calls | per call |')
    print('|---|---|---|---|---|')

total, incl, calls = parse(sys.argv[1])
evals = int(sys.argv[3]) if sys.argv[3] else 0
c = lambda p, f: calls.get((p, f), (0, 0))

def evaluation_parts(caller, solve, unit):
    """The rows of an evaluation's kinematics, element loads and articulated-body recursion under caller."""
    for lab, f in [('kinematics', 'body_kinematics'), ('element loads', 'compute_loads'), (solve, 'articulated_body_solve')]:
        ir, n = c(caller, f)
        row('&nbsp;&nbsp;&nbsp;&nbsp;' + lab, ir, total, n, unit)
head(f'NBDL 15 g, input/nbdl15g.inp ({evals:,} evaluations; HDF5 every 0.1 ms)')
row('whole program', total, total)
row('start (deck read, model built, HDF5 file opened)', incl.get('run_start', 0), total)
row('&nbsp;&nbsp;of it HDF5 file and datasets created', incl.get('results_open', 0), total)
adv = incl.get('run_advance_to', 0)
row('**integration**', adv, total)
rhs, nrhs = integrator_rhs(calls)
row('&nbsp;&nbsp;evaluations', rhs, total, nrhs, 'evaluation')
evaluation_parts('dynamics_evaluate', 'a_ij, f_i and solve (articulated-body recursion)', 'evaluation')
jac, nj = c('rosw_step', 'rosw_jacobian')
fac, nf = c('rosw_stages', 'im_factor')
sol, ns = c('rosw_stages', 'im_solve')
row('&nbsp;&nbsp;structured Jacobians', jac, total, nj, 'Jacobian')
row('&nbsp;&nbsp;factorizations', fac, total, nf, 'factorization')
row('&nbsp;&nbsp;stage solves', sol, total, ns, 'solve')
row('&nbsp;&nbsp;step control and the rest', adv - rhs - jac - fac - sol, total)
out, nout = c('run_execute', 'run_output')
row('**output samples**', out, total, nout, 'sample')
dyn, _ = c('run_output', 'dynamics_outputs')
row('&nbsp;&nbsp;evaluation at the sample (kinematics, loads, solve)', dyn, total, nout, 'sample')
evaluation_parts('dynamics_outputs', 'articulated-body solve', 'sample')
ch, _ = c('run_output', 'channels_compute')
h5w, _ = c('run_output', 'results_flush')
row('&nbsp;&nbsp;channel values', ch, total, nout, 'sample')
row('&nbsp;&nbsp;HDF5 writes (buffered, flushed in blocks)', h5w, total, nout, 'sample')
row('&nbsp;&nbsp;dense output, peaks, the rest', out - dyn - ch - h5w, total)
fin = incl.get('run_finish', 0)
row('finish (assessment, listing, HDF5 criteria and close)', fin, total)
h5 = incl.get('results_open', 0) + h5w + c('run_finish', 'results_close')[0] + c('run_finish', 'results_criteria')[0]
row('HDF5 in all (open, writes, criteria, close)', h5, total)

# the element loads by family: every call of compute_loads (the integration's
# evaluations and the output samples), each family's loads binding under it
fams = sorted(((ir, n, f) for (p, f), (ir, n) in calls.items() if p == 'compute_loads' and f.endswith('_loads')
               and f != 'loads_clear'), reverse=True)
loads_ir = incl.get('compute_loads', 0)
ncl = max((n for _, n, _ in fams), default=0)
head('The element loads of the NBDL 15 g run by family (every call of compute_loads)')
row('element loads (compute_loads)', loads_ir, total, ncl, 'call')
for ir, n, f in fams:
    if ir >= 1e-3 * loads_ir:
        row('&nbsp;&nbsp;' + f.replace('_loads', ''), ir, total, n, 'call')

total, incl, calls = parse(sys.argv[2])
ev = incl.get('evaluate', 0)
head('One evaluation of the 12 g calibration: input/calibrate_controller.inp scored once (the deck\'s values, one thread)')
row('whole program', total, total)
row('calibration deck read, cases bound', incl.get('read_calibration', 0), total)
row('**one evaluation of the objective**', ev, total)
row('&nbsp;&nbsp;analyses at rest (with and without muscles)', incl.get('case_growth', 0), total)
run = incl.get('run_member', 0)
row('&nbsp;&nbsp;the 12 g member run (rated channels only, no result file)', run, total)
judge = max((ir for f, ir in incl.items() if f.startswith('standing_excursions')), default=0)
row('&nbsp;&nbsp;the standing, return and rest cases (their runs)', judge, total)
rhs, nrhs = integrator_rhs(calls)
row('&nbsp;&nbsp;&nbsp;&nbsp;integration evaluations of all the runs', rhs, total, nrhs, 'evaluation')
row('&nbsp;&nbsp;ISO 18571 ratings of the rated channels', incl.get('score_iso_volunteers', 0), total)
row('&nbsp;&nbsp;CORA-style ratings and peaks', incl.get('score_curves', 0), total)
EOF
